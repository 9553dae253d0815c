//! What a scene's runs say beyond their numbers, as values a front end prints or raises: per
//! run ([`run_notes`]: failures with their reason, horizons with the setting that moves them,
//! settled contacts with their force balance, CoRs whose check against `e_tol` was not met),
//! per study ([`study_notes`]: interpolated runs, sweeps that found no interpolant) and one per
//! kind for all runs ([`kind_notes`], for front ends that warn once a kind).

use super::runs::{Outcome, Run};
use super::scene::Scene;
use super::simulate::Tally;
use crate::format::tidy;
use bw_models::{Check, ModelKind, LADDER};

/// A note on a run: a warning (the result is not what was asked for) or information.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Note {
    /// Something the user should act on, with the setting that would help.
    Warning(String),
    /// What happened, for the record.
    Info(String),
}

/// The notes on run `r` of `scene`, each naming the run.
pub fn run_notes(scene: &Scene, r: &Run) -> Vec<Note> {
    let label = match r.label().as_str() {
        "run" => "the run".to_string(),
        l => format!("run {l}"),
    };
    match r.outcome {
        Outcome::Separated => unmet_e_tol(scene, &label, r).into_iter().collect(),
        Outcome::Failed => vec![Note::Info(format!(
            "{label} failed: {}",
            r.error.as_deref().unwrap_or("unknown error")
        ))],
        Outcome::Horizon => vec![Note::Warning(horizon(scene, &label, r))],
        Outcome::Settled => (r.rest.iter())
            .map(|q| {
                Note::Info(format!(
                    "{label}: the contact settled at t = {:.6e} ({}): at rest with F = {:.6e} \
                     balancing u = {:.6e}; it never separates",
                    q.t, r.time_unit, q.f, q.u
                ))
            })
            .collect(),
    }
}

/// A run that met the horizon: when, and why where the BWMCM's dashpot yields.
fn horizon(scene: &Scene, label: &str, r: &Run) -> String {
    let t_max = scene.settings.t_max;
    let when = match r.t_c {
        Some(t_c) if r.time_unit == "s" => format!(
            "t_max = {t_max} T_c = {:.6e} s (T_c = {t_c:.6e} s)",
            t_max * t_c
        ),
        _ => format!("t_max = {t_max} (nondimensional)"),
    };
    // A BWMCM whose series dashpot is soft against the contact (σ = m / (c T_c) large) lets
    // the bodies creep together instead of rebounding.
    let sigma = r.nondimensional.map(|q| q.sigma).filter(|s| *s > 1.0);
    let why = match sigma {
        Some(s) if r.model == ModelKind::Mcm => format!(
            "; the series dashpot yields (sigma = m / (c T_c) = {s:.3e} > 1): a larger c makes \
             the contact spring back"
        ),
        _ => String::new(),
    };
    format!("{label}: no separation by {when}: the horizon came first; raise [solver].t_max{why}")
}

/// Where a checked CoR's own error estimate stayed above `[solver].e_tol`, or where no run at
/// another tolerance could check it.
fn unmet_e_tol(scene: &Scene, label: &str, r: &Run) -> Option<Note> {
    let (e_tol, c) = (scene.settings.e_tol?, r.solver.as_ref()?);
    let (check, rtol) = (c.check, c.rtol);
    // Why no tighter run settled it, and the setting that would let one finish.
    let stop = match c.tighter_failed {
        Some(f) if f.out_of_steps => format!(
            "the run at rtol {:e} needed more than [solver].max_steps = {} steps; a larger \
             max_steps lets it finish",
            tidy(f.rtol),
            scene.settings.max_steps
        ),
        Some(f) => format!("the run at rtol {:e} failed", tidy(f.rtol)),
        None => format!("rtol {:e} is the tightest", LADDER.floor_rtol),
    };
    match (check, c.e_error) {
        (Check::Unmet, Some(estimate)) => {
            let retry = match c.double_double_declined {
                Some(why) => format!("; the double-double retry ([solver] double_double) {why}"),
                None => String::new(),
            };
            Some(Note::Warning(format!(
                "{label}: e at rtol {:e} differs by {estimate:.1e} from the same impact at a \
                 looser rtol, more than [solver].e_tol = {e_tol:e}, and no tighter run was \
                 possible ({stop}){retry}: take e as known to about {estimate:.0e}",
                tidy(rtol)
            )))
        }
        (Check::Unverified, _) => {
            let tighter = if rtol > LADDER.floor_rtol {
                format!("so did the tighter one ({stop})")
            } else {
                format!(
                    "rtol is at the floor, {:e}, with no tighter run",
                    LADDER.floor_rtol
                )
            };
            Some(Note::Warning(format!(
                "{label}: e is one unchecked run at rtol {rtol:e}: the check against \
                 [solver].e_tol = {e_tol:e} failed at rtol {check:e}, and {tighter}; [solver] \
                 method = \"{method}\", rtol = {check:e} with e_tol = 0 shows why the check \
                 failed",
                check = tidy(LADDER.tighten * rtol),
                method = LADDER.check_method.name.to_lowercase()
            )))
        }
        _ => None,
    }
}

/// The notes on a whole study: how many runs came from interpolants, and why a sweep found
/// none.
pub fn study_notes(scene: &Scene, tally: &Tally) -> Vec<String> {
    let mut notes = Vec::new();
    if tally.interpolated > 0 {
        notes.push(format!(
            "{} of {} runs took e and t_s from interpolants in ln v0 verified against \
             simulations (largest error estimate {:.1e}, [sweep].tolerance {:e}); [sweep] \
             interpolate = false simulates every speed",
            tally.interpolated, tally.runs, tally.largest_estimate, scene.sweep.tolerance
        ));
    }
    notes.extend(tally.no_interpolant_notes(scene));
    notes
}

/// One note a kind for all of a scene's runs (a sweep may have thousands): the scene's hints,
/// a sweep that found no interpolant, runs that met the horizon, and CoRs whose check against
/// `e_tol` was not met.
pub fn kind_notes(scene: &Scene, runs: &[Run]) -> Vec<String> {
    let mut notes = scene.hints.clone();
    notes.extend(Tally::of(scene, runs).no_interpolant_notes(scene));
    let n = runs.len();
    let (k, labels) = labels_of(runs, |r| r.outcome == Outcome::Horizon);
    if k > 0 {
        notes.push(format!(
            "{k} of {n} runs did not separate by [solver].t_max = {} (outcome \"horizon\", e = \
             0: {labels}): the horizon came first; raise [solver].t_max",
            scene.settings.t_max
        ));
    }
    let unmet = |r: &Run| {
        r.outcome == Outcome::Separated
            && matches!(
                r.solver.map(|c| c.check),
                Some(Check::Unmet | Check::Unverified)
            )
    };
    let (k, labels) = labels_of(runs, unmet);
    if k > 0 {
        notes.push(format!(
            "{k} of {n} CoRs did not meet [solver].e_tol = {:e} (check \"unmet\" or \
             \"unverified\": {labels}): e_error says how well each e is known (NaN where \
             unverified), and bwc-simulate on the same scene says why for each",
            scene.settings.e_tol.unwrap_or(0.0)
        ));
    }
    notes
}

/// How many runs `keep` picks, and the labels of the first three.
fn labels_of(runs: &[Run], keep: impl Fn(&Run) -> bool) -> (usize, String) {
    let picked: Vec<String> = runs.iter().filter(|r| keep(r)).map(|r| r.label()).collect();
    let more = if picked.len() > 3 { "; ..." } else { "" };
    (
        picked.len(),
        format!("{}{more}", picked[..picked.len().min(3)].join("; ")),
    )
}
