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
//! onto a zero of `Z` (or `X`, `Y`) and onto the separation, where one Newton step along `f`
//! polishes the root.
//!
//! A contact that comes to rest is reported as settled, as on the Runge-Kutta path. Where this
//! path cannot go on (a start step that meets an event, more than [`MAX_SERIES_STEPS`] steps,
//! e.g. a stiff contact, a state sliding along a switching surface, an ill-conditioned root, or
//! the horizon) it hands the impact over ([`SeriesRun::HandOver`]) and the Runge-Kutta path
//! continues from the last state the series reached.
//!
//! Accuracy and cost (BENCHMARKS.md): on the paper's cases errors about 100x below the
//! Runge-Kutta path's at the same rtol, 1.2-1.8x faster at equal error; on the stress sweep's
//! extreme parameters more accurate in `e` than the Runge-Kutta path (of 75,059 runs with series
//! steps, 71 in which the Runge-Kutta path is worse by more than 10x and 1e-9, 23 the other way
//! besides contacts that hover at zero force; STABILITY.md), which is why it is the default for
//! CoR evaluations.

use crate::impact::{at_rest, pad, Impact, Settings};
use crate::input::Input;
use crate::models::{CollisionModel, NdCoefficients, Ndbwmcm, Ndbwshccm};
use crate::power::Pow;
use crate::State;
use bwc_ode::{Integrator, Options, Stats};

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

/// Orders whose coefficients set the step size.
pub const ESTIMATE_TERMS: usize = 4;

/// Most series steps of one impact before it is handed to the Runge-Kutta path.
pub const MAX_SERIES_STEPS: u64 = 150;

/// Most event steps in a row that leave the time where it was (the state sliding along a
/// switching surface, e.g. the MCM creeping with `Y' = 0` under a pull) before the impact is
/// handed to the Runge-Kutta path, whose stops at the kinks and RODAS4 handle such runs.
pub const MAX_STALLED: u32 = 2;

/// What the series path made of an impact ([`crate::CollisionModel::series_impact`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SeriesRun {
    /// The impact, finished by the series.
    Done(Impact),
    /// The series declined at time `t` (a stiff or sliding contact, an ill-conditioned root,
    /// more than [`MAX_SERIES_STEPS`] steps, the horizon): the Runge-Kutta path continues from
    /// the state there, adding its work to `stats`.
    HandOver {
        /// Time reached (0: nothing done).
        t: f64,
        /// State there (the model's components first).
        state: [f64; 4],
        /// Work done so far.
        stats: Stats,
        /// Series steps taken so far.
        series_steps: u64,
    },
}

/// Taylor coefficients `c_0 ..= c_ORDER` of one function about the start of a step.
pub(crate) type Series = [f64; ORDER + 1];

/// The Taylor polynomials of one step.
pub(crate) struct Jet<const N: usize> {
    /// The state components.
    state: [Series; N],
    /// The contact force `F`.
    force: Series,
    /// The rate across the hysteretic element (`V` or `Y'`), whose sign picks the branch.
    rate: Series,
    /// Scratch of [`Expand::expand`], kept between steps: the bases of the powers and the
    /// powers (each expansion writes every coefficient it reads).
    bases: [Base; 2],
    powers: [Power; 3],
}

impl<const N: usize> Jet<N> {
    fn new() -> Self {
        Self {
            state: [[0.0; ORDER + 1]; N],
            force: [0.0; ORDER + 1],
            rate: [0.0; ORDER + 1],
            bases: [Base::ZERO, Base::ZERO],
            powers: [Power::ZERO, Power::ZERO, Power::ZERO],
        }
    }

    /// The state and rate polynomials at `s` (Horner's scheme on all of them at once, so that
    /// the dependency chains overlap; the force is evaluated from the state instead).
    fn at(&self, s: f64) -> ([f64; N], f64) {
        let (mut y, mut r) = ([0.0; N], 0.0);
        for k in (0..=ORDER).rev() {
            for (yi, c) in y.iter_mut().zip(&self.state) {
                *yi = *yi * s + c[k];
            }
            r = r * s + self.rate[k];
        }
        (y, r)
    }
}

/// A nondimensional model whose solution the series path can expand.
pub(crate) trait Expand<const N: usize>: CollisionModel<N> {
    /// Index of the displacement whose power is in the force (`X` or `Y`).
    const BASE: usize;
    /// Index of `Z`.
    const Z: usize;
    /// Whether the rate is the velocity `V` (NDBWSHCCM).
    const RATE_IS_VELOCITY: bool;

    /// The Taylor coefficients of the solution through `y` in the branch where the rate has
    /// sign `rate_sign`, for the constant input `u`; `y[BASE]` and `y[Z]` are nonzero.
    fn expand(&self, y: &State<N>, rate_sign: f64, u: f64, jet: &mut Jet<N>);
}

/// `Σ_j p_j q_j` over the common length, in four lanes.
#[inline(always)]
fn dot(p: &[f64], q: &[f64]) -> f64 {
    let n = p.len().min(q.len());
    let (p, q) = (p[..n].chunks_exact(4), q[..n].chunks_exact(4));
    let tail: f64 = p
        .remainder()
        .iter()
        .zip(q.remainder())
        .map(|(a, b)| a * b)
        .sum();
    let mut acc = [0.0; 4];
    for (a, b) in p.zip(q) {
        for l in 0..4 {
            acc[l] += a[l] * b[l];
        }
    }
    (acc[0] + acc[1]) + (acc[2] + acc[3]) + tail
}

/// `(Σ_j a_j q_j, Σ_j b_j q_j)` over the common length of `a`, `b` (equal) and `q`, in four
/// lanes: two convolutions with one pass over `q`.
#[inline(always)]
fn dot2(a: &[f64], b: &[f64], q: &[f64]) -> (f64, f64) {
    let n = a.len().min(q.len());
    let (a, b, q) = (
        a[..n].chunks_exact(4),
        b[..n].chunks_exact(4),
        q[..n].chunks_exact(4),
    );
    let (mut tx, mut ty) = (0.0, 0.0);
    for ((x, y), z) in a.remainder().iter().zip(b.remainder()).zip(q.remainder()) {
        tx += x * z;
        ty += y * z;
    }
    let (mut x, mut y) = ([0.0; 4], [0.0; 4]);
    for ((ca, cb), cq) in a.zip(b).zip(q) {
        for l in 0..4 {
            x[l] += ca[l] * cq[l];
            y[l] += cb[l] * cq[l];
        }
    }
    (
        (x[0] + x[1]) + (x[2] + x[3]) + tx,
        (y[0] + y[1]) + (y[2] + y[3]) + ty,
    )
}

/// The base `b` of a power: its coefficients and the coefficients times their index.
struct Base {
    c: Series,
    kc: Series,
}

impl Base {
    const ZERO: Self = Self {
        c: [0.0; ORDER + 1],
        kc: [0.0; ORDER + 1],
    };

    #[inline(always)]
    fn set(&mut self, k: usize, v: f64) {
        self.c[k] = v;
        self.kc[k] = k as f64 * v;
    }
}

/// A power `y = b^e` of a base, stored in reverse (`r[ORDER - k] = y_k`) so that the
/// convolutions of the recurrence, `Σ_m w_m y_{k-m}`, are forward dot products.
struct Power {
    r: Series,
}

impl Power {
    const ZERO: Self = Self {
        r: [0.0; ORDER + 1],
    };

    #[inline(always)]
    fn set(&mut self, k: usize, v: f64) {
        self.r[ORDER - k] = v;
    }

    /// Coefficient `k >= 1` of `y = b^e` from `b_0 ..= b_k` and `y_0 .. y_{k-1}` (`b_0 > 0`):
    /// `k b_0 y_k = e Σ_{m=1..k} m b_m y_{k-m} - Σ_{m=1..k} b_m (k-m) y_{k-m}
    /// = (e + 1) A - k B` with `A = Σ m b_m y_{k-m}`, `B = Σ b_m y_{k-m}` (one pass).
    #[inline(always)]
    fn term(&self, b: &Base, e: f64, k: usize) -> f64 {
        let w = ORDER + 1 - k;
        let (a, s) = dot2(&b.kc[1..=k], &b.c[1..=k], &self.r[w..]);
        ((e + 1.0) * a - k as f64 * s) / (k as f64 * b.c[0])
    }

    /// Coefficients `k >= 1` of two powers `y = b^e1`, `u = b^e2` of one base, as
    /// [`Power::term`] with one pass over the base for both.
    #[inline(always)]
    fn terms(y: &Power, u: &Power, b: &Base, (e1, e2): (f64, f64), k: usize) -> (f64, f64) {
        let w = ORDER + 1 - k;
        let (kc, c) = (&b.kc[1..=k], &b.c[1..=k]);
        let (yr, ur) = (&y.r[w..], &u.r[w..]);
        let (mut a1, mut s1, mut a2, mut s2) = ([0.0; 2], [0.0; 2], [0.0; 2], [0.0; 2]);
        let whole = k - k % 2;
        for i in (0..whole).step_by(2) {
            for l in 0..2 {
                a1[l] += kc[i + l] * yr[i + l];
                s1[l] += c[i + l] * yr[i + l];
                a2[l] += kc[i + l] * ur[i + l];
                s2[l] += c[i + l] * ur[i + l];
            }
        }
        if whole < k {
            let i = whole;
            a1[0] += kc[i] * yr[i];
            s1[0] += c[i] * yr[i];
            a2[0] += kc[i] * ur[i];
            s2[0] += c[i] * ur[i];
        }
        let (kf, b0) = (k as f64, b.c[0]);
        let term = |a: [f64; 2], s: [f64; 2], e: f64| {
            ((e + 1.0) * (a[0] + a[1]) - kf * (s[0] + s[1])) / (kf * b0)
        };
        (term(a1, s1, e1), term(a2, s2, e2))
    }

    /// Coefficient `k` of the product of this power and the series `w`.
    #[inline(always)]
    fn times(&self, w: &Series, k: usize) -> f64 {
        dot(&w[..=k], &self.r[ORDER - k..])
    }
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
/// ulps of the root): Newton's iteration kept inside the shrinking bracket (bisection where it
/// would leave it; a probe just past the iterate once Newton creeps up on the root from one
/// side). After [`NEWTON_ITERATIONS`], a bisection wherever two iterations failed to halve the
/// bracket: where `g` is tiny but far from its root (a force `|X|^p (...)` near `X = 0`) the
/// slope does not describe it and Newton's steps crawl.
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
        s = if !(newton > lo && newton < hi) || stalled {
            0.5 * (lo + hi)
        } else if (newton - s).abs() > tiny {
            newton
        } else if class(p) == start {
            (newton + tiny).min(0.5 * (newton + hi))
        } else {
            (newton - tiny).max(0.5 * (newton + lo))
        };
    }
    hi
}

/// Iterations of [`root`] before a bracket that does not shrink fast enough is bisected (Newton
/// converges on the roots of the step polynomials within a few).
const NEWTON_ITERATIONS: usize = 8;

/// Jorba & Zou's step size for the coefficients of `jet` about `y`, made robust to series whose
/// last coefficients happen to be small (nearly polynomial stretches, integer exponents):
/// `0.9 min_k ρ_k` over the last [`ESTIMATE_TERMS`] orders, `ρ_k = (tol / |c_k|_∞)^(1/k)` over the
/// state and the force, with `tol = TOLERANCE_SCALE (atol + rtol |y|_∞)`.
fn step_size<const N: usize>(jet: &Jet<N>, y: &State<N>, settings: &Settings) -> f64 {
    let tol = TOLERANCE_SCALE * (settings.atol + settings.rtol * y.amax());
    let lt = tol.log2();
    // One exp2 for the smallest (log2 0 = -inf gives an infinite ρ).
    let mut x = f64::INFINITY;
    for k in ORDER + 1 - ESTIMATE_TERMS..=ORDER {
        let c = jet
            .state
            .iter()
            .chain([&jet.force])
            .fold(0.0f64, |m, s| m.max(s[k].abs()));
        x = x.min((lt - c.log2()) / k as f64);
    }
    0.9 * x.exp2()
}

/// What ends a step early.
#[derive(Clone, Copy, PartialEq)]
enum Event {
    Rate,
    Z,
    Base,
    Force,
    Velocity,
}

/// One impact by Taylor series, or `None` where this path declines (see the module docs).
pub(crate) fn impact<M: Expand<N>, const N: usize>(
    model: &M,
    settings: &Settings,
) -> Option<SeriesRun> {
    if !model.input_is_constant() {
        return None;
    }
    let u = model.input(0.0);
    let velocity = |y: &State<N>| model.velocity(y);
    let mut t = 0.0;
    let mut y = model.initial_state();
    let mut stats = Stats::default();
    let mut series_steps = 0u64;
    // The last step's size: a step may be at most MAX_GROWTH times it.
    let mut h_last = f64::INFINITY;
    let mut rate_class = class(model.kinks(t, &y)[0]);
    let mut jet = Jet::new();
    // Event steps in a row that did not advance the time (a sliding mode: the rate across the
    // hysteretic element stays at zero and its sign flips at every step).
    let mut stalled = 0;
    // Where this path declines, the Runge-Kutta path takes over from the last state the series
    // reached (not from contact: the work done so far is kept).
    let hand_over = |t: f64, y: &State<N>, stats: Stats, series_steps: u64| {
        Some(SeriesRun::HandOver {
            t,
            state: pad(y),
            stats,
            series_steps,
        })
    };
    // The force at the end of the last step, where this one starts (computed there already).
    let mut force_here: Option<f64> = None;
    loop {
        let force = force_here.take().unwrap_or_else(|| model.force(&y));
        let velocity_now = velocity(&y);
        if force <= 0.0 && velocity_now >= 0.0 && t > 0.0 {
            // Reached at the end of the last step.
            stats.events += 1;
            return Some(SeriesRun::Done(Impact {
                t_s: Some(t),
                e: velocity_now.max(0.0) / model.impact_speed(),
                state: pad(&y),
                settled_at: None,
                stiff_from: None,
                series_steps,
                stats,
            }));
        }
        if series_steps >= MAX_SERIES_STEPS || stats.accepted >= settings.max_steps {
            return hand_over(t, &y, stats, series_steps);
        }
        if t >= settings.t_max {
            return hand_over(t, &y, stats, series_steps);
        }
        if y[M::BASE] == 0.0 || y[M::Z] == 0.0 {
            let (t_start, y_start, stats_start) = (t, y, stats);
            let Some(next) = start_step(model, settings, t, &y, &mut stats) else {
                return hand_over(t_start, &y_start, stats_start, series_steps);
            };
            (t, y) = next;
            h_last = t - t_start;
            let met = class(model.kinks(t, &y)[0]) != rate_class
                || y[M::BASE] == 0.0
                || y[M::Z] == 0.0
                || (model.force(&y) <= 0.0 && velocity(&y) >= 0.0);
            if met {
                // The start step met an event: the Runge-Kutta path retakes it.
                return hand_over(t_start, &y_start, stats_start, series_steps);
            }
            continue;
        }
        model.expand(&y, f64::from(rate_class), u, &mut jet);
        // At rest under the constant input: an equilibrium, the contact has settled.
        let rate_of_change = State::<N>::from_fn(|i, _| jet.state[i][1]);
        if at_rest(model, &rate_of_change, settings.atol) {
            return Some(SeriesRun::Done(Impact {
                t_s: None,
                e: 0.0,
                state: pad(&y),
                settled_at: Some(t),
                stiff_from: None,
                series_steps,
                stats,
            }));
        }
        series_steps += 1;
        stats.accepted += 1;
        let h = step_size(&jet, &y, settings)
            .min(MAX_GROWTH * h_last)
            .min(settings.max_step)
            .min(settings.t_max - t);
        h_last = h;
        // The event functions in the order ties are resolved (the separation first), their
        // class at the start, and whether they are watched in this step.
        let (z, base) = (M::Z, M::BASE);
        let watch = [
            (Event::Force, 1, force > 0.0),
            (
                Event::Velocity,
                -1,
                !M::RATE_IS_VELOCITY && velocity_now < 0.0,
            ),
            (Event::Rate, rate_class, true),
            (Event::Z, class(y[z]), true),
            (Event::Base, class(y[base]), true),
        ];
        // The state and the event values at `s`: the force from the state (its sign is exact
        // where the force has a multiple root, e.g. -|X|^(p-1) X at X = 0), the others from
        // their series.
        let values = |s: f64| {
            let (ys, rate) = jet.at(s);
            let force = model.force(&State::<N>::from(ys));
            (ys, [force, ys[N - 1], rate, ys[z], ys[base]])
        };
        let series_of = |event: Event| match event {
            Event::Force => &jet.force,
            Event::Velocity => &jet.state[N - 1],
            Event::Rate => &jet.rate,
            Event::Z => &jet.state[z],
            Event::Base => &jet.state[base],
        };
        let changed = |at: &[f64; 5]| {
            watch
                .iter()
                .zip(at)
                .any(|(&(_, start, on), v)| on && class(*v) != start)
        };
        // The earliest root: search where a class has changed (in the first half of the step
        // if one has changed there already), then again up to the root found, until no function
        // changes earlier (a function may cross and cross back inside a long step).
        let (end, at_end) = values(h);
        let (_, at_mid) = values(0.5 * h);
        let (mut upto, mut at) = if changed(&at_mid) {
            (0.5 * h, at_mid)
        } else {
            (h, at_end)
        };
        let mut first: Option<(f64, Event)> = None;
        for _ in 0..8 {
            let mut best: Option<(f64, Event)> = None;
            for (&(event, start, on), v) in watch.iter().zip(&at) {
                if !on || class(*v) == start {
                    continue;
                }
                let c = series_of(event);
                let s = if event == Event::Force {
                    root(|s| (values(s).1[0], eval_d(c, s).1), upto, start)
                } else {
                    root(|s| eval_d(c, s), upto, start)
                };
                // Ties go to the function listed first (the separation).
                if best.is_none_or(|(b, _)| s < b) {
                    best = Some((s, event));
                }
            }
            let Some((s, _)) = best else { break };
            first = best;
            if s >= upto {
                break;
            }
            upto = s;
            at = values(upto).1;
        }
        let Some((s, event)) = first else {
            y = State::<N>::from(end);
            force_here = Some(at_end[0]);
            t += h;
            stalled = 0;
            continue;
        };
        if t + s > t {
            stalled = 0;
        } else {
            stalled += 1;
            if stalled > MAX_STALLED {
                return hand_over(t, &y, stats, series_steps);
            }
        }
        match event {
            // A base vanishes at its root: there the series converge slowest (the root is their
            // radius of convergence), so the explicit method takes the state there.
            Event::Z | Event::Base => {
                stats.events += 1;
                let i = if event == Event::Z { z } else { base };
                let target = Target::Component(i);
                let Some(next) = reach_root(model, settings, (t, &y), t + s, target, &mut stats)
                else {
                    return hand_over(t, &y, stats, series_steps);
                };
                (t, y) = next;
            }
            Event::Rate => {
                stats.events += 1;
                rate_class = -rate_class;
                y = State::<N>::from(jet.at(s).0);
                t += s;
                if M::RATE_IS_VELOCITY {
                    y[N - 1] = 0.0;
                }
            }
            // A separation: the explicit method takes the state there (the force can vanish
            // where a base does, at the radius of convergence of the series).
            Event::Force if jet.at(s).0[N - 1] >= 0.0 => {
                let force = Target::Force;
                let Some(next) = reach_root(model, settings, (t, &y), t + s, force, &mut stats)
                else {
                    return hand_over(t, &y, stats, series_steps);
                };
                (t, y) = next;
            }
            Event::Velocity | Event::Force => {
                y = State::<N>::from(jet.at(s).0);
                t += s;
                if event == Event::Velocity {
                    y[N - 1] = 0.0;
                }
            }
        }
        // The separation F <= 0 <= V, checked at every event (at a located root of the force,
        // F is zero to rounding, either sign).
        let force_zero = event == Event::Force && velocity(&y) >= 0.0;
        if force_zero || (model.force(&y) <= 0.0 && velocity(&y) >= 0.0) {
            stats.events += 1;
            return Some(SeriesRun::Done(Impact {
                t_s: Some(t),
                e: velocity(&y).max(0.0) / model.impact_speed(),
                state: pad(&y),
                settled_at: None,
                stiff_from: None,
                series_steps,
                stats,
            }));
        }
    }
}

/// One step of the settings' explicit method from `(t, y)`, where a base vanishes, at
/// [`START_TOLERANCE`] times the settings' tolerances.
fn start_step<M: CollisionModel<N>, const N: usize>(
    model: &M,
    settings: &Settings,
    t: f64,
    y: &State<N>,
    stats: &mut Stats,
) -> Option<(f64, State<N>)> {
    let (rtol, atol) = (
        START_TOLERANCE * settings.rtol,
        START_TOLERANCE * settings.atol,
    );
    let options = Options::new(rtol, atol).with_max_step(settings.max_step);
    let rhs = |t: f64, y: &State<N>| model.rhs(t, y);
    let mut it = Integrator::new(rhs, settings.method, t, *y, options).ok()?;
    it.step(settings.t_max).ok()?;
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

/// From `start`, the explicit method of the settings up to `t1`, where the series put a root of
/// `target`; then one Newton step along `f` onto the root (declined unless it is tiny: an
/// ill-conditioned root is left to the Runge-Kutta path).
fn reach_root<M: CollisionModel<N>, const N: usize>(
    model: &M,
    settings: &Settings,
    start: (f64, &State<N>),
    t1: f64,
    target: Target,
    stats: &mut Stats,
) -> Option<(f64, State<N>)> {
    let (t0, y0) = start;
    let options = Options::new(settings.rtol, settings.atol)
        .with_max_step(settings.max_step)
        .with_h0(t1 - t0);
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
    let tiny = dt.abs() <= 1e-6 * (t1 - t0);
    if !tiny {
        return None;
    }
    // The error of this step, about dt^2 |y''| / 2, is below 1e-12 |y''| (t1 - t0)^2.
    y += f * dt;
    if let Target::Component(i) = target {
        y[i] = 0.0;
    }
    Some((t1 + dt, y))
}

/// Order by order, the powers of an expansion: `|D|^p` of the displacement `D` (`X` or `Y`),
/// `|Z|^p` (that of `D` while `Z = D`) and `|Z|^n` (only where the hysteresis needs it).
struct JetPowers<'a> {
    p: Pow,
    n: Pow,
    /// `Z = D` and stays so (loading with `Γ = -B` from contact).
    shared: bool,
    /// The hysteresis bracket is nonzero in this branch: `|Z|^n` is needed.
    hysteretic: bool,
    bases: &'a mut [Base; 2],
    powers: &'a mut [Power; 3],
}

impl<'a> JetPowers<'a> {
    /// The powers of the model with coefficients `k` in the branch with hysteresis bracket
    /// factor `c`, in the scratch `bases` and `powers`.
    fn new(
        k: &NdCoefficients,
        shared: bool,
        c: f64,
        bases: &'a mut [Base; 2],
        powers: &'a mut [Power; 3],
    ) -> Self {
        Self {
            p: k.p,
            n: k.n,
            shared,
            hysteretic: c != 0.0,
            bases,
            powers,
        }
    }

    /// Coefficient `j` of `|D|^p` and `|Z|^p` from coefficient `j` of `|D|` and `|Z|` (the
    /// lower ones were given before).
    #[inline(always)]
    fn order(&mut self, j: usize, d_j: f64, z_j: f64) -> (f64, f64) {
        let [d, z] = &mut *self.bases;
        let [dp, zp, zn] = &mut *self.powers;
        let of = |power: &Power, base: &Base, e: Pow| {
            if j == 0 {
                e.of_abs(base.c[0])
            } else {
                power.term(base, e.exponent(), j)
            }
        };
        d.set(j, d_j);
        let dpj = of(dp, d, self.p);
        dp.set(j, dpj);
        let zpj = if self.shared {
            dpj
        } else {
            z.set(j, z_j);
            if !self.hysteretic {
                of(zp, z, self.p)
            } else if j == 0 {
                // |Z|^n and |Z|^p of one base share its logarithm.
                let mut powers = crate::power::Powers::of(z.c[0]);
                zn.set(0, powers.get(self.n));
                powers.get(self.p)
            } else {
                let (znj, zpj) = Power::terms(zn, zp, z, (self.n.exponent(), self.p.exponent()), j);
                zn.set(j, znj);
                zpj
            }
        };
        zp.set(j, zpj);
        (dpj, zpj)
    }

    /// Coefficient `j` of `|D|^p w`.
    #[inline(always)]
    fn displacement_times(&self, w: &Series, j: usize) -> f64 {
        self.powers[0].times(w, j)
    }

    /// Coefficients `j` of `|D|^p w` and `|Z|^n w`, in one pass over `w`.
    #[inline(always)]
    fn both_times(&self, w: &Series, j: usize) -> (f64, f64) {
        let [dp, _, zn] = &*self.powers;
        let at = ORDER - j;
        let (a, b) = dot2(&dp.r[at..], &zn.r[at..], &w[..=j]);
        (a, b)
    }

    /// Coefficient `j` of `|Z|^n w`.
    #[inline(always)]
    fn hysteresis_times(&self, w: &Series, j: usize) -> f64 {
        self.powers[2].times(w, j)
    }
}

impl<I: Input> Expand<3> for Ndbwshccm<I> {
    const BASE: usize = 0;
    const Z: usize = 1;
    const RATE_IS_VELOCITY: bool = true;

    fn expand(&self, y: &State<3>, sw: f64, u: f64, jet: &mut Jet<3>) {
        let k = &self.k;
        let (sx, sz) = (y[0].signum(), y[1].signum());
        // Z' = V - |Z|^n (B sgn(Z) |V| + Γ V) = V - c |Z|^n V in this branch.
        let c = k.b * sz * sw + k.gamma;
        // Loading with Γ = -B from Z = X: Z' = X' exactly, Z stays X.
        let shared = c == 0.0 && y[1] == y[0];
        let kc = 1.0 - k.kappa;
        let Jet {
            state: [x, z, v],
            force,
            bases,
            powers,
            ..
        } = jet;
        let mut pw = JetPowers::new(k, shared, c, bases, powers);
        (x[0], z[0], v[0]) = (y[0], y[1], y[2]);
        for j in 0..=ORDER {
            let (xp, zp) = pw.order(j, sx * x[j], sz * z[j]);
            // |X|^p V and |Z|^n V (the latter where the hysteresis needs it) in one pass.
            let (xpv, znv) = if c == 0.0 || j == ORDER {
                (pw.displacement_times(v, j), 0.0)
            } else {
                pw.both_times(v, j)
            };
            force[j] = -k.kappa * sx * xp - kc * sz * zp - k.sigma * xpv;
            if j == ORDER {
                break;
            }
            let inv = 1.0 / (j + 1) as f64;
            x[j + 1] = v[j] * inv;
            z[j + 1] = if c == 0.0 {
                x[j + 1]
            } else {
                (v[j] - c * znv) * inv
            };
            v[j + 1] = (force[j] + if j == 0 { u } else { 0.0 }) * inv;
        }
        jet.rate = jet.state[2];
    }
}

impl<I: Input> Expand<4> for Ndbwmcm<I> {
    const BASE: usize = 1;
    const Z: usize = 2;
    const RATE_IS_VELOCITY: bool = false;

    fn expand(&self, y: &State<4>, sw: f64, u: f64, jet: &mut Jet<4>) {
        let k = &self.k;
        let (sy, sz) = (y[1].signum(), y[2].signum());
        // Z' = Y' - c |Z|^n Y' in this branch (rate Y' = V + σ F).
        let c = k.b * sz * sw + k.gamma;
        let shared = c == 0.0 && y[2] == y[1];
        let kc = 1.0 - k.kappa;
        let Jet {
            state: [r, yy, z, v],
            force,
            rate,
            bases,
            powers,
        } = jet;
        let mut pw = JetPowers::new(k, shared, c, bases, powers);
        (r[0], yy[0], z[0], v[0]) = (y[0], y[1], y[2], y[3]);
        for j in 0..=ORDER {
            let (yp, zp) = pw.order(j, sy * yy[j], sz * z[j]);
            force[j] = -k.kappa * sy * yp - kc * sz * zp;
            rate[j] = v[j] + k.sigma * force[j];
            if j == ORDER {
                break;
            }
            let inv = 1.0 / (j + 1) as f64;
            r[j + 1] = -k.sigma * force[j] * inv;
            yy[j + 1] = rate[j] * inv;
            z[j + 1] = if c == 0.0 {
                yy[j + 1]
            } else {
                (rate[j] - c * pw.hysteresis_times(rate, j)) * inv
            };
            v[j + 1] = (force[j] + if j == 0 { u } else { 0.0 }) * inv;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Coefficients of `(1 + s)^e` by the binomial series.
    fn binomial(e: f64) -> Series {
        let mut c = [0.0; ORDER + 1];
        c[0] = 1.0;
        for k in 1..=ORDER {
            c[k] = c[k - 1] * (e - (k - 1) as f64) / k as f64;
        }
        c
    }

    #[test]
    fn power_recurrence_gives_the_binomial_series() {
        let mut b = Base::ZERO;
        b.set(0, 1.0);
        b.set(1, 1.0);
        for e in [1.0, 1.75, 2.62, 2.93, 0.5] {
            let want = binomial(e);
            let mut y = Power::ZERO;
            y.set(0, 1.0);
            for (k, wk) in want.iter().enumerate().skip(1) {
                let yk = y.term(&b, e, k);
                y.set(k, yk);
                assert!((yk - wk).abs() <= 1e-14 * wk.abs().max(1e-3), "e {e} k {k}");
            }
            // (1 + s)^e (1 - s): coefficient k is want_k - want_{k-1}.
            let mut w = [0.0; ORDER + 1];
            (w[0], w[1]) = (1.0, -1.0);
            for (k, pair) in want.windows(2).enumerate() {
                let k = k + 1;
                let got = y.times(&w, k);
                let exact = pair[1] - pair[0];
                assert!(
                    (got - exact).abs() <= 1e-14 * exact.abs().max(1e-3),
                    "e {e} k {k}"
                );
            }
        }
        // Two powers of one base in one pass: the same binomial series for both exponents.
        let (e1, e2) = (2.93, 2.62);
        let (w1, w2) = (binomial(e1), binomial(e2));
        let (mut y, mut u) = (Power::ZERO, Power::ZERO);
        (y.r[ORDER], u.r[ORDER]) = (1.0, 1.0);
        for k in 1..=ORDER {
            let (yk, uk) = Power::terms(&y, &u, &b, (e1, e2), k);
            y.set(k, yk);
            u.set(k, uk);
            for (got, want) in [(yk, w1[k]), (uk, w2[k])] {
                assert!((got - want).abs() <= 1e-14 * want.abs().max(1e-3), "k {k}");
            }
        }
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
}
