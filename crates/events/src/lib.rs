//! # bwc-events: event location on Runge-Kutta dense output
//!
//! Drives an integrator ([`bwc_ode::Stepper`]: explicit, Rosenbrock, or a solver switching
//! between them) step by step and, inside each accepted step, locates on the step's dense
//! output:
//!
//! * **terminal conditions** ([`Condition`]): a set of states described by signs of up to
//!   [`MAX_FUNCTIONS`] boundary functions; the event is the *infimum* of the instants where the
//!   condition holds, e.g. separation `t_s = inf{t : F <= 0 <= v}` (two functions and a
//!   predicate). A single crossing with a direction is the special case [`Crossing`].
//! * **switching points** ([`Switches`]): zeros of functions where the right-hand side is not
//!   smooth (`v = 0`, `z = 0` in the Bouc-Wen models). The integrator stops exactly there and
//!   restarts, so no step straddles a kink. A trial step that straddles one is rejected by the
//!   error control; the next trial is then *aimed* at the predicted zero (see the `aim`
//!   module), and a step that ends within `LANDING` noise floors of it stops there without a
//!   retake, so a kink costs a few trials instead of a collapse of the step size.
//!
//! Crossings are bracketed with an Illinois root finder and a bisection safeguard down to
//! adjacent floating-point numbers, so zeros of high multiplicity (a force vanishing like
//! `(t_s - t)^p`) are located to the last bit of the interpolant. A function that merely
//! *leaves* zero (as the contact force does at `t = 0`) is not a crossing: no event fires at the
//! initial instant. A boundary function that leaves its class and comes back inside one step
//! (equal classes at both ends) is caught by a cubic model of it from its values and rates at
//! the ends, confirmed on the dense output (one extra evaluation of the condition per step;
//! see the `interior` module), and a condition that holds at a switching point where a step
//! stopped is reported there.
//!
//! ```
//! use bwc_events::{Crossing, Direction, Locator, NoSwitches, Outcome};
//! use bwc_ode::{Integrator, Options, State, DOP853};
//! // A ball dropped from 10 m: y'' = -g. Impact when the height crosses zero downwards.
//! let g = 9.81;
//! let f = move |_t: f64, y: &State<2>| State::<2>::new(y[1], -g);
//! let mut it = Integrator::new(f, &DOP853, 0.0, State::<2>::new(10.0, 0.0), Options::new(1e-10, 1e-12))?;
//! let impact = Crossing::new(|_t: f64, y: &State<2>| y[0], Direction::Down);
//! let mut locator = Locator::new(impact, NoSwitches);
//! match locator.run(&mut it, 100.0)? {
//!     Outcome::Event { t, .. } => assert!((t - (2.0 * 10.0 / g).sqrt()).abs() < 1e-14),
//!     Outcome::Horizon { .. } => unreachable!("the ball lands"),
//! }
//! # Ok::<(), bwc_events::Error>(())
//! ```
#![deny(missing_docs)]

mod aim;
mod interior;
mod root;

pub use root::{class, find_crossing, Bracket};

use bwc_ode::{State, Stepper};

/// A step ending within this many noise floors of a switching point stops there (no retake).
const LANDING: f64 = 100.0;

/// Most boundary or switching functions one condition may have.
pub const MAX_FUNCTIONS: usize = 4;

/// Values of the boundary or switching functions; entries past `count()` are ignored.
pub type Values = [f64; MAX_FUNCTIONS];

/// Failures of an integration with events.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Error {
    /// The underlying integration failed.
    #[error(transparent)]
    Solver(#[from] bwc_ode::Error),
    /// A condition or switch set declares more functions than supported.
    #[error("{what} declares {len} functions; at most {max} are supported")]
    TooManyFunctions {
        /// `"condition"` or `"switches"`.
        what: &'static str,
        /// Declared count.
        len: usize,
        /// [`MAX_FUNCTIONS`].
        max: usize,
    },
}

/// A terminal condition: a set of states described by the signs of `count()` boundary functions.
///
/// The condition must only change truth value where one of its functions changes sign (or
/// reaches zero); the event is the first instant after the start where it holds.
pub trait Condition<const N: usize> {
    /// Number of boundary functions (at most [`MAX_FUNCTIONS`]).
    fn count(&self) -> usize;
    /// The boundary functions at `(t, y)`.
    fn values(&self, t: f64, y: &State<N>) -> Values;
    /// Whether the condition holds, given the function values now and at the start of the step.
    fn holds(&self, start: &Values, now: &Values) -> bool;
}

/// Functions whose zeros are non-smooth points of the right-hand side.
pub trait Switches<const N: usize> {
    /// Number of switching functions (at most [`MAX_FUNCTIONS`]).
    fn count(&self) -> usize;
    /// The switching functions at `(t, y)`.
    fn values(&self, t: f64, y: &State<N>) -> Values;
    /// Noise floor of each function: a sign change inside a step where `|g|` stays below the
    /// floor at both ends is round-off around a resting point, not a kink, and is ignored
    /// (otherwise a state at rest on a switching surface would chatter). Default: 0.
    fn floor(&self) -> Values {
        [0.0; MAX_FUNCTIONS]
    }
}

/// No switching points: step over everything.
#[derive(Debug, Clone, Copy, Default)]
pub struct NoSwitches;

impl<const N: usize> Switches<N> for NoSwitches {
    fn count(&self) -> usize {
        0
    }
    fn values(&self, _t: f64, _y: &State<N>) -> Values {
        [0.0; MAX_FUNCTIONS]
    }
}

/// Switching points at the zeros of a function `g(t, y) -> [f64; K]` with `K <= 4`.
#[derive(Debug, Clone, Copy)]
pub struct SwitchAt<G, const K: usize>(pub G);

impl<const N: usize, const K: usize, G: Fn(f64, &State<N>) -> [f64; K]> Switches<N>
    for SwitchAt<G, K>
{
    fn count(&self) -> usize {
        K
    }
    fn values(&self, t: f64, y: &State<N>) -> Values {
        let mut v = [0.0; MAX_FUNCTIONS];
        v[..K].copy_from_slice(&(self.0)(t, y));
        v
    }
}

/// Direction of a crossing.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Direction {
    /// From negative to zero or positive.
    Up,
    /// From positive to zero or negative.
    Down,
    /// Either way.
    Either,
}

/// The first zero crossing of one function in a given direction.
#[derive(Debug, Clone, Copy)]
pub struct Crossing<G> {
    g: G,
    direction: Direction,
}

impl<G> Crossing<G> {
    /// The event `g(t, y)` crosses zero in `direction`.
    pub fn new(g: G, direction: Direction) -> Self {
        Self { g, direction }
    }
}

impl<const N: usize, G: Fn(f64, &State<N>) -> f64> Condition<N> for Crossing<G> {
    fn count(&self) -> usize {
        1
    }
    fn values(&self, t: f64, y: &State<N>) -> Values {
        [(self.g)(t, y), 0.0, 0.0, 0.0]
    }
    fn holds(&self, start: &Values, now: &Values) -> bool {
        let (s, g) = (class(start[0]), class(now[0]));
        match self.direction {
            Direction::Up => s < 0 && g >= 0,
            Direction::Down => s > 0 && g <= 0,
            Direction::Either => s != 0 && g != s,
        }
    }
}

/// What one call of [`Locator::step`] did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Step<const N: usize> {
    /// An ordinary step; the integrator is at its end.
    Continued,
    /// The step crossed switching function `index`; the integrator was stopped exactly at the
    /// switching instant `t` (and restarts from there on the next step).
    Switched {
        /// Which switching function.
        index: usize,
        /// The switching instant.
        t: f64,
    },
    /// The terminal condition first holds at `t`, state `y`; the integrator was stopped exactly
    /// at `t` (the last step retaken to end there), so it can be restarted from the event.
    Event {
        /// Event instant.
        t: f64,
        /// State at the event.
        y: State<N>,
    },
}

/// How a run ended.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Outcome<const N: usize> {
    /// The terminal condition first holds at `t`.
    Event {
        /// Event instant.
        t: f64,
        /// State at the event.
        y: State<N>,
    },
    /// The horizon was reached without the condition holding.
    Horizon {
        /// The horizon.
        t: f64,
        /// State there.
        y: State<N>,
    },
}

/// Drives an integrator through terminal conditions and switching points.
#[derive(Debug, Clone)]
pub struct Locator<C, S> {
    condition: C,
    switches: S,
    /// Class imposed on each switching function at the start of the next step, right after the
    /// integrator stopped at its zero (the restarted state may sit a rounding error on the old
    /// side).
    forced: [Option<i8>; MAX_FUNCTIONS],
    /// A switching point predicted just ahead by the last aimed step: function and instant.
    pending: Option<(usize, f64)>,
    /// Size of the last aimed step that was accepted: where to resume after the switch.
    resume_h: f64,
    /// Function values at the end of the last step (each is evaluated once per step).
    last: Option<Last>,
    /// Whether the terminal condition can fire: false after an event until the condition has
    /// ceased to hold, so that continuing past an event does not report it again.
    armed: bool,
}

/// Boundary and switching values at the end of a step, valid while the integrator has not
/// moved since: same time and same RHS-evaluation count (every step, retake or restart
/// evaluates the right-hand side).
#[derive(Debug, Clone, Copy)]
struct Last {
    t: f64,
    rhs_evals: u64,
    g: Values,
    s: Values,
    /// Rates of the boundary functions (see the `interior` module).
    rate: Values,
}

impl<C, S> Locator<C, S> {
    /// A locator for `condition` with non-smooth points at the zeros of `switches`.
    pub fn new(condition: C, switches: S) -> Self {
        Self {
            condition,
            switches,
            forced: [None; MAX_FUNCTIONS],
            pending: None,
            resume_h: 0.0,
            last: None,
            armed: true,
        }
    }

    /// The locator for an integration that restarts at an event this condition reported (or
    /// at any state where it holds): the condition fires again only after it has ceased to
    /// hold. The same locator continues past its own events this way without being told:
    /// after a [`Step::Event`], keep calling [`Locator::step`] (or [`Locator::run`]).
    pub fn after_event(mut self) -> Self {
        self.armed = false;
        self
    }

    /// The terminal condition.
    pub fn condition(&self) -> &C {
        &self.condition
    }

    /// Takes one accepted step of `it` (ending at `t_end` at the latest) and handles the events
    /// inside it.
    ///
    /// # Errors
    /// [`Error::Solver`] when the integration fails, [`Error::TooManyFunctions`] for a condition
    /// or switch set with more than [`MAX_FUNCTIONS`] functions.
    pub fn step<T: Stepper<N>, const N: usize>(
        &mut self,
        it: &mut T,
        t_end: f64,
    ) -> Result<Step<N>, Error>
    where
        C: Condition<N>,
        S: Switches<N>,
    {
        let (nc, ns) = (self.condition.count(), self.switches.count());
        for (what, len) in [("condition", nc), ("switches", ns)] {
            if len > MAX_FUNCTIONS {
                return Err(Error::TooManyFunctions {
                    what,
                    len,
                    max: MAX_FUNCTIONS,
                });
            }
        }
        // Disarmed (just after an event), the step looks for switching points only.
        let armed = self.armed;
        let nc = if armed { nc } else { 0 };
        let (t0, y0, f0) = (it.t(), *it.y(), *it.derivative());
        // The values at the end of the previous step, unless the integrator moved since.
        let (g_start, mut s_start, rate_start) = match self.last.take() {
            Some(last) if last.t == t0 && last.rhs_evals == it.stats().rhs_evals => {
                (last.g, last.s, Some(last.rate))
            }
            _ => (
                self.condition.values(t0, &y0),
                self.switches.values(t0, &y0),
                None,
            ),
        };
        let mut s_class = [0i8; MAX_FUNCTIONS];
        for i in 0..ns {
            s_class[i] = self.forced[i].take().unwrap_or_else(|| class(s_start[i]));
            if s_class[i] != class(s_start[i]) {
                // Keep the value consistent with the imposed class for the root finder.
                s_start[i] = f64::from(s_class[i]) * f64::MIN_POSITIVE;
            }
        }

        let floor = self.switches.floor();
        let switches = &self.switches;
        let mut aim = aim::Aim::new(ns, s_start, s_class, floor);
        // Stop at a switching point predicted just ahead (if the step would reach it).
        let pending = self.pending.take().filter(|(_, t)| *t > t0 && *t < t_end);
        let t_stop = pending.map_or(t_end, |(_, t)| t);
        it.step_aiming(t_stop, &mut |trial| aim.after_rejection(switches, trial))?;
        let (t1, y1, f1) = (it.t(), *it.y(), *it.derivative());
        let g_end = self.condition.values(t1, &y1);
        let s_end = self.switches.values(t1, &y1);
        if !armed && !self.condition.holds(&g_end, &g_end) {
            self.armed = true;
        }
        let h = t1 - t0;
        let rate_end = if nc > 0 {
            interior::rates(&self.condition, nc, (t1, &y1, &f1), &g_end, h)
        } else {
            [0.0; MAX_FUNCTIONS]
        };
        self.last = Some(Last {
            t: t1,
            rhs_evals: it.stats().rhs_evals,
            g: g_end,
            s: s_end,
            rate: rate_end,
        });
        let crosses =
            |a: f64, ca: i8, b: f64| ca != 0 && class(b) != ca && !b.is_nan() && !a.is_nan();
        // A boundary function that left its class and came back inside the step: the scan
        // below first covers the step up to the first dense-output sample past the crossing.
        let mut scan_end = (t1, g_end, s_end);
        if nc > 0 {
            let rate_start = rate_start.unwrap_or_else(|| {
                interior::rates(&self.condition, nc, (t0, &y0, &f0), &g_start, h)
            });
            let suspected = (0..nc)
                .filter_map(|i| {
                    interior::suspect(g_start[i], h * rate_start[i], g_end[i], h * rate_end[i])
                })
                .min_by(f64::total_cmp);
            if let Some(theta) = suspected {
                let dense = it.dense();
                let mut thetas = [theta; interior::SAMPLES];
                for (j, th) in thetas.iter_mut().enumerate().skip(1) {
                    *th = j as f64 / interior::SAMPLES as f64;
                }
                thetas.sort_by(f64::total_cmp);
                for th in thetas {
                    let t = t0 + th * h;
                    let y = dense.eval(t);
                    let g = self.condition.values(t, &y);
                    if (0..nc).any(|i| crosses(g_start[i], class(g_start[i]), g[i])) {
                        scan_end = (t, g, self.switches.values(t, &y));
                        break;
                    }
                }
            }
        }
        let inside = scan_end.0 < t1;
        let above = |i: usize, a: f64, b: f64| a.abs() > floor[i] || b.abs() > floor[i];
        let any = inside
            || (0..nc).any(|i| crosses(g_start[i], class(g_start[i]), g_end[i]))
            || (0..ns).any(|i| {
                crosses(s_start[i], s_class[i], s_end[i]) && above(i, s_start[i], s_end[i])
            });
        // A step that ends on a switching point, within LANDING noise floors, stops there
        // without a retake: reached from the old side (a predicted point) or just past it.
        // (Ending a distance d short of a kink costs the next step an error of about h J d for
        // a jump J in the derivative of f: at 100 floors = 1000 atol, well inside that step's
        // tolerance; passing it is covered by the accepted step's own error estimate.)
        let landed = |i: usize| s_end[i].abs() <= LANDING * floor[i];
        let reached = pending.filter(|&(i, t)| t == t1 && class(s_end[i]) == s_class[i]);
        let passed =
            |i: usize| crosses(s_start[i], s_class[i], s_end[i]) && s_start[i].abs() > floor[i];
        let boundary_crossed =
            inside || (0..nc).any(|i| crosses(g_start[i], class(g_start[i]), g_end[i]));
        if !boundary_crossed {
            let stop = reached
                .map(|(i, _)| i)
                .or_else(|| (0..ns).find(|&i| passed(i)));
            if let Some(index) = stop.filter(|&i| landed(i)) {
                it.record_event();
                self.forced[index] = Some(-s_class[index]);
                self.resume(it);
                return Ok(Step::Switched { index, t: t1 });
            }
        }
        if !any {
            if let Some(predicted) = aim.after_acceptance(t1, &s_end) {
                self.pending = Some(predicted);
                self.resume_h = self.resume_h.max(t1 - t0);
            }
            return Ok(Step::Continued);
        }

        let dense = it.dense();
        let (mut ta, mut ga, mut sa) = (t0, g_start, s_start);
        let (mut te, mut ge, mut se) = scan_end;
        loop {
            // Earliest crossing in (ta, te] of a boundary function and of a switching function.
            let earliest = |acc: Option<(Bracket, usize)>, b: Bracket, i: usize| match acc {
                Some((a, _)) if a.hi <= b.hi => acc,
                _ => Some((b, i)),
            };
            let mut boundary: Option<(Bracket, usize)> = None;
            for i in 0..nc {
                if crosses(ga[i], class(ga[i]), ge[i]) {
                    let g = |t: f64| self.condition.values(t, &dense.eval(t))[i];
                    boundary = earliest(boundary, find_crossing(g, ta, te, ga[i], ge[i]), i);
                }
            }
            let mut switch: Option<(Bracket, usize)> = None;
            for i in 0..ns {
                let ca = if ta == t0 { s_class[i] } else { class(sa[i]) };
                if crosses(sa[i], ca, se[i]) && above(i, sa[i], se[i]) {
                    let g = |t: f64| self.switches.values(t, &dense.eval(t))[i];
                    switch = earliest(switch, find_crossing(g, ta, te, sa[i], se[i]), i);
                }
            }
            if let Some((b, _)) = boundary {
                if switch.is_none_or(|(s, _)| b.hi <= s.hi) {
                    let t = b.hi;
                    let y = dense.eval(t);
                    let g = self.condition.values(t, &y);
                    if self.condition.holds(&g_start, &g) {
                        it.record_event();
                        // Retake the step to end exactly at the event: the state there then
                        // comes from a full step (the method's order) rather than from the
                        // interpolant of a step that may straddle a non-smooth point (a force
                        // like |x|^p with non-integer p vanishes exactly at separation).
                        if t < t1 {
                            it.retake_to(t)?;
                            return Ok(self.fired(Step::Event { t, y: *it.y() }));
                        }
                        return Ok(self.fired(Step::Event { t, y }));
                    }
                    // A boundary crossed without entering the set. Unless a switching point
                    // falls on the same instant, keep scanning the rest of the step (if any is
                    // left: at its end the interpolant and the step's state can differ by a
                    // rounding error, which must not count as a crossing again).
                    if switch.is_none_or(|(s, _)| b.hi < s.hi) && t < te {
                        ta = t;
                        ga = g;
                        sa = self.switches.values(t, &y);
                        continue;
                    }
                }
            }
            let Some((bracket, index)) = switch else {
                if te < t1 {
                    // Nothing more up to the interior sample: scan the rest of the step.
                    (ta, ga, sa) = (te, ge, se);
                    (te, ge, se) = (t1, g_end, s_end);
                    continue;
                }
                return Ok(Step::Continued);
            };
            it.record_event();
            if te == t1 && ta == t0 && passed(index) && landed(index) {
                // The step ends on the switching point. A boundary crossing just past the
                // point (inside the landing zone) is still the event: the next step would start
                // inside the set and never see it cross.
                if let Some((b, _)) = boundary {
                    let y = dense.eval(b.hi);
                    if self
                        .condition
                        .holds(&g_start, &self.condition.values(b.hi, &y))
                    {
                        if b.hi < t1 {
                            it.retake_to(b.hi)?;
                            return Ok(self.fired(Step::Event {
                                t: b.hi,
                                y: *it.y(),
                            }));
                        }
                        return Ok(self.fired(Step::Event { t: t1, y: y1 }));
                    }
                }
                self.forced[index] = Some(-s_class[index]);
                self.resume(it);
                return Ok(Step::Switched { index, t: t1 });
            }
            let t = bracket.hi;
            self.forced[index] = Some(class(self.switches.values(t, &dense.eval(t))[index]));
            if t < t1 {
                self.resume_h = self.resume_h.max(t1 - t0);
                it.retake_to(t)?;
            }
            // The condition may hold at the switching point itself (a boundary function that
            // reaches zero there).
            if armed
                && self
                    .condition
                    .holds(&g_start, &self.condition.values(t, it.y()))
            {
                return Ok(self.fired(Step::Event { t, y: *it.y() }));
            }
            self.resume(it);
            return Ok(Step::Switched { index, t });
        }
    }

    /// Disarms the condition after reporting `event` (see [`Locator::after_event`]).
    fn fired<const N: usize>(&mut self, event: Step<N>) -> Step<N> {
        self.armed = false;
        event
    }

    /// After a stop at a switching point: resume with the step size that fitted before it
    /// (the controller's proposal after the short steps that closed in on the point is tiny).
    fn resume<T: Stepper<N>, const N: usize>(&mut self, it: &mut T) {
        it.propose_step_size(it.next_step_size().max(self.resume_h));
        self.resume_h = 0.0;
    }

    /// Steps until the terminal condition holds or `t_end` is reached.
    ///
    /// # Errors
    /// As [`Locator::step`].
    pub fn run<T: Stepper<N>, const N: usize>(
        &mut self,
        it: &mut T,
        t_end: f64,
    ) -> Result<Outcome<N>, Error>
    where
        C: Condition<N>,
        S: Switches<N>,
    {
        while it.t() < t_end {
            if let Step::Event { t, y } = self.step(it, t_end)? {
                return Ok(Outcome::Event { t, y });
            }
        }
        Ok(Outcome::Horizon {
            t: it.t(),
            y: *it.y(),
        })
    }
}
