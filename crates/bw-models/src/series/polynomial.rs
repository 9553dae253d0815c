//! Truncated power series of order [`ORDER`] as polynomials: their values and slopes, their roots,
//! and the step size their coefficients allow (Jorba & Zou).

/// Orders whose coefficients set the step size.
pub const ESTIMATE_TERMS: usize = 4;

/// Taylor coefficients `c_0 ..= c_ORDER` of one function about the start of a step.
pub(crate) type Series = [f64; ORDER + 1];

/// Order of the Taylor polynomials (chosen by the work-precision benchmark, BENCHMARKS.md).
pub const ORDER: usize = 16;

/// The polynomial and its derivative at `s`.
pub(super) fn eval_d(c: &Series, s: f64) -> (f64, f64) {
    let (mut p, mut d) = (0.0, 0.0);
    for ci in c.iter().rev() {
        d = d * s + p;
        p = p * s + ci;
    }
    (p, d)
}

/// Sign class: -1, 0 or 1.
pub(super) fn class(v: f64) -> i8 {
    if v > 0.0 {
        1
    } else if v < 0.0 {
        -1
    } else {
        0
    }
}

/// The root in `(0, h]` of a function `g` (value and slope at `s`) that has class `start` just
/// after 0 and another class at `h`, as the first point found on the far side (within a few
/// ulps of the root): Newton's iteration kept inside the shrinking bracket, ends included
/// (bisection where it would leave it; a probe just past the root once Newton creeps up on it
/// from one side). After [`NEWTON_ITERATIONS`], a bisection wherever two iterations failed to
/// halve the bracket: where `g` is tiny but far from its root (a force `|X|^p (...)` near
/// `X = 0`) the slope does not describe it and Newton's steps crawl.
pub(super) fn root(g: impl Fn(f64) -> (f64, f64), h: f64, start: i8) -> f64 {
    let (mut lo, mut hi) = (0.0, h);
    let mut s = h;
    let (mut width_two_ago, mut width_one_ago) = (f64::INFINITY, h);
    for iteration in 0..200 {
        let (p, d) = g(s);
        if class(p) == start {
            lo = s;
        } else {
            hi = s;
        }
        let tiny = 4.0 * f64::EPSILON * hi;
        if hi - lo <= tiny {
            break;
        }
        let stalled = iteration >= NEWTON_ITERATIONS && hi - lo > 0.5 * width_two_ago;
        (width_two_ago, width_one_ago) = (width_one_ago, hi - lo);
        let newton = s - p / d;
        // Newton's iterate may be an end of the bracket: where a search is repeated up to the
        // root found, it starts on that root.
        s = if !(newton >= lo && newton <= hi) || stalled {
            0.5 * (lo + hi)
        } else if (newton - s).abs() > tiny {
            newton
        } else if class(p) == start {
            // Newton's estimate of the root is within `tiny` of the bracket's low end `s`: a
            // probe just past it leaves a bracket narrow enough to stop.
            (newton + PROBE * tiny).min(0.5 * (newton + hi))
        } else {
            (newton - PROBE * tiny).max(0.5 * (newton + lo))
        };
    }
    hi
}

/// Distance of [`root`]'s probe past Newton's estimate of the root, as a fraction of the final
/// width: less than 1, so that the bracket a probe leaves, rounding included, is narrow enough
/// to stop.
const PROBE: f64 = 0.75;

/// Iterations of [`root`] before a bracket that does not shrink fast enough is bisected (Newton
/// converges on the roots of the step polynomials within a few).
const NEWTON_ITERATIONS: usize = 8;

/// `0.9 min_k (tol / c_k)^(1/k)` over the last [`ESTIMATE_TERMS`] orders up to `order`, for the
/// largest coefficients `c_k` of a series (a zero coefficient gives an infinite `ρ_k`).
pub(super) fn jorba_zou(tol: f64, order: usize, largest: impl Fn(usize) -> f64) -> f64 {
    let lt = coarse_log2(tol);
    // One exp2 for the smallest.
    let mut x = f64::INFINITY;
    for k in order + 1 - ESTIMATE_TERMS..=order {
        let c = largest(k);
        if c > 0.0 {
            x = x.min((lt - coarse_log2(c)) / k as f64);
        }
    }
    0.9 * x.exp2()
}

/// `log2 a` for a positive `a` to within 1.1e-3 (the binary exponent and a cubic in the
/// mantissa, exact at powers of 2): enough for a step size, whose `ρ_k` it changes by less than
/// `1e-4` relative, at a fraction of the cost of `log2`. Subnormal `a` read as `2^-1023` (a
/// smaller step).
pub(super) fn coarse_log2(a: f64) -> f64 {
    const MANTISSA: u64 = (1 << 52) - 1;
    let bits = a.to_bits();
    let exponent = ((bits >> 52) & 0x7ff) as f64 - 1023.0;
    let t = f64::from_bits((bits & MANTISSA) | (1023 << 52)) - 1.0;
    exponent
        + t * (1.420_864_537_430_105 + t * (-0.577_250_650_806_472 + t * 0.156_386_113_376_367))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coarse_log2_is_within_its_bound() {
        for i in 0..20_000 {
            let a = 10f64.powf(-300.0 + 600.0 * f64::from(i) / 20_000.0);
            assert!((coarse_log2(a) - a.log2()).abs() <= 1.1e-3, "{a}");
        }
        assert_eq!(coarse_log2(1.0), 0.0);
        assert_eq!(coarse_log2(0.25), -2.0);
    }

    #[test]
    fn roots_of_polynomials() {
        // s^2 - 0.3 on (0, 1]: root sqrt(0.3), from either side.
        let mut q = [0.0; ORDER + 1];
        (q[0], q[2]) = (-0.3, 1.0);
        let r = root(|s| eval_d(&q, s), 1.0, -1);
        assert!((r - 0.3f64.sqrt()).abs() <= 1e-15 && eval_d(&q, r).0 >= 0.0);
        let neg = q.map(|c| -c);
        let r = root(|s| eval_d(&neg, s), 1.0, 1);
        assert!((r - 0.3f64.sqrt()).abs() <= 1e-15 && eval_d(&neg, r).0 <= 0.0);
        assert_eq!(eval_d(&q, 2.0), (3.7, 4.0));
        // A value that is tiny past its root and a slope that does not describe it (a force
        // |X|^p (...) near X = 0): Newton's steps from the far end would crawl 2e-12 at a time.
        let g = |s: f64| (if s < 0.05 { 1e-20 } else { -4e-25 }, -1.9e-13);
        let r = root(g, 0.068, 1);
        assert!((r - 0.05).abs() <= 1e-15, "{r}");
    }

    #[test]
    fn a_root_at_the_end_of_the_span_takes_two_evaluations() {
        // Each event is searched for again up to the root found, where its function is zero
        // to rounding: Newton's iterate is then the end itself. A bisection from there would
        // send the iterates from below past the end of a convex function, bisecting each time.
        type Function = fn(f64) -> (f64, f64);
        let cases: [(Function, i8); 3] = [
            (|s| (s - 0.25, 1.0), -1),
            (|s| (s * s - 0.0625, 2.0 * s), -1),
            (|s| (0.0625 - s * s, -2.0 * s), 1),
        ];
        for (g, start) in cases {
            let calls = std::cell::Cell::new(0);
            let r = root(
                |s| {
                    calls.set(calls.get() + 1);
                    g(s)
                },
                0.25,
                start,
            );
            assert_eq!(r, 0.25);
            assert!(calls.get() <= 2, "{} evaluations", calls.get());
        }
    }
}
