//! Speed at equal error for the phase path (`bw_models::phase`), on Table 3's DSS (1) and DSA (1)
//! fits of both models with no input: the largest error in `e` over 19 speeds from 0.5 to
//! 5 m/s against the time of the sweep, one thread, for
//!
//! * the phase path at `tol` 1e-5 ... 1e-12, one node count from `tol` without a check (as the
//!   series rows are one run each), for `e` alone and with `T_s`,
//! * the series path (one run per CoR, `e_tol` off) at rtol 1e-4 ... 1e-12,
//! * plain DOP853 (`series = false`, `stop_at_kinks = false`) at rtol 1e-4 ... 1e-13.
//!
//! Errors are against the series path at rtol 1e-13. Each phase and series row is timed side by
//! side, in turns, with the two plain rows that bracket its error; the ratio is plain's time at
//! the row's error (log-log interpolation) over the row's time (a lower bound, marked `>=`,
//! where the row's error is below plain's smallest).
//!
//! `cargo run --release -p bwc-benches --bin phase-precision`

use bw_models::phase::{self, PhaseSettings};
use bw_models::{BaseMap, ModelKind, Settings};
use bwc_benches::cor::{self, one_run, plain};
use bwc_benches::side_by_side;

const SPEEDS: usize = 19;
const PHASE_TOLS: [f64; 6] = [1e-4, 1e-5, 1e-7, 1e-10, 1e-12, 1e-14];
const SERIES_RTOLS: [f64; 9] = [1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12];
const PLAIN_RTOLS: [f64; 10] = [
    1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13,
];

fn series(map: &BaseMap, speeds: &[f64], s: &Settings) -> Vec<f64> {
    let cor = |v| cor::evaluate(map, v, s).map_or(f64::NAN, |c| c.e);
    speeds.iter().map(|&v| cor(v)).collect()
}

fn phased(map: &BaseMap, speeds: &[f64], s: &PhaseSettings) -> Vec<f64> {
    let cor = |v| {
        let params = map.at(v).expect("admissible").0;
        phase::cor(&params, s).map_or(f64::NAN, |c| c.e)
    };
    speeds.iter().map(|&v| cor(v)).collect()
}

/// One node count from `tol`, no check (like a series run at `rtol`), with or without `T_s`.
fn one_phase(tol: f64, duration: bool) -> PhaseSettings {
    PhaseSettings {
        tol,
        check: false,
        duration,
    }
}

fn largest_error(es: &[f64], reference: &[f64]) -> f64 {
    es.iter()
        .zip(reference)
        .map(|(e, r)| (e - r).abs())
        .fold(
            0.0,
            |a: f64, b| if b.is_nan() { f64::INFINITY } else { a.max(b) },
        )
}

/// Plain's time at `err`, log-log between the rows `i` and `i + 1` of `plain` whose errors
/// bracket it, from the times `lo` and `hi` measured beside the row.
fn interpolated(plain: &[(f64, f64)], i: usize, lo: f64, hi: f64, err: f64) -> f64 {
    let (e0, e1) = (plain[i].0.ln(), plain[i + 1].0.ln());
    let w = ((err.ln() - e0) / (e1 - e0)).clamp(0.0, 1.0);
    (lo.ln() + w * (hi.ln() - lo.ln())).exp()
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if args.len() == 4 && args[1] == "loop" {
        // `phase-precision loop TOL CASE`: 20,000 CoRs at 2 m/s, for a profiler; CASE is
        // `dss1-shccm`, `dss1-mcm`, `dsa1-shccm` or `dsa1-mcm`.
        let tol: f64 = args[2].parse().expect("a tolerance");
        let s = one_phase(tol, false);
        let kind = match &args[3][5..] {
            "mcm" => ModelKind::Mcm,
            _ => ModelKind::Shccm,
        };
        let map = match &args[3][..4] {
            "dsa1" => cor::dsa1(kind),
            _ => cor::dss1(kind),
        };
        let params = map.at(2.0).expect("admissible").0;
        let start = std::time::Instant::now();
        let mut sum = 0.0;
        for _ in 0..20_000 {
            sum += phase::cor(std::hint::black_box(&params), &s).map_or(f64::NAN, |c| c.e);
        }
        let us = start.elapsed().as_secs_f64() / 20_000.0 * 1e6;
        println!("{us:.2} us per CoR (mean e {:.15})", sum / 20_000.0);
        return;
    }
    let cases = [
        ("NDBWSHCCM DSS (1)", cor::dss1(ModelKind::Shccm)),
        ("NDBWMCM DSS (1)", cor::dss1(ModelKind::Mcm)),
        ("NDBWSHCCM DSA (1)", cor::dsa1(ModelKind::Shccm)),
        ("NDBWMCM DSA (1)", cor::dsa1(ModelKind::Mcm)),
    ];
    for (name, map) in cases {
        println!("\n{name}\n");
        report(&map);
    }
}

/// The table of one case.
fn report(map: &BaseMap) {
    let speeds: Vec<f64> = (0..SPEEDS)
        .map(|i| 0.5 + 4.5 * i as f64 / (SPEEDS - 1) as f64)
        .collect();
    let reference = series(map, &speeds, &one_run(1e-13));
    let mut plain_rows: Vec<(f64, f64)> = Vec::new();
    for &r in &PLAIN_RTOLS {
        let err = largest_error(&series(map, &speeds, &plain(r)), &reference);
        if plain_rows.last().is_none_or(|&(last, _)| err < last) {
            plain_rows.push((err, r));
        }
    }
    println!(
        "| path | setting | largest error in e | us per CoR | plain DOP853 at that error | ratio |"
    );
    println!("| --- | ---: | ---: | ---: | ---: | ---: |");
    let rows = PHASE_TOLS
        .iter()
        .map(|&t| ("phase", t))
        .chain(PHASE_TOLS.iter().map(|&t| ("phase with T_s", t)))
        .chain(SERIES_RTOLS.iter().map(|&r| ("series", r)));
    for (path, setting) in rows {
        let run = |m: &BaseMap| match path {
            "phase" => phased(m, &speeds, &one_phase(setting, false)),
            "phase with T_s" => phased(m, &speeds, &one_phase(setting, true)),
            _ => series(m, &speeds, &one_run(setting)),
        };
        let err = largest_error(&run(map), &reference);
        let i = plain_rows
            .iter()
            .position(|&(e, _)| e <= err)
            .unwrap_or(plain_rows.len())
            .clamp(1, plain_rows.len() - 1)
            - 1;
        let (r0, r1) = (plain_rows[i].1, plain_rows[i + 1].1);
        let t = side_by_side(&mut [
            Box::new(|| drop(std::hint::black_box(run(map)))),
            Box::new(|| drop(std::hint::black_box(series(map, &speeds, &plain(r0))))),
            Box::new(|| drop(std::hint::black_box(series(map, &speeds, &plain(r1))))),
        ]);
        let below = err < plain_rows[plain_rows.len() - 1].0;
        let at = interpolated(&plain_rows, i, t[1], t[2], err);
        let per = 1e6 / SPEEDS as f64;
        println!(
            "| {path} | {setting:.0e} | {err:.1e} | {:.2} | {:.2} | {}{:.1} |",
            t[0] * per,
            at * per,
            if below { ">= " } else { "" },
            at / t[0]
        );
    }
}
