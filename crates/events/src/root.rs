//! Bracketing root finder: Illinois (modified regula falsi) with a bisection safeguard.

/// Sign class of a value: -1, 0 or +1.
#[inline]
pub fn class(x: f64) -> i8 {
    if x > 0.0 {
        1
    } else if x < 0.0 {
        -1
    } else {
        0
    }
}

/// The narrowest bracket found around the first change of class of `g` in `[a, b]`:
/// `g(lo)` still has the class it had at `a`, `g(hi)` has left it (zero or the opposite sign).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bracket {
    /// Last point before the crossing.
    pub lo: f64,
    /// First point after the crossing (the reported instant).
    pub hi: f64,
    /// Evaluations of `g` used.
    pub evaluations: u32,
}

/// Locates the crossing of `g` between `a` (where `g = ga`, class non-zero) and `b` (where
/// `g = gb` has another class) down to adjacent floating-point numbers.
///
/// Illinois steps converge superlinearly on simple roots; whenever two steps fail to halve the
/// bracket, a bisection step is taken, so zeros of high multiplicity (`g ~ (t* - t)^p`) are
/// still found to the last bit in at most about 2 × 64 evaluations.
pub fn find_crossing(mut g: impl FnMut(f64) -> f64, a: f64, b: f64, ga: f64, gb: f64) -> Bracket {
    let ca = class(ga);
    let (mut lo, mut hi, mut glo, mut ghi) = (a, b, ga, gb);
    let mut side = 0i8;
    let mut width_two_ago = f64::INFINITY;
    let mut width_one_ago = hi - lo;
    let mut evaluations = 0;
    loop {
        let mid = lo + 0.5 * (hi - lo);
        if mid <= lo || mid >= hi {
            break;
        }
        let width = hi - lo;
        let x = if ghi != 0.0 && width * 2.0 <= width_two_ago && glo != ghi {
            let s = lo - glo * (hi - lo) / (ghi - glo);
            if s > lo && s < hi {
                s
            } else {
                mid
            }
        } else {
            mid
        };
        width_two_ago = width_one_ago;
        width_one_ago = width;
        let gx = g(x);
        evaluations += 1;
        if class(gx) == ca {
            lo = x;
            glo = gx;
            if side == -1 {
                ghi *= 0.5;
            }
            side = -1;
        } else {
            hi = x;
            ghi = gx;
            if side == 1 {
                glo *= 0.5;
            }
            side = 1;
        }
    }
    Bracket {
        lo,
        hi,
        evaluations,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn simple_root_to_adjacent_floats() {
        let b = find_crossing(|t| t * t - 2.0, 1.0, 2.0, -1.0, 2.0);
        assert!(b.hi - b.lo <= f64::EPSILON * 2.0);
        assert!((b.hi - 2f64.sqrt()).abs() <= 2.0 * f64::EPSILON);
        assert!(b.evaluations < 20, "{}", b.evaluations);
    }

    #[test]
    fn high_multiplicity_root_is_exact() {
        // g = (0.7 - t)^5: flat near the root, sign still exact.
        let r: f64 = 0.7;
        let b = find_crossing(|t| (r - t).powi(5), 0.0, 1.0, r.powi(5), (r - 1.0).powi(5));
        assert!((b.hi - r).abs() <= 2.0 * f64::EPSILON, "{}", b.hi - r);
        assert!(b.evaluations <= 130, "{}", b.evaluations);
    }

    #[test]
    fn entering_zero_counts_as_crossing() {
        // g reaches exactly zero on [0.5, 1] and stays there.
        let b = find_crossing(|t| (0.5 - t).max(0.0), 0.0, 1.0, 0.5, 0.0);
        assert!((b.hi - 0.5).abs() <= f64::EPSILON);
    }
}
