//! A CoR evaluation ([`impact`]): the cascade of paths that serves it and the checks that say
//! how far its `e` can be trusted. In turn:
//!
//! 1. **The phase path** ([`Settings::phase`]; unforced impacts of the built-in models): `e` and
//!    `t_s` as quadratures in phase space, taken where the path applies and its own check is
//!    met.
//! 2. **One run** at `rtol` ([`simulate`]: the Taylor series between the non-smooth points where
//!    the model and its input allow, [`Settings::series`], handing over to the Runge-Kutta path
//!    where they do not); without [`Settings::e_tol`] that run is the result.
//! 3. **The checking ladder** under [`Settings::e_tol`] ([`Ladder`](crate::Ladder)): the run at `rtol` against
//!    a check at `tighten * rtol` by another method, then tighter runs down to the floor until
//!    two agree; the result says what the check found ([`Check`]).
//! 4. **The double-double retry** ([`Settings::double_double`]) where the ladder does not
//!    settle, or [`DdDeclined`] saying why not.
//!
//! Nothing here stores a trajectory or allocates.

use crate::error::ModelError;
use crate::fast_paths;
use crate::input::{Input, Scaled};
use crate::models::{CollisionModel, Ndbwmcm, Ndbwshccm};
use crate::outcome::DdFailure;
use crate::outcome::{Check, Cor, DdDeclined, FailedRun, Impact};
use crate::params::ModelKind;
use crate::scaling::BaseMap;
use crate::settings::{Settings, LADDER};
use crate::simulate::{simulate, Sampling};
use bwc_ode::{Extrapolation, Stats, Tableau};

/// Coefficient of restitution, separation time and statistics of one impact, under
/// [`Settings::e_tol`] checked against runs at other tolerances; stores nothing and allocates
/// nothing. Under [`Settings::phase`] an unforced impact of a model with that path is first
/// tried there ([`crate::phase`], [`Impact::phase`]). The steps are those of the module's
/// documentation.
///
/// # Errors
/// As [`simulate`]. Under [`Settings::e_tol`], a failure of the first run at `rtol` (the check
/// at `tighten * rtol` counts as a differing run); a failure of a tighter run returns the run
/// before it, with its estimate.
pub fn impact<M: CollisionModel<N>, const N: usize>(
    model: &M,
    settings: &Settings,
) -> Result<Impact<N>, ModelError> {
    if settings.phase {
        if let Some(out) = fast_paths::phase(model, settings) {
            return Ok(out);
        }
    }
    let Some(e_tol) = settings.e_tol else {
        return simulate(model, settings, Sampling::None, |_, _| {});
    };
    settings.validate()?;
    checked(&ModelRuns(model), settings, e_tol)
}

/// One impact of the nondimensional model `P(P*, u, v0)`: parameters from the base map and the
/// physical input `u(t)` (N) rescaled to `U(T)`. Times in the result are nondimensional;
/// multiply by [`BaseMap::time_scale`] for seconds (`Θ_2`, eq:Theta_2). `e` is `Θ_1`.
///
/// # Errors
/// As [`BaseMap::at`] and [`impact`].
pub fn impact_at<I: Input>(
    map: &BaseMap,
    u: I,
    v0: f64,
    settings: &Settings,
) -> Result<Cor, ModelError> {
    let (nd, s) = map.at(v0)?;
    let input = Scaled {
        inner: u,
        factor: s.factor,
        time_scale: s.time_scale,
    };
    match map.kind() {
        ModelKind::Shccm => impact(&Ndbwshccm::new(&nd, input)?, settings).map(|i| i.cor()),
        ModelKind::Mcm => impact(&Ndbwmcm::new(&nd, input)?, settings).map(|i| i.cor()),
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
    fast_paths::double_double(model, ext, settings)
}

/// The runs the checks ask for: the one run of step 2 at other settings, and one
/// double-double run. A seam for the tests, which script them.
pub(crate) trait Runs<const N: usize> {
    /// One run at `settings` (no `e_tol`).
    fn run(&self, settings: &Settings) -> Result<Impact<N>, ModelError>;
    /// One double-double run at `rtol` (as [`impact_double_double`]).
    fn double_double(&self, rtol: f64, settings: &Settings)
        -> Option<Result<Impact<N>, DdFailure>>;
}

/// A model's runs.
struct ModelRuns<'a, M>(&'a M);

impl<M: CollisionModel<N>, const N: usize> Runs<N> for ModelRuns<'_, M> {
    fn run(&self, settings: &Settings) -> Result<Impact<N>, ModelError> {
        simulate(self.0, settings, Sampling::None, |_, _| {})
    }
    fn double_double(
        &self,
        rtol: f64,
        settings: &Settings,
    ) -> Option<Result<Impact<N>, DdFailure>> {
        impact_double_double(self.0, rtol, settings)
    }
}

/// Steps 3 and 4: the ladder, then the double-double retry where it did not settle.
pub(crate) fn checked<R: Runs<N>, const N: usize>(
    runs: &R,
    settings: &Settings,
    e_tol: f64,
) -> Result<Impact<N>, ModelError> {
    let (mut out, mut work) = ladder(runs, settings, e_tol)?;
    // Two runs that did not agree to `accept e_tol` by the floor (or up to a failed tighter
    // run) are both about as far off as their difference, or farther where rounding decides
    // the digits: their difference no longer bounds the error (on the stress sweep, rtol 1e-12
    // and 1e-14 agreeing to 5e-11, both 6e-10 off). So every run with an estimate that did not
    // settle is retried, met or not.
    let unsettled = out.e_error.is_some_and(|d| d > LADDER.accept * e_tol);
    if unsettled && settings.double_double {
        // Where even the tightest run went stiff: the double-double path is explicit. (A
        // looser run can switch where the tightest does not.)
        let retry = match out.stiff_from {
            Some(from) => Err(DdDeclined::Stiff { from }),
            None => double_double(runs, settings, e_tol, &mut work),
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

/// Step 3: the run at `rtol` checked against the run at `tighten * rtol` by the check method,
/// then tighter runs until two agree to `accept e_tol` or the floor is reached. The last run
/// with its estimate and verdict, and the work of every run.
fn ladder<R: Runs<N>, const N: usize>(
    runs: &R,
    settings: &Settings,
    e_tol: f64,
) -> Result<(Impact<N>, Stats), ModelError> {
    let run = |method: &'static Tableau, rtol: f64| {
        runs.run(&Settings {
            method,
            rtol,
            atol: settings.atol * (rtol / settings.rtol),
            e_tol: None,
            ..*settings
        })
    };
    let check = run(LADDER.check_method, LADDER.tighten * settings.rtol).ok();
    let mut out = run(settings.method, settings.rtol)?;
    let mut work = out.stats;
    if let Some(c) = &check {
        work += c.stats;
        estimate(&mut out, c);
    }
    let mut rtol = settings.rtol;
    let mut failed = None;
    while !out.e_error.is_some_and(|d| d <= LADDER.accept * e_tol) && rtol > LADDER.floor_rtol {
        rtol = LADDER.tighter(rtol);
        let mut next = match run(LADDER.tighter_method, rtol) {
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
    Ok((out, work))
}

/// What an estimate says against `e_tol`.
fn verdict(e_error: Option<f64>, e_tol: f64) -> Check {
    match e_error {
        None => Check::Unverified,
        Some(d) if d <= e_tol => Check::Met,
        Some(_) => Check::Unmet,
    }
}

/// The impact in double-double arithmetic: runs at [`Ladder::double_double_rtols`](crate::Ladder::double_double_rtols) in turn
/// until one agrees with the one before it to `e_tol`, each after the first held to
/// [`Ladder::dd_step_limit`](crate::Ladder::dd_step_limit) of its predecessor's steps. `work` (the double-precision runs' cost)
/// gains every finished run's statistics, and is the reported run's.
fn double_double<R: Runs<N>, const N: usize>(
    runs: &R,
    settings: &Settings,
    e_tol: f64,
    work: &mut bwc_ode::Stats,
) -> Result<Impact<N>, DdDeclined> {
    let mut before: Option<Impact<N>> = None;
    for rtol in LADDER.double_double_rtols {
        let limit = before
            .as_ref()
            .map(|b| LADDER.dd_step_limit(b.stats.accepted));
        let at = Settings {
            max_steps: limit.map_or(settings.max_steps, |l| l.min(settings.max_steps)),
            ..*settings
        };
        let mut out = match runs.double_double(rtol, &at).ok_or(DdDeclined::NoPath)? {
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
