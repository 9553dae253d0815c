//! Stress sweep over random admissible parameter sets of both models (STABILITY.md, "The stress sweep"): counts and time
//! per class, the slowest cases, and any energy created without input.
//!
//! `cargo run --release -p bwc-benches --bin stress -- [COUNT] [SEED] [series|rk] [double]`
//! (default 100000, 1, the default settings: the Taylor-series path for the runs it takes,
//! `series`; `rk`: the Runge-Kutta path throughout, `Settings::series = false`; `double`:
//! double precision only, `Settings::double_double = false`, without the retry of the few runs
//! whose check stays unmet, which takes most of the defaults' time)

use bw_models::Settings;
use bwc_benches::stress::{settings, sweep_with, Class, Outcome};
use std::collections::BTreeMap;
use std::time::Instant;

fn main() {
    let count: u64 = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(100_000);
    let seed: u64 = std::env::args()
        .nth(2)
        .and_then(|a| a.parse().ok())
        .unwrap_or(1);
    let flags: Vec<String> = std::env::args().skip(3).collect();
    let series = !flags.iter().any(|f| f == "rk");
    let double_double = !flags.iter().any(|f| f == "double");
    let settings = Settings {
        series,
        double_double,
        ..settings()
    };
    let clock = Instant::now();
    let outcomes = sweep_with(seed, count, &settings);
    let wall = clock.elapsed().as_secs_f64();
    let retried = outcomes.iter().filter(|o| o.double_double).count();
    bwc_app::out!(
        "# {count} cases, seed {seed}, {} path, {wall:.1} s wall ({} threads), {}",
        if series {
            "Taylor-series"
        } else {
            "Runge-Kutta"
        },
        rayon::current_num_threads(),
        if double_double {
            format!("{retried} reported in double-double")
        } else {
            "double precision only".to_string()
        }
    );
    print_classes(&outcomes, count);
    print_slowest(&outcomes);
    print_unexpected(&outcomes);
}

/// Count, share, mean and largest time, switches to RODAS4 and series runs per class.
fn print_classes(outcomes: &[Outcome], count: u64) {
    let mut classes: BTreeMap<&str, (usize, f64, f64, usize, usize)> = BTreeMap::new();
    for o in outcomes {
        let e = classes.entry(o.class.name()).or_default();
        e.0 += 1;
        e.1 += o.seconds;
        e.2 = e.2.max(o.seconds);
        e.3 += usize::from(o.switched);
        e.4 += usize::from(o.series);
    }
    bwc_app::out!(
        "{:<32} {:>8} {:>8} {:>12} {:>10} {:>10} {:>8}",
        "class",
        "count",
        "share",
        "mean_ms",
        "max_ms",
        "to_RODAS4",
        "series"
    );
    for (name, (n, total, max, switched, series)) in &classes {
        bwc_app::out!(
            "{name:<32} {n:>8} {:>7.3}% {:>12.3} {:>10.1} {switched:>10} {series:>8}",
            100.0 * *n as f64 / count as f64,
            1e3 * total / *n as f64,
            1e3 * max
        );
    }
}

/// The eight slowest cases.
fn print_slowest(outcomes: &[Outcome]) {
    let mut slow: Vec<_> = outcomes.iter().collect();
    slow.sort_by(|a, b| b.seconds.total_cmp(&a.seconds));
    bwc_app::out!("\n# slowest cases");
    for o in slow.iter().take(8) {
        bwc_app::out!(
            "{:>8.1} ms {:>9} evals {:<28} {:?}",
            o.seconds * 1e3,
            o.rhs_evals,
            o.class.name(),
            o.case
        );
    }
}

/// Energy created without input, and failures the sweep cannot classify: bugs, if any.
fn print_unexpected(outcomes: &[Outcome]) {
    let bugs: Vec<_> = outcomes
        .iter()
        .filter(|o| matches!(o.class, Class::EnergyCreated(_) | Class::Other(_)))
        .collect();
    bwc_app::out!(
        "\n# energy created without input, or unclassified failures: {}",
        bugs.len()
    );
    for o in bugs.iter().take(20) {
        bwc_app::out!("{:?} {:?}", o.class, o.case);
    }
}
