//! Work-precision of one CoR evaluation (NDBWSHCCM and NDBWMCM at Table 3's DSS (1), several
//! impact speeds): error in e and T_s against a reference at rtol 1e-14, RHS evaluations and
//! time, for each method, stepping over the non-smooth points or stopping at them.
//!
//! `cargo run --release -p bwc-benches --bin work-precision-cor`

use bw_models::{ModelKind, Settings};
use bwc_benches::{cor, median_seconds};
use bwc_ode::{tableau, DOP853, VERN7};

fn main() {
    let speeds = [0.5, 2.0, 5.0];
    println!("# error = max over v0 in {speeds:?} m/s of |e - e_ref| and |T_s - T_ref|; evals and time summed over the speeds");
    println!(
        "{:<6} {:<7} {:<6} {:>7} {:>11} {:>11} {:>8} {:>10}",
        "model", "method", "kinks", "rtol", "err_e", "err_Ts", "evals", "time_us"
    );
    for kind in [ModelKind::Shccm, ModelKind::Mcm] {
        let map = cor::dss1(kind);
        // Reference: two independent tight runs must agree.
        let refs: Vec<(f64, f64)> = speeds
            .iter()
            .map(|&v0| {
                let a = cor::evaluate(
                    &map,
                    v0,
                    &Settings {
                        method: &VERN7,
                        rtol: 1e-14,
                        atol: 1e-16,
                        ..Settings::default()
                    },
                )
                .unwrap();
                let b = cor::evaluate(
                    &map,
                    v0,
                    &Settings {
                        method: &DOP853,
                        rtol: 1e-14,
                        atol: 1e-16,
                        stop_at_kinks: false,
                        ..Settings::default()
                    },
                )
                .unwrap();
                assert!(
                    (a.e - b.e).abs() < 1e-11,
                    "references disagree: {} vs {}",
                    a.e,
                    b.e
                );
                (a.e, a.t_s.unwrap())
            })
            .collect();
        for tab in tableau::all() {
            for kinks in [false, true] {
                for k in 4..=13 {
                    let rtol = 10f64.powi(-k);
                    let s = Settings {
                        method: tab,
                        rtol,
                        atol: rtol * 1e-2,
                        stop_at_kinks: kinks,
                        ..Settings::default()
                    };
                    let (mut err_e, mut err_t, mut evals) = (0.0f64, 0.0f64, 0);
                    for (&v0, &(e_ref, t_ref)) in speeds.iter().zip(&refs) {
                        let out = cor::evaluate(&map, v0, &s).unwrap();
                        err_e = err_e.max((out.e - e_ref).abs());
                        err_t = err_t.max((out.t_s.unwrap() - t_ref).abs());
                        evals += out.stats.rhs_evals;
                    }
                    let secs = median_seconds(|| {
                        for &v0 in &speeds {
                            std::hint::black_box(cor::evaluate(&map, v0, &s).unwrap());
                        }
                    });
                    println!(
                        "{:<6} {:<7} {:<6} {:>7.0e} {:>11.2e} {:>11.2e} {:>8} {:>10.1}",
                        kind.name(),
                        tab.name,
                        kinks,
                        rtol,
                        err_e,
                        err_t,
                        evals,
                        secs * 1e6
                    );
                }
            }
        }
    }
}
