//! Boundary crossings inside a step that its ends do not show.
//!
//! A boundary function can leave its sign class and come back within one accepted step: a
//! contact force that dips below zero while the bodies part and meet again under a pull. Its
//! values at the two ends then agree and the crossing (the event) would be missed. After each
//! step, each boundary function gets a cubic Hermite model from its values and rates at the
//! ends (rates by a forward difference along the solution, one extra evaluation of the
//! condition per step, reused by the next step); where the model's extremum inside the step
//! has left the class both ends share, or comes within [`NEAR`] of the boundary (the model's
//! own error can hide a shallow excursion), the step's dense output is sampled to confirm it:
//! at [`SAMPLES`] points and at the function's extremum near the model's, found on the dense
//! output by golden-section search. The crossing is bracketed between the start and the first
//! sample past it.

use crate::functions::{Condition, Values, MAX_FUNCTIONS};
use crate::root::class;
use bwc_ode::State;

/// Relative size of the forward-difference step, as a fraction of the step size.
const DIFFERENCE: f64 = 1e-8;

/// Samples of the dense output (per unit step) that confirm a suspected interior crossing.
pub(crate) const SAMPLES: usize = 8;

/// A model extremum within this fraction of the larger end value of the boundary is suspected
/// too: the cubic's error (about `h^4 g'''' / 384`) can be larger than a shallow excursion.
const NEAR: f64 = 0.1;

/// Golden-section steps that locate a suspected extremum on the dense output, from a bracket
/// of `2 / SAMPLES` of the step: to 4e-4 of the step.
const GOLDEN_STEPS: usize = 14;

/// The `θ` of the extremum of `g` (a minimum where `sign > 0`, a maximum where `sign < 0`)
/// within `1 / SAMPLES` of `theta`, by golden-section search on `g(θ)`.
pub(crate) fn extremum(theta: f64, sign: f64, mut g: impl FnMut(f64) -> f64) -> f64 {
    const INV_PHI: f64 = 0.618_033_988_749_894_8;
    let half = 1.0 / SAMPLES as f64;
    let (mut a, mut b) = ((theta - half).max(0.0), (theta + half).min(1.0));
    let mut x1 = b - INV_PHI * (b - a);
    let mut x2 = a + INV_PHI * (b - a);
    let (mut f1, mut f2) = (sign * g(x1), sign * g(x2));
    for _ in 0..GOLDEN_STEPS {
        if f1 < f2 {
            b = x2;
            (x2, f2) = (x1, f1);
            x1 = b - INV_PHI * (b - a);
            f1 = sign * g(x1);
        } else {
            a = x1;
            (x1, f1) = (x2, f2);
            x2 = a + INV_PHI * (b - a);
            f2 = sign * g(x2);
        }
    }
    if f1 < f2 {
        x1
    } else {
        x2
    }
}

/// Rates `dg/dt` of the first `n` boundary functions along the solution through `(t, y)` with
/// derivative `f`, by a forward difference over `DIFFERENCE * h`; `g` are their values there.
pub(crate) fn rates<C: Condition<N>, const N: usize>(
    condition: &C,
    n: usize,
    (t, y, f): (f64, &State<N>, &State<N>),
    g: &Values,
    h: f64,
) -> Values {
    let eps = DIFFERENCE * h;
    let ahead = condition.values(t + eps, &(y + f * eps));
    let mut r = [0.0; MAX_FUNCTIONS];
    for i in 0..n {
        r[i] = (ahead[i] - g[i]) / eps;
    }
    r
}

/// The cubic `p(θ)` on `[0, 1]` with `p(0) = g0`, `p'(0) = d0`, `p(1) = g1`, `p'(1) = d1` (rates
/// times the step size): the `θ` in `(0, 1)` of an extremum whose sign class differs from the
/// class `g0` and `g1` share, or that comes within [`NEAR`] of the boundary, if any.
pub(crate) fn suspect(g0: f64, d0: f64, g1: f64, d1: f64) -> Option<f64> {
    let c0 = class(g0);
    if c0 == 0 || class(g1) != c0 || !(d0.is_finite() && d1.is_finite()) {
        return None;
    }
    let delta = g1 - g0;
    let b = 3.0 * delta - 2.0 * d0 - d1;
    let c = -2.0 * delta + d0 + d1;
    let p = |s: f64| g0 + s * (d0 + s * (b + s * c));
    // p'(θ) = d0 + 2 b θ + 3 c θ².
    let (qa, qb, qc) = (3.0 * c, 2.0 * b, d0);
    let mut roots = [f64::NAN; 2];
    if qa == 0.0 {
        if qb != 0.0 {
            roots[0] = -qc / qb;
        }
    } else {
        let disc = qb * qb - 4.0 * qa * qc;
        if disc >= 0.0 {
            let q = -0.5 * (qb + qb.signum() * disc.sqrt());
            roots[0] = q / qa;
            if q != 0.0 {
                roots[1] = qc / q;
            }
        }
    }
    let near = NEAR * g0.abs().max(g1.abs());
    roots
        .into_iter()
        .filter(|s| *s > 0.0 && *s < 1.0 && (class(p(*s)) != c0 || p(*s).abs() <= near))
        .min_by(f64::total_cmp)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_dip_through_zero_between_positive_ends_is_suspected() {
        // g = (θ - 0.3)(θ - 0.6) + 0.01 dips to -0.0125 at θ = 0.45 and is positive at the ends.
        let g = |s: f64| (s - 0.3) * (s - 0.6) + 0.01;
        let dg = |s: f64| 2.0 * s - 0.9;
        let s = suspect(g(0.0), dg(0.0), g(1.0), dg(1.0)).expect("suspected");
        assert!((s - 0.45).abs() < 1e-12, "{s}");
        // Lifted above zero, well clear of it: nothing to suspect.
        let lifted = |s: f64| g(s) + 0.05;
        assert_eq!(suspect(lifted(0.0), dg(0.0), lifted(1.0), dg(1.0)), None);
        // Lifted just above zero (0.0075 at the bottom, 4 % of the ends' 0.19): suspected, as
        // the model's own error could hide a dip below.
        let shallow = |s: f64| g(s) + 0.02;
        let s = suspect(shallow(0.0), dg(0.0), shallow(1.0), dg(1.0)).expect("near");
        assert!((s - 0.45).abs() < 1e-12, "{s}");
        // Ends in different classes are an ordinary crossing, not an interior one.
        assert_eq!(suspect(1.0, -3.0, -1.0, -1.0), None);
        // A function leaving zero is not a crossing.
        assert_eq!(suspect(0.0, -1.0, 0.0, 1.0), None);
    }

    #[test]
    fn the_extremum_near_a_guess_is_found() {
        // A narrow dip at 0.4637 (width 0.005), guessed at 0.45.
        let g = |s: f64| 1.0 - (-((s - 0.4637) / 0.005).powi(2)).exp();
        let s = extremum(0.45, 1.0, g);
        assert!((s - 0.4637).abs() < 5e-4, "{s}");
        // A maximum, at the edge of the step.
        let s = extremum(0.95, -1.0, |s: f64| s * s);
        assert!(s > 0.999, "{s}");
    }
}
