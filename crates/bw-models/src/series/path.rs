//! The walk of one impact by Taylor series: from contact, step after step (a start step where
//! a base vanishes, then expansions in logarithmic time about that zero while they grow fast,
//! else an expansion in time, its step size, the earliest event inside the step and what that
//! event does) until the separation, rest, or a hand-over to the Runge-Kutta path.

use super::jet::{Clock, Expand, Jet};
use super::polynomial::{class, eval_d, jorba_zou, root, Series, ORDER};
use super::steps::{
    reach_root, start_step, step_tolerance, Target, FORCE_MARGIN, LOG_STEP_MIN, MAX_GROWTH,
    MAX_SERIES_STEPS, MAX_STALLED, RETRY_SPAN, START_TOLERANCE,
};
use crate::models::at_rest;
use crate::outcome::Impact;
use crate::settings::Settings;
use crate::{separated, State};
use bwc_ode::Stats;

/// What the series path made of an impact.
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

/// Whether the root at `a.0` of the function `watch[a.1]` comes before the root at `b.0` of
/// `watch[b.1]`. Roots within a few ulps of each other are a tie: a zero of a base (set exactly
/// to zero) comes before a root of the force, which can vanish with it and is then flat there
/// (its run onto the root would stop short); between other functions the smaller root wins,
/// and of two equal roots that of the function listed first.
fn earlier(watch: &[Watched; 5], a: (f64, usize), b: (f64, usize)) -> bool {
    let tie = (a.0 - b.0).abs() <= 8.0 * f64::EPSILON * a.0.abs().max(b.0.abs());
    if !tie {
        return a.0 < b.0;
    }
    let zero_before_force = |i: usize, j: usize| {
        matches!(watch[i].0, Event::Z | Event::Base) && watch[j].0 == Event::Force
    };
    if zero_before_force(a.1, b.1) || zero_before_force(b.1, a.1) {
        return zero_before_force(a.1, b.1);
    }
    a.0 < b.0 || (a.0 == b.0 && a.1 < b.1)
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

/// An event function of a step: which, its class at the step's start, whether it is watched.
type Watched = (Event, i8, bool);

/// Whether a watched function has left its class at the step's start, by its values `at`.
fn changed(watch: &[Watched; 5], at: &[f64; 5]) -> bool {
    watch
        .iter()
        .zip(at)
        .any(|(&(_, start, on), v)| on && class(*v) != start)
}

/// The state of the walk.
pub(super) struct SeriesPath<'a, M, const N: usize> {
    model: &'a M,
    settings: &'a Settings,
    /// The constant input.
    u: f64,
    t: f64,
    y: State<N>,
    stats: Stats,
    series_steps: u64,
    /// The last step's size: a step may be at most `MAX_GROWTH` times it.
    h_last: f64,
    /// Sign of the rate across the hysteretic element: the branch of the expansion.
    rate_class: i8,
    jet: Jet<N>,
    /// Event steps in a row that did not advance the time (a sliding mode: the rate across the
    /// hysteretic element stays at zero and its sign flips at every step).
    stalled: u32,
    /// The force where this step starts, if the last step computed it already (at its end, or
    /// zero at a located root).
    force_here: Option<f64>,
    /// `Z*` of the branch (signs of the rate and of `Z`) it was last computed for.
    z_star: Option<((i8, i8), Option<f64>)>,
    /// The time where a base last vanished, while the steps are taken in the logarithmic
    /// variable about it ([`Clock::Log`]): from the start step off that zero until an event
    /// lies ahead.
    anchor: Option<f64>,
    /// The last logarithmic step (in `σ`).
    h_log: f64,
}

/// What lies ahead in a step: an event at `s`, or its end (the state and event values there).
enum Ahead<const N: usize> {
    Event(f64, Event),
    End([f64; N], [f64; 5]),
}

/// What a phase of the walk decided.
enum Next<const N: usize> {
    /// Go on with the next step.
    Step,
    /// The impact is over, or handed over.
    Finish(SeriesRun<N>),
}

impl<'a, M: Expand<N>, const N: usize> SeriesPath<'a, M, N> {
    /// The walk at contact (after the model's contact series, where it has one), or `None`
    /// for a time-varying input.
    pub(super) fn start(model: &'a M, settings: &'a Settings) -> Option<Self> {
        if !model.input_is_constant() {
            return None;
        }
        let y = model.initial_state();
        let mut path = Self {
            model,
            settings,
            u: model.input(0.0),
            t: 0.0,
            y,
            stats: Stats::default(),
            series_steps: 0,
            h_last: f64::INFINITY,
            rate_class: class(model.kinks(0.0, &y)[0]),
            jet: Jet::new(),
            stalled: 0,
            force_here: None,
            z_star: None,
            anchor: None,
            h_log: 0.0,
        };
        if let Some((t1, y1)) = model.contact_step(path.u, settings) {
            path.series_steps += 1;
            path.stats.accepted += 1;
            (path.t, path.y, path.h_last) = (t1, y1, t1);
            if model.velocity(&path.y) == 0.0 {
                // It ended on the maximum compression.
                path.stats.events += 1;
                path.rate_class = -path.rate_class;
            }
        }
        Some(path)
    }

    /// Steps until the impact is over or handed over.
    pub(super) fn run(mut self) -> SeriesRun<N> {
        loop {
            let next = match self.ended() {
                Err(done) => Next::Finish(done),
                Ok(_) if self.y[M::BASE] == 0.0 || self.y[M::Z] == 0.0 => self.leave_zero(),
                Ok(start) => match self.anchor {
                    Some(anchor) => self
                        .log_step(anchor, start)
                        .unwrap_or_else(|start| self.series_step(start)),
                    None => self.series_step(start),
                },
            };
            if let Next::Finish(run) = next {
                return run;
            }
        }
    }

    /// The Runge-Kutta path continues from here.
    fn hand_over(&self) -> SeriesRun<N> {
        SeriesRun::HandOver {
            t: self.t,
            state: self.y,
            stats: self.stats,
            series_steps: self.series_steps,
        }
    }

    /// The separation where the step starts, or a limit that hands the impact over; else the
    /// force and the velocity there.
    // The large error is the finished impact, returned once per run; boxing it would allocate
    // in a CoR evaluation, which allocates nothing.
    #[allow(clippy::result_large_err)]
    fn ended(&mut self) -> Result<(f64, f64), SeriesRun<N>> {
        let (model, settings) = (self.model, self.settings);
        let force = self
            .force_here
            .take()
            .unwrap_or_else(|| model.force(&self.y));
        let velocity = model.velocity(&self.y);
        if self.t > 0.0 && separated(force, velocity) {
            // The separation, reached at the end of the last step or at its event.
            self.stats.events += 1;
            let e = velocity.max(0.0) / model.impact_speed();
            let steps = self.series_steps;
            return Err(SeriesRun::Done(
                Impact::unchecked((Some(self.t), e, self.y), self.stats, settings.rtol)
                    .with(|c| c.series_steps = steps),
            ));
        }
        let limit = self.series_steps >= MAX_SERIES_STEPS
            || self.stats.accepted >= settings.max_steps
            || self.t >= settings.t_max;
        if limit {
            return Err(self.hand_over());
        }
        Ok((force, velocity))
    }

    /// Where a base vanishes: at contact the loading's leading terms ([`Expand::contact_start`]),
    /// elsewhere (or where those decline) one step of the explicit method leaves the point; the
    /// Runge-Kutta path retakes it if it met an event.
    fn leave_zero(&mut self) -> Next<N> {
        let (model, settings) = (self.model, self.settings);
        if self.y[M::Z] == 0.0 && self.y[M::BASE] != 0.0 && self.leave_root_of_z() {
            return Next::Step;
        }
        if self.t == 0.0 && self.leave_contact() {
            return Next::Step;
        }
        let (t_start, y_start, stats_start) = (self.t, self.y, self.stats);
        let k = model.coefficients();
        let q = 1.0 + k.p.exponent().min(k.n.exponent());
        let Some((t, y)) = start_step(model, settings, (self.t, &self.y), q, &mut self.stats)
        else {
            (self.t, self.y, self.stats) = (t_start, y_start, stats_start);
            return Next::Finish(self.hand_over());
        };
        (self.t, self.y) = (t, y);
        self.h_last = t - t_start;
        if self.met_an_event(t, &y) {
            (self.t, self.y, self.stats) = (t_start, y_start, stats_start);
            return Next::Finish(self.hand_over());
        }
        // The start step spans σ from -∞ to 0: the first logarithmic step may be MAX_GROWTH.
        (self.anchor, self.h_log) = (Some(t_start), 1.0);
        Next::Step
    }

    /// Whether a first step off a zero of a base, to `(t, y)`, met an event: the rate changed
    /// sign, a base vanished, or the contact separated.
    fn met_an_event(&self, t: f64, y: &State<N>) -> bool {
        let model = self.model;
        class(model.kinks(t, y)[0]) != self.rate_class
            || y[M::BASE] == 0.0
            || y[M::Z] == 0.0
            || separated(model.force(y), model.velocity(y))
    }

    /// Off contact, the state from the loading's leading terms ([`Expand::contact_start`])
    /// where no event function has changed sign there; whether it took that step.
    fn leave_contact(&mut self) -> bool {
        let (model, settings) = (self.model, self.settings);
        let tol = START_TOLERANCE * step_tolerance(&self.y, settings);
        let Some((t, y)) = model.contact_start(self.u, tol) else {
            return false;
        };
        // In loading every base is negative.
        if self.met_an_event(t, &y) || y[M::BASE] > 0.0 || y[M::Z] > 0.0 {
            return false;
        }
        self.series_steps += 1;
        self.stats.accepted += 1;
        (self.t, self.y, self.h_last) = (t, y, t);
        (self.anchor, self.h_log) = (Some(0.0), 1.0);
        true
    }

    /// Off a root of `Z`, the model's series in `D = |Z|` where it has one for this branch
    /// ([`Expand::crossing_step`]); whether it took the step.
    fn leave_root_of_z(&mut self) -> bool {
        let s = f64::from(self.rate_class);
        let tol = step_tolerance(&self.y, self.settings);
        let Some((dt, y, separated)) = self.model.crossing_step(&self.y, s, self.u, tol) else {
            return false;
        };
        self.series_steps += 1;
        self.stats.accepted += 1;
        (self.t, self.y, self.h_last) = (self.t + dt, y, dt);
        if separated {
            // Ended on the force's root with V >= 0: the next step's start reports it.
            self.force_here = Some(0.0);
        }
        true
    }

    /// One expansion: rest, or a step to its end or to the earliest event inside it.
    fn series_step(&mut self, (force, velocity): (f64, f64)) -> Next<N> {
        let (model, settings) = (self.model, self.settings);
        let force = self.expand(force, Clock::Time);
        // At rest under the constant input: an equilibrium, the contact has settled.
        let rate_of_change = State::<N>::from_fn(|i, _| self.jet.state[i][1]);
        if at_rest(model, &rate_of_change, settings.atol) {
            let (t, steps) = (self.t, self.series_steps);
            return Next::Finish(SeriesRun::Done(
                Impact::unchecked((None, 0.0, self.y), self.stats, settings.rtol).with(|c| {
                    c.settled_at = Some(t);
                    c.series_steps = steps;
                }),
            ));
        }
        self.series_steps += 1;
        self.stats.accepted += 1;
        let tol = step_tolerance(&self.y, settings);
        let h = step_size(&self.jet, tol)
            .min(MAX_GROWTH * self.h_last)
            .min(settings.max_step)
            .min(settings.t_max - self.t);
        self.h_last = h;
        let watch = self.watch(force, velocity, tol);
        match self.earliest_event(h, tol, &watch) {
            Ahead::End(end, at_end) => {
                self.y = State::<N>::from(end);
                self.force_here = Some(at_end[0]);
                self.t += h;
                self.stalled = 0;
                Next::Step
            }
            Ahead::Event(s, event) => self.apply_event(s, event),
        }
    }

    /// Expands the solution from here in `clock` ([`Expand::expand`]), `Z` held at its branch's
    /// equilibrium where it has come near it ([`SeriesPath::saturate`]); the force here
    /// (`force`, or the force of the state moved onto the equilibrium).
    fn expand(&mut self, force: f64, clock: Clock) -> f64 {
        let (saturated, snapped) = self.saturate();
        let force = if snapped {
            self.model.force(&self.y)
        } else {
            force
        };
        let rate_sign = f64::from(self.rate_class);
        let model = self.model;
        model.expand(&self.y, rate_sign, saturated, self.u, clock, &mut self.jet);
        force
    }

    /// The event functions of a step from here (`force` and `velocity` at its start, `tol` its
    /// tolerance).
    fn watch(&self, force: f64, velocity: f64, tol: f64) -> [Watched; 5] {
        // The separation F <= 0 <= V: a root of V matters only where F <= 0 already (F is
        // nonpositive within the margin of its computed value; a force farther above zero
        // reaches its own root, an event of this step, before it can be).
        let force_may_be_down = force <= FORCE_MARGIN * tol;
        [
            (Event::Force, 1, force > 0.0),
            (
                Event::Velocity,
                -1,
                !M::RATE_IS_VELOCITY && velocity < 0.0 && force_may_be_down,
            ),
            (Event::Rate, self.rate_class, true),
            (Event::Z, class(self.y[M::Z]), true),
            (Event::Base, class(self.y[M::BASE]), true),
        ]
    }

    /// One expansion in the logarithmic variable about `anchor` ([`Clock::Log`]), taken where
    /// no event function changes sign at its end, or else at its middle (a step to the middle
    /// ends the logarithmic steps: the event is near, and the steps in time locate it), and
    /// the last one once it spans less than [`LOG_STEP_MIN`]. Declines, returning the force and
    /// the velocity at the start for a step in time, where a function changes sign by the
    /// middle or where the contact may be at rest (the step in time decides).
    fn log_step(&mut self, anchor: f64, start: (f64, f64)) -> Result<Next<N>, (f64, f64)> {
        let (model, settings) = (self.model, self.settings);
        let span = self.t - anchor;
        let (force, velocity) = (self.expand(start.0, Clock::Log(span)), start.1);
        let rate_of_change = State::<N>::from_fn(|i, _| self.jet.state[i][1] / span);
        if at_rest(model, &rate_of_change, settings.atol) {
            self.anchor = None;
            return Err((force, velocity));
        }
        let tol = step_tolerance(&self.y, settings);
        // σ for the largest span in time the settings allow.
        let limit = (settings.max_step.min(settings.t_max - self.t) / span).ln_1p();
        let mut h = step_size(&self.jet, tol)
            .min(MAX_GROWTH * self.h_log)
            .min(limit);
        let watch = self.watch(force, velocity, tol);
        let (mut end, mut at_end) = self.values(h, tol);
        if changed(&watch, &at_end) {
            self.anchor = None;
            let (mid, at_mid) = self.values(0.5 * h, tol);
            if changed(&watch, &at_mid) {
                return Err((force, velocity));
            }
            (h, end, at_end) = (0.5 * h, mid, at_mid);
        }
        self.series_steps += 1;
        self.stats.accepted += 1;
        self.h_log = h;
        if h < LOG_STEP_MIN {
            self.anchor = None;
        }
        self.h_last = span * h.exp_m1();
        self.t = anchor + span * h.exp();
        self.y = State::<N>::from(end);
        self.force_here = Some(at_end[0]);
        self.stalled = 0;
        Ok(Next::Step)
    }

    /// Whether `Z` is held at its branch's equilibrium `Z*` ([`Expand::saturation`]) for this
    /// step, and whether it was moved there now: once within [`START_TOLERANCE`] step
    /// tolerances of `Z*`. The exact `Z` approaches `Z*` monotonically while the branch lasts,
    /// so holding it there changes the state by at most that much once; the series then no
    /// longer carry the decay towards `Z*`, whose rate (`c n |Z*|^(n-1) |rate|`, large for a
    /// large `B`) caps explicit steps however small the deviation has become.
    fn saturate(&mut self) -> (bool, bool) {
        let branch = (self.rate_class, class(self.y[M::Z]));
        let z_star = match self.z_star {
            Some((b, z_star)) if b == branch => z_star,
            _ => {
                let z_star = self.model.saturation(&self.y, f64::from(self.rate_class));
                self.z_star = Some((branch, z_star));
                z_star
            }
        };
        let Some(z_star) = z_star else {
            return (false, false);
        };
        if self.y[M::Z] == z_star {
            return (true, false);
        }
        let near = START_TOLERANCE * step_tolerance(&self.y, self.settings);
        if (self.y[M::Z] - z_star).abs() > near {
            return (false, false);
        }
        self.y[M::Z] = z_star;
        (true, true)
    }

    /// The state and the event values at `s` in the step, from their series; near zero the
    /// force from the state instead (its sign is exact where the force has a multiple root,
    /// e.g. -|X|^(p-1) X at X = 0). Only its sign is used away from zero, where the series'
    /// value (error about the tolerance) has the sign of the force.
    fn values(&self, s: f64, tol: f64) -> ([f64; N], [f64; 5]) {
        let (ys, rate, series_force) = if M::RATE_IS_VELOCITY {
            self.jet.with_force_at::<true>(s)
        } else {
            self.jet.with_force_at::<false>(s)
        };
        let force = if series_force.abs() > FORCE_MARGIN * tol {
            series_force
        } else {
            self.model.force(&State::<N>::from(ys))
        };
        (ys, [force, ys[N - 1], rate, ys[M::Z], ys[M::BASE]])
    }

    /// The series of an event function.
    fn series_of(&self, event: Event) -> &Series {
        let jet = &self.jet;
        match event {
            Event::Force => &jet.force,
            Event::Velocity => &jet.state[N - 1],
            Event::Rate if M::RATE_IS_VELOCITY => &jet.state[N - 1],
            Event::Rate => &jet.rate,
            Event::Z => &jet.state[M::Z],
            Event::Base => &jet.state[M::BASE],
        }
    }

    /// The earliest root in the step of `h`: searched where a class has changed (in the first
    /// half of the step if one has changed there already), then again up to the root found,
    /// until no function changes earlier (a function may cross and cross back inside a long
    /// step). The function whose root ends the search is not searched again: its iteration
    /// would start on that root and return it. Ties are decided by [`earlier`].
    fn earliest_event(&self, h: f64, tol: f64, watch: &[Watched; 5]) -> Ahead<N> {
        let (end, at_end) = self.values(h, tol);
        let (_, at_mid) = self.values(0.5 * h, tol);
        let (mut upto, mut at) = if changed(watch, &at_mid) {
            (0.5 * h, at_mid)
        } else {
            (h, at_end)
        };
        // The earliest root found: where, and the index of its function in `watch`.
        let mut first: Option<(f64, usize)> = None;
        for _ in 0..8 {
            let mut best = first;
            for (i, (&(event, start, on), v)) in watch.iter().zip(&at).enumerate() {
                if !on || class(*v) == start || first.is_some_and(|(_, f)| f == i) {
                    continue;
                }
                let c = self.series_of(event);
                let s = if event == Event::Force {
                    root(|s| (self.values(s, tol).1[0], eval_d(c, s).1), upto, start)
                } else {
                    root(|s| eval_d(c, s), upto, start)
                };
                if best.is_none_or(|found| earlier(watch, (s, i), found)) {
                    best = Some((s, i));
                }
            }
            let Some((s, _)) = best else { break };
            let earlier = best != first;
            first = best;
            if !earlier || s >= upto {
                break;
            }
            upto = s;
            at = self.values(upto, tol).1;
        }
        match first {
            Some((s, i)) => Ahead::Event(s, watch[i].0),
            None => Ahead::End(end, at_end),
        }
    }

    /// Onto the root of `target` that the series put at `s` in this step (`at_root`, the
    /// series' state there), by the explicit method from the step's start ([`reach_root`]),
    /// trying the whole span as its first step. One Runge-Kutta step that long can pass its error
    /// test far from the solution (DOP853's estimate is asymptotic, and a series step spans
    /// several Runge-Kutta steps): where its end and the series' state differ by more than the
    /// step tolerance, the run is redone from a first step of [`RETRY_SPAN`] of the span.
    fn onto_root(&mut self, s: f64, target: Target, at_root: &State<N>) -> Option<(f64, State<N>)> {
        let (model, settings) = (self.model, self.settings);
        let span = ((self.t, &self.y), self.t + s);
        let reached = reach_root(model, settings, span, target, s, &mut self.stats)?;
        let apart = (reached.1 - at_root).amax();
        if apart <= step_tolerance(&self.y, settings) {
            return Some(reached);
        }
        reach_root(
            model,
            settings,
            span,
            target,
            RETRY_SPAN * s,
            &mut self.stats,
        )
    }

    /// The step ends at the event at `s`: onto a zero of a base by the explicit method (the
    /// series converge slowest there), across a sign change of the rate, or onto the force's
    /// root (by the explicit method near a zero of a base, where the force can vanish with
    /// it).
    fn apply_event(&mut self, s: f64, event: Event) -> Next<N> {
        let model = self.model;
        self.anchor = None;
        if self.t + s > self.t {
            self.stalled = 0;
        } else {
            self.stalled += 1;
            if self.stalled > MAX_STALLED {
                return Next::Finish(self.hand_over());
            }
        }
        let at_root = State::<N>::from(self.jet.state_at(s));
        let reached = match event {
            Event::Z | Event::Base => {
                self.stats.events += 1;
                let i = if event == Event::Z { M::Z } else { M::BASE };
                self.onto_root(s, Target::Component(i), &at_root)
            }
            Event::Rate => {
                self.stats.events += 1;
                self.rate_class = -self.rate_class;
                let mut y = at_root;
                if M::RATE_IS_VELOCITY {
                    y[N - 1] = 0.0;
                }
                Some((self.t + s, y))
            }
            Event::Force if at_root[N - 1] >= 0.0 => {
                // A separation near a zero of a base (one no farther from zero, by its slope,
                // than the root from the step's start): the explicit method takes the state.
                let near_a_base_zero = [M::BASE, M::Z].iter().any(|&i| {
                    let (b, db) = eval_d(&self.jet.state[i], s);
                    b.abs() <= s * db.abs()
                });
                if near_a_base_zero {
                    self.onto_root(s, Target::Force, &at_root)
                } else {
                    Some((self.t + s, at_root))
                }
            }
            Event::Velocity | Event::Force => {
                let mut y = at_root;
                if event == Event::Velocity {
                    y[N - 1] = 0.0;
                }
                Some((self.t + s, y))
            }
        };
        let Some((t, y)) = reached else {
            return Next::Finish(self.hand_over());
        };
        (self.t, self.y) = (t, y);
        // The separation F <= 0 <= V is checked where the next step starts; at a located root
        // of the force, F is zero to rounding, either sign.
        if event == Event::Force && model.velocity(&self.y) >= 0.0 {
            self.force_here = Some(0.0);
        }
        Next::Step
    }
}
