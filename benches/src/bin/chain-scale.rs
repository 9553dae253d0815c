//! The cost of a chain by its length: `N` touching steel beads (10 mm, the elastic Hertz law of
//! `fixtures/granular_chain.toml`), the first struck at 0.5 m/s, run until the solitary wave
//! has crossed the chain (`N` x 10 mm at 580 m/s, and 20 % more). Per size: the wall time
//! (median of `R` runs), the integration's steps, contacts and events, the time per step, per
//! body-step and per contact, and the peak resident memory of the process.
//!
//! `cargo run --release -p bwc-benches --bin chain-scale -- N [R]` (one size per process, so
//! that the memory is that size's)

use bw_models::chain::{Chain, ChainBody, ChainSettings, PairLaw, Stop, Walls};
use bw_models::input::Zero;
use bw_models::{ModelKind, Physical, PhysicalParams};
use std::time::Instant;

/// The peak resident set of this process (kB), from `/proc/self/status` (0 where there is none).
fn peak_kb() -> u64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmHWM:"))
                .and_then(|l| l.split_whitespace().nth(1).and_then(|v| v.parse().ok()))
        })
        .unwrap_or(0)
}

fn main() {
    let args: Vec<usize> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    let (n, rounds) = match args.as_slice() {
        [n] => (*n, 3),
        [n, r, ..] => (*n, (*r).max(1)),
        [] => {
            eprintln!("usage: chain-scale N [ROUNDS]");
            std::process::exit(2)
        }
    };
    let (r, m) = (0.005, 4.1092e-3);
    let law = Physical {
        k: 7.326e9,
        c: 0.0,
        n: 1.0,
        p: 1.5,
        alpha: 0.5,
        beta: 0.0,
        gamma: 0.0,
        a: 1.0,
    };
    let law = PairLaw::new(&PhysicalParams::new(ModelKind::Shccm, law).expect("law")).expect("law");
    let bodies: Vec<_> = (0..n)
        .map(|i| {
            let v = if i == 0 { 0.5 } else { 0.0 };
            ChainBody::new(m, 2.0 * r * i as f64, v, 2.0 * r, Zero)
        })
        .collect();
    let chain = Chain::new(
        bodies,
        vec![law],
        Walls::default(),
        ChainSettings::default(),
    )
    .expect("chain");
    let horizon = 1.2 * n as f64 * 2.0 * r / 580.0;
    let mut times = Vec::new();
    let mut last = None;
    for _ in 0..rounds {
        let start = Instant::now();
        let run = chain.run(Stop::at(horizon), None, |_| {}).expect("run");
        times.push(start.elapsed().as_secs_f64());
        last = Some(run);
    }
    times.sort_by(f64::total_cmp);
    let wall = times[times.len() / 2];
    let run = last.expect("one run");
    let steps = run.stats.accepted as f64;
    let contacts = run.contacts.len() as f64;
    println!(
        "| {n} | {horizon:.3e} | {wall:.3e} | {} | {} | {} | {:.2e} | {:.2e} | {:.2e} | {} |",
        run.stats.accepted,
        run.contacts.len(),
        run.stats.events,
        wall / steps,
        wall / (steps * n as f64),
        wall / contacts,
        peak_kb() / 1024,
    );
}
