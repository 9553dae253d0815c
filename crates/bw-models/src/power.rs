//! Powers `|x|^p` with cheap paths for the exponents that occur in practice.
//!
//! The general path is `2^(p log2 a)` rather than `powf`: about half the cost, and two powers
//! of the same base share the logarithm (`Powers`). The relative error is at most a few
//! `ε (1 + p |log2 a|)` (the rounding of `log2 a` scaled by the exponent), i.e. `1e-14` for
//! `a` in `[1e-3, 1e3]` and `p <= 10`, far below any solver tolerance.

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
            Kind::General => (self.p * a.log2()).exp2(),
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

/// Powers of one base `a >= 0` that share `log2 a`, computed on the first power that takes the
/// general path (so a power that turns out not to be needed costs nothing).
pub(crate) struct Powers {
    a: f64,
    log2: Option<f64>,
}

impl Powers {
    /// The base `a >= 0`.
    #[inline]
    pub(crate) fn of(a: f64) -> Self {
        Self { a, log2: None }
    }

    /// The base `a > 0` with its `log2 a` known.
    #[inline]
    pub(crate) fn with_log2(a: f64, log2: f64) -> Self {
        Self {
            a,
            log2: Some(log2),
        }
    }

    /// `a^p`, bit for bit equal to `p.of_abs(a)`.
    #[inline]
    pub(crate) fn get(&mut self, p: Pow) -> f64 {
        match p.kind {
            Kind::General => (p.p * *self.log2.get_or_insert_with(|| self.a.log2())).exp2(),
            _ => p.of_abs(self.a),
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
                // The error bound of the module docs (exact paths: 4 ε).
                let tol = 4.0 * f64::EPSILON * want * (1.0 + p * x.log2().abs().min(1e3));
                let got = e.of_abs(x);
                assert!((got - want).abs() <= tol, "p {p} x {x}: {got} vs {want}");
                if p > 0.0 {
                    let s = e.signed(-x);
                    assert!((s + want).abs() <= tol, "p {p} x {x}: {s}");
                }
                let mut shared = Powers::of(x);
                let (b, a) = (shared.get(Pow::new(2.93)), shared.get(e));
                assert_eq!(
                    a.to_bits(),
                    got.to_bits(),
                    "shared p {p} x {x}: {a} vs {got}"
                );
                let want_b = f64::powf(x, 2.93);
                let tol_b = 4.0 * f64::EPSILON * want_b * (1.0 + 2.93 * x.log2().abs().min(1e3));
                assert!((b - want_b).abs() <= tol_b, "pair 2.93 x {x}: {b}");
            }
        }
    }
}
