//! Accuracy of `e` on the stress sweep (STABILITY.md, "Global error control"): for each setting, the
//! separated runs that miss the reference by more than 1e-10 where a second reference agrees
//! with it to a tenth of that miss (so the miss is the run's), how many of them the series
//! path finished, the largest miss, and the wall time of the sweep. The reference is Verner's
//! 9(8) at rtol `fine`, the second Verner's 7(6) at rtol `check` (both on the Runge-Kutta path,
//! atol = rtol / 100, at most 20 million steps): at a tolerance no run of the defaults takes,
//! so that a run's own error cannot pass for the truth. Where they agree on a miss, the library's
//! double-double path referees it (rtol 1e-21 and 1e-23, where the model has that path and the
//! two agree to a tenth of the miss threshold): the references themselves can be off by about
//! 1e-10 where rounding decides, and a run within 1e-10 of the referee is not a miss
//! (`refereed`; STABILITY.md, "Global error control"). The last column counts the runs reported by the
//! double-double retry.
//!
//! `cargo run --release -p bwc-benches --bin stress-accuracy -- [COUNT] [SEED] [RTOL | default |
//! library | double-double | double | e_tol=TOL ...] [fine=RTOL] [check=RTOL] [list] [audit=K]` (default 30000, 1, `default` and
//! rtol 1e-11 1e-12 1e-13, references at rtol 3e-15: with compensated summation the references
//! agree to about 1e-11 there, STABILITY.md, "Checks by other methods"). An RTOL is one run at that tolerance
//! (`e_tol` off, atol = rtol / 100); `default` is the sweep's settings, the defaults, whose CoRs
//! are checked to `e_tol` = 1e-10: for it the table also counts the runs whose own estimate exceeds
//! `e_tol`, or that have none (`flagged`), the misses among the rest (`silent`) and the runs no
//! other tolerance could check (`unverified`, among the flagged); `library` is the defaults with
//! the library's step limit (`Settings::default().max_steps`) in place of the sweep's 200,000;
//! `double-double` is `library` with `Settings::double_double` on (the library's default) and `double` is `library` with it off (double precision only);
//! `e_tol=TOL` is the defaults with that target (the misses still counted above 1e-10). `list`
//! prints each miss, and each flagged run of a setting with `double_double` on.
//!
//! `audit=K` also referees K separated runs of each setting that did not go stiff, drawn at
//! random (seeded) whether or not the references agree with them, by the double-double path as
//! above (at most 100,000 steps a run): a line per setting with how many had a referee, the
//! largest distance of a run and of the Runge-Kutta reference from it, and how many runs were
//! more than 1e-10 off (each listed with `list`). The misses above can only show where a run
//! and the references differ; the audit also sees an error they share.

use bw_models::{Check, Settings};
use bwc_benches::stress::{
    double_double_reference, library_settings, settings, sweep_with, Case, Outcome,
};
use bwc_ode::{VERN7, VERN9};
use rand::SeedableRng;
use rayon::prelude::*;
use std::time::Instant;

/// A miss in `e` that counts.
const MISS: f64 = 1e-10;

/// The references' step limit: at rtol 3e-15 the hardest runs take a few million steps, and a
/// reference that gave up would leave its case out of the count.
const REFERENCE_MAX_STEPS: u64 = 20_000_000;

/// The tolerances of the double-double referee: tighter than any the library's retry takes
/// (`bw_models::LADDER.double_double_rtols`), so that it does not repeat a run reported in
/// double-double.
const REFEREE_RTOLS: [f64; 2] = [1e-21, 1e-23];

/// The audit's step limit for each double-double run: a few seconds at most, so that a few
/// hard cases do not hold up the audit (they count as without a referee).
const AUDIT_MAX_STEPS: u64 = 100_000;

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
    let (fine_rtol, check_rtol) = (reference("fine=", 3e-15), reference("check=", 3e-15));
    let list = args.iter().any(|a| a == "list");
    let audit: Option<usize> = args
        .iter()
        .find_map(|a| a.strip_prefix("audit=").and_then(|k| k.parse().ok()));
    let on_runge_kutta = |method, rtol| Settings {
        method,
        max_steps: REFERENCE_MAX_STEPS,
        ..at(rtol, false)
    };
    let references = References {
        fine: sweep_with(seed, count, &on_runge_kutta(&VERN9, fine_rtol)),
        check: sweep_with(seed, count, &on_runge_kutta(&VERN7, check_rtol)),
    };
    bwc_app::out!(
        "# {count} cases, seed {seed}: misses above {MISS:e} against Vern9 at rtol {fine_rtol:e} \
         (checked against Vern7 at {check_rtol:e})"
    );
    bwc_app::out!(
        "settings\tseparated\toff\toff_series\tlargest\tflagged\tsilent\tunverified\twall_s\trefereed\tdouble_double"
    );
    for (name, s) in settings_from(&args[args.len().min(2)..]) {
        let clock = Instant::now();
        let runs = sweep_with(seed, count, &s);
        let wall = clock.elapsed().as_secs_f64();
        let t = tally(&name, &runs, &references, (list, list && s.double_double));
        let (flagged, silent, unverified) = match s.e_tol {
            Some(_) => (
                t.flagged.to_string(),
                t.silent.to_string(),
                t.unverified.to_string(),
            ),
            None => ("-".to_string(), "-".to_string(), "-".to_string()),
        };
        bwc_app::out!(
            "{name}\t{}\t{}\t{}\t{:.1e}\t{flagged}\t{silent}\t{unverified}\t{wall:.1}\t{}\t{}",
            t.separated,
            t.off,
            t.off_series,
            t.largest,
            t.refereed,
            runs.iter().filter(|r| r.double_double).count()
        );
        if let Some(k) = audit {
            audit_runs(&name, &runs, &references.fine, (seed, k), list);
        }
    }
}

/// Referees `k` separated runs of setting `name`, drawn with `seed`, in double-double against
/// both the runs and the reference `fine`, and prints what it found.
fn audit_runs(name: &str, runs: &[Outcome], fine: &[Outcome], (seed, k): (u64, usize), list: bool) {
    // Runs that went stiff are left out: the explicit double-double steps are not reliable
    // there, which is why the library's retry skips them too.
    let separated: Vec<usize> = (0..runs.len())
        .filter(|&i| separated_e(&runs[i]).is_some() && !runs[i].switched)
        .collect();
    // Its own stream: the draw does not depend on the sweep's cases.
    let mut rng = rand::rngs::StdRng::seed_from_u64(seed ^ 0xA0D1_7A0D_17A0_D17A);
    let mut drawn: Vec<usize> =
        rand::seq::index::sample(&mut rng, separated.len(), k.min(separated.len()))
            .into_iter()
            .map(|j| separated[j])
            .collect();
    drawn.sort_unstable();
    let clock = Instant::now();
    let refereed: Vec<(usize, f64)> = drawn
        .par_iter()
        .filter_map(|&i| referee(&runs[i].case, AUDIT_MAX_STEPS).map(|e_dd| (i, e_dd)))
        .collect();
    let (mut largest, mut largest_reference, mut off) = ((0.0, 0), 0.0_f64, 0);
    for &(i, e_dd) in &refereed {
        let miss = (separated_e(&runs[i]).unwrap_or(f64::NAN) - e_dd).abs();
        if miss > largest.0 {
            largest = (miss, i);
        }
        if let Some(ef) = separated_e(&fine[i]) {
            largest_reference = largest_reference.max((ef - e_dd).abs());
        }
        if miss > MISS || miss.is_nan() {
            off += 1;
            if list {
                bwc_app::out!(
                    "# audit of {name}, case {i}: {miss:.1e} off the double-double referee"
                );
            }
        }
    }
    bwc_app::out!(
        "# audit of {name}: {} of {} separated runs drawn, {} with a referee ({:.0} s): \
         largest distance {:.1e} (case {}), the reference's {:.1e}; more than {MISS:e} off: {off}",
        drawn.len(),
        separated.len(),
        refereed.len(),
        clock.elapsed().as_secs_f64(),
        largest.0,
        largest.1,
        largest_reference
    );
}

/// The settings named on the command line (after COUNT and SEED), or `default` and rtol 1e-11,
/// 1e-12 and 1e-13 where none is.
fn settings_from(args: &[String]) -> Vec<(String, Settings)> {
    let runs: Vec<(String, Settings)> = args
        .iter()
        .filter_map(|a| match a.as_str() {
            "default" => Some(("default".to_string(), settings())),
            "library" => Some(("library".to_string(), library_settings())),
            "double-double" => Some((
                "double-double".to_string(),
                Settings {
                    double_double: true,
                    ..library_settings()
                },
            )),
            "double" => Some((
                "double".to_string(),
                Settings {
                    double_double: false,
                    ..library_settings()
                },
            )),
            _ => match a.strip_prefix("e_tol=").and_then(|t| t.parse().ok()) {
                Some(t) => Some((
                    format!("e_tol={t:e}"),
                    Settings {
                        e_tol: Some(t),
                        ..settings()
                    },
                )),
                None => a.parse().ok().map(|r| (format!("{r:e}"), at(r, true))),
            },
        })
        .collect();
    if !runs.is_empty() {
        return runs;
    }
    let mut runs = vec![("default".to_string(), settings())];
    runs.extend([1e-11, 1e-12, 1e-13].map(|r| (format!("{r:e}"), at(r, true))));
    runs
}

/// The two reference sweeps: Verner's 9(8) at `fine` and Verner's 7(6) at `check`.
struct References {
    fine: Vec<Outcome>,
    check: Vec<Outcome>,
}

/// Counts the misses of the sweep `runs` of setting `name`, printing each if `list.0` and each
/// flagged run if `list.1`.
fn tally(name: &str, runs: &[Outcome], references: &References, list: (bool, bool)) -> Tally {
    let mut t = Tally::default();
    let pairs = references.fine.iter().zip(&references.check);
    for (i, (run, (f, c))) in runs.iter().zip(pairs).enumerate() {
        // Runs without `e_tol` are `Check::Off`: never flagged.
        let flagged = matches!(run.check, Some(Check::Unmet | Check::Unverified));
        let retry = run
            .double_double_declined
            .map_or(String::new(), |d| format!(": the retry {d}"));
        let (Some(e), Some(ef), Some(ec)) = (separated_e(run), separated_e(f), separated_e(c))
        else {
            if flagged && list.1 {
                bwc_app::out!(
                    "# {name} case {i}: flagged, {:?}, e {:?}, no reference (not counted) \
                     estimate {:?}{retry}",
                    run.check,
                    separated_e(run),
                    run.e_error
                );
            }
            continue;
        };
        t.separated += 1;
        t.flagged += usize::from(flagged);
        t.unverified += usize::from(run.check == Some(Check::Unverified));
        let miss = (e - ef).abs();
        if flagged && list.1 {
            bwc_app::out!(
                "# {name} case {i}: flagged, {:?}, e {e} reference {ef} ({miss:.1e} off) estimate \
                 {:?} double-double {}{retry}",
                run.check,
                run.e_error,
                run.double_double,
            );
        }
        if miss > MISS && (ec - ef).abs() < 0.1 * miss {
            let (miss, ef) = match referee(&run.case, library_settings().max_steps) {
                Some(e_dd) if (e - e_dd).abs() <= MISS => {
                    t.refereed += 1;
                    if list.0 {
                        bwc_app::out!(
                            "# {name} case {i}: e {e} misses the Runge-Kutta reference {ef} by \
                             {miss:.1e}, but the double-double referee {e_dd} by {:.1e}: not a miss",
                            (e - e_dd).abs()
                        );
                    }
                    continue;
                }
                Some(e_dd) => ((e - e_dd).abs(), e_dd),
                None => (miss, ef),
            };
            t.off += 1;
            t.off_series += usize::from(run.series);
            t.silent += usize::from(!flagged);
            t.largest = t.largest.max(miss);
            if list.0 {
                let case = &run.case;
                bwc_app::out!(
                    "# {name} case {i}: {:?} e {e} reference {ef} miss {miss:.1e} \
                     estimate {:?} tighter run failed {:?} series {} stiff {} input {:?} v0 {}",
                    case.kind,
                    run.e_error,
                    run.tighter_failed,
                    run.series,
                    run.switched,
                    case.input,
                    case.v0
                );
            }
        }
    }
    t
}

/// `e` of `case` by the double-double path at [`REFEREE_RTOLS`] with at most `max_steps` steps,
/// where both runs finish and agree to a tenth of [`MISS`]; `None` otherwise (no such path for
/// the model, a failure, or runs that disagree).
fn referee(case: &Case, max_steps: u64) -> Option<f64> {
    let settings = Settings {
        max_steps,
        ..library_settings()
    };
    let [a, b] = REFEREE_RTOLS.map(|rtol| {
        double_double_reference(case, rtol, &settings)
            .and_then(Result::ok)
            .map(|(e, _, _)| e)
    });
    let (a, b) = (a?, b?);
    ((a - b).abs() <= 0.1 * MISS).then_some(b)
}

/// One run at `rtol` (atol = rtol / 100, `e_tol` off) with the sweep's other settings.
fn at(rtol: f64, series: bool) -> Settings {
    Settings {
        rtol,
        atol: rtol / 100.0,
        series,
        e_tol: None,
        ..settings()
    }
}

/// The counts of one setting.
#[derive(Default)]
struct Tally {
    separated: usize,
    off: usize,
    off_series: usize,
    largest: f64,
    flagged: usize,
    silent: usize,
    unverified: usize,
    /// Misses of the Runge-Kutta references that the double-double referee overturned.
    refereed: usize,
}
