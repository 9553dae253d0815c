//! The first step from contact where the loading is a Hunt-Crossley contact: the NDBWSHCCM with
//! `Γ = -B` (every fit of the paper) and no input.
//!
//! In loading (`X, Z, V < 0`) with `Γ = -B` the hysteresis bracket vanishes, `Z' = X'`, so
//! `Z = X` from contact and `V' = |X|^p (1 - σ V)`. The solution is not analytic in `T` at
//! contact (`X = -T + O(T^(p+2))`), which costs the series of the main loop a geometric ramp
//! of steps; but it is analytic in `s = T^(p+1)`:
//!
//! `X = -T G(s)`, `V = -(G + (p+1) s G'(s))`, with `(p+1) D V = s G^p (1 - σ V)`, `D = s d/ds`,
//!
//! so that, with `G_0 = 1`, `V_0 = -1` and `k >= 1`,
//!
//! `V_k = [G^p (1 - σ V)]_(k-1) / ((p+1) k)`, `G_k = -V_k / (1 + (p+1) k)`,
//!
//! `G^p` by the recurrence of the powers (`G_0 = 1`). One step of this series in `s` covers
//! most of the compression (on Table 3's DSS (1), `T` from 0 to 1.3 at rtol 1e-11, where the
//! series in `T` take a start step and nine more); the step is Jorba & Zou's, as in the main
//! loop, in the variable `s`. Where the velocity reaches zero inside the step (the maximum
//! compression), the step ends on that root.

use super::polynomial::{eval_d, jorba_zou, root, Series, ORDER};
use super::recurrence::{Base, Power};
use super::steps::TOLERANCE_SCALE;
use crate::power::Pow;
use crate::settings::Settings;

/// Where the contact step ends: time `T`, `X = Z` and `V` there (`V = 0` exactly at the
/// maximum compression).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ContactStep {
    pub(crate) t: f64,
    pub(crate) x: f64,
    pub(crate) v: f64,
}

/// Samples of the velocity along the step, for the first sign change.
const SAMPLES: usize = 8;

/// The Taylor coefficients of `G` and `V` in `s` for exponent `p` and damping `σ`.
fn coefficients(p: Pow, sigma: f64) -> (Series, Series) {
    let q = p.exponent() + 1.0;
    let (mut g, mut gp) = (Base::ZERO, Power::ZERO);
    let mut v: Series = [0.0; ORDER + 1];
    // 1 - σ V, coefficient by coefficient.
    let mut w: Series = [0.0; ORDER + 1];
    g.set(0, 1.0);
    gp.set(0, 1.0);
    v[0] = -1.0;
    w[0] = 1.0 + sigma;
    for k in 1..=ORDER {
        let kf = k as f64;
        v[k] = gp.times(&w, k - 1) / (q * kf);
        w[k] = -sigma * v[k];
        g.set(k, -v[k] / (1.0 + q * kf));
        let gpk = gp.term(&g, p.exponent(), k);
        gp.set(k, gpk);
    }
    (g.c, v)
}

/// The step from contact (`T = 0`, `X = Z = 0`, `V = -1`) of the Hunt-Crossley loading with
/// exponent `p` and damping `σ` under the settings' tolerances, at most to the settings'
/// `max_step` and `t_max`; `None` where the coefficients over- or underflow (extreme `σ`, `p`),
/// where the explicit method's start step takes over.
///
/// `short`: the step never ends on the maximum compression (it ends at the last sample before
/// it instead), for a model whose branch changes a little before `V = 0` (the NDBWMCM, where
/// the rate `Y' = V + σ F` changes sign first).
pub(crate) fn hunt_crossley_step(
    p: Pow,
    sigma: f64,
    settings: &Settings,
    short: bool,
) -> Option<ContactStep> {
    let q = p.exponent() + 1.0;
    let (g, v) = coefficients(p, sigma);
    // |y|_inf is 1 at contact (V = -1) and stays about 1 in the compression.
    let tol = TOLERANCE_SCALE * (settings.atol + settings.rtol);
    let limit = settings.max_step.min(settings.t_max).powf(q);
    let mut s = jorba_zou(tol, ORDER, |k| g[k].abs().max(v[k].abs())).min(limit);
    if !(s > 0.0 && s.is_finite()) || g.iter().chain(&v).any(|c| !c.is_finite()) {
        return None;
    }
    // The first sign change of V on eight samples of the step (V increases in loading; a
    // polynomial that stops increasing has left the compression: the step ends before that).
    let mut vs = -1.0;
    let mut s_prev = 0.0;
    for i in 1..=SAMPLES {
        let si = s * i as f64 / SAMPLES as f64;
        let vi = eval_d(&v, si).0;
        if vi >= 0.0 {
            // The maximum compression: end on it (or, `short`, at the sample before it).
            if short {
                s = s_prev;
            } else {
                let d = root(|d| eval_d(&v, s_prev + d), si - s_prev, -1);
                (s, vs) = (s_prev + d, 0.0);
            }
            break;
        }
        if vi <= vs {
            // vs is V at s_prev already.
            s = s_prev;
            break;
        }
        (s_prev, vs) = (si, vi);
    }
    if s == 0.0 {
        return None;
    }
    let t = s.powf(1.0 / q);
    let x = -t * eval_d(&g, s).0;
    (t > 0.0 && x < 0.0 && x.is_finite()).then_some(ContactStep { t, x, v: vs })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn settings(rtol: f64) -> Settings {
        Settings {
            rtol,
            atol: rtol / 100.0,
            e_tol: None,
            ..Settings::default()
        }
    }

    #[test]
    fn linear_elastic_loading_is_a_sine() {
        // p = 1, σ = 0: X'' = -X from X = 0, V = -1: X = -sin T, V = -cos T; the step ends
        // on the maximum compression T = π/2 if it gets there.
        for rtol in [1e-6, 1e-9, 1e-12] {
            let c = hunt_crossley_step(Pow::new(1.0), 0.0, &settings(rtol), false).unwrap();
            assert!(c.t > 0.5, "rtol {rtol}: step {}", c.t);
            assert!((c.x + c.t.sin()).abs() <= 10.0 * rtol, "rtol {rtol}: {c:?}");
            if c.v == 0.0 {
                assert!(
                    (c.t - std::f64::consts::FRAC_PI_2).abs() <= 10.0 * rtol,
                    "{c:?}"
                );
            } else {
                assert!((c.v + c.t.cos()).abs() <= 10.0 * rtol, "rtol {rtol}: {c:?}");
            }
        }
    }

    #[test]
    fn the_step_keeps_the_hunt_crossley_first_integral() {
        // dV/dw = -(1 - σV)/V with w = |X|^(p+1)/(p+1): w = (V+1)/σ + ln((1-σV)/(1+σ))/σ²
        // (σ > 0), w = (1 - V²)/2 (σ = 0).
        for (p, sigma) in [(2.62, 0.0696), (1.5, 0.5), (2.0, 0.0), (6.0, 0.2)] {
            for rtol in [1e-8, 1e-11] {
                let c = hunt_crossley_step(Pow::new(p), sigma, &settings(rtol), false).unwrap();
                let w = c.x.abs().powf(p + 1.0) / (p + 1.0);
                let want = if sigma == 0.0 {
                    0.5 * (1.0 - c.v * c.v)
                } else {
                    (c.v + 1.0) / sigma + ((1.0 - sigma * c.v) / (1.0 + sigma)).ln() / sigma.powi(2)
                };
                assert!(
                    (w - want).abs() <= 10.0 * rtol * want,
                    "p {p} σ {sigma} rtol {rtol}: {c:?}, w {w} want {want}"
                );
                // Most of the compression in one step (the series in T reach 7e-3 here).
                assert!(c.t > 0.5, "p {p} σ {sigma} rtol {rtol}: {c:?}");
            }
        }
    }
}
