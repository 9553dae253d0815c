//! The locator: one accepted step at a time, the events and switching points inside it.

use crate::error::Error;
use crate::functions::{Condition, Switches, Values, LANDING, MAX_FUNCTIONS};
use crate::root::{class, find_crossing, Bracket};
use crate::{aim, interior};
use bwc_ode::{Dense, State, Stepper};

/// The earliest crossing of one kind of function in a span, if any: where (bracketed) and which.
type Crossing = Option<(Bracket, usize)>;

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

/// Most rounds of [`Locator::retake_to_event`].
const POLISH_ROUNDS: usize = 4;

/// A root found again on a retaken step is retaken to only where it moved by more than this
/// many units in the last place of the time: a retake costs a step.
const MOVE_ULPS: f64 = 8.0;

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
    /// Whether an event was put off since the last one fired ([`Locator::retake_to_event`]):
    /// once only, so that a condition that holds or not by rounding (a creeping contact, `F`
    /// and `v` both near zero for a long time) is reported where it first holds on the
    /// interpolant, not carried to the horizon.
    deferred: bool,
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
            deferred: false,
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
    /// inside it, in four phases: the values where the step starts, the step itself (aimed at a
    /// predicted switching point), a scan for a boundary function that leaves its class and
    /// returns inside the step, and, where anything crossed, the earliest crossing located and
    /// acted on.
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
        let counts = Counts {
            nc: if self.armed { nc } else { 0 },
            ns,
            armed: self.armed,
        };
        let start = self.start(it, counts);
        let (end, pending, aim) = self.advance(it, t_end, counts, &start)?;
        let scan_end = self.interior(it, counts, &start, &end);
        if let Some(step) = self.land(it, counts, &start, &end, scan_end.0, pending, &aim) {
            return Ok(step);
        }
        self.locate(it, counts, &start, &end, scan_end)
    }

    /// The boundary and switching values where the step starts (cached from the last step's
    /// end unless the integrator moved since), switching classes imposed after a stop.
    fn start<T: Stepper<N>, const N: usize>(&mut self, it: &T, c: Counts) -> Ends<N>
    where
        C: Condition<N>,
        S: Switches<N>,
    {
        let (t0, y0, f0) = (it.t(), *it.y(), *it.derivative());
        let (g, mut s, rate) = match self.last.take() {
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
        for i in 0..c.ns {
            s_class[i] = self.forced[i].take().unwrap_or_else(|| class(s[i]));
            if s_class[i] != class(s[i]) {
                // Keep the value consistent with the imposed class for the root finder.
                s[i] = f64::from(s_class[i]) * f64::MIN_POSITIVE;
            }
        }
        Ends {
            t: t0,
            y: y0,
            f: f0,
            g,
            s,
            s_class,
            rate,
        }
    }

    /// The step itself, stopping at a switching point predicted just ahead and aiming rejected
    /// trials at the switching points they straddle; the values where it ends (cached for the
    /// next step), and whether the condition, disarmed, has ceased to hold.
    #[allow(clippy::type_complexity)]
    fn advance<T: Stepper<N>, const N: usize>(
        &mut self,
        it: &mut T,
        t_end: f64,
        c: Counts,
        start: &Ends<N>,
    ) -> Result<(Ends<N>, Option<(usize, f64)>, aim::Aim), Error>
    where
        C: Condition<N>,
        S: Switches<N>,
    {
        let floor = self.switches.floor();
        let switches = &self.switches;
        let mut aim = aim::Aim::new(c.ns, start.s, start.s_class, floor);
        let t0 = start.t;
        let pending = self.pending.take().filter(|(_, t)| *t > t0 && *t < t_end);
        let t_stop = pending.map_or(t_end, |(_, t)| t);
        it.step_aiming(t_stop, &mut |trial| aim.after_rejection(switches, trial))?;
        let (t1, y1, f1) = (it.t(), *it.y(), *it.derivative());
        let g = self.condition.values(t1, &y1);
        let s = self.switches.values(t1, &y1);
        if !self.armed && !self.condition.holds(&g, &g) {
            self.armed = true;
        }
        let rate = if c.nc > 0 {
            interior::rates(&self.condition, c.nc, (t1, &y1, &f1), &g, t1 - t0)
        } else {
            [0.0; MAX_FUNCTIONS]
        };
        self.last = Some(Last {
            t: t1,
            rhs_evals: it.stats().rhs_evals,
            g,
            s,
            rate,
        });
        let end = Ends {
            t: t1,
            y: y1,
            f: f1,
            g,
            s,
            s_class: [0; MAX_FUNCTIONS],
            rate: Some(rate),
        };
        Ok((end, pending, aim))
    }

    /// Where the scan for crossings ends: the step's end, or the first dense-output sample past
    /// a boundary function that left its class and came back inside the step (a cubic model
    /// from its values and rates at the ends, confirmed on the dense output).
    fn interior<T: Stepper<N>, const N: usize>(
        &self,
        it: &mut T,
        c: Counts,
        start: &Ends<N>,
        end: &Ends<N>,
    ) -> (f64, Values, Values)
    where
        C: Condition<N>,
        S: Switches<N>,
    {
        let mut scan_end = (end.t, end.g, end.s);
        if c.nc == 0 {
            return scan_end;
        }
        let (t0, h) = (start.t, end.t - start.t);
        let rate_start = start.rate.unwrap_or_else(|| {
            interior::rates(&self.condition, c.nc, (t0, &start.y, &start.f), &start.g, h)
        });
        let rate_end = end.rate.unwrap_or([0.0; MAX_FUNCTIONS]);
        let suspected = (0..c.nc)
            .filter_map(|i| {
                interior::suspect(start.g[i], h * rate_start[i], end.g[i], h * rate_end[i])
                    .map(|theta| (theta, i))
            })
            .min_by(|a, b| a.0.total_cmp(&b.0));
        if let Some((theta, i)) = suspected {
            let dense = it.dense();
            let sign = f64::from(class(start.g[i]));
            let on_dense = |th: f64| {
                let t = t0 + th * h;
                self.condition.values(t, &dense.eval(t))[i]
            };
            let mut thetas = [theta; interior::SAMPLES + 1];
            for (j, th) in thetas.iter_mut().enumerate().skip(2) {
                *th = (j - 1) as f64 / interior::SAMPLES as f64;
            }
            thetas[1] = interior::extremum(theta, sign, on_dense);
            thetas.sort_by(f64::total_cmp);
            for th in thetas {
                let t = t0 + th * h;
                let y = dense.eval(t);
                let g = self.condition.values(t, &y);
                if (0..c.nc).any(|i| crosses(start.g[i], class(start.g[i]), g[i])) {
                    scan_end = (t, g, self.switches.values(t, &y));
                    break;
                }
            }
        }
        scan_end
    }

    /// The quick endings of a step: nothing crossed (the step continues, with a switching point
    /// predicted just ahead), or it ends on a switching point within `LANDING` noise floors,
    /// reached from the old side or just past it, with no boundary crossed: it stops there
    /// without a retake. (Ending a distance d short of a kink costs the next step an error of
    /// about h J d for a jump J in the derivative of f: at 100 floors = 1000 atol, well inside
    /// that step's tolerance; passing it is covered by the accepted step's own error estimate.)
    #[allow(clippy::too_many_arguments)]
    fn land<T: Stepper<N>, const N: usize>(
        &mut self,
        it: &mut T,
        c: Counts,
        start: &Ends<N>,
        end: &Ends<N>,
        scan_end: f64,
        pending: Option<(usize, f64)>,
        aim: &aim::Aim,
    ) -> Option<Step<N>>
    where
        S: Switches<N>,
    {
        let floor = self.switches.floor();
        let inside = scan_end < end.t;
        let boundary_crossed =
            inside || (0..c.nc).any(|i| crosses(start.g[i], class(start.g[i]), end.g[i]));
        let switch_crossed = (0..c.ns).any(|i| {
            crosses(start.s[i], start.s_class[i], end.s[i])
                && above(&floor, i, start.s[i], end.s[i])
        });
        if !boundary_crossed {
            let reached =
                pending.filter(|&(i, t)| t == end.t && class(end.s[i]) == start.s_class[i]);
            let stop = reached
                .map(|(i, _)| i)
                .or_else(|| (0..c.ns).find(|&i| passed(&floor, start, end, i)));
            if let Some(index) = stop.filter(|&i| landed(&floor, end, i)) {
                it.record_event();
                self.forced[index] = Some(-start.s_class[index]);
                self.resume(it);
                return Some(Step::Switched { index, t: end.t });
            }
        }
        if boundary_crossed || switch_crossed {
            return None;
        }
        if let Some(predicted) = aim.after_acceptance(end.t, &end.s) {
            self.pending = Some(predicted);
            self.resume_h = self.resume_h.max(end.t - start.t);
        }
        Some(Step::Continued)
    }

    /// The earliest crossing in the step, scanned up to `scan_end` and then to the step's end:
    /// a boundary crossing where the condition holds is the event (the step retaken to end
    /// exactly there); a switching point stops the integrator there (retaken) unless the
    /// condition holds at it.
    fn locate<T: Stepper<N>, const N: usize>(
        &mut self,
        it: &mut T,
        c: Counts,
        start: &Ends<N>,
        end: &Ends<N>,
        scan_end: (f64, Values, Values),
    ) -> Result<Step<N>, Error>
    where
        C: Condition<N>,
        S: Switches<N>,
    {
        let (t0, t1) = (start.t, end.t);
        let dense = it.dense();
        let (mut ta, mut ga, mut sa) = (t0, start.g, start.s);
        let (mut te, mut ge, mut se) = scan_end;
        loop {
            let (boundary, switch) =
                self.crossings(&dense, c, start, (ta, &ga, &sa), (te, &ge, &se));
            if let Some((b, _)) = boundary {
                if switch.is_none_or(|(s, _)| b.hi <= s.hi) {
                    let t = b.hi;
                    let y = dense.eval(t);
                    let g = self.condition.values(t, &y);
                    if self.condition.holds(&start.g, &g) {
                        // Retake the step to end exactly at the event: the state there then
                        // comes from a full step (the method's order) rather than from the
                        // interpolant of a step that may straddle a non-smooth point (a force
                        // like |x|^p with non-integer p vanishes exactly at separation).
                        if t < t1 {
                            let Some((t, y)) = self.retake_to_event(it, c, start, (t, &y))? else {
                                return Ok(Step::Continued);
                            };
                            it.record_event();
                            return Ok(self.fired(Step::Event { t, y }));
                        }
                        it.record_event();
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
                    (te, ge, se) = (t1, end.g, end.s);
                    continue;
                }
                return Ok(Step::Continued);
            };
            it.record_event();
            let whole = te == t1 && ta == t0;
            return self.stop_at_switch(it, c, (start, end), whole, (bracket, index), boundary);
        }
    }

    /// Retakes the step to end at the event `t` found on its interpolant (state `y` there).
    /// Where the retaken state differs from `y` by more than the error tolerance, the
    /// interpolant was worse than the step and its root may be off: the crossing is looked for
    /// again on the interpolant of the retaken (shorter) step and retaken to where it moved (by
    /// more than [`MOVE_ULPS`], at most [`POLISH_ROUNDS`] rounds). The event and the state
    /// there, or `None` where the condition does not hold at a retaken state: the root lies
    /// ahead (or the interpolant's crossing was a touch the step does not make), and the
    /// integration goes on from there with an ordinary step, whose interpolant finds it near
    /// its start. An event is put off once only: the next one is reported where its
    /// interpolant puts it.
    ///
    /// Why: where a fast mode rests at its equilibrium (a saturated Bouc-Wen element, `h λ`
    /// beyond the method's stability interval) the extra stages of the interpolant amplify its
    /// rounding, so a long step's interpolant can place the root of a flat boundary function
    /// far off (2.3e-10 at rtol 1e-13 on a stress case, STABILITY.md), and the state moves with
    /// that error times its rate.
    fn retake_to_event<T: Stepper<N>, const N: usize>(
        &mut self,
        it: &mut T,
        c: Counts,
        start: &Ends<N>,
        (mut t, y): (f64, &State<N>),
    ) -> Result<Option<(f64, State<N>)>, Error>
    where
        C: Condition<N>,
        S: Switches<N>,
    {
        let boundaries = Counts { ns: 0, ..c };
        let none = [0.0; MAX_FUNCTIONS];
        it.retake_to(t)?;
        if it.tolerances(&(it.y() - y)) <= 1.0 {
            // The interpolant was as good as the step there: so is its root.
            return Ok(Some((t, *it.y())));
        }
        for _ in 0..POLISH_ROUNDS {
            let g = self.condition.values(t, it.y());
            if !self.condition.holds(&start.g, &g) {
                if self.deferred {
                    break;
                }
                self.deferred = true;
                return Ok(None);
            }
            let dense = it.dense();
            let ta = dense.t0();
            let ga = self.condition.values(ta, &dense.eval(ta));
            let earlier = self
                .crossings(&dense, boundaries, start, (ta, &ga, &none), (t, &g, &none))
                .0
                .map(|(b, _)| b.hi)
                .filter(|&tb| {
                    t - tb > MOVE_ULPS * f64::EPSILON * t.abs()
                        && self
                            .condition
                            .holds(&start.g, &self.condition.values(tb, &dense.eval(tb)))
                });
            let Some(tb) = earlier else { break };
            it.retake_to(tb)?;
            t = tb;
        }
        Ok(Some((t, *it.y())))
    }

    /// The step's earliest switching point, `switch` (function `index`), found when scanning the
    /// whole step (`whole`) or a part of it: where the step ends on it, its boundary crossing
    /// just past it is the event, else the integrator stops there with the function's class
    /// forced; elsewhere the step is retaken to end on it, and the condition may hold there.
    fn stop_at_switch<T: Stepper<N>, const N: usize>(
        &mut self,
        it: &mut T,
        c: Counts,
        (start, end): (&Ends<N>, &Ends<N>),
        whole: bool,
        (bracket, index): (Bracket, usize),
        boundary: Crossing,
    ) -> Result<Step<N>, Error>
    where
        C: Condition<N>,
        S: Switches<N>,
    {
        let floor = self.switches.floor();
        let (t0, t1) = (start.t, end.t);
        let dense = it.dense();
        if whole && passed(&floor, start, end, index) && landed(&floor, end, index) {
            // The step ends on the switching point. A boundary crossing just past the point
            // (inside the landing zone) is still the event: the next step would start inside
            // the set and never see it cross.
            if let Some((b, _)) = boundary {
                let y = dense.eval(b.hi);
                if self
                    .condition
                    .holds(&start.g, &self.condition.values(b.hi, &y))
                {
                    if b.hi < t1 {
                        it.retake_to(b.hi)?;
                        return Ok(self.fired(Step::Event {
                            t: b.hi,
                            y: *it.y(),
                        }));
                    }
                    return Ok(self.fired(Step::Event { t: t1, y: end.y }));
                }
            }
            self.forced[index] = Some(-start.s_class[index]);
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
        if c.armed
            && self
                .condition
                .holds(&start.g, &self.condition.values(t, it.y()))
        {
            return Ok(self.fired(Step::Event { t, y: *it.y() }));
        }
        self.resume(it);
        Ok(Step::Switched { index, t })
    }

    /// The earliest crossing in `(ta, te]` of a boundary function and of a switching function,
    /// from their values at both ends (`a`, `e`: time, boundary values, switching values); a
    /// switching function counts where it leaves its class at the step's start and moves by
    /// more than its floor.
    fn crossings<const N: usize>(
        &self,
        dense: &Dense<N>,
        c: Counts,
        start: &Ends<N>,
        (ta, ga, sa): (f64, &Values, &Values),
        (te, ge, se): (f64, &Values, &Values),
    ) -> (Crossing, Crossing)
    where
        C: Condition<N>,
        S: Switches<N>,
    {
        let floor = self.switches.floor();
        let earliest = |acc: Crossing, b: Bracket, i: usize| match acc {
            Some((a, _)) if a.hi <= b.hi => acc,
            _ => Some((b, i)),
        };
        let mut boundary: Crossing = None;
        for i in 0..c.nc {
            if crosses(ga[i], class(ga[i]), ge[i]) {
                let g = |t: f64| self.condition.values(t, &dense.eval(t))[i];
                boundary = earliest(boundary, find_crossing(g, ta, te, ga[i], ge[i]), i);
            }
        }
        let mut switch: Crossing = None;
        for i in 0..c.ns {
            let ca = if ta == start.t {
                start.s_class[i]
            } else {
                class(sa[i])
            };
            if crosses(sa[i], ca, se[i]) && above(&floor, i, sa[i], se[i]) {
                let g = |t: f64| self.switches.values(t, &dense.eval(t))[i];
                switch = earliest(switch, find_crossing(g, ta, te, sa[i], se[i]), i);
            }
        }
        (boundary, switch)
    }

    /// Disarms the condition after reporting `event` (see [`Locator::after_event`]).
    fn fired<const N: usize>(&mut self, event: Step<N>) -> Step<N> {
        self.armed = false;
        self.deferred = false;
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

/// How many boundary functions a step watches (none while disarmed) and switching functions.
#[derive(Debug, Clone, Copy)]
struct Counts {
    nc: usize,
    ns: usize,
    /// Whether the condition could fire when the step started.
    armed: bool,
}

/// The state and the function values at one end of a step.
struct Ends<const N: usize> {
    t: f64,
    y: State<N>,
    f: State<N>,
    g: Values,
    s: Values,
    /// Switching classes (imposed after a stop; start only).
    s_class: [i8; MAX_FUNCTIONS],
    /// Rates of the boundary functions, where known.
    rate: Option<Values>,
}

/// Whether a function with class `ca` at value `a` has another class at `b`.
fn crosses(a: f64, ca: i8, b: f64) -> bool {
    ca != 0 && class(b) != ca && !b.is_nan() && !a.is_nan()
}

/// Whether switching function `i` is above its noise floor at either end.
fn above(floor: &Values, i: usize, a: f64, b: f64) -> bool {
    a.abs() > floor[i] || b.abs() > floor[i]
}

/// Whether the step ends within `LANDING` noise floors of switching function `i`'s zero.
fn landed<const N: usize>(floor: &Values, end: &Ends<N>, i: usize) -> bool {
    end.s[i].abs() <= LANDING * floor[i]
}

/// Whether switching function `i` crossed in the step from above its noise floor.
fn passed<const N: usize>(floor: &Values, start: &Ends<N>, end: &Ends<N>, i: usize) -> bool {
    crosses(start.s[i], start.s_class[i], end.s[i]) && start.s[i].abs() > floor[i]
}
