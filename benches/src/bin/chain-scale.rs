//! The cost of a chain by its length: `N` steel beads (10 mm, the elastic Hertz law of
//! `fixtures/granular_chain.toml`), the first struck at 0.5 m/s, run until the pulse has
//! crossed the chain. Touching beads (`GAP` 0, the default) carry a solitary wave at 580 m/s
//! and stay in contact, at rest, behind it; beads `GAP` metres apart pass the momentum on in
//! separate collisions (`GAP / 0.5 m/s` of flight and about 0.1 ms of contact per bead). The
//! horizon is that crossing time and 20 % more. Per size: the wall time (median of `R`
//! runs), the integration's steps, contacts and events, the contacts open on average over the
//! run, the time per step, per body-step and per contact, and the peak resident memory of the
//! process.
//!
//! `cargo run --release -p bwc-benches --bin chain-scale -- N [R] [GAP]` (one size per
//! process, so that the memory is that size's); `BWC_SCHEME=whole` integrates every bead at
//! every step, the scheme the default is checked against.

use bw_models::chain::{Chain, ChainBody, ChainSettings, PairLaw, Scheme, Stop, Walls};
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
    let args: Vec<f64> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    let (n, rounds, gap) = match args.as_slice() {
        [n] => (*n as usize, 3, 0.0),
        [n, r] => (*n as usize, (*r as usize).max(1), 0.0),
        [n, r, g, ..] => (*n as usize, (*r as usize).max(1), *g),
        [] => {
            eprintln!("usage: chain-scale N [ROUNDS] [GAP]");
            std::process::exit(2)
        }
    };
    let (r, m) = (0.005, 4.1092e-3);
    let law = Physical::hertz_damped(7.326e9, 0.0);
    let law = PairLaw::new(&PhysicalParams::new(ModelKind::Shccm, law).expect("law")).expect("law");
    let scheme = if std::env::var("BWC_SCHEME").is_ok_and(|s| s == "whole") {
        Scheme::Whole
    } else {
        Scheme::Contacts
    };
    let bodies: Vec<_> = (0..n)
        .map(|i| {
            let v = if i == 0 { 0.5 } else { 0.0 };
            ChainBody::new(m, (2.0 * r + gap) * i as f64, v, 2.0 * r, Zero)
        })
        .collect();
    let chain = Chain::new(
        bodies,
        vec![law],
        Walls::default(),
        ChainSettings::default().with_scheme(scheme),
    )
    .expect("chain");
    let per_bead = if gap > 0.0 {
        gap / 0.5 + 1e-4
    } else {
        2.0 * r / 580.0
    };
    let horizon = 1.2 * n as f64 * per_bead;
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
    let open: f64 = run
        .contacts
        .iter()
        .map(|c| c.separation.unwrap_or(run.t_end) - c.onset)
        .sum::<f64>()
        / run.t_end;
    println!(
        "| {n} | {gap:.0e} | {horizon:.3e} | {wall:.3e} | {} | {} | {} | {open:.1} | {:.2e} | {:.2e} | {:.2e} | {} |",
        run.stats.accepted,
        run.contacts.len(),
        run.stats.events,
        wall / steps,
        wall / (steps * n as f64),
        wall / contacts,
        peak_kb() / 1024,
    );
}
