//! Issue 21's item 1 measured over whole sweeps, in one process: the largest error in `e` over
//! a sweep of `N` speeds (0.5 to 5 m/s, evenly spaced) against the time of the sweep, for the
//! default path (series, interpolants to the tolerance `rtol` where the sweep has at least
//! `sweep::MIN_SPEEDS` speeds, every other speed simulated) and for plain DOP853 simulating
//! every speed (`series = false`, `stop_at_kinks = false`, no stiffness switch). Both at
//! atol = rtol / 100 and one run per CoR (`e_tol` off); errors against the series path at rtol
//! 1e-13 at every speed. Each series row is timed side by side, in turns, with the two plain
//! rows that bracket its error; `ratio` is plain's time at the row's error (log-log
//! interpolation) over the row's time; `> x` where the row's error is below plain's smallest
//! (x: plain's time at rtol 1e-13 over the row's).
//!
//! `cargo run --release -p bwc-benches --bin sweep-precision -- [N ...]` (default 19 136 200
//! 2000; one thread)

use bw_models::sweep::{self, Row, SweepSettings};
use bw_models::{BaseMap, ModelKind, Settings, Stiffness};
use bwc_benches::{cor, side_by_side};
use bwc_ode::DOP853;

/// The series rows' tolerances (the errors 1e-6 to 1e-12 lie between their errors).
const SERIES_RTOLS: [f64; 9] = [1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12];
/// Plain DOP853's tolerances.
const PLAIN_RTOLS: [f64; 10] = [
    1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13,
];

fn one_run(rtol: f64) -> Settings {
    Settings {
        rtol,
        atol: rtol / 100.0,
        e_tol: None,
        ..Settings::default()
    }
}

fn plain(rtol: f64) -> Settings {
    Settings {
        method: &DOP853,
        stop_at_kinks: false,
        stiffness: Stiffness::Ignore,
        series: false,
        ..one_run(rtol)
    }
}

/// `e` at every speed, each simulated.
fn every_speed(map: &BaseMap, speeds: &[f64], s: &Settings) -> Vec<f64> {
    speeds
        .iter()
        .map(|&v| cor::evaluate(map, v, s).map_or(f64::NAN, |c| c.e))
        .collect()
}

/// `e` at every speed as the defaults give it: interpolated where the sweep's plan says so,
/// simulated elsewhere, the plan's own simulations at speeds of the sweep kept (as
/// `bwc-simulate` does).
fn by_plan(map: &BaseMap, speeds: &[f64], s: &Settings) -> Vec<f64> {
    let mut done: Vec<(f64, f64)> = Vec::new();
    let plan = sweep::plan(speeds, &SweepSettings { tolerance: s.rtol }, |batch| {
        batch
            .iter()
            .map(|&v| {
                let c = cor::evaluate(map, v, s).ok()?;
                done.push((v, c.e));
                Some([c.e, c.t_s?])
            })
            .collect()
    });
    plan.rows
        .iter()
        .zip(speeds)
        .map(|(row, &v)| match row {
            Row::Interpolated { values, .. } => values[0],
            Row::Simulate => match done.iter().find(|&&(u, _)| u == v) {
                Some(&(_, e)) => e,
                None => cor::evaluate(map, v, s).map_or(f64::NAN, |c| c.e),
            },
        })
        .collect()
}

fn largest_error(e: &[f64], reference: &[f64]) -> f64 {
    e.iter()
        .zip(reference)
        .map(|(a, b)| {
            // A speed that failed on either side counts as an infinite error.
            let d = (a - b).abs();
            if d.is_nan() {
                f64::INFINITY
            } else {
                d
            }
        })
        .fold(0.0, f64::max)
}

/// The plain rows `(error, rtol)` whose errors bracket `err`, if any.
fn bracket(plain: &[(f64, f64)], err: f64) -> Option<((f64, f64), (f64, f64))> {
    plain
        .windows(2)
        .find(|w| w[0].0 >= err && w[1].0 <= err && w[0].0 > w[1].0)
        .map(|w| (w[0], w[1]))
}

fn case(name: &str, map: &BaseMap, n: usize) {
    let speeds: Vec<f64> = (0..n)
        .map(|i| 0.5 + 4.5 * i as f64 / (n - 1) as f64)
        .collect();
    let reference = every_speed(map, &speeds, &one_run(1e-13));
    // Plain rows with a falling error only: the interpolation needs them monotone.
    let mut plain_rows: Vec<(f64, f64)> = Vec::new();
    for &r in &PLAIN_RTOLS {
        let err = largest_error(&every_speed(map, &speeds, &plain(r)), &reference);
        if plain_rows.last().is_none_or(|&(last, _)| err < last) {
            plain_rows.push((err, r));
        }
    }
    let listed: Vec<String> = plain_rows
        .iter()
        .map(|(err, r)| format!("{r:.0e}: {err:.1e}"))
        .collect();
    bwc_cli::out!(
        "# {name}, {n} speeds, plain DOP853 (rtol: error in e): {}",
        listed.join(", ")
    );
    // The first plain row is always kept, so there is a last one.
    let (best_err, best_rtol) = plain_rows[plain_rows.len() - 1];
    for &r in &SERIES_RTOLS {
        let s = one_run(r);
        let err = largest_error(&by_plan(map, &speeds, &s), &reference);
        // Below plain's smallest error its best row's time bounds the ratio from below.
        let (below, (e_hi, r_hi), (e_lo, r_lo)) = match bracket(&plain_rows, err) {
            Some((hi, lo)) => (false, hi, lo),
            None if err < best_err => (true, (best_err, best_rtol), (best_err, best_rtol)),
            None => {
                bwc_cli::out!("{name:<18} {n:>5} {r:>7.0e} {err:>9.2e}         -         -      -");
                continue;
            }
        };
        let times = side_by_side(&mut [
            Box::new(|| {
                std::hint::black_box(by_plan(map, &speeds, &s));
            }),
            Box::new(|| {
                std::hint::black_box(every_speed(map, &speeds, &plain(r_hi)));
            }),
            Box::new(|| {
                std::hint::black_box(every_speed(map, &speeds, &plain(r_lo)));
            }),
        ]);
        let w = if below {
            0.0
        } else {
            (err.ln() - e_hi.ln()) / (e_lo.ln() - e_hi.ln())
        };
        let t_plain = (times[1].ln() + w * (times[2].ln() - times[1].ln())).exp();
        bwc_cli::out!(
            "{name:<18} {n:>5} {r:>7.0e} {err:>9.2e} {:>9.3} {:>9.3} {}{:>5.2}",
            times[0] * 1e3,
            t_plain * 1e3,
            if below { ">" } else { " " },
            t_plain / times[0]
        );
    }
}

fn main() {
    let sizes: Vec<usize> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .filter(|&n| n >= 2)
        .collect();
    let sizes = if sizes.is_empty() {
        vec![19, 136, 200, 2000]
    } else {
        sizes
    };
    bwc_cli::out!(
        "# sweeps of N speeds from 0.5 to 5 m/s, one thread; interpolants from {} speeds",
        sweep::MIN_SPEEDS
    );
    bwc_cli::out!("case                   N    rtol  err_in_e   sweep_ms  plain_ms  ratio");
    let cases = [
        ("NDBWSHCCM DSS (1)", cor::dss1(ModelKind::Shccm)),
        ("NDBWMCM DSS (1)", cor::dss1(ModelKind::Mcm)),
        ("NDBWSHCCM DSA (1)", cor::dsa1(ModelKind::Shccm)),
        ("NDBWMCM DSA (1)", cor::dsa1(ModelKind::Mcm)),
    ];
    for n in sizes {
        for (name, map) in &cases {
            case(name, map, n);
        }
    }
}
