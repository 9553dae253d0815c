//! Speed at equal error measured over whole sweeps, in one process: the largest error in `e` over
//! a sweep of `N` speeds (0.5 to 5 m/s, evenly spaced) against the time of the sweep, for the
//! default path (series, interpolants to the tolerance `rtol` where the sweep has at least
//! `sweep::MIN_SPEEDS` speeds, every other speed simulated) and for plain DOP853 (`series =
//! false`, `stop_at_kinks = false`, no stiffness switch) twice: simulating every speed, and
//! through the same sweep plan at a sweep tolerance of `PLAIN_SWEEP` times its rtol (at rtol
//! itself the plan finds plain's `e(v0)` too noisy and simulates every speed). All at
//! atol = rtol / 100 and one run per CoR (`e_tol` off); errors against the series path at rtol
//! 1e-13 at every speed. Each series row is timed side by side, in turns, with the plain rows
//! that bracket its error; `ratio` is plain's time at the row's error (log-log interpolation)
//! over the row's time; `> x` where the row's error is below plain's smallest (x: plain's time
//! at its best row over the row's).
//!
//! `cargo run --release -p bwc-benches --bin sweep-precision -- [N ...]` (default 19 136 200
//! 2000; one thread)

use bw_models::sweep::{self, Row, SweepSettings};
use bw_models::{BaseMap, ModelKind, Settings};
use bwc_benches::cor::{self, one_run, plain};
use bwc_benches::side_by_side;

/// The series rows' tolerances (the errors 1e-6 to 1e-12 lie between their errors).
const SERIES_RTOLS: [f64; 9] = [1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12];
/// Plain DOP853's tolerances.
const PLAIN_RTOLS: [f64; 10] = [
    1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13,
];

/// Plain DOP853's sweep tolerance through the plan, in multiples of its rtol.
const PLAIN_SWEEP: f64 = 100.0;

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
fn by_plan(map: &BaseMap, speeds: &[f64], s: &Settings, tolerance: f64) -> Vec<f64> {
    let mut done: Vec<(f64, f64)> = Vec::new();
    let plan = sweep::plan(speeds, &SweepSettings { tolerance }, |batch| {
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

/// Plain DOP853's rows `(error, rtol)` with a falling error only (the interpolation between
/// them needs them monotone), each sweep run by `run`.
fn plain_rows(reference: &[f64], run: impl Fn(&Settings) -> Vec<f64>) -> Vec<(f64, f64)> {
    let mut rows: Vec<(f64, f64)> = Vec::new();
    for &r in &PLAIN_RTOLS {
        let err = largest_error(&run(&plain(r)), reference);
        if rows.last().is_none_or(|&(last, _)| err < last) {
            rows.push((err, r));
        }
    }
    rows
}

/// The plain rows `(error, rtol)` that bracket an error, and the rtols to time.
#[derive(Clone, Copy)]
struct Bracket {
    /// The error is below plain's smallest: both rows are plain's best.
    below: bool,
    hi: (f64, f64),
    lo: (f64, f64),
}

impl Bracket {
    /// The rows bracketing `err`, or `None` where `err` is above plain's largest error.
    fn of(rows: &[(f64, f64)], err: f64) -> Option<Bracket> {
        // The first plain row is always kept, so there is a last one.
        let best = rows[rows.len() - 1];
        let found = rows
            .windows(2)
            .find(|w| w[0].0 >= err && w[1].0 <= err && w[0].0 > w[1].0);
        match found {
            Some(w) => Some(Bracket {
                below: false,
                hi: w[0],
                lo: w[1],
            }),
            None if err < best.0 => Some(Bracket {
                below: true,
                hi: best,
                lo: best,
            }),
            None => None,
        }
    }

    /// Plain's time at `err` by log-log interpolation between the rows' times `t`.
    fn time_at(&self, err: f64, t: [f64; 2]) -> f64 {
        let w = if self.below {
            0.0
        } else {
            (err.ln() - self.hi.0.ln()) / (self.lo.0.ln() - self.hi.0.ln())
        };
        (t[0].ln() + w * (t[1].ln() - t[0].ln())).exp()
    }

    fn mark(&self) -> &'static str {
        if self.below {
            ">"
        } else {
            " "
        }
    }
}

fn case(name: &str, map: &BaseMap, n: usize) {
    let speeds: Vec<f64> = (0..n)
        .map(|i| 0.5 + 4.5 * i as f64 / (n - 1) as f64)
        .collect();
    let reference = every_speed(map, &speeds, &one_run(1e-13));
    let every = plain_rows(&reference, |s| every_speed(map, &speeds, s));
    // Plain DOP853 through the same sweep plan. Its `e(v0)` carries noise of the size of its
    // error (up to about 100 rtol), and at a sweep tolerance of rtol the plan then simulates
    // every speed; at 100 rtol it interpolates as it does for the series.
    let planned = plain_rows(&reference, |s| {
        by_plan(map, &speeds, s, PLAIN_SWEEP * s.rtol)
    });
    let listed = |rows: &[(f64, f64)]| {
        let l: Vec<String> = rows
            .iter()
            .map(|(err, r)| format!("{r:.0e}: {err:.1e}"))
            .collect();
        l.join(", ")
    };
    bwc_app::out!(
        "# {name}, {n} speeds, plain DOP853 (rtol: error in e): every speed {}; planned {}",
        listed(&every),
        listed(&planned)
    );
    for &r in &SERIES_RTOLS {
        let s = one_run(r);
        let err = largest_error(&by_plan(map, &speeds, &s, r), &reference);
        let (Some(be), Some(bp)) = (Bracket::of(&every, err), Bracket::of(&planned, err)) else {
            bwc_app::out!("{name:<18} {n:>5} {r:>7.0e} {err:>9.2e}         -         -      -         -      -");
            continue;
        };
        let (re, rp) = ([be.hi.1, be.lo.1], [bp.hi.1, bp.lo.1]);
        let times = side_by_side(&mut [
            Box::new(|| {
                std::hint::black_box(by_plan(map, &speeds, &s, r));
            }),
            Box::new(|| {
                std::hint::black_box(every_speed(map, &speeds, &plain(re[0])));
            }),
            Box::new(|| {
                std::hint::black_box(every_speed(map, &speeds, &plain(re[1])));
            }),
            Box::new(|| {
                std::hint::black_box(by_plan(map, &speeds, &plain(rp[0]), PLAIN_SWEEP * rp[0]));
            }),
            Box::new(|| {
                std::hint::black_box(by_plan(map, &speeds, &plain(rp[1]), PLAIN_SWEEP * rp[1]));
            }),
        ]);
        let t_every = be.time_at(err, [times[1], times[2]]);
        let t_planned = bp.time_at(err, [times[3], times[4]]);
        bwc_app::out!(
            "{name:<18} {n:>5} {r:>7.0e} {err:>9.2e} {:>9.3} {:>9.3} {}{:>5.2} {:>9.3} {}{:>5.2}",
            times[0] * 1e3,
            t_every * 1e3,
            be.mark(),
            t_every / times[0],
            t_planned * 1e3,
            bp.mark(),
            t_planned / times[0]
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
    bwc_app::out!(
        "# sweeps of N speeds from 0.5 to 5 m/s, one thread; interpolants from {} speeds",
        sweep::MIN_SPEEDS
    );
    bwc_app::out!(
        "case                   N    rtol  err_in_e   sweep_ms  plain_ms  ratio planned_ms  ratio"
    );
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
