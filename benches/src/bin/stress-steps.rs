//! Missed events on the stress sweep: each run at the default settings against the
//! Runge-Kutta path with steps of at most `MAX_STEP`, whose interpolants are too short to miss a
//! separation that a long step's might (a force that dips below zero and back inside one step).
//! Prints every run whose class differs or whose `e` differs by more than 1e-6, and the counts
//! (STABILITY.md, "Not done").
//!
//! `cargo run --release -p bwc-benches --bin stress-steps -- [COUNT] [SEED] [MAX_STEP]`
//! (default 30000, 1, 0.01)

use bw_models::Settings;
use bwc_benches::stress::{settings, sweep_with};
use std::collections::BTreeMap;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let count: u64 = args.first().and_then(|a| a.parse().ok()).unwrap_or(30_000);
    let seed: u64 = args.get(1).and_then(|a| a.parse().ok()).unwrap_or(1);
    let max_step: f64 = args.get(2).and_then(|a| a.parse().ok()).unwrap_or(0.01);
    let default = sweep_with(seed, count, &settings());
    let short = Settings {
        max_step,
        series: false,
        e_tol: None,
        ..settings()
    };
    let short = sweep_with(seed, count, &short);
    let mut kinds: BTreeMap<String, usize> = BTreeMap::new();
    let e = |o: &bwc_benches::stress::Outcome| o.result.map_or(f64::NAN, |r| r.0);
    bwc_app::out!("case\tdefault\te\tshort_steps\te_short\tinput");
    for (i, (a, b)) in default.iter().zip(&short).enumerate() {
        let (ea, eb) = (e(a), e(b));
        let close = (ea - eb).abs() <= 1e-6 || (ea.is_nan() && eb.is_nan());
        if a.class.name() == b.class.name() && close {
            continue;
        }
        let kind = format!("{} -> {}", a.class.name(), b.class.name());
        bwc_app::out!(
            "{i}\t{}\t{ea}\t{}\t{eb}\t{:?}",
            a.class.name(),
            b.class.name(),
            a.case.input
        );
        *kinds.entry(kind).or_default() += 1;
    }
    bwc_app::out!(
        "# {count} cases, seed {seed}, steps of at most {max_step}: default -> short steps"
    );
    for (kind, n) in kinds {
        bwc_app::out!("# {n}\t{kind}");
    }
}
