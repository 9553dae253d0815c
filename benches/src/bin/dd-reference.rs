//! Double-double references for single stress cases (STABILITY.md, "Double-double"): `e` and
//! `T_s` of each case by the library's double-double path (`bw_models::impact_double_double`:
//! Gragg-Bulirsch-Stoer extrapolation of order 16 in double-double arithmetic) at each of a
//! list of tolerances, beside the defaults' run (at the library's step limit, with and without
//! `Settings::double_double`) and their distances from the last reference. Cases run in
//! parallel, one per thread.
//!
//! `cargo run --release -p bwc-benches --bin dd-reference -- SEED RTOL[,RTOL...] CASE [CASE...]`

use bw_models::Settings;
use bwc_benches::stress::{
    cases_args, double_double_reference, library_settings, run_with, sample,
};
use rayon::prelude::*;
use std::time::Instant;

fn main() {
    let (seed, rtols, cases) = cases_args("dd-reference");
    let reports: Vec<String> = cases.par_iter().map(|&i| report(seed, i, &rtols)).collect();
    for r in reports {
        bwc_app::out!("{r}");
    }
}

/// Everything printed for case `i`.
fn report(seed: u64, i: u64, rtols: &[f64]) -> String {
    let case = sample(seed, i);
    let mut lines = vec![format!(
        "# case {i} of seed {seed}: {:?}, v0 {}, input {:?}, {:?}",
        case.kind, case.v0, case.input, case.base
    )];
    let library = library_settings();
    lines.push("rtol\te\tt_s\tsteps\trejected\tevals\tevents\tseconds".into());
    let mut last = None;
    for &rtol in rtols {
        let clock = Instant::now();
        let out = double_double_reference(&case, rtol, &library);
        let seconds = clock.elapsed().as_secs_f64();
        lines.push(match out {
            None => format!("{rtol:e}\tno double-double path (inadmissible)"),
            Some(Err(f)) => format!("{rtol:e}\tfailed: {f}"),
            Some(Ok((e, t_s, st))) => {
                last = Some(e);
                format!(
                    "{rtol:e}\t{e:.17e}\t{t_s:.17e}\t{}\t{}\t{}\t{}\t{seconds:.1}",
                    st.accepted, st.rejected, st.rhs_evals, st.events
                )
            }
        });
    }
    for (name, double_double) in [
        ("the defaults (double precision)", false),
        ("with double_double", true),
    ] {
        let d = run_with(
            &case,
            &Settings {
                double_double,
                ..library
            },
        );
        let off = match (d.result, last) {
            (Some((e, _)), Some(r)) => format!("{:.2e}", (r - e).abs()),
            _ => "-".into(),
        };
        lines.push(format!(
            "# {name}: e {:?}, estimate {:?}, check {:?}, double-double {}, stiff {}, {:.1} s; \
             off the last reference by {off}",
            d.result.map(|r| r.0),
            d.e_error,
            d.check,
            d.double_double,
            d.switched,
            d.seconds
        ));
    }
    lines.join("\n")
}
