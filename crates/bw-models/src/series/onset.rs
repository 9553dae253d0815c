//! The state just after contact from the leading terms of the loading, where the contact
//! series does not apply (`B + Γ != 0`, or an input): in place of the explicit method's start
//! step, whose trials are sized by the exponent of the vanishing powers.
//!
//! At contact `X = Z = 0`, `V = -1`, and in loading every base and the rate are negative. With
//! `|X|^p = T^p (1 + O(T))` and `|Z|^p`, `|Z|^n` alike, the force is `F = (1 + σ) T^p` to
//! leading order for the NDBWSHCCM (`-σ |X|^p V = σ T^p`) and `F = T^p` for the NDBWMCM, and
//! the hysteresis adds `c |Z|^n = c T^n` (`c = B + Γ`) to the rate of `Z - X` (`Z - Y`):
//!
//! - NDBWSHCCM: `V = -1 + u T + a T^(p+1)`, `a = (1 + σ) / (p+1)`,
//!   `X = -T + u T² / 2 + a T^(p+2) / (p+2)`, `Z = X + c T^(n+1) / (n+1)`;
//! - NDBWMCM: `V = -1 + u T + T^(p+1) / (p+1)`, `R = -σ T^(p+1) / (p+1)`,
//!   `Y = -T + u T² / 2 + σ T^(p+1) / (p+1) + T^(p+2) / ((p+1)(p+2))`,
//!   `Z = Y + c T^(n+1) / (n+1)`.
//!
//! The terms left out are of the orders `T^(p+2)` (the input's and `Z`'s corrections of the
//! powers in `V`), `T^(2p+1)`, `T^(p+n+1)`, `T^(n+2)` and `T^(2n+1)`, with coefficients at most
//! [`bound`] (checked against the Runge-Kutta path in the tests). The state is taken at the time
//! `Δ` where that bound is the start tolerance.

use crate::models::NdCoefficients;

/// The largest `Δ`: the terms kept describe the solution only near contact.
const MAX_SPAN: f64 = 1e-2;

/// A bound on the coefficients of the terms left out, from the sizes of the input, the
/// hysteresis, the damping and the exponents.
fn bound(k: &NdCoefficients, u: f64) -> f64 {
    let c = (k.b + k.gamma).abs();
    let e = k.p.exponent().max(k.n.exponent());
    (1.0 + u.abs()) * (1.0 + c).powi(2) * (1.0 + k.sigma).powi(2) * e * e
}

/// The time after contact where the terms left out reach `tol`: `bound Δ^q = tol` with `q` the
/// lowest order left out.
fn span(k: &NdCoefficients, u: f64, tol: f64) -> Option<f64> {
    let (p, n) = (k.p.exponent(), k.n.exponent());
    let q = (p + 2.0)
        .min(2.0 * p + 1.0)
        .min(p + n + 1.0)
        .min(n + 2.0)
        .min(2.0 * n + 1.0);
    let span = (tol / bound(k, u)).powf(1.0 / q).min(MAX_SPAN);
    (span > 0.0 && span.is_finite()).then_some(span)
}

/// The NDBWSHCCM's `(T, [X, Z, V])` just after contact, for the input `u` and tolerance `tol`.
pub(super) fn shccm(k: &NdCoefficients, u: f64, tol: f64) -> Option<(f64, [f64; 3])> {
    let t = span(k, u, tol)?;
    let (p, n) = (k.p.exponent(), k.n.exponent());
    let c = k.b + k.gamma;
    let tp1 = t * k.p.of_abs(t);
    let a = (1.0 + k.sigma) / (p + 1.0);
    let v = -1.0 + u * t + a * tp1;
    let x = -t + 0.5 * u * t * t + a * tp1 * t / (p + 2.0);
    let z = x + c * t * k.n.of_abs(t) / (n + 1.0);
    Some((t, [x, z, v]))
}

/// The NDBWMCM's `(T, [R, Y, Z, V])` just after contact, for the input `u` and tolerance `tol`.
pub(super) fn mcm(k: &NdCoefficients, u: f64, tol: f64) -> Option<(f64, [f64; 4])> {
    let t = span(k, u, tol)?;
    let (p, n) = (k.p.exponent(), k.n.exponent());
    let c = k.b + k.gamma;
    let tp1 = t * k.p.of_abs(t) / (p + 1.0);
    let v = -1.0 + u * t + tp1;
    let r = -k.sigma * tp1;
    let y = -t + 0.5 * u * t * t + k.sigma * tp1 + tp1 * t / (p + 2.0);
    let z = y + c * t * k.n.of_abs(t) / (n + 1.0);
    Some((t, [r, y, z, v]))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::input::Constant;
    use crate::{CollisionModel, ModelKind, Ndbwmcm, Ndbwshccm, Nondim, NondimParams, State};
    use bwc_ode::{Integrator, Options};

    /// The state at `t` by DOP853 at rtol 1e-14 from contact.
    fn reference<M: CollisionModel<N>, const N: usize>(model: &M, t: f64) -> State<N> {
        let options = Options::new(1e-14, 1e-18);
        let rhs = |t: f64, y: &State<N>| model.rhs(t, y);
        let tableau = &bwc_ode::DOP853;
        let mut it = Integrator::new(rhs, tableau, 0.0, model.initial_state(), options).unwrap();
        it.integrate_to(t).unwrap();
        *it.y()
    }

    /// Over exponents from 1 to 6, hysteresis brackets `c = B + Γ` from 1e-3 to 80, damping
    /// and inputs, both models: the leading terms are within the tolerance they were sized for
    /// of the Runge-Kutta path at rtol 1e-14, at tolerances from 1e-6 to 1e-12.
    #[test]
    fn the_leading_terms_meet_the_runge_kutta_path_within_the_tolerance() {
        for (p, n) in [(1.0, 1.0), (1.2, 4.0), (2.6, 2.9), (4.0, 1.1), (6.0, 6.0)] {
            for (b, gamma) in [(2.0, -1.5), (5.0, 4.7), (5.0, -5.0 + 1e-3), (40.0, 40.0)] {
                for (sigma, u) in [(0.01, 0.0), (0.5, -0.8), (2.0, 0.6)] {
                    let params = |kind| {
                        let nd = Nondim {
                            b,
                            gamma,
                            kappa: 0.4,
                            sigma,
                            n,
                            p,
                        };
                        NondimParams::new(kind, nd).unwrap()
                    };
                    for tol in [1e-6, 1e-9, 1e-12] {
                        let s = Ndbwshccm::new(&params(ModelKind::Shccm), Constant(u)).unwrap();
                        let (t, y) = shccm(&s.k, u, tol).unwrap();
                        let gap = (State::<3>::from(y) - reference(&s, t)).amax();
                        let m = Ndbwmcm::new(&params(ModelKind::Mcm), Constant(u)).unwrap();
                        let (t4, y4) = mcm(&m.k, u, tol).unwrap();
                        let gap4 = (State::<4>::from(y4) - reference(&m, t4)).amax();
                        assert!(
                            gap <= tol && gap4 <= tol,
                            "p {p} n {n} B {b} Γ {gamma} σ {sigma} u {u} tol {tol}: \
                             {gap:e} at {t:e}, {gap4:e} at {t4:e}"
                        );
                    }
                }
            }
        }
    }
}
