//! Taylor-series integration of one impact of the nondimensional models under a constant input:
//! the fast path of a CoR evaluation ([`crate::Settings::series`]).
//!
//! Between the non-smooth points each right-hand side is analytic in its branch (fixed signs of
//! `X` or `Y`, of `Z` and of the rate across the hysteretic element), so the solution is
//! expanded about the start of each step in its Taylor series of order [`ORDER`], computed by
//! automatic differentiation: the coefficients of `y = b^e` (`|X|^p`, `|Z|^n`, `|Z|^p`) follow
//! from `b y' = e b' y`,
//!
//! `y_k = (1 / (k b_0)) Σ_{i<k} (e (k - i) - i) b_{k-i} y_i`,
//!
//! and products by the Cauchy rule (Jorba & Zou, Experiment. Math. 14 (2005) 99-117). The step
//! is Jorba & Zou's, `h = 0.9 min_k ρ_k` over the last [`ESTIMATE_TERMS`] orders with
//! `ρ_k = (tol / |c_k|_∞)^(1/k)` over the state and the force and
//! `tol = TOLERANCE_SCALE (atol + rtol |y|_∞)`, growing at most [`MAX_GROWTH`] times per step;
//! there are no rejected steps. The non-smooth points (the rate and `Z` changing sign) and the
//! separation `F <= 0 <= V` are roots of the step's polynomials, found by safeguarded Newton
//! iteration; sign changes are looked for at the middle and the end of the step and again up to
//! each root found, so that a function crossing twice inside one step is not missed.
//!
//! Where a base of a power vanishes (`X = Z = 0` at contact, `Z = 0` at its kink) the solution is
//! only finitely smooth and the recurrence divides by zero. Both there and at the roots that
//! matter most the series converge slowest (a zero of a base is their radius of convergence),
//! so the explicit method of the settings takes over: it leaves each such point with one step
//! (at [`START_TOLERANCE`] times the tolerances), and it integrates from the start of the step
//! onto a zero of `Z` (or `X`, `Y`) and onto a separation near one (the force can vanish where
//! a base does), where one Newton step along `f` polishes the root; a separation away from the
//! zeros of the bases is the root of the step's polynomials. At contact, where the NDBWSHCCM loads as a Hunt-Crossley contact
//! (`Γ = -B`, no input: every fit of the paper), a series in `s = T^(p+1)`, in which the
//! solution is analytic, takes the first step instead (`series/contact.rs`): one step over most of the
//! compression in place of the start step and the ramp after it.
//!
//! Off a zero of a base where neither series applies (a loading with hysteresis, `B + Γ != 0`,
//! or under an input), the start step is followed by steps in `σ = ln(T - T_a)` about the time
//! `T_a` where the base vanished ([`jet::Clock::Log`]): the solution's terms `(T - T_a)^a` are
//! `e^(a σ)`, analytic in `σ`, so these steps are not bounded by the distance to `T_a` as the
//! steps in `T` are (which grow by at most `MAX_GROWTH` per step from the start step's span).
//! They end at the first event ahead or once a step spans less than [`LOG_STEP_MIN`], where the
//! solution's other singularities bound the steps and a step in time costs less. At contact
//! the start step is not the explicit method's: the loading's leading terms give the state at
//! a time where the terms they leave out are below the start tolerance (`series/onset.rs`),
//! and the logarithmic steps ramp from there.
//!
//! Off a root of `Z` into a branch without hysteresis bracket (`B + Γ = 0`, every fit of the
//! paper), a series in `D = |Z|` and `D^p`, in which the solution is analytic, takes the first
//! step instead of the start step and the ramp after it (`series/crossing.rs`).
//!
//! Where `Z` runs into the equilibrium of its branch (`|Z| = c^(-1/n)` with
//! `c = B sgn(Z) sgn(rate) + Γ > 0`, `Z` moving with the rate), it is held there once within
//! [`START_TOLERANCE`] step tolerances of it: the exact `Z` only approaches it further, and the
//! decay towards it would otherwise cap the steps at its rate.
//!
//! A contact that comes to rest is reported as settled, as on the Runge-Kutta path. Where this
//! path cannot go on (a start step that meets an event, more than [`MAX_SERIES_STEPS`] steps,
//! e.g. a stiff contact, a state sliding along a switching surface, an ill-conditioned root, or
//! the horizon) it hands the impact over ([`SeriesRun::HandOver`]) and the Runge-Kutta path
//! continues from the last state the series reached.
//!
//! Accuracy and cost are measured, not claimed here: BENCHMARKS.md, "Session 8: the target timed
//! side by side" (time at equal error against plain DOP853 on the paper's DSS (1) cases) and
//! STABILITY.md (accuracy on the stress sweep's extreme parameters against the Runge-Kutta
//! path), which is why it is the default for CoR evaluations.

mod contact;
mod crossing;
mod jet;
mod onset;
mod path;
mod recurrence;

use crate::impact::{Impact, Settings};
use crate::models::CollisionModel;
use crate::State;
use bwc_ode::{Integrator, Options, Stats};
use jet::{Expand, Jet, Series};

/// Order of the Taylor polynomials (chosen by the work-precision benchmark, BENCHMARKS.md).
pub const ORDER: usize = 16;

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
/// (BENCHMARKS.md, session 15).
pub const LOG_STEP_MIN: f64 = 1.0;

/// Orders whose coefficients set the step size.
pub const ESTIMATE_TERMS: usize = 4;

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

/// The key to [`crate::CollisionModel`]'s hidden fast path: constructible only in this crate.
#[derive(Debug, Clone, Copy)]
pub struct Private(pub(crate) ());

/// What the series path made of an impact ([`crate::CollisionModel::series_impact`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SeriesRun<const N: usize> {
    /// The impact, finished by the series.
    Done(Impact<N>),
    /// The series declined at time `t` (a stiff or sliding contact, an ill-conditioned root,
    /// more than [`MAX_SERIES_STEPS`] steps, the horizon): the Runge-Kutta path continues from
    /// the state there, adding its work to `stats`.
    HandOver {
        /// Time reached (0: nothing done).
        t: f64,
        /// State there.
        state: State<N>,
        /// Work done so far.
        stats: Stats,
        /// Series steps taken so far.
        series_steps: u64,
    },
}

/// The polynomial and its derivative at `s`.
fn eval_d(c: &Series, s: f64) -> (f64, f64) {
    let (mut p, mut d) = (0.0, 0.0);
    for ci in c.iter().rev() {
        d = d * s + p;
        p = p * s + ci;
    }
    (p, d)
}

/// Sign class: -1, 0 or 1.
fn class(v: f64) -> i8 {
    if v > 0.0 {
        1
    } else if v < 0.0 {
        -1
    } else {
        0
    }
}

/// The root in `(0, h]` of a function `g` (value and slope at `s`) that has class `start` just
/// after 0 and another class at `h`, as the first point found on the far side (within a few
/// ulps of the root): Newton's iteration kept inside the shrinking bracket, ends included
/// (bisection where it would leave it; a probe just past the root once Newton creeps up on it
/// from one side). After [`NEWTON_ITERATIONS`], a bisection wherever two iterations failed to
/// halve the bracket: where `g` is tiny but far from its root (a force `|X|^p (...)` near
/// `X = 0`) the slope does not describe it and Newton's steps crawl.
fn root(g: impl Fn(f64) -> (f64, f64), h: f64, start: i8) -> f64 {
    let (mut lo, mut hi) = (0.0, h);
    let mut s = h;
    let (mut width_two_ago, mut width_one_ago) = (f64::INFINITY, h);
    for iteration in 0..200 {
        let (p, d) = g(s);
        if class(p) == start {
            lo = s;
        } else {
            hi = s;
        }
        let tiny = 4.0 * f64::EPSILON * hi;
        if hi - lo <= tiny {
            break;
        }
        let stalled = iteration >= NEWTON_ITERATIONS && hi - lo > 0.5 * width_two_ago;
        (width_two_ago, width_one_ago) = (width_one_ago, hi - lo);
        let newton = s - p / d;
        // Newton's iterate may be an end of the bracket: where a search is repeated up to the
        // root found, it starts on that root.
        s = if !(newton >= lo && newton <= hi) || stalled {
            0.5 * (lo + hi)
        } else if (newton - s).abs() > tiny {
            newton
        } else if class(p) == start {
            // Newton's estimate of the root is within `tiny` of the bracket's low end `s`: a
            // probe just past it leaves a bracket narrow enough to stop.
            (newton + PROBE * tiny).min(0.5 * (newton + hi))
        } else {
            (newton - PROBE * tiny).max(0.5 * (newton + lo))
        };
    }
    hi
}

/// Distance of [`root`]'s probe past Newton's estimate of the root, as a fraction of the final
/// width: less than 1, so that the bracket a probe leaves, rounding included, is narrow enough
/// to stop.
const PROBE: f64 = 0.75;

/// Iterations of [`root`] before a bracket that does not shrink fast enough is bisected (Newton
/// converges on the roots of the step polynomials within a few).
const NEWTON_ITERATIONS: usize = 8;

/// The local tolerance of a series step from `y`: `TOLERANCE_SCALE (atol + rtol |y|_∞)`.
fn step_tolerance<const N: usize>(y: &State<N>, settings: &Settings) -> f64 {
    TOLERANCE_SCALE * (settings.atol + settings.rtol * y.amax())
}

/// Jorba & Zou's step size for the coefficients of `jet` about `y`, made robust to series whose
/// last coefficients happen to be small (nearly polynomial stretches, integer exponents):
/// `0.9 min_k ρ_k` over the last [`ESTIMATE_TERMS`] orders, `ρ_k = (tol / |c_k|_∞)^(1/k)` over the
/// state and the force, with the local tolerance `tol` ([`step_tolerance`]).
fn step_size<const N: usize>(jet: &Jet<N>, tol: f64) -> f64 {
    jorba_zou(tol, ORDER, |k| {
        jet.state
            .iter()
            .chain([&jet.force])
            .fold(0.0f64, |m, s| m.max(s[k].abs()))
    })
}

/// `0.9 min_k (tol / c_k)^(1/k)` over the last [`ESTIMATE_TERMS`] orders up to `order`, for the
/// largest coefficients `c_k` of a series (a zero coefficient gives an infinite `ρ_k`).
fn jorba_zou(tol: f64, order: usize, largest: impl Fn(usize) -> f64) -> f64 {
    let lt = coarse_log2(tol);
    // One exp2 for the smallest.
    let mut x = f64::INFINITY;
    for k in order + 1 - ESTIMATE_TERMS..=order {
        let c = largest(k);
        if c > 0.0 {
            x = x.min((lt - coarse_log2(c)) / k as f64);
        }
    }
    0.9 * x.exp2()
}

/// `log2 a` for a positive `a` to within 1.1e-3 (the binary exponent and a cubic in the
/// mantissa, exact at powers of 2): enough for a step size, whose `ρ_k` it changes by less than
/// `1e-4` relative, at a fraction of the cost of `log2`. Subnormal `a` read as `2^-1023` (a
/// smaller step).
fn coarse_log2(a: f64) -> f64 {
    const MANTISSA: u64 = (1 << 52) - 1;
    let bits = a.to_bits();
    let exponent = ((bits >> 52) & 0x7ff) as f64 - 1023.0;
    let t = f64::from_bits((bits & MANTISSA) | (1023 << 52)) - 1.0;
    exponent
        + t * (1.420_864_537_430_105 + t * (-0.577_250_650_806_472 + t * 0.156_386_113_376_367))
}

/// One impact by Taylor series, or `None` where this path declines (see the module docs).
pub(crate) fn impact<M: Expand<N>, const N: usize>(
    model: &M,
    settings: &Settings,
) -> Option<SeriesRun<N>> {
    path::SeriesPath::start(model, settings).map(path::SeriesPath::run)
}

/// One step of the settings' explicit method from `(t, y)`, where a base vanishes, at
/// [`START_TOLERANCE`] times the settings' tolerances. There the solution's leading non-smooth
/// terms are `τ^q` (`q = e + 1` for the exponent `e` of a power of a vanishing base: `Z`
/// gains `τ^(n+1)`, `V` gains `τ^(p+1)`), and a Runge-Kutta step's error scales as `h^q`
/// whatever the method's order: after a rejected trial the next is sized by that exponent
/// (`h (0.9 / err)^(1/q)`), not by the method's order, which would shrink it only by its
/// controller's limit per trial (measured: 8-9 rejections where `n` is near 1).
fn start_step<M: CollisionModel<N>, const N: usize>(
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
enum Target {
    /// A state component, set to exactly zero at its root.
    Component(usize),
    /// The contact force.
    Force,
}

/// First step of a repeated [`reach_root`] run, as a fraction of its span: a series step of
/// order 16 spans about `tol^(1/16 - 1/8)` (3-6) Runge-Kutta steps of order 8 at rtol 1e-8 ...
/// 1e-12, and a first step of an eighth lets the run find its own.
const RETRY_SPAN: f64 = 0.125;

/// Largest step along `f` onto a root after [`reach_root`]'s Runge-Kutta run, as a fraction of
/// that run's span.
const NEWTON_SPAN: f64 = 1e-2;

/// From `start`, the explicit method of the settings up to `t1`, where the series put a root of
/// `target`, with first trial step `h0`; then one Newton step along `f` onto the root (declined
/// unless it is tiny, or small against the span and accurate by an estimate of its error: an
/// ill-conditioned root is left to the Runge-Kutta path).
fn reach_root<M: CollisionModel<N>, const N: usize>(
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
#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coarse_log2_is_within_its_bound() {
        for i in 0..20_000 {
            let a = 10f64.powf(-300.0 + 600.0 * f64::from(i) / 20_000.0);
            assert!((coarse_log2(a) - a.log2()).abs() <= 1.1e-3, "{a}");
        }
        assert_eq!(coarse_log2(1.0), 0.0);
        assert_eq!(coarse_log2(0.25), -2.0);
    }

    #[test]
    fn roots_of_polynomials() {
        // s^2 - 0.3 on (0, 1]: root sqrt(0.3), from either side.
        let mut q = [0.0; ORDER + 1];
        (q[0], q[2]) = (-0.3, 1.0);
        let r = root(|s| eval_d(&q, s), 1.0, -1);
        assert!((r - 0.3f64.sqrt()).abs() <= 1e-15 && eval_d(&q, r).0 >= 0.0);
        let neg = q.map(|c| -c);
        let r = root(|s| eval_d(&neg, s), 1.0, 1);
        assert!((r - 0.3f64.sqrt()).abs() <= 1e-15 && eval_d(&neg, r).0 <= 0.0);
        assert_eq!(eval_d(&q, 2.0), (3.7, 4.0));
        // A value that is tiny past its root and a slope that does not describe it (a force
        // |X|^p (...) near X = 0): Newton's steps from the far end would crawl 2e-12 at a time.
        let g = |s: f64| (if s < 0.05 { 1e-20 } else { -4e-25 }, -1.9e-13);
        let r = root(g, 0.068, 1);
        assert!((r - 0.05).abs() <= 1e-15, "{r}");
    }

    #[test]
    fn a_root_at_the_end_of_the_span_takes_two_evaluations() {
        // Each event is searched for again up to the root found, where its function is zero
        // to rounding: Newton's iterate is then the end itself. A bisection from there would
        // send the iterates from below past the end of a convex function, bisecting each time.
        type Function = fn(f64) -> (f64, f64);
        let cases: [(Function, i8); 3] = [
            (|s| (s - 0.25, 1.0), -1),
            (|s| (s * s - 0.0625, 2.0 * s), -1),
            (|s| (0.0625 - s * s, -2.0 * s), 1),
        ];
        for (g, start) in cases {
            let calls = std::cell::Cell::new(0);
            let r = root(
                |s| {
                    calls.set(calls.get() + 1);
                    g(s)
                },
                0.25,
                start,
            );
            assert_eq!(r, 0.25);
            assert!(calls.get() <= 2, "{} evaluations", calls.get());
        }
    }
}
