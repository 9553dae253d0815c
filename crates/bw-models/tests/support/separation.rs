//! Separations that are easy to miss, found by the stress sweep (STABILITY.md): both paths (the
//! Runge-Kutta path with its event location, and the Taylor-series path) must find the first
//! instant with `F <= 0 <= V`.

use super::nd;
use bw_models::input::{self, Constant};
use bw_models::*;

fn both() -> [Settings; 2] {
    let rk = Settings {
        t_max: 100.0,
        series: false,
        e_tol: None,
        ..Settings::default()
    };
    [rk, Settings { series: true, ..rk }]
}

/// Elastic contact under a strong constant pull: the bodies part where `X` returns to 0 with
/// the impact speed (the spring gives back its energy and the pull has done no net work, so
/// `e = 1` exactly), but the pull brings them back together within a fraction of a step. The
/// force is positive at both ends of that step, so a locator that only compares the ends misses
/// the separation inside it (and bounces on until the horizon, `e = 0`).
#[test]
fn elastic_contact_under_a_strong_pull_separates_with_e_1() {
    for (p, u) in [(6.0, -150.0), (10.0, -40.0), (10.0, -80.0), (10.0, -150.0)] {
        let model = Ndbwshccm::new(
            &nd(ModelKind::Shccm, 0.0, 0.0, 0.5, 0.0, 1.0, p),
            Constant(u),
        )
        .unwrap();
        let mut t_s = Vec::new();
        for s in both() {
            let out = impact(&model, &s).unwrap();
            let t = out.t_s.expect("separates");
            assert!(
                (out.e - 1.0).abs() < 1e-8,
                "p {p} U {u} series {}: e = {}",
                s.series,
                out.e
            );
            // X = 0 there (the first return: T_s is under one time unit).
            assert!(out.state[0].abs() < 1e-9 && t < 1.0, "p {p} U {u}: {out:?}");
            t_s.push(t);
        }
        assert!(
            (t_s[0] - t_s[1]).abs() < 1e-9 * t_s[0],
            "p {p} U {u}: {t_s:?}"
        );
    }
}

/// Stress case 23226 (seed 1): nearly elastic, `p = 10`, pulled back by `U = -4.46`; the bodies
/// part at `X = 0` with `V = 0.245` and meet again 0.11 later, inside one step.
#[test]
fn a_separation_inside_a_step_is_found() {
    let model = Ndbwshccm::new(
        &nd(
            ModelKind::Shccm,
            0.0,
            0.0,
            0.9999988482675066,
            0.015026785099308337,
            1.0,
            10.0,
        ),
        Constant(-4.457591246739221),
    )
    .unwrap();
    let [rk, series] = both().map(|s| impact(&model, &s).unwrap());
    for out in [&rk, &series] {
        assert!(out.t_s.expect("separates") < 1.5, "{out:?}");
        assert!(out.state[0].abs() < 1e-9 && out.e > 0.2, "{out:?}");
    }
    assert!((rk.e - series.e).abs() < 1e-9, "{} vs {}", rk.e, series.e);
}

/// Stress case 83189 (seed 1): MCM with a nearly rigid dashpot at 0.5 mm/s; `Y` and `Z` reach
/// 0 together, and the force changes sign a rounding error after the switching point `Z = 0`
/// where the step stopped: a locator that starts the next step inside the set never sees the
/// force cross, and loses the separation.
#[test]
fn a_separation_at_a_switching_point_is_found() {
    let model = Ndbwmcm::new(
        &nd(
            ModelKind::Mcm,
            7.51913987871537e-15,
            3.652694995812471e-15,
            0.9999817914014651,
            4.8946162967984925,
            5.833216825171758,
            2.4031684894516014,
        ),
        Constant(0.0),
    )
    .unwrap();
    let [rk, series] = both().map(|s| impact(&model, &s).unwrap());
    for out in [&rk, &series] {
        let t = out.t_s.expect("separates");
        assert!((t - 34.1424516).abs() < 1e-6, "{out:?}");
        assert!(out.state[1].abs() < 1e-12 && out.e > 4e-3, "{out:?}");
    }
    assert!((rk.e - series.e).abs() < 1e-10, "{} vs {}", rk.e, series.e);
}

/// Stress case 78848 (seed 1): `p = 10` under a push `U = 7.8`. The force
/// `|X|^10 (κ + (1-κ)|Z/X|^10 - σV)` (X, Z < 0) reaches 0 where its bracket does, at `X = -0.014`,
/// while `|X|^10` is 1e-19: a Newton search on the force crawls towards `X = 0`, where the force
/// is tiny for another reason, and would report the separation there (e = 1.0 instead of 0.88).
#[test]
fn a_separation_where_the_force_is_tiny_is_found_at_its_root() {
    let (kappa, sigma, p) = (0.4987207909673853, 1.1310166164322775, 10.0);
    let model = Ndbwshccm::new(
        &nd(
            ModelKind::Shccm,
            41.87241984363382,
            -41.87241984363382,
            kappa,
            sigma,
            6.722502259974871,
            p,
        ),
        Constant(7.797042325326018),
    )
    .unwrap();
    let [rk, series] = both().map(|s| impact(&model, &s).unwrap());
    for out in [&rk, &series] {
        let (x, z, v) = (out.state[0], out.state[1], out.state[2]);
        // The bracket vanishes: σ V = κ + (1-κ) |Z/X|^p.
        let bracket = kappa + (1.0 - kappa) * (z / x).abs().powf(p) - sigma * v;
        assert!(bracket.abs() < 1e-9 && x < -0.01, "{out:?}: {bracket}");
    }
    assert!((rk.e - series.e).abs() < 1e-9, "{} vs {}", rk.e, series.e);
    assert!((rk.t_s.unwrap() - series.t_s.unwrap()).abs() < 1e-9);
}

/// Stress case 15440 (seed 1): an NDBWMCM whose Bouc-Wen element rests saturated while a
/// sinusoidal pull `U` drives the contact. At the separation the force is a difference of two
/// terms of 1.7e-9 and falls at 2.8e-7 per unit time, and `V` rises at `U = 7.8`. A step of
/// 0.024 over the saturated element (`h λ` about 12) has an interpolant whose root of the force
/// is 2.3e-10 late at rtol 1e-13, and 1e-9 early at 1e-8: `e` was off by 1.8e-9 and 1.0e-8.
/// Where the retaken state shows the interpolant off by more than the tolerance, the root is
/// located again on the shorter step (or, where the retaken state has not separated yet, on
/// the next step): within 1e-11 at these tolerances, against a reference whose steps are short
/// enough (at most 1e-3) for their interpolants to be exact. (At rtol 1e-9 the interpolant is
/// within the tolerance and `e` is off by 3.7e-11, as before.)
#[test]
fn a_flat_separation_under_a_pull_is_located_on_the_retaken_step() {
    let base = BaseParams {
        b_b: 120.17124534690431,
        gamma_b: 22.667507618296153,
        kappa: 0.0002309241467076506,
        sigma_b: 92.23223271975556,
        n: 1.0,
        p: 3.4988449741323335,
        u_b: 1.0,
        t_b: 1.0,
    };
    let (v0, b, w) = (6.0159557611712415, 7.836683768652238, 7.944967873505246);
    let map = BaseMap::new(ModelKind::Mcm, base).unwrap();
    let factor = map.at(v0).unwrap().1.factor;
    let pull = input::FromFn(move |t: f64| b * (w * t).sin() / factor);
    let at = |rtol: f64, max_step: f64| {
        let s = Settings {
            rtol,
            atol: rtol / 100.0,
            max_step,
            t_max: 100.0,
            e_tol: None,
            ..Settings::default()
        };
        impact_at(&map, pull, v0, &s).unwrap()
    };
    let reference = at(1e-14, 1e-3);
    for rtol in [1e-8, 1e-10, 1e-11, 1e-13] {
        let run = at(rtol, f64::INFINITY);
        let (de, dt) = (
            (run.e - reference.e).abs(),
            (run.t_s.unwrap() - reference.t_s.unwrap()).abs(),
        );
        assert!(
            de < 1e-11 && dt < 1e-11,
            "rtol {rtol:e}: e off by {de:e}, T_s by {dt:e}"
        );
    }
}

/// Elastic Hertz-type contact (`B = Γ = σ = 0`, so `Z = X` and `F = -|X|^p sgn X`) on the
/// Runge-Kutta path, against its closed forms: energy is conserved, so `e = 1`, and
/// `V²/2 + |X|^(p+1)/(p+1) = 1/2` gives `T_s = 2 X_m B(1/(p+1), 1/2) / (p+1)` with
/// `X_m = ((p+1)/2)^(1/(p+1))` (SciPy: 3.2149455346421716 for `p = 1.91`, 3.1698318538197094
/// for `p = 2.5`). The bodies part where `X` returns to 0, where `|X|^p` is not analytic. Steps
/// that end close to it pass DOP853's error estimate with errors in `e` of 2 to 9 times rtol
/// unless they are kept to half the time left to it (`CollisionModel::clearance`).
#[test]
fn steps_that_end_near_the_root_of_x_keep_their_error_within_the_tolerance() {
    for (p, t_s) in [(1.91, 3.2149455346421716), (2.5, 3.1698318538197094)] {
        let model = Ndbwshccm::new(
            &nd(ModelKind::Shccm, 0.0, 0.0, 0.7, 0.0, 1.0, p),
            input::Zero,
        )
        .unwrap();
        for rtol in [1e-10, 1e-11] {
            let s = Settings {
                rtol,
                atol: rtol / 100.0,
                series: false,
                e_tol: None,
                ..Settings::default()
            };
            let out = impact(&model, &s).unwrap();
            assert!(
                (out.e - 1.0).abs() <= 0.5 * rtol,
                "p {p} rtol {rtol:e}: e - 1 = {:e}",
                out.e - 1.0
            );
            let t = out.t_s.unwrap();
            assert!(
                (t - t_s).abs() <= rtol * t_s,
                "p {p} rtol {rtol:e}: {t} vs {t_s}"
            );
        }
    }
}
