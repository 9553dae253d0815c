//! Does the default search find the optimum in its bounds? For every `[[fit]]` of the given
//! configs: one reference search with a budget of at least 10x the default's evaluations
//! (30 starts, no early stop, swarms of twice the particles and iterations), then the default
//! search for seeds 1-5; prints each default J against the best J any run found.
//!
//! `cargo run --release -p bwc-benches --bin identify-convergence -- fixtures/*.toml`
//! (loop fits are skipped); `BWC_SEEDS=6-10` runs other seeds.

use bwc_app::fit::config::Config;
use bwc_identify::{fit, Budget, Objective};
use std::time::Instant;

/// The seeds of the default searches: `BWC_SEEDS` as `first-last`, else 1-5.
fn seeds() -> std::ops::RangeInclusive<u64> {
    let Ok(range) = std::env::var("BWC_SEEDS") else {
        return 1..=5;
    };
    let parsed = range
        .split_once('-')
        .and_then(|(a, b)| Some((a.trim().parse().ok()?, b.trim().parse().ok()?)));
    match parsed {
        Some((first, last)) if first <= last => first..=last,
        _ => {
            eprintln!("BWC_SEEDS = {range:?}: expected first-last, such as 6-10");
            std::process::exit(2);
        }
    }
}

fn main() {
    let paths: Vec<String> = std::env::args().skip(1).collect();
    let seeds = seeds();
    bwc_app::out!(
        "| fit | reference J (evals) | seed | J | J / best | starts agreeing | evals | wall s |"
    );
    bwc_app::out!("|---|---|---|---|---|---|---|---|");
    for path in paths {
        let config = match Config::load(std::path::Path::new(&path)) {
            Ok(c) => c,
            Err(e) => {
                eprintln!("{path}: {e}");
                continue;
            }
        };
        for f in &config.fits {
            let objective = Objective::new(&f.space, &f.data, &f.input, f.settings, f.weights)
                .expect("validated config");
            let reference = Budget {
                particles: 2 * f.budget.particles,
                iterations: 2 * f.budget.iterations,
                starts: 30,
                max_starts: 30,
                agree: 30,
                ..f.budget
            };
            let r = fit(&objective, &reference, 0xC0FFEE ^ f.seed, None).expect("reference fit");
            let runs: Vec<_> = seeds
                .clone()
                .map(|seed| {
                    let clock = Instant::now();
                    let o = Objective::new(&f.space, &f.data, &f.input, f.settings, f.weights)
                        .expect("validated config");
                    let m = fit(&o, &f.budget, seed ^ f.seed, None).expect("default fit");
                    (seed, m, clock.elapsed().as_secs_f64())
                })
                .collect();
            let best = runs.iter().map(|(_, m, _)| m.cost).fold(r.cost, f64::min);
            for (seed, m, wall) in &runs {
                bwc_app::out!(
                    "| {} | {:.5e} ({}) | {seed} | {:.5e} | {:.4} | {}/{} | {} | {wall:.2} |",
                    f.name,
                    r.cost,
                    r.evaluations,
                    m.cost,
                    m.cost / best,
                    m.convergence.agreeing,
                    m.convergence.starts,
                    m.evaluations
                );
            }
        }
    }
}
