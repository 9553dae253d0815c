//! A posterior of the synthetic design of the credible band's coverage study (a known NDBWSHCCM,
//! κ and σ_b searched; the study itself, 20-40 replicates of minutes each, is the benchmark
//! `posterior-band`: BENCHMARKS.md, "Posteriors").

use bw_models::input::Zero;
use bw_models::{BaseParams, ModelKind, Settings};
use bwc_identify::{
    run_spread, sample, Budget, Dataset, Param, PosteriorProblem, PosteriorSpec, PosteriorTask,
    SmcReference, SmcSettings, Space, Weights, RUN_SPREAD,
};

fn task(given_noise: bool) -> PosteriorTask {
    let truth = BaseParams {
        b_b: 1.0,
        gamma_b: -1.0,
        kappa: 0.6,
        sigma_b: 0.03,
        n: 1.5,
        p: 1.5,
        u_b: 1.0,
        t_b: 1.0,
    };
    let fixed = Param::Fixed;
    let space = Space::new(
        ModelKind::Shccm,
        [
            fixed(1.0),
            fixed(-1.0),
            Param::Free {
                lo: 0.1,
                hi: 0.9,
                log: false,
            },
            Param::Free {
                lo: 1e-4,
                hi: 0.3,
                log: true,
            },
            fixed(1.5),
            fixed(1.5),
            fixed(1.0),
            fixed(1.0),
        ],
        None,
    )
    .unwrap();
    PosteriorTask {
        space,
        truth,
        speeds: vec![0.2, 0.5, 1.0, 2.0, 4.0],
        noise: 0.01,
        given_noise,
        from_prior: false,
        smc: SmcSettings::new(150, 4),
        budget: Budget {
            particles: 10,
            iterations: 10,
            ..Budget::default()
        },
        draws: 300,
        settings: Settings {
            rtol: 1e-8,
            atol: 1e-10,
            ..Settings::default()
        },
    }
}

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
