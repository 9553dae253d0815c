//! Work-precision of one CoR evaluation: error in e and T_s against RHS evaluations and time,
//! for each method, stepping over the non-smooth points or stopping at them, over rtol 1e-4 ...
//! 1e-13, on these cases:
//!
//! * NDBWSHCCM and NDBWMCM at Table 3's DSS (1) and DSA (1), v0 in {0.5, 2, 5} m/s (errors
//!   against a reference at rtol 1e-14; evaluations and time summed over the speeds);
//! * the elastic limit (p = 2.5: T_s = 3.16983185381971, e = 1) and the Hunt-Crossley limit
//!   (sigma = 0.5: e = 0.748434931597434), where the answer is known exactly;
//! * a stiff MCM case from the stress sweep, where the explicit methods run with the switch to
//!   RODAS4 (method names `...>R`).
//!
//! Methods: DOPRI5, DOP853, Vern7, Vern9 and RODAS4 (Rosenbrock, `Stiffness::Rosenbrock`) on the
//! Runge-Kutta path, and the Taylor-series path of order 16 (`Settings::series`;
//! `Taylor16`, its RHS evaluations are those of its DOP853 start steps, so it is left out of the
//! evaluations plot; `steps` counts every step).
//!
//! A run that fails (the stiff case at loose tolerances can exceed the step limit) is reported
//! as a `failed` row (empty fields in the CSV) and left out of the plots.
//!
//! At the end of the table, the issue's RHS-evaluation target (">= 2x fewer RHS evaluations than
//! plain DOP853 stepping over the kinks, at equal error") row by row: the work of each run with
//! stops at the kinks (its RHS evaluations) and of each series run (its time over the time of
//! one right-hand side of the case's model: conservative, as it charges the series for all its
//! work and the Runge-Kutta runs only for their evaluations), plain DOP853's evaluations at the
//! same error (interpolated log-log between its runs) and their ratio; and beside it the ratio
//! in time (plain DOP853's time at the same error over the row's time), which does not depend
//! on how fast a lone right-hand side runs against the rest of the code on the day. Each row
//! with stops is timed side by side (in turns, `side_by_side`) with the two plain DOP853 runs
//! whose errors bracket its error and, for a series row, with the right-hand side, so that the
//! machine's drift within a run cancels from both ratios. "Error" there is the larger of the
//! errors in `e` and `T_s`; a series row also has `in_time_e`, the ratio in time at equal error
//! in `e` alone (the measure of BENCHMARKS.md), timed beside the plain runs that bracket that error.
//!
//! Side by side in the same run: the paper's setup in SciPy (benches/scipy_cor.py, skipped with a
//! message when python3 is absent). Writes `cor.csv` and SVG plots into the directory given as
//! the first argument (default `target/work-precision`).
//!
//! `cargo run --release -p bwc-benches --bin work-precision-cor [-- OUT_DIR]`

use bw_models::input::Zero;
use bw_models::{
    impact, impact_at, BaseMap, BaseParams, Cor, ModelKind, Ndbwmcm, Ndbwshccm, Nondim,
    NondimParams, Settings, State, Stiffness,
};
use bwc_app::plot::{chart, Axis, Series, Style};
use bwc_benches::{cor, side_by_side};
use bwc_ode::{System, Tableau, DOP853, METHODS, VERN7};
use std::fmt::Write as _;

/// A case: its name, its runs at given settings, their references `(e, T_s)`, and the model
/// whose right-hand side is the unit of a series row's work.
type Case = (
    &'static str,
    Box<dyn Fn(&Settings) -> Result<Vec<Cor>, String>>,
    Vec<(Option<f64>, Option<f64>)>,
    BaseMap,
);

/// One row of the report.
struct Row {
    method: String,
    kinks: bool,
    rtol: f64,
    err: f64,
    evals: u64,
    time_us: f64,
    /// Time of one right-hand side of the case's model, timed side by side with this row's
    /// runs (ns; series rows only).
    rhs_ns: Option<f64>,
    /// Plain DOP853's time at this row's error over the row's time, both timed side by side
    /// (rows with stops whose error plain DOP853's rows bracket).
    in_time: Option<f64>,
    /// The same at equal error in `e` alone (series rows only).
    in_time_e: Option<f64>,
}

/// A thousand right-hand sides of the model of `map` at v0 = 2 m/s, at a state in the
/// unloading: timed side by side with each series row (its seconds per call are the ns of one
/// right-hand side), the unit of the series' work for the RHS-evaluation target.
fn rhs_batch(map: &BaseMap) -> Box<dyn FnMut()> {
    let (params, _) = map.at(2.0).unwrap();
    match map.kind() {
        ModelKind::Shccm => thousand(
            Ndbwshccm::new(&params, Zero).unwrap(),
            State::<3>::new(-0.8, -0.7, 0.3),
        ),
        ModelKind::Mcm => thousand(
            Ndbwmcm::new(&params, Zero).unwrap(),
            State::<4>::new(0.0, -0.8, -0.7, 0.3),
        ),
    }
}

/// A thousand right-hand sides of `model` at `y`.
fn thousand<const N: usize>(model: impl System<N> + 'static, y: State<N>) -> Box<dyn FnMut()> {
    Box::new(move || {
        for _ in 0..1000 {
            std::hint::black_box(model.rhs(0.0, std::hint::black_box(&y)));
        }
    })
}

/// Plain DOP853 (stepping over the kinks) at one tolerance: the baseline of the RHS-evaluation
/// target.
struct Plain {
    rtol: f64,
    /// The larger of the errors in `e` and `T_s`.
    err: f64,
    /// The error in `e`.
    err_e: f64,
    evals: u64,
}

/// Plain DOP853's settings at `rtol` (atol = rtol / 100, as every row).
fn plain_dop853(rtol: f64) -> Settings {
    Settings {
        method: &DOP853,
        rtol,
        atol: rtol * 1e-2,
        stop_at_kinks: false,
        stiffness: Stiffness::Ignore,
        series: false,
        e_tol: None,
        ..Settings::default()
    }
}

/// The largest errors in `e` and in `T_s` of a case's runs against its references.
fn errors(outs: &[Cor], refs: &[(Option<f64>, Option<f64>)]) -> (f64, f64) {
    let (mut ee, mut et) = (0.0f64, 0.0f64);
    for (o, (e_ref, t_ref)) in outs.iter().zip(refs) {
        if let Some(e) = e_ref {
            ee = ee.max((o.e - e).abs());
        }
        if let (Some(t), Some(ts)) = (t_ref, o.t_s) {
            et = et.max((ts - t).abs());
        }
    }
    (ee, et)
}

/// The first two of plain DOP853's runs (in the order of the tolerances) whose errors bracket
/// `err`, and where `err` lies between them on a log scale (0 at the first, 1 at the second).
fn bracket(plain: &[Plain], err: f64) -> Option<(&Plain, &Plain, f64)> {
    bracket_by(plain, err, |p| p.err)
}

/// [`bracket`] by the error `of` each run.
fn bracket_by(
    plain: &[Plain],
    err: f64,
    of: impl Fn(&Plain) -> f64,
) -> Option<(&Plain, &Plain, f64)> {
    plain.windows(2).find_map(|w| {
        let (a, b) = (&w[0], &w[1]);
        let (ea, eb) = (of(a), of(b));
        let (hi, lo) = (ea.max(eb), ea.min(eb));
        (err <= hi && err >= lo && hi > lo)
            .then(|| (a, b, (err.ln() - ea.ln()) / (eb.ln() - ea.ln())))
    })
}

/// Log-log interpolation between `a` (at `f` = 0) and `b` (at `f` = 1).
fn between(a: f64, b: f64, f: f64) -> f64 {
    (a.ln() + f * (b.ln() - a.ln())).exp()
}

/// The lines of the RHS-evaluation target for one case: each row with stops at the kinks and
/// each series row, its work (evaluations; the series' time over the time of one right-hand
/// side timed beside it), plain DOP853's evaluations at its error and their ratio, and the
/// ratio of plain DOP853's time at that error to the row's time (timed side by side).
fn rhs_target(name: &str, rows: &[Row], plain: &[Plain]) -> String {
    let mut out = String::new();
    for r in rows.iter().filter(|r| r.kinks) {
        let work = match r.rhs_ns {
            Some(rhs_ns) => r.time_us * 1e3 / rhs_ns,
            None => r.evals as f64,
        };
        let evals =
            bracket(plain, r.err).map(|(a, b, f)| between(a.evals as f64, b.evals as f64, f));
        let (plain_evals, ratio) = match evals {
            Some(e) => (format!("{e:.0}"), format!("{:.2}", e / work)),
            None => ("-".into(), "-".into()),
        };
        let time_ratio = r.in_time.map_or("-".into(), |t| format!("{t:.2}"));
        let time_ratio_e = r.in_time_e.map_or(String::new(), |t| format!("{t:.2}"));
        let rhs = r.rhs_ns.map_or(String::new(), |ns| format!("{ns:.1}"));
        let _ = writeln!(
            out,
            "{name:<18} {:<9} {:>7.0e} {:>10.2e} {:>8.0} {plain_evals:>8} {ratio:>6} {rhs:>7} \
             {time_ratio:>6} {time_ratio_e:>9}",
            r.method, r.rtol, r.err, work
        );
    }
    out
}

fn main() {
    let out = std::path::PathBuf::from(
        std::env::args()
            .nth(1)
            .unwrap_or_else(|| "target/work-precision".into()),
    );
    std::fs::create_dir_all(&out).expect("output directory");
    let cases = cases();
    let mut target = String::new();
    let mut csv = String::from("case,method,kinks,rtol,err_e,err_Ts,rhs_evals,time_us,steps\n");
    println!(
        "{:<18} {:<9} {:<6} {:>7} {:>10} {:>10} {:>8} {:>9} {:>6}",
        "case", "method", "kinks", "rtol", "err_e", "err_Ts", "evals", "time_us", "steps"
    );
    for case in &cases {
        target.push_str(&run_case(case, &out, &mut csv));
    }
    println!(
        "\n# RHS-evaluation target (>= 2x fewer than plain DOP853 at equal error): the work of \
         each row with stops and of each series row (its time over one RHS evaluation of the \
         case's model, at DSS (1) for the cases that are not published fits, timed next to it; \
         rhs_ns) against plain DOP853's evaluations \
         at the same error (log-log interpolation between its rows; - outside their range); \
         in_time: plain DOP853's time at the same error over the row's time; in_time_e: the \
         same at equal error in e alone (series rows); each row timed side by side with the \
         plain runs that bracket its errors and the right-hand side"
    );
    println!(
        "{:<18} {:<9} {:>7} {:>10} {:>8} {:>8} {:>6} {:>7} {:>6} {:>9}",
        "case",
        "method",
        "rtol",
        "error",
        "work",
        "plain",
        "ratio",
        "rhs_ns",
        "in_time",
        "in_time_e"
    );
    print!("{target}");
    std::fs::write(out.join("cor.csv"), csv).unwrap();
    scipy_comparison(&cases[0].2);
    println!("\nwrote {}", out.display());
}

/// The cases: the four published fits, the two limits with known answers, the stiff case.
fn cases() -> Vec<Case> {
    let mut cases: Vec<Case> = vec![
        published("shccm_dss1", cor::dss1(ModelKind::Shccm)),
        published("mcm_dss1", cor::dss1(ModelKind::Mcm)),
        published("shccm_dsa1", cor::dsa1(ModelKind::Shccm)),
        published("mcm_dsa1", cor::dsa1(ModelKind::Mcm)),
    ];
    #[allow(clippy::excessive_precision)]
    cases.push(limit(
        "elastic_p2.5",
        0.0,
        2.5,
        (Some(1.0), Some(3.1698318538197101997)),
    ));
    #[allow(clippy::excessive_precision)]
    cases.push(limit(
        "hunt_crossley_0.5",
        0.5,
        1.5,
        (Some(0.748434931597434158), None),
    ));
    cases.push(stiff());
    cases
}

/// A published fit at v0 = 0.5, 2, 5 m/s, against Vern7 at rtol 1e-14.
fn published(name: &'static str, map: BaseMap) -> Case {
    let speeds = [0.5, 2.0, 5.0];
    let tight = Settings {
        method: &VERN7,
        rtol: 1e-14,
        atol: 1e-16,
        series: false,
        e_tol: None,
        ..Settings::default()
    };
    let run = move |s: &Settings| {
        speeds
            .iter()
            .map(|&v0| cor::evaluate(&map, v0, s).map_err(|e| e.to_string()))
            .collect::<Result<Vec<_>, _>>()
    };
    let refs = run(&tight)
        .expect("reference")
        .iter()
        .map(|o| (Some(o.e), o.t_s))
        .collect();
    (name, Box::new(run), refs, map)
}

/// The NDBWSHCCM without hysteresis (`κ = 0.5`, `B = Γ = 0`, `n = 1`) at damping `sigma` and
/// exponent `p`, whose answer `reference` is known exactly.
fn limit(name: &'static str, sigma: f64, p: f64, reference: (Option<f64>, Option<f64>)) -> Case {
    let params = NondimParams::new(
        ModelKind::Shccm,
        Nondim {
            b: 0.0,
            gamma: 0.0,
            kappa: 0.5,
            sigma,
            n: 1.0,
            p,
        },
    )
    .unwrap();
    let model = Ndbwshccm::new(&params, Zero).unwrap();
    let run = move |s: &Settings| Ok(vec![impact(&model, s).map_err(|e| e.to_string())?.cor()]);
    (
        name,
        Box::new(run),
        vec![reference],
        cor::dss1(ModelKind::Shccm),
    )
}

/// A stiff case from the stress sweep (MCM, n = 8.7, kappa = 9e-4, v0 = 124 m/s): explicit
/// methods alone exhaust 10^6 steps; they run here with the switch to RODAS4. Reference:
/// RODAS4 at rtol 1e-13 (checked against DOP853 switching at rtol 1e-13).
fn stiff() -> Case {
    let stiff_map = BaseMap::new(
        ModelKind::Mcm,
        BaseParams {
            b_b: 0.7701717736752235,
            gamma_b: -0.7701717736752235,
            kappa: 0.0009339372916279058,
            sigma_b: 2.468383259716545,
            n: 8.731291903102164,
            p: 1.5573680392509233,
            u_b: 1.0,
            t_b: 1.0,
        },
    )
    .unwrap();
    let stiff_v0 = 123.65181439237939;
    let stiff_run = move |s: &Settings| {
        Ok(vec![
            impact_at(&stiff_map, Zero, stiff_v0, s).map_err(|e| e.to_string())?
        ])
    };
    let tight_with = |stiffness| Settings {
        rtol: 1e-13,
        atol: 1e-15,
        stiffness,
        series: false,
        e_tol: None,
        ..Settings::default()
    };
    let stiff_ref = stiff_run(&tight_with(Stiffness::Rosenbrock)).expect("reference")[0];
    let stiff_check = stiff_run(&tight_with(Stiffness::Switch)).expect("reference")[0];
    println!(
        "# stiff case reference: e = {:.15}, T_s = {:.15}; DOP853 switching at rtol 1e-13 \
         differs by {:.1e} in e and {:.1e} in T_s",
        stiff_ref.e,
        stiff_ref.t_s.unwrap(),
        (stiff_check.e - stiff_ref.e).abs(),
        (stiff_check.t_s.unwrap() - stiff_ref.t_s.unwrap()).abs()
    );
    (
        "mcm_stiff",
        Box::new(stiff_run),
        vec![(Some(stiff_ref.e), stiff_ref.t_s)],
        cor::dss1(ModelKind::Mcm),
    )
}

/// Plain DOP853 at rtol 1e-4 ... 1e-13 on a case (its rows come again in the table).
fn plain_runs((_, run, refs, _): &Case) -> Vec<Plain> {
    (4..=13)
        .filter_map(|k| {
            let rtol = 10f64.powi(-k);
            let outs = run(&plain_dop853(rtol)).ok()?;
            let (ee, et) = errors(&outs, refs);
            Some(Plain {
                rtol,
                err: ee.max(et).max(1e-17),
                err_e: ee.max(1e-17),
                evals: outs.iter().map(|o| o.stats.rhs_evals).sum(),
            })
        })
        .collect()
}

/// A method of the report: its name, tableau, stiffness handling, whether it is the series
/// path, and whether it stops at the kinks.
struct Method {
    name: String,
    tab: &'static Tableau,
    stiffness: Stiffness,
    series: bool,
    kinks: bool,
}

/// Every method on one case: the table rows (and their CSV lines), the two plots, and the
/// case's lines of the RHS-evaluation target.
fn run_case(case: &Case, out: &std::path::Path, csv: &mut String) -> String {
    let name = case.0;
    // Explicit methods alone, or (on the stiff case) switching to RODAS4; RODAS4 throughout.
    let explicit = if name == "mcm_stiff" {
        Stiffness::Switch
    } else {
        Stiffness::Ignore
    };
    // Each row with stops is timed beside the plain runs whose errors bracket its error. Not on
    // the stiff case, where the explicit methods alone exhaust the step limit.
    let plain = if explicit == Stiffness::Ignore {
        plain_runs(case)
    } else {
        Vec::new()
    };
    let methods = METHODS
        .map(|tab| (tab.name, tab, explicit, false))
        .into_iter()
        .chain([
            ("RODAS4", &DOP853, Stiffness::Rosenbrock, false),
            ("Taylor16", &DOP853, Stiffness::Switch, true),
        ]);
    let (mut rows, mut by_evals, mut by_time) = (Vec::new(), Vec::new(), Vec::new());
    for (method, tab, stiffness, series) in methods {
        let method = if stiffness == Stiffness::Switch && !series {
            format!("{method}>R")
        } else {
            method.to_string()
        };
        let stops: &[bool] = if series { &[true] } else { &[false, true] };
        for &kinks in stops {
            let m = Method {
                name: method.clone(),
                tab,
                stiffness,
                series,
                kinks,
            };
            let measured: Vec<Row> = (4..=13)
                .filter_map(|k| measure(case, &plain, &m, 10f64.powi(-k), csv))
                .collect();
            let label = match (series, kinks) {
                (true, _) => format!("{method} (series)"),
                (false, true) => format!("{method} + stops at kinks"),
                (false, false) => method.clone(),
            };
            let color = by_time.len();
            if !series {
                by_evals.push(Series {
                    label: label.clone(),
                    points: measured.iter().map(|r| (r.evals as f64, r.err)).collect(),
                    style: Style::LineAndMarkers,
                    color,
                });
            }
            by_time.push(Series {
                label,
                points: measured.iter().map(|r| (r.time_us, r.err)).collect(),
                style: Style::LineAndMarkers,
                color,
            });
            rows.extend(measured);
        }
    }
    plots(out, name, &by_evals, &by_time);
    rhs_target(name, &rows, &plain)
}

/// One method on one case at `rtol`: its row (printed, and written to the CSV), timed side by
/// side with the plain runs that bracket its errors and, for the series, one right-hand side;
/// `None` where the run fails (reported, not plotted: the stiff case at loose tolerances can
/// exceed the step limit, depending on where the series hand over).
fn measure(case: &Case, plain: &[Plain], m: &Method, rtol: f64, csv: &mut String) -> Option<Row> {
    let (name, run, refs, unit) = case;
    let (method, kinks, series) = (&m.name, m.kinks, m.series);
    let s = Settings {
        method: m.tab,
        rtol,
        atol: rtol * 1e-2,
        stop_at_kinks: kinks,
        stiffness: m.stiffness,
        series,
        e_tol: None,
        ..Settings::default()
    };
    let outs = match run(&s) {
        Ok(outs) => outs,
        Err(e) => {
            println!("{name:<18} {method:<9} {kinks:<6} {rtol:>7.0e} failed: {e}");
            let _ = writeln!(csv, "{name},{method},{kinks},{rtol:e},,,,,");
            return None;
        }
    };
    let (ee, et) = errors(&outs, refs);
    let evals: u64 = outs.iter().map(|o| o.stats.rhs_evals).sum();
    let steps: u64 = outs
        .iter()
        .map(|o| o.stats.accepted + o.stats.rejected)
        .sum();
    let err = ee.max(et).max(1e-17);
    // A row with stops is timed side by side with the plain DOP853 runs that bracket its error
    // and, for the series, with those that bracket its error in e alone and with one right-hand
    // side of the case's model (the unit of their work for the RHS-evaluation target).
    let bracketed = bracket(plain, err)
        .filter(|_| kinks)
        .map(|(a, b, f)| (a.rtol, b.rtol, f));
    let bracketed_e = bracket_by(plain, ee.max(1e-17), |p| p.err_e)
        .filter(|_| series)
        .map(|(a, b, f)| (a.rtol, b.rtol, f));
    let ends: Vec<f64> = bracketed
        .iter()
        .chain(&bracketed_e)
        .flat_map(|&(a, b, _)| [a, b])
        .collect();
    let times = timed(run, &s, &ends, series.then_some(unit));
    let secs = times[0];
    let in_time = bracketed.map(|(_, _, f)| between(times[1], times[2], f) / secs);
    let at = if bracketed.is_some() { 3 } else { 1 };
    let in_time_e = bracketed_e.map(|(_, _, f)| between(times[at], times[at + 1], f) / secs);
    let rhs_ns = series.then(|| times[times.len() - 1] * 1e6);
    println!(
        "{name:<18} {method:<9} {:<6} {:>7.0e} {:>10.2e} {:>10.2e} {:>8} {:>9.1} {:>6}",
        kinks,
        rtol,
        ee,
        et,
        evals,
        secs * 1e6,
        steps
    );
    let _ = writeln!(
        csv,
        "{name},{method},{kinks},{rtol:e},{ee:e},{et:e},{evals},{:.3},{steps}",
        secs * 1e6
    );
    Some(Row {
        method: method.clone(),
        kinks,
        rtol,
        err,
        evals,
        time_us: secs * 1e6,
        rhs_ns,
        in_time,
        in_time_e,
    })
}

/// Seconds per call of `run` at `s`, then of the plain DOP853 runs at each tolerance of
/// `plain`, then (where given) of one right-hand side of `unit`'s model, timed side by side.
fn timed(
    run: &dyn Fn(&Settings) -> Result<Vec<Cor>, String>,
    s: &Settings,
    plain: &[f64],
    unit: Option<&BaseMap>,
) -> Vec<f64> {
    let mut fs: Vec<Box<dyn FnMut() + '_>> = vec![Box::new(|| {
        let _ = std::hint::black_box(run(s));
    })];
    for &rtol in plain {
        let plain = plain_dop853(rtol);
        fs.push(Box::new(move || {
            let _ = std::hint::black_box(run(&plain));
        }));
    }
    fs.extend(unit.map(rhs_batch));
    side_by_side(&mut fs)
}

/// A case's plots: error against RHS evaluations and against time.
fn plots(out: &std::path::Path, name: &str, by_evals: &[Series], by_time: &[Series]) {
    let error = Axis {
        label: "max(|error in e|, |error in T_s|) (-)",
        log: true,
    };
    let charts = [
        (
            "evals",
            "RHS evaluations",
            "RHS evaluations per case (summed over its speeds)",
            by_evals,
        ),
        (
            "time",
            "time",
            "time per case (us, summed over its speeds)",
            by_time,
        ),
    ];
    for (suffix, what, label, series) in charts {
        let title = format!("{name}: error vs {what}");
        let x = Axis { label, log: true };
        let svg = chart(&title, x, error, series).unwrap();
        std::fs::write(out.join(format!("{name}_{suffix}.svg")), svg).unwrap();
    }
}

/// The paper's setup in SciPy, on the SHCCM case (`refs`: its references).
fn scipy_comparison(refs: &[(Option<f64>, Option<f64>)]) {
    let script = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scipy_cor.py");
    match std::process::Command::new("python3").arg(&script).output() {
        Ok(o) if o.status.success() => {
            println!(
                "\n# SciPy solve_ivp DOP853 rtol 1e-10 atol 1e-12 (the paper's setup), shccm_dss1:"
            );
            println!(
                "{:<6} {:>9} {:>10} {:>10} {:>8} {:>10}",
                "v0", "max_step", "err_e", "err_Ts", "nfev", "time_us"
            );
            for (line, (e_ref, t_ref)) in String::from_utf8_lossy(&o.stdout)
                .lines()
                .zip(refs.iter().flat_map(|r| [r, r]))
            {
                let v: serde_json::Value = serde_json::from_str(line).unwrap();
                println!(
                    "{:<6} {:>9} {:>10.2e} {:>10.2e} {:>8} {:>10.1}",
                    v["v0"],
                    v["max_step"],
                    (v["e"].as_f64().unwrap() - e_ref.unwrap()).abs(),
                    (v["T_s"].as_f64().unwrap() - t_ref.unwrap()).abs(),
                    v["nfev"],
                    v["time_s"].as_f64().unwrap() * 1e6
                );
            }
        }
        Ok(o) => println!(
            "\n# SciPy comparison failed: {}",
            String::from_utf8_lossy(&o.stderr)
                .lines()
                .last()
                .unwrap_or("")
        ),
        Err(_) => println!("\n# SciPy comparison skipped: python3 not found"),
    }
}
