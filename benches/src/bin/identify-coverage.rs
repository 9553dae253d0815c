//! Coverage of the 95 % confidence band of `e(v0)` by simulation: synthetic CoR data at the 28
//! speeds of the measured baseball dataset, from the two models' fits to it, with Gaussian noise
//! of the fits' residual standard deviation; each replicate fitted from the fixture's bounds with
//! the default search. Prints, per model, the fraction of data points whose band contains the
//! true curve (target 0.85-0.99) and the band's mean half-width.
//!
//! `cargo run --release -p bwc-benches --bin identify-coverage -- [REPLICATES]` (default 40)

use bwc_app::fit::config::Config;
use bwc_identify::{coverage, study};

fn main() {
    let replicates: u64 = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(40);
    let config = Config::load(std::path::Path::new("fixtures/baseball_wood.toml"))
        .expect("run from the repository root");
    let truths = bwc_benches::baseball_truths();
    bwc_app::out!(
        "| model | replicates | noise | coverage | mean half-width | without intervals | wall s |"
    );
    bwc_app::out!("|---|---|---|---|---|---|---|");
    for (f, (truth, noise)) in config.fits.iter().zip(truths) {
        let task = bwc_app::fit::identify::coverage_task(f, truth, noise);
        let clock = std::time::Instant::now();
        let reps = study(&task, 1..replicates + 1).expect("replicates");
        let with: Vec<_> = reps.iter().filter(|r| r.error.is_none()).collect();
        let hw = with.iter().map(|r| r.halfwidth).sum::<f64>() / with.len().max(1) as f64;
        bwc_app::out!(
            "| {} | {replicates} | {noise} | {:.3} | {hw:.4} | {} | {:.0} |",
            f.kind.name(),
            coverage(&reps),
            reps.len() - with.len(),
            clock.elapsed().as_secs_f64()
        );
        for r in &reps {
            eprintln!(
                "{} seed {}: {}/{} covered, half-width {:.4}, J1 {:.3e} {}",
                f.kind.name(),
                r.seed,
                r.covered,
                r.points,
                r.halfwidth,
                r.j1,
                r.error.clone().unwrap_or_default()
            );
        }
    }
}
