//! Accuracy of `e` on the stress sweep at several tolerances (issue 21, item 2; STABILITY.md):
//! for each rtol (atol = rtol / 100, the default path choice), the separated runs that miss the
//! Runge-Kutta reference at rtol 1e-14 by more than 1e-10 where a second reference at rtol
//! 1e-13 agrees with it to a tenth of that miss (so the miss is the run's), how many of them
//! the series path finished, the largest miss, and the wall time of the sweep.
//!
//! `cargo run --release -p bwc-benches --bin stress-accuracy -- [COUNT] [SEED] [RTOL ...]
//! [fine=RTOL] [check=RTOL]` (default 30000, 1, rtol 1e-9 1e-10 1e-11 1e-12, and references at
//! rtol 1e-14 and 1e-13; runs at rtol 1e-13 need references at 1e-15 and 1e-14, since a run on
//! the Runge-Kutta path at the check's own tolerance is the check); `list` prints each miss

use bw_models::Settings;
use bwc_benches::stress::{settings, sweep_with, Outcome};
use std::time::Instant;

/// A miss in `e` that counts.
const MISS: f64 = 1e-10;

/// `e` of a run that separated.
fn separated_e(o: &Outcome) -> Option<f64> {
    match o.result {
        Some((e, Some(_))) => Some(e),
        _ => None,
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let count: u64 = args.first().and_then(|a| a.parse().ok()).unwrap_or(30_000);
    let seed: u64 = args.get(1).and_then(|a| a.parse().ok()).unwrap_or(1);
    let reference = |key: &str, default: f64| {
        args.iter()
            .find_map(|a| a.strip_prefix(key).and_then(|v| v.parse().ok()))
            .unwrap_or(default)
    };
    let (fine_rtol, check_rtol) = (reference("fine=", 1e-14), reference("check=", 1e-13));
    let list = args.iter().any(|a| a == "list");
    let mut rtols: Vec<f64> = args.iter().skip(2).filter_map(|a| a.parse().ok()).collect();
    if rtols.is_empty() {
        rtols = vec![1e-9, 1e-10, 1e-11, 1e-12];
    }
    let at = |rtol: f64, series: bool| Settings {
        rtol,
        atol: rtol / 100.0,
        series,
        ..settings()
    };
    let fine = sweep_with(seed, count, &at(fine_rtol, false));
    let check = sweep_with(seed, count, &at(check_rtol, false));
    bwc_cli::out!(
        "# {count} cases, seed {seed}: misses above {MISS:e} against rtol {fine_rtol:e} \
         (checked against {check_rtol:e})"
    );
    bwc_cli::out!("rtol\tseparated\toff\toff_series\tlargest\twall_s");
    for rtol in rtols {
        let clock = Instant::now();
        let runs = sweep_with(seed, count, &at(rtol, true));
        let wall = clock.elapsed().as_secs_f64();
        let (mut separated, mut off, mut off_series, mut largest) = (0, 0, 0, 0.0f64);
        for (i, ((run, f), c)) in runs.iter().zip(&fine).zip(&check).enumerate() {
            let (Some(e), Some(ef), Some(ec)) = (separated_e(run), separated_e(f), separated_e(c))
            else {
                continue;
            };
            separated += 1;
            let miss = (e - ef).abs();
            if miss > MISS && (ec - ef).abs() < 0.1 * miss {
                off += 1;
                off_series += usize::from(run.series);
                largest = largest.max(miss);
                if list {
                    let case = &run.case;
                    bwc_cli::out!(
                        "# rtol {rtol:e} case {i}: {:?} e {e} reference {ef} miss {miss:.1e} \
                         series {} stiff {} input {:?} v0 {}",
                        case.kind,
                        run.series,
                        run.switched,
                        case.input,
                        case.v0
                    );
                }
            }
        }
        bwc_cli::out!("{rtol:e}\t{separated}\t{off}\t{off_series}\t{largest:.1e}\t{wall:.1}");
    }
}
