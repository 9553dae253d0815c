//! One stress case at a time (STABILITY.md): `e` and the integrator's work of single cases of
//! the stress sweep, with the defaults (at the sweep's step limit and at the library's) and with
//! each Runge-Kutta method at each of a list of tolerances (one run, `e_tol` off, atol = rtol /
//! 100, at most 50 million steps). For reading a case that `stress-accuracy` lists: whether its
//! references have converged, and what its runs spend their steps on.
//!
//! `cargo run --release -p bwc-benches --bin stress-case -- SEED RTOL[,RTOL...] CASE [CASE...]`

use bw_models::input::Constant;
use bw_models::{impact_at, BaseMap, Settings};
use bwc_benches::stress::{cases_args, input, library_settings, run_with, sample, settings, Case};
use bwc_ode::{Tableau, DOP853, VERN7, VERN9};

/// A reference may take this many steps: the hardest cases take a few hundred thousand at rtol
/// 1e-13 and tens of millions of evaluations at 5e-16.
const MAX_STEPS: u64 = 50_000_000;

fn main() {
    let (seed, rtols, cases) = cases_args("stress-case");
    for i in cases {
        let case = sample(seed, i);
        bwc_app::out!(
            "# case {i} of seed {seed}: {:?}, v0 {}, input {:?}, {:?}",
            case.kind,
            case.v0,
            case.input,
            case.base
        );
        // The sweep caps a run at 200,000 steps; the library's default allows more.
        let library = library_settings();
        for (name, s) in [
            ("the sweep's settings", settings()),
            ("the defaults", library),
        ] {
            let d = run_with(&case, &s);
            bwc_app::out!(
                "# {name} (at most {} steps): (e, t_s) {:?}, estimate {:?}, check {:?}, tighter \
                 run failed {:?}, {:.2} s",
                s.max_steps,
                d.result,
                d.e_error,
                d.check,
                d.tighter_failed,
                d.seconds
            );
        }
        bwc_app::out!("method\trtol\te\tt_s\trhs_evals\taccepted\trejected\tevents\tseconds");
        for method in [&VERN7, &VERN9, &DOP853] {
            for &rtol in &rtols {
                one(&case, method, rtol);
            }
        }
    }
}

/// Prints one run of `case` on the Runge-Kutta path with `method` at `rtol`.
fn one(case: &Case, method: &'static Tableau, rtol: f64) {
    let s = Settings {
        method,
        rtol,
        atol: rtol / 100.0,
        series: false,
        e_tol: None,
        max_steps: MAX_STEPS,
        ..settings()
    };
    let (a, b, _) = case.input;
    let clock = std::time::Instant::now();
    // The sweep's input, scaled as `stress::run_with` scales it.
    let out = BaseMap::new(case.kind, case.base).and_then(|map| {
        let (_, scales) = map.at(case.v0)?;
        let f = scales.factor;
        if b == 0.0 {
            impact_at(&map, Constant(a / f), case.v0, &s)
        } else {
            impact_at(&map, input(case, f), case.v0, &s)
        }
    });
    let seconds = clock.elapsed().as_secs_f64();
    match out {
        Ok(o) => bwc_app::out!(
            "{}\t{rtol:e}\t{}\t{}\t{}\t{}\t{}\t{}\t{seconds:.2}",
            method.name,
            o.e,
            o.t_s.map_or("-".to_string(), |t| t.to_string()),
            o.stats.rhs_evals,
            o.stats.accepted,
            o.stats.rejected,
            o.stats.events
        ),
        Err(err) => bwc_app::out!("{}\t{rtol:e}\tfailed: {err}", method.name),
    }
}
