//! Global error control of a CoR evaluation ([`Settings::e_tol`]): the run at `rtol` checked
//! against the same impact at `TIGHTEN rtol` by another method ([`CHECK_METHOD`]), and tighter
//! runs ([`TIGHTER_METHOD`]) down to [`FLOOR_RTOL`] until two agree to `ACCEPT e_tol`; the
//! result says what the check found ([`Check`]).

use crate::impact::{simulate, Impact, Sampling, Settings};
use crate::models::CollisionModel;
use crate::precise::DdFailure;
use crate::series::Private;
use crate::ModelError;
use bwc_ode::{Extrapolation, Tableau, VERN7, VERN9};

/// A CoR evaluation under [`Settings::e_tol`] is accepted when its `e` differs from the check's
/// by at most this fraction of `e_tol`: where the check's error is the difference, the
/// reported run's is about a hundredth of it, and the margin covers runs whose error does not
/// fall in proportion to rtol (STABILITY.md).
const ACCEPT: f64 = 0.1;

/// The factor between the tolerances of successive runs under [`Settings::e_tol`]: the check
/// runs at `TIGHTEN rtol`, a tighter run at `rtol / TIGHTEN`.
pub const TIGHTEN: f64 = 100.0;

/// The tightest rtol [`Settings::e_tol`] goes down to: below it DOP853's and the series'
/// errors are those of rounding.
pub const FLOOR_RTOL: f64 = 1e-14;

/// The Runge-Kutta method of the run that checks a CoR under [`Settings::e_tol`] (at
/// `TIGHTEN rtol`): Verner's 9(8), another method than the default DOP853, so that an error a
/// method makes at every tolerance (DOP853's in steps limited by stability, say) shows as a
/// difference instead of passing the check (STABILITY.md, "Session 21").
pub const CHECK_METHOD: &Tableau = &VERN9;

/// The Runge-Kutta method of the tighter runs under [`Settings::e_tol`] (at `rtol / TIGHTEN`
/// and below): Verner's 7(6), which of the built-in methods comes closest to the truth at
/// rtol 1e-14 on the stress sweep's hardest runs; Verner's 9(8) there spends its steps on
/// rounding noise in its error estimate (STABILITY.md, "Session 21").
pub const TIGHTER_METHOD: &Tableau = &VERN7;

/// What the check of an impact under [`Settings::e_tol`] found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Check {
    /// Not checked: one run at `rtol` (no `e_tol`, or a sampled run), without an estimate.
    Off,
    /// The estimate `e_error` is at most `e_tol`.
    Met,
    /// The estimate `e_error` stayed above `e_tol`: the tightest run (rtol 1e-14) still
    /// differed from the one before it, or a tighter run failed ([`Impact::tighter_failed`]).
    Unmet,
    /// No run at another tolerance finished (the check at `100 rtol` failed, and so did the
    /// run at `rtol / 100` or it was below 1e-14): `e` is one unchecked run at `rtol`.
    Unverified,
}

/// A run under [`Settings::e_tol`] tighter than the reported one that failed, so that the
/// check stopped there ([`Impact::tighter_failed`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FailedRun {
    /// Its relative tolerance.
    pub rtol: f64,
    /// Whether it needed more than [`Settings::max_steps`] steps (a larger `max_steps` lets it
    /// finish); `false` for another failure (a step size too small, a non-finite state).
    pub out_of_steps: bool,
}

impl Check {
    /// The name in outputs: `"off"`, `"met"`, `"unmet"` or `"unverified"`.
    pub fn name(self) -> &'static str {
        match self {
            Check::Off => "off",
            Check::Met => "met",
            Check::Unmet => "unmet",
            Check::Unverified => "unverified",
        }
    }
}

/// Coefficient of restitution, separation time and statistics of one impact, under
/// [`Settings::e_tol`] checked against runs at other tolerances; stores nothing and allocates
/// nothing. Under [`Settings::phase`] an unforced impact of a model with that path is first
/// tried there ([`crate::phase`], [`Impact::phase`]).
///
/// # Errors
/// As [`simulate`]. Under [`Settings::e_tol`], a failure of the first run at `rtol` (the check
/// at `100 rtol` counts as a differing run); a failure of a tighter run returns the run before
/// it, with its estimate.
pub fn impact<M: CollisionModel<N>, const N: usize>(
    model: &M,
    settings: &Settings,
) -> Result<Impact<N>, ModelError> {
    if let Some(out) = settings
        .phase
        .then(|| model.phase_impact(Private(()), settings))
        .flatten()
    {
        return Ok(out);
    }
    let Some(e_tol) = settings.e_tol else {
        return simulate(model, settings, Sampling::None, |_, _| {});
    };
    settings.validate()?;
    let run = |method: &'static Tableau, rtol: f64| {
        let at = Settings {
            method,
            rtol,
            atol: settings.atol * (rtol / settings.rtol),
            e_tol: None,
            ..*settings
        };
        simulate(model, &at, Sampling::None, |_, _| {})
    };
    let check = run(CHECK_METHOD, TIGHTEN * settings.rtol).ok();
    let mut out = run(settings.method, settings.rtol)?;
    let mut work = out.stats;
    if let Some(c) = &check {
        work += c.stats;
        estimate(&mut out, c);
    }
    let mut rtol = settings.rtol;
    let mut failed = None;
    while !out.e_error.is_some_and(|d| d <= ACCEPT * e_tol) && rtol > FLOOR_RTOL {
        rtol = tighter(rtol);
        let mut next = match run(TIGHTER_METHOD, rtol) {
            Ok(next) => next,
            Err(err) => {
                failed = Some(FailedRun {
                    rtol,
                    out_of_steps: out_of_steps(&err),
                });
                break;
            }
        };
        work += next.stats;
        estimate(&mut next, &out);
        out = next;
    }
    out.tighter_failed = failed;
    out.check = verdict(out.e_error, e_tol);
    // Two runs that did not agree to `ACCEPT e_tol` by the floor (or up to a failed tighter
    // run) are both about as far off as their difference, or farther where rounding decides
    // the digits: their difference no longer bounds the error (case 15913 of the stress
    // sweep's seed 9: rtol 1e-12 and 1e-14 agree to 5e-11, both 6e-10 off; STABILITY.md,
    // "Session 27"). So every run with an estimate that did not settle is retried, met or not.
    let unsettled = out.e_error.is_some_and(|d| d > ACCEPT * e_tol);
    if unsettled && settings.double_double {
        // Where even the tightest run went stiff: the double-double path is explicit. (A
        // looser run can switch where the tightest does not: case 3373 of seed 2.)
        let retry = match out.stiff_from {
            Some(from) => Err(DdDeclined::Stiff { from }),
            None => double_double(model, settings, e_tol, &mut work),
        };
        match retry {
            Ok(precise) => return Ok(precise),
            // A run whose estimate is within `e_tol` stays met, as it was before the retry.
            Err(why) if out.check == Check::Unmet => out.double_double_declined = Some(why),
            Err(_) => {}
        }
    }
    out.stats = work;
    Ok(out)
}

/// What an estimate says against `e_tol`.
fn verdict(e_error: Option<f64>, e_tol: f64) -> Check {
    match e_error {
        None => Check::Unverified,
        Some(d) if d <= e_tol => Check::Met,
        Some(_) => Check::Unmet,
    }
}

/// The tolerances of the double-double runs ([`Settings::double_double`]), in turn until one
/// agrees with the run before it to `e_tol`; that one is reported. On the stress sweep's runs
/// that double precision cannot settle, rtol 1e-16 gets `e` to about 1e-13 and 1e-18 to about
/// 1e-15, except on a few long forced contacts where 1e-16 is off by 1e-10 and the third run
/// settles it; at 1e-14 the steps can pass over a pair of kinks and miss `e` by 7e-9
/// (STABILITY.md, "Session 23" and "Session 25").
pub const DOUBLE_DOUBLE_RTOLS: [f64; 3] = [1e-16, 1e-18, 1e-20];

/// A double-double run after the first may take at most this many times the accepted steps of
/// the run before it (plus [`DD_STEP_SLACK`]). An extrapolation of order 16 needs about
/// `100^(1/16)` = 1.33 times the steps at a hundredth of the tolerance, and the stress sweep's
/// runs take 1.1 to 1.6 times; a run that needs far more is not in that regime, and its
/// result would be refused after a long wait (case 5523 of seed 3: 257 steps at rtol 1e-16,
/// 326,460 and 45 s at 1e-18; STABILITY.md, "Session 25").
pub const DD_STEP_GROWTH: u64 = 8;

/// The steps a double-double run after the first may take beyond [`DD_STEP_GROWTH`] times
/// the run before it, so that short runs are not held to a few steps.
pub const DD_STEP_SLACK: u64 = 1_000;

/// Why the double-double retry ([`Settings::double_double`]) of a CoR whose check stayed
/// [`Check::Unmet`] reported nothing ([`Impact::double_double_declined`]); the reported `e` is
/// then the double-precision one, flagged.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum DdDeclined {
    /// The reported double-precision run (the tightest) switched to RODAS4 at `from` (model
    /// time units; [`Impact::stiff_from`]): the double-double path is explicit, and on such
    /// runs its error estimate does not hold (on three seeds of the stress sweep it settled
    /// none of the five, after up to 139 s; STABILITY.md, "Session 25"). Not tried.
    Stiff {
        /// When the run switched.
        from: f64,
    },
    /// The model, or its input, has no double-double form ([`impact_double_double`]).
    NoPath,
    /// The run at `rtol` stopped short of the separation.
    Failed {
        /// Its relative tolerance.
        rtol: f64,
        /// Why.
        failure: DdFailure,
    },
    /// The run at `rtol` needed more than [`DD_STEP_GROWTH`] times the steps of the run before
    /// it (`steps_before`, plus [`DD_STEP_SLACK`]): it is not in the regime where a tighter
    /// tolerance costs a few more steps, and its result would not be trusted.
    StepsGrew {
        /// Its relative tolerance.
        rtol: f64,
        /// The accepted steps of the run before it.
        steps_before: u64,
    },
    /// The last two runs (the tightest at rtol 1e-20) still differ by `e_error`, more than
    /// `e_tol`.
    Disagreed {
        /// Their difference in `e`.
        e_error: f64,
    },
}

impl DdDeclined {
    /// The name in outputs: `"stiff"`, `"no-path"`, `"failed"`, `"steps-grew"` or
    /// `"disagreed"`.
    pub fn name(self) -> &'static str {
        match self {
            DdDeclined::Stiff { .. } => "stiff",
            DdDeclined::NoPath => "no-path",
            DdDeclined::Failed { .. } => "failed",
            DdDeclined::StepsGrew { .. } => "steps-grew",
            DdDeclined::Disagreed { .. } => "disagreed",
        }
    }
}

/// A predicate of "the double-double retry", as the command-line tools print it.
impl std::fmt::Display for DdDeclined {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            DdDeclined::Stiff { .. } => write!(
                f,
                "was not tried: the tightest double-precision run went stiff (it switched to \
                 RODAS4), where the explicit double-double steps are not reliable"
            ),
            DdDeclined::NoPath => write!(
                f,
                "is not possible: the model or its input has no double-double form"
            ),
            DdDeclined::Failed { rtol, failure } => {
                write!(f, "failed at rtol {rtol:e}: {failure}")
            }
            DdDeclined::StepsGrew { rtol, steps_before } => write!(
                f,
                "was stopped: its run at rtol {rtol:e} needed more than {DD_STEP_GROWTH} times \
                 the {steps_before} steps of the run before it"
            ),
            DdDeclined::Disagreed { e_error } => write!(
                f,
                "did not settle it: its runs down to rtol {:e} still differ by {e_error:.1e} in e",
                DOUBLE_DOUBLE_RTOLS[DOUBLE_DOUBLE_RTOLS.len() - 1]
            ),
        }
    }
}

/// One run of the double-double path ([`Settings::double_double`]) at `rtol` (`atol` scaled
/// as `settings.atol / settings.rtol`), with `settings.max_steps` and `settings.t_max`; `None`
/// where `model` has no such path (the nondimensional and SI models, [`crate::Ndbwshccm`],
/// [`crate::Ndbwmcm`], [`crate::Bwshccm`] and [`crate::Bwmcm`], have it under an input with
/// [`crate::input::Input::at_dd`]). For references: its statistics are its own.
///
/// # Errors
/// [`DdFailure`] where the run does not reach the separation.
pub fn impact_double_double<M: CollisionModel<N>, const N: usize>(
    model: &M,
    rtol: f64,
    settings: &Settings,
) -> Option<Result<Impact<N>, DdFailure>> {
    let ext = Extrapolation::new(rtol, settings.atol * (rtol / settings.rtol));
    model.double_double_impact(Private(()), ext, settings)
}

/// The impact in double-double arithmetic: runs at [`DOUBLE_DOUBLE_RTOLS`] in turn until one
/// agrees with the one before it to `e_tol`, each after the first held to
/// [`DD_STEP_GROWTH`] times its predecessor's steps. `work` (the double-precision runs' cost)
/// gains every finished run's statistics, and is the reported run's.
fn double_double<M: CollisionModel<N>, const N: usize>(
    model: &M,
    settings: &Settings,
    e_tol: f64,
    work: &mut bwc_ode::Stats,
) -> Result<Impact<N>, DdDeclined> {
    let mut before: Option<Impact<N>> = None;
    for rtol in DOUBLE_DOUBLE_RTOLS {
        let limit = before
            .as_ref()
            .map(|b| DD_STEP_GROWTH * b.stats.accepted + DD_STEP_SLACK);
        let at = Settings {
            max_steps: limit.map_or(settings.max_steps, |l| l.min(settings.max_steps)),
            ..*settings
        };
        let mut out = match impact_double_double(model, rtol, &at).ok_or(DdDeclined::NoPath)? {
            Ok(out) => out,
            Err(DdFailure::TooManySteps) if at.max_steps < settings.max_steps => {
                let steps_before = before.map_or(0, |b| b.stats.accepted);
                return Err(DdDeclined::StepsGrew { rtol, steps_before });
            }
            Err(failure) => return Err(DdDeclined::Failed { rtol, failure }),
        };
        *work += out.stats;
        if let Some(b) = &before {
            estimate(&mut out, b);
            // The reported `e` is rounded to double precision: its error is at least that
            // rounding, even where both runs round to the same double.
            out.e_error = out.e_error.map(|d| d.max(0.5 * f64::EPSILON * out.e.abs()));
            out.check = verdict(out.e_error, e_tol);
            if out.check == Check::Met {
                out.stats = *work;
                return Ok(out);
            }
        }
        before = Some(out);
    }
    let e_error = before.and_then(|b| b.e_error).unwrap_or(f64::NAN);
    Err(DdDeclined::Disagreed { e_error })
}

/// Whether `err` is a run that needed more than [`Settings::max_steps`] steps.
fn out_of_steps(err: &ModelError) -> bool {
    matches!(
        err,
        ModelError::Solver(bwc_events::Error::Solver(
            bwc_ode::Error::TooManySteps { .. }
        ))
    )
}

/// The tolerance of the run after one at `rtol` under [`Settings::e_tol`]: `rtol / TIGHTEN`,
/// or [`FLOOR_RTOL`] where that would pass it (so a chain of runs from any `rtol` ends on the
/// floor, not short of it).
pub fn tighter(rtol: f64) -> f64 {
    (rtol / TIGHTEN).max(FLOOR_RTOL)
}

/// Sets `out`'s error estimates from the run `before` it, at a looser tolerance. Runs that
/// differ in outcome differ by `e` itself.
fn estimate<const N: usize>(out: &mut Impact<N>, before: &Impact<N>) {
    out.e_error = Some(if out.separated() == before.separated() {
        (out.e - before.e).abs()
    } else {
        out.e.max(before.e)
    });
    out.t_s_error = before.t_s.zip(out.t_s).map(|(a, c)| (a - c).abs());
}

#[cfg(test)]
mod tests;
