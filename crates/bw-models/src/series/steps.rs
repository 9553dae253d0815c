//! The control of the series steps (their tolerances, growth and limits) and the steps the
//! explicit method takes for them where a base vanishes: off such a point, and onto a root.

use crate::models::CollisionModel;
use crate::settings::Settings;
use bwc_ode::{Integrator, Options, State, Stats};

/// The series steps are controlled with this multiple of the settings' tolerances: the
/// truncation error of a step is well below Jorba & Zou's estimate (the last term); at
/// `10 rtol` the errors in `e` and `T_s` are at most those of the Runge-Kutta path at `rtol`
/// on the benchmark's cases (BENCHMARKS.md) and within a few times them on random parameters
/// (tested).
pub const TOLERANCE_SCALE: f64 = 10.0;

/// The start steps leave a point where the right-hand side is only finitely smooth (`C^1` for
/// exponents near 1), where the error estimate of a Runge-Kutta step is least reliable: they
/// run at this multiple of the settings' tolerances.
pub const START_TOLERANCE: f64 = 0.01;

/// Largest ratio of a series step to the step before it. Next to a point where a base vanished,
/// the coefficients up to the order can be nearly those of a polynomial while the orders beyond
/// it are not (`|X|^p` with `X = -T + O(T^(p+2))`): the estimate alone would then jump far
/// ahead (measured: a hundredfold, with a local error of 2e-7 at rtol 1e-11, p = 10).
pub const MAX_GROWTH: f64 = 2.0;

/// The logarithmic steps off a zero of a base end after one spanning less than this in
/// `σ = ln(T - T_a)` (a growth of `e` in `T - T_a`): from there on the steps are bounded by the
/// solution's other singularities, not by the branch point at `T_a`, and a step in time, with no
/// products by `dT/dσ`, costs less. Chosen on the search box of the fits and Table 3's DSA (1)
/// (BENCHMARKS.md, "One CoR: the series path").
pub const LOG_STEP_MIN: f64 = 1.0;

/// Most series steps of one impact before it is handed to the Runge-Kutta path.
pub const MAX_SERIES_STEPS: u64 = 150;

/// Where the force's series is farther than this multiple of the step's tolerance from zero,
/// its sign is taken from the series (whose error is about the tolerance); nearer, the force is
/// computed from the state.
pub const FORCE_MARGIN: f64 = 1e3;

/// Most event steps in a row that leave the time where it was (the state sliding along a
/// switching surface, e.g. the MCM creeping with `Y' = 0` under a pull) before the impact is
/// handed to the Runge-Kutta path, whose stops at the kinks and RODAS4 handle such runs.
pub const MAX_STALLED: u32 = 2;

/// The local tolerance of a series step from `y`: `TOLERANCE_SCALE (atol + rtol |y|_∞)`.
pub(super) fn step_tolerance<const N: usize>(y: &State<N>, settings: &Settings) -> f64 {
    TOLERANCE_SCALE * (settings.atol + settings.rtol * y.amax())
}

/// One step of the settings' explicit method from `(t, y)`, where a base vanishes, at
/// [`START_TOLERANCE`] times the settings' tolerances. There the solution's leading non-smooth
/// terms are `τ^q` (`q = e + 1` for the exponent `e` of a power of a vanishing base: `Z`
/// gains `τ^(n+1)`, `V` gains `τ^(p+1)`), and a Runge-Kutta step's error scales as `h^q`
/// whatever the method's order: after a rejected trial the next is sized by that exponent
/// (`h (0.9 / err)^(1/q)`), not by the method's order, which would shrink it only by its
/// controller's limit per trial (measured: 8-9 rejections where `n` is near 1).
pub(super) fn start_step<M: CollisionModel<N>, const N: usize>(
    model: &M,
    settings: &Settings,
    (t, y): (f64, &State<N>),
    q: f64,
    stats: &mut Stats,
) -> Option<(f64, State<N>)> {
    let (rtol, atol) = (
        START_TOLERANCE * settings.rtol,
        START_TOLERANCE * settings.atol,
    );
    let options = Options::new(rtol, atol).with_max_step(settings.max_step);
    let rhs = |t: f64, y: &State<N>| model.rhs(t, y);
    let mut it = Integrator::new(rhs, settings.method, t, *y, options).ok()?;
    it.step_aiming(settings.t_max, |trial| {
        let ratio = (0.9 / trial.error).powf(1.0 / q).clamp(1e-4, 0.5);
        ratio
            .is_finite()
            .then_some(trial.t0 + ratio * (trial.t1 - trial.t0))
    })
    .ok()?;
    *stats += it.stats();
    Some((it.t(), *it.y()))
}

/// What [`reach_root`] closes in on.
#[derive(Clone, Copy)]
pub(super) enum Target {
    /// A state component, set to exactly zero at its root.
    Component(usize),
    /// The contact force.
    Force,
}

/// First step of a repeated [`reach_root`] run, as a fraction of its span: a series step of
/// order 16 spans about `tol^(1/16 - 1/8)` (3-6) Runge-Kutta steps of order 8 at rtol 1e-8 ...
/// 1e-12, and a first step of an eighth lets the run find its own.
pub(super) const RETRY_SPAN: f64 = 0.125;

/// Largest step along `f` onto a root after [`reach_root`]'s Runge-Kutta run, as a fraction of
/// that run's span.
const NEWTON_SPAN: f64 = 1e-2;

/// From `start`, the explicit method of the settings up to `t1`, where the series put a root of
/// `target`, with first trial step `h0`; then one Newton step along `f` onto the root (declined
/// unless it is tiny, or small against the span and accurate by an estimate of its error: an
/// ill-conditioned root is left to the Runge-Kutta path).
pub(super) fn reach_root<M: CollisionModel<N>, const N: usize>(
    model: &M,
    settings: &Settings,
    (start, t1): ((f64, &State<N>), f64),
    target: Target,
    h0: f64,
    stats: &mut Stats,
) -> Option<(f64, State<N>)> {
    let (t0, y0) = start;
    let options = Options::new(settings.rtol, settings.atol)
        .with_max_step(settings.max_step)
        .with_h0(h0);
    let rhs = |t: f64, y: &State<N>| model.rhs(t, y);
    let mut it = Integrator::new(rhs, settings.method, t0, *y0, options).ok()?;
    it.integrate_to(t1).ok()?;
    *stats += it.stats();
    let (mut y, f) = (*it.y(), *it.derivative());
    let dt = match target {
        Target::Component(i) => -y[i] / f[i],
        Target::Force => {
            // dF/dt along the flow by a central difference.
            let d = 1e-7 * (t1 - t0);
            let slope = (model.force(&(y + f * d)) - model.force(&(y - f * d))) / (2.0 * d);
            -model.force(&y) / slope
        }
    };
    // The error of the step along f, about dt^2 |y''| / 2, is below 1e-12 |y''| (t1 - t0)^2
    // where dt is tiny. At loose tolerances the Runge-Kutta end is off the root by about its
    // tolerance: there the error is estimated from the change of f over the step and kept below
    // START_TOLERANCE times the local tolerance. A step that is not small against the span
    // (a root where the target's slope is small, ill-conditioned) is left to the Runge-Kutta
    // path.
    let tiny = dt.abs() <= 1e-6 * (t1 - t0);
    if !tiny {
        // False for a NaN step (a force that vanishes with its slope).
        let small = dt.abs() <= NEWTON_SPAN * (t1 - t0);
        if !small {
            return None;
        }
        let f1 = model.rhs(t1 + dt, &(y + f * dt));
        stats.rhs_evals += 1;
        let error = ((f1 - f) * (0.5 * dt)).amax();
        let accurate = error <= START_TOLERANCE * (settings.atol + settings.rtol * y.amax());
        if !accurate {
            return None;
        }
    }
    y += f * dt;
    if let Target::Component(i) = target {
        y[i] = 0.0;
    }
    Some((t1 + dt, y))
}
