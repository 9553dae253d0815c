//! Global error control of CoR evaluations (`Settings::e_tol`) against closed forms: the
//! Hunt-Crossley limit (B = Γ = 0) of the NDBWSHCCM, whose `e` solves
//! `σ - ln(1 + σ) = -σ e - ln(1 - σ e)` (independent of `κ`, `n`, `p`).

use bw_models::input::Zero;
use bw_models::{impact, ModelError, ModelKind, Ndbwshccm, Settings};

use super::nd;

/// `(σ, e)` pairs of the Hunt-Crossley closed form (mpmath, 18 digits).
const HUNT_CROSSLEY: [(f64, f64); 2] = [(0.2, 0.882189986247306374), (0.9, 0.619736466081975129)];

fn hunt_crossley(sigma: f64) -> Ndbwshccm<Zero> {
    Ndbwshccm::new(&nd(ModelKind::Shccm, 0.0, 0.0, 0.5, sigma, 1.5, 1.5), Zero).unwrap()
}

/// DOP853 alone (the series would be far more accurate than these tolerances ask).
fn runge_kutta(rtol: f64, e_tol: Option<f64>) -> Settings {
    Settings {
        rtol,
        atol: rtol / 100.0,
        series: false,
        e_tol,
        ..Settings::default()
    }
}

#[test]
fn a_loose_rtol_is_tightened_until_the_check_meets_e_tol() {
    for (sigma, e_exact) in HUNT_CROSSLEY {
        let model = hunt_crossley(sigma);
        let single = impact(&model, &runge_kutta(1e-5, None)).unwrap();
        assert_eq!((single.rtol, single.e_error), (1e-5, None));
        // What the check is for: one run at this rtol is far off the target.
        assert!((single.e - e_exact).abs() > 1e-9, "σ {sigma}: {}", single.e);
        let checked = impact(&model, &runge_kutta(1e-5, Some(1e-10))).unwrap();
        let estimate = checked.e_error.expect("a checked run has an estimate");
        assert!(estimate <= 1e-11, "σ {sigma}: estimate {estimate:e}");
        assert!(
            checked.rtol < 1e-5,
            "σ {sigma}: stayed at rtol {}",
            checked.rtol
        );
        assert!(
            (checked.e - e_exact).abs() <= 1e-10,
            "σ {sigma}: e {} vs {e_exact}, rtol {}",
            checked.e,
            checked.rtol
        );
        // The work of every run is counted.
        assert!(checked.stats.rhs_evals > 2 * single.stats.rhs_evals);
        assert!(checked.t_s_error.is_some());
    }
}

#[test]
fn the_estimate_bounds_the_reported_error() {
    // The estimate is the difference from the run at 100 times the tolerance, whose error is
    // about a hundred times the reported run's: it bounds the reported error.
    for (sigma, e_exact) in HUNT_CROSSLEY {
        for rtol in [1e-4, 1e-6, 1e-8] {
            let checked = impact(&hunt_crossley(sigma), &runge_kutta(rtol, Some(1.0))).unwrap();
            assert_eq!(checked.rtol, rtol, "σ {sigma}: accepted at once");
            let (error, estimate) = ((checked.e - e_exact).abs(), checked.e_error.unwrap());
            assert!(
                error <= estimate && estimate <= 1e4 * rtol,
                "σ {sigma} rtol {rtol:e}: error {error:e}, estimate {estimate:e}"
            );
        }
    }
}

#[test]
fn the_defaults_check_every_cor_to_1e_10() {
    for (sigma, e_exact) in HUNT_CROSSLEY {
        for series in [true, false] {
            let s = Settings {
                series,
                ..Settings::default()
            };
            let out = impact(&hunt_crossley(sigma), &s).unwrap();
            let estimate = out.e_error.expect("the defaults check");
            assert!(estimate <= 1e-11, "σ {sigma} series {series}: {estimate:e}");
            assert!((out.e - e_exact).abs() <= 1e-11, "σ {sigma}: e {}", out.e);
        }
    }
}

#[test]
fn a_bad_e_tol_is_named() {
    for bad in [0.0, -1e-10, f64::NAN, f64::INFINITY] {
        let s = Settings {
            e_tol: Some(bad),
            ..Settings::default()
        };
        match impact(&hunt_crossley(0.2), &s) {
            Err(ModelError::InvalidSetting { name, .. }) => assert_eq!(name, "e_tol"),
            other => panic!("e_tol {bad}: {other:?}"),
        }
    }
}
