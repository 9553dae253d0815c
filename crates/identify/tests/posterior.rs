//! A posterior of the synthetic design of the credible band's coverage study (a known NDBWSHCCM,
//! κ and σ_b searched; the study itself, 20-40 replicates of minutes each, is the benchmark
//! `posterior-band`: BENCHMARKS.md, "Posteriors").

#[path = "support/band_design.rs"]
pub(crate) mod band_design;
use band_design::task;
use bw_models::input::Zero;
use bw_models::Settings;
use bwc_identify::{
    disagreement, run_spread, sample, Dataset, PosteriorProblem, PosteriorSpec, RunSpread,
    SmcReference, SmcSettings, Weights, RUN_SPREAD,
};

/// A posterior with one region (κ and σ_b of the synthetic design, the CoRs of the truth to four
/// digits, noise 0.01 given): four runs of 200 particles from the uniform reference agree on
/// its marginals' medians to a small part of their 95 % intervals, far inside the threshold of
/// the warning that runs disagree.
#[test]
fn runs_of_a_posterior_with_one_region_agree_on_its_marginals() {
    let task = task(true);
    let map = task.space.map(&task.truth).unwrap();
    let mut csv = String::from("v_0,e,e_std\n");
    for v0 in &task.speeds {
        let e = map.impact(Zero, *v0, &Settings::default()).unwrap().e;
        csv.push_str(&format!("{v0},{e:.4},0.01\n"));
    }
    let data = Dataset::parse(std::path::Path::new("one-region.csv"), &csv).unwrap();
    let spec = PosteriorSpec::new(&data, Weights { j1: 1.0, j2: 0.0 });
    let problem = PosteriorProblem::new(&task.space, &data, &Zero, task.settings, &spec).unwrap();
    let post = sample(
        &problem,
        &SmcSettings::new(200, 4),
        &SmcReference::uniform(),
        7,
    )
    .unwrap();
    let spread = run_spread(&problem, &post);
    assert_eq!(spread.len(), 2);
    for r in &spread {
        eprintln!(
            "{}: run medians {:?}, error {:.3} of the interval",
            r.name, r.medians, r.error
        );
        assert!(r.error < RUN_SPREAD / 2.0, "{r:?}");
    }
}

fn spread(name: &'static str, error: f64) -> RunSpread {
    RunSpread {
        name,
        medians: [1.0, 2.0],
        error,
    }
}

/// Only the quantities whose pooled median's Monte Carlo error exceeds the threshold are
/// named, in one warning; none (an error at the threshold included), no warning.
#[test]
fn the_runs_disagreement_names_only_the_quantities_it_concerns() {
    let w = disagreement("F", 4, &[spread("B_b", 0.17), spread("kappa", 0.01)]).unwrap();
    assert!(w.starts_with("\"F\": the 4 runs disagree on B_b (medians 1.0000e0 to 2.0000e0;"));
    assert!(w.contains("error 17 % of its 95 % interval") && !w.contains("kappa"));
    assert!(w.ends_with("raise runs"), "{w}");
    assert_eq!(disagreement("F", 4, &[spread("kappa", RUN_SPREAD)]), None);
}
