//! Coverage of the posterior's 95 % credible band of `e(v0)` by simulation: synthetic CoR data
//! at the 28 points (26 distinct speeds) of the measured baseball dataset, from the two models'
//! fits to it, with Gaussian noise of the fits' residual standard deviation; per replicate the posterior over the
//! fixture's bounds (uniform prior), told the noise (`given`) or sampling it (`sampled`). Prints,
//! per model and noise model, the fraction of the distinct speeds whose band contains the true
//! curve, pooled over the replicates (target 0.90-0.99), and the band's mean half-width.
//!
//! `cargo run --release -p bwc-benches --bin posterior-coverage -- [REPLICATES] [PARTICLES]`
//! (default 20 replicates, 250 particles x 4 runs); `BWC_ONLY="mcm sampled"` runs only the
//! rows whose model and noise model it names.

use bw_models::BaseParams;
use bwc_app::fit::config::Config;
use bwc_identify::{coverage, posterior_replicate, PosteriorTask, SmcSettings};
use rayon::prelude::*;

fn main() {
    let arg = |i: usize, default: usize| {
        std::env::args()
            .nth(i)
            .and_then(|a| a.parse().ok())
            .unwrap_or(default)
    };
    let (replicates, particles) = (arg(1, 20) as u64, arg(2, 250));
    let config = Config::load(std::path::Path::new("fixtures/baseball_wood.toml"))
        .expect("run from the repository root");
    let truths = bwc_benches::baseball_truths();
    // BWC_INTERIOR=1: truths moved inside the bounds (kappa, n, p off their bounds).
    let truths = if std::env::var("BWC_INTERIOR").is_ok() {
        truths.map(|(t, noise)| {
            (
                BaseParams {
                    kappa: t.kappa.max(0.06),
                    n: t.n.min(3.0),
                    p: t.p.min(3.0),
                    ..t
                },
                noise,
            )
        })
    } else {
        truths
    };
    bwc_app::out!(
        "| model | noise | replicates | particles | coverage | mean half-width | evaluations per replicate | wall s |"
    );
    bwc_app::out!("|---|---|---|---|---|---|---|---|");
    let only = std::env::var("BWC_ONLY").ok();
    // BWC_TRUTH=prior: each replicate's truth drawn from the prior (PosteriorTask::from_prior).
    let from_prior = std::env::var("BWC_TRUTH").is_ok_and(|v| v == "prior");
    for given in [true, false] {
        for (f, (truth, noise)) in config.fits.iter().zip(truths) {
            let row = format!(
                "{} {}",
                f.kind.name(),
                if given { "given" } else { "sampled" }
            );
            if only.as_ref().is_some_and(|o| !row.contains(o.as_str())) {
                continue;
            }
            let task = PosteriorTask {
                space: f.space.clone(),
                truth,
                speeds: f.data.points.iter().map(|p| p.v0).collect(),
                noise,
                given_noise: given,
                from_prior,
                smc: SmcSettings::new(particles, 4),
                budget: f.budget,
                draws: 400,
                settings: f.settings,
            };
            let clock = std::time::Instant::now();
            let reps: Vec<_> = (1..replicates + 1)
                .into_par_iter()
                .map(|s| posterior_replicate(&task, s).expect("replicate"))
                .collect();
            let hw = reps.iter().map(|r| r.halfwidth).sum::<f64>() / reps.len() as f64;
            bwc_app::out!(
                "| {} | {} | {replicates} | {particles} x 4 | {:.3} | {hw:.4} | {} | {:.0} |",
                f.kind.name(),
                if given { "given" } else { "sampled" },
                coverage(&reps),
                reps.iter().map(|r| r.evaluations).sum::<u64>() / replicates,
                clock.elapsed().as_secs_f64()
            );
            for r in &reps {
                eprintln!(
                    "{} seed {}: {}/{} covered, half-width {:.4}",
                    f.kind.name(),
                    r.seed,
                    r.covered,
                    r.points,
                    r.halfwidth
                );
            }
        }
    }
}
