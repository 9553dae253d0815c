//! The posterior's 95 % credible band of `e(v0)` by simulation: synthetic CoR data from a known
//! NDBWSHCCM (κ and σ_b searched) with Gaussian noise, told to the likelihood or sampled. The
//! study of BENCHMARKS.md ("Posteriors"), 40 replicates each, measures 0.91 and 0.94
//! (`BWC_REPLICATES=40`); the test runs its first 20 and asks for 0.85-0.99: the five speeds of
//! a replicate share one posterior, so 100 points weigh like a few dozen.

use bw_models::input::Zero;
use bw_models::{BaseParams, ModelKind, Settings};
use bwc_identify::{
    coverage, posterior_replicate, run_spread, sample, Budget, Dataset, Param, PosteriorProblem,
    PosteriorSpec, PosteriorTask, SmcReference, SmcSettings, Space, Weights, RUN_SPREAD,
};
use rayon::prelude::*;

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

#[test]
fn the_credible_band_covers_the_true_curve_at_its_level() {
    for given in [true, false] {
        let task = task(given);
        let n: u64 = std::env::var("BWC_REPLICATES")
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(20);
        let reps: Vec<_> = (1..=n)
            .into_par_iter()
            .map(|s| posterior_replicate(&task, s).unwrap())
            .collect();
        let c = coverage(&reps);
        eprintln!(
            "noise given {given}: coverage {c:.3} of {} points",
            5 * reps.len()
        );
        assert!(
            (0.85..=0.99).contains(&c),
            "noise given {given}: coverage {c}"
        );
    }
}

/// A posterior with one region (κ and σ_b of the synthetic design, the CoRs of the truth to four
/// digits, noise 0.01 given): four runs of 500 particles from the uniform reference agree on
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
        &SmcSettings::new(500, 4),
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
