//! Powers `|x|^p` with cheap paths for the exponents that occur in practice.

/// A fixed exponent `p >= 0`, classified once so that `|x|^p` avoids `powf` where it can
/// (integers up to 4 by multiplication, half-integers by one `sqrt`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pow {
    p: f64,
    kind: Kind,
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Kind {
    Zero,
    One,
    Two,
    Three,
    Four,
    /// `p = k + 1/2` with `k` in `0..=4`.
    Half(i32),
    General,
}

impl Pow {
    /// Classifies `p`.
    pub fn new(p: f64) -> Self {
        let kind = if p == 0.0 {
            Kind::Zero
        } else if p == 1.0 {
            Kind::One
        } else if p == 2.0 {
            Kind::Two
        } else if p == 3.0 {
            Kind::Three
        } else if p == 4.0 {
            Kind::Four
        } else if (p - 0.5).fract() == 0.0 && (0.5..=4.5).contains(&p) {
            Kind::Half((p - 0.5) as i32)
        } else {
            Kind::General
        };
        Self { p, kind }
    }

    /// The exponent.
    pub fn exponent(self) -> f64 {
        self.p
    }

    /// `a^p` for `a >= 0`.
    #[inline]
    pub fn of_abs(self, a: f64) -> f64 {
        match self.kind {
            Kind::Zero => 1.0,
            Kind::One => a,
            Kind::Two => a * a,
            Kind::Three => a * a * a,
            Kind::Four => (a * a) * (a * a),
            Kind::Half(k) => a.powi(k) * a.sqrt(),
            Kind::General => a.powf(self.p),
        }
    }

    /// `|x|^(p-1) x`, i.e. `sign(x) |x|^p`, for `p > 0` (0 at 0).
    #[inline]
    pub fn signed(self, x: f64) -> f64 {
        match self.kind {
            Kind::One => x,
            Kind::Three => x * x * x,
            _ => self.of_abs(x.abs()).copysign(x),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fast_paths_agree_with_powf() {
        for p in [
            0.0, 1.0, 1.5, 2.0, 2.5, 3.0, 3.5, 4.0, 4.5, 1.27, 2.62, 10.0,
        ] {
            let e = Pow::new(p);
            for x in [0.0, 1e-300, 1e-8, 0.3, 1.0, 2.7, 1e5] {
                let want = if p == 0.0 { 1.0 } else { f64::powf(x, p) };
                let got = e.of_abs(x);
                assert!(
                    (got - want).abs() <= 4.0 * f64::EPSILON * want,
                    "p {p} x {x}: {got} vs {want}"
                );
                if p > 0.0 {
                    let s = e.signed(-x);
                    assert!(
                        (s + want).abs() <= 4.0 * f64::EPSILON * want,
                        "p {p} x {x}: {s}"
                    );
                }
            }
        }
    }
}
