//! One impact: integrate a model from the instant of contact to separation
//! `t_s = inf{t > 0 : F <= 0 <= v}` and report `t_s`, `e = v(t_s) / v0` and `t_d = t_s`.

#[cfg(doc)]
use crate::checked::{impact, tighter, CHECK_METHOD, TIGHTER_METHOD};
use crate::checked::{Check, DdDeclined, FailedRun};
use crate::models::CollisionModel;
use crate::params::check;
use crate::series::SeriesRun;
use crate::{ModelError, Separation, State};
use bwc_events::{Locator, Step, Switches, Values, MAX_FUNCTIONS};
use bwc_ode::{Jacobian, Matrix, Method, Options, Solver, Stats, Stepper, System, Tableau, DOP853};

/// Solver settings of an impact. Tolerances, steps and the horizon are in the model's natural
/// units: nondimensional for the ND models; for SI models they are multiplied by the scales of
/// Table 1 (`atol` per component by `X_c`, `Z_c`, `v0`; times by `T_c`), so the same settings
/// give the same accuracy both ways.
#[derive(Debug, Clone, Copy)]
pub struct Settings {
    /// Runge-Kutta method.
    pub method: &'static Tableau,
    /// Relative tolerance.
    pub rtol: f64,
    /// Absolute tolerance (natural units).
    pub atol: f64,
    /// Largest step (natural time units; `+inf` for none).
    pub max_step: f64,
    /// Horizon: no separation by then is reported as such, with `e = 0` (natural time units).
    pub t_max: f64,
    /// Most steps.
    pub max_steps: u64,
    /// Stop exactly at the non-smooth points of the right-hand side and restart there.
    pub stop_at_kinks: bool,
    /// What to do about stiffness (a nearly rigid dashpot in the MCM, large `B` and `n`).
    pub stiffness: Stiffness,
    /// Integrate CoR evaluations ([`impact`]: no samples) under a constant input by Taylor
    /// series between the non-smooth points (the SI models [`crate::Bwshccm`] and
    /// [`crate::Bwmcm`] through their nondimensional form, Table 1), with
    /// `method` for the steps next to the points where a base vanishes and onto the separation;
    /// runs that path declines (stiff, time-varying input, ill-conditioned roots) take the
    /// Runge-Kutta path. Not with [`Stiffness::Rosenbrock`]. On by default: faster at equal error
    /// and more accurate at the same rtol than the Runge-Kutta path on the paper's cases
    /// (BENCHMARKS.md, STABILITY.md). Trajectories ([`simulate`] with samples) always take the
    /// Runge-Kutta path, so a CoR from a trajectory run can differ from a CoR evaluation by
    /// about the Runge-Kutta path's error (1e-11 at rtol 1e-11).
    pub series: bool,
    /// Global error control of CoR evaluations ([`impact`]), the target for the error in `e`.
    /// `Some(e_tol)`: each impact is computed at `rtol` and checked against the impact at
    /// `100 rtol` (`atol` scaled alike), whose Runge-Kutta steps are [`CHECK_METHOD`]'s
    /// (Verner's 9(8)); where their `e` differ by more than `0.1 e_tol` (or only one
    /// separated), it is computed again at `rtol / 100` with [`TIGHTER_METHOD`] (Verner's 7(6))
    /// and checked against the run at `rtol`, and so on down to rtol 1e-14 ([`tighter`]). The
    /// result is the tightest run, with the last difference as its error estimate
    /// ([`Impact::e_error`]; at most `0.1 e_tol` except where rtol 1e-14 did not get there).
    /// Validated on the stress sweep (STABILITY.md, "Session 19: global error control" and
    /// "Session 21"). `None`: one run at `rtol`. Trajectories ([`simulate`]) are one run either
    /// way.
    pub e_tol: Option<f64>,
    /// Under [`Settings::e_tol`], where the check stays [`Check::Unmet`] after the tightest
    /// double-precision run, or is met only by an estimate above `e_tol / 10` there (where
    /// rounding decides the runs' last digits, their difference does not bound their error):
    /// compute the impact again in double-double arithmetic
    /// ([`bwc_ode::Extrapolation`] at rtol 1e-16, 1e-18 and 1e-20 in turn,
    /// [`crate::DOUBLE_DOUBLE_RTOLS`], each checked against the one before it), and report the
    /// first that agrees to `e_tol` ([`Impact::double_double`]). For the few long, forced
    /// contacts whose `e` double precision cannot pin down below about 1e-9 (STABILITY.md,
    /// "Session 23"); seconds to a minute per impact, and nothing where the check is met.
    /// Not tried where the tightest double-precision run went stiff (the path is explicit),
    /// and stopped where a run's steps grow far past its predecessor's; where it reports
    /// nothing, [`Impact::double_double_declined`] says why. Every model of the crate but the
    /// earlier BWMCM form has this path, under inputs with a double-double form
    /// ([`crate::input::Input::at_dd`]: all of the crate's but closures). On by default: on
    /// five seeds of the stress sweep (150,000 cases) it settles every unmet run that did not
    /// go stiff, and leaves no run off by more than 1e-10 (STABILITY.md, "Session 25").
    pub double_double: bool,
    /// CoR evaluations ([`impact`]) of unforced impacts of the nondimensional models (and so of
    /// [`crate::impact_at`]) by the phase path ([`crate::phase`]): `e` and `t_s` as quadratures
    /// in phase space, checked to `e_tol` (without `e_tol`, one node count chosen from `rtol`,
    /// unchecked). Where it declines or its check is not met, the impact takes the usual path.
    /// Off by default: 4.3-9x faster than plain DOP853 at equal error on the paper's fits
    /// (BENCHMARKS.md, "Session 30"), but younger than the series path, and on the stress
    /// sweep one checked result in about 15,000 was seven times its estimate off (within
    /// `e_tol`; STABILITY.md, "Session 30").
    pub phase: bool,
}

/// The largest step of the Runge-Kutta path with [`Settings::stop_at_kinks`], as a fraction of
/// the time to the next point where the right-hand side is not analytic
/// ([`CollisionModel::clearance`]).
const CLEARANCE: f64 = 0.5;

/// How a run treats stiff dynamics.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stiffness {
    /// The explicit `method` throughout (the paper's setup; a stiff run crawls until
    /// `max_steps`).
    Ignore,
    /// The explicit `method` until Hairer's stiffness test fires, then RODAS4 (L-stable
    /// Rosenbrock, order 4) with the model's Jacobian from that point on (the default).
    Switch,
    /// RODAS4 throughout (`method` is not used).
    Rosenbrock,
}

impl Default for Settings {
    /// Taylor series for CoR evaluations, DOP853 otherwise, at rtol 1e-12, atol 1e-14,
    /// stopping at the non-smooth points, no step limit, horizon 1000, and CoR evaluations
    /// checked against a run at rtol 1e-10 for an error in `e` of at most `e_tol` = 1e-10.
    /// Chosen from the data (issue 21): no single tolerance keeps the error in `e` below 1e-10
    /// on every separated run of the stress sweep (STABILITY.md, "Session 21": 565 of about
    /// 52,600 miss at rtol 1e-11, 55 at 1e-14); the checked runs miss about 6, by up to 1.1e-9,
    /// each with an estimate above `e_tol` (runs whose truth double precision pins down only to
    /// a few 1e-10: "Session 22"), at about twice the cost of one run at rtol 1e-11 on the
    /// paper's cases. On the work-precision cases (BENCHMARKS.md) one run at rtol 1e-11 already
    /// keeps the error below 1e-12. Those few are computed again in double-double
    /// ([`Settings::double_double`]), which leaves no separated run of three seeds of the
    /// sweep off by more than 1e-10 (STABILITY.md, "Session 24").
    fn default() -> Self {
        Self {
            method: &DOP853,
            rtol: 1e-12,
            atol: 1e-14,
            max_step: f64::INFINITY,
            t_max: 1e3,
            max_steps: 1_000_000,
            stop_at_kinks: true,
            stiffness: Stiffness::Switch,
            series: true,
            e_tol: Some(1e-10),
            double_double: true,
            phase: false,
        }
    }
}

impl Settings {
    /// The paper's numerical setup (Appendix D): DOP853, rtol 1e-10, atol 1e-12, max_step 1e-2
    /// (nondimensional), stepping over the non-smooth points.
    pub fn paper() -> Self {
        Self {
            method: &DOP853,
            rtol: 1e-10,
            atol: 1e-12,
            max_step: 1e-2,
            stop_at_kinks: false,
            stiffness: Stiffness::Ignore,
            series: false,
            e_tol: None,
            ..Self::default()
        }
    }

    /// Checks the settings.
    ///
    /// # Errors
    /// [`ModelError::InvalidSetting`] naming the first offending setting.
    pub fn validate(&self) -> Result<(), ModelError> {
        let bad = |name, value, allowed| {
            Err(ModelError::InvalidSetting {
                name,
                value,
                allowed,
            })
        };
        if !(self.rtol.is_finite() && self.rtol > f64::EPSILON) {
            return bad("rtol", self.rtol, "finite and > 2.2e-16");
        }
        if !(self.atol.is_finite() && self.atol >= 0.0) {
            return bad("atol", self.atol, "finite and >= 0");
        }
        if self.max_step.is_nan() || self.max_step <= 0.0 {
            return bad("max_step", self.max_step, "> 0 (may be inf)");
        }
        if !(self.t_max.is_finite() && self.t_max > 0.0) {
            return bad("t_max", self.t_max, "finite and > 0");
        }
        if self.max_steps == 0 {
            return bad("max_steps", 0.0, ">= 1");
        }
        if let Some(e_tol) = self.e_tol {
            if !(e_tol.is_finite() && e_tol > 0.0) {
                return bad(
                    "e_tol",
                    e_tol,
                    "finite and > 0 (none, or 0 in a scene, for one run at rtol)",
                );
            }
        }
        Ok(())
    }
}

/// The outcome of one impact of a model with `N` states, in the model's units: seconds and SI
/// states for [`crate::Bwshccm`] (`x, z, v`) and [`crate::Bwmcm`] (`r, y, z, v`),
/// nondimensional for the ND models. `e = v(t_s) / v0 >= 0` with the relative velocity `v`
/// positive as the bodies part.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Impact<const N: usize> {
    /// Separation time `t_s` in the model's time unit (s for SI models), `None` when the bodies
    /// had not separated by the horizon.
    pub t_s: Option<f64>,
    /// Coefficient of restitution `e = v(t_s) / v0` (0 without separation).
    pub e: f64,
    /// State at separation (at the horizon, or where the contact settled, without separation).
    pub state: State<N>,
    /// Without separation: the time at which the contact had settled (at rest with the force
    /// balancing a constant input, an equilibrium), if the simulation stopped there early.
    pub settled_at: Option<f64>,
    /// When the run switched to RODAS4 because it had become stiff ([`Stiffness::Switch`]).
    pub stiff_from: Option<f64>,
    /// Steps taken by Taylor series ([`Settings::series`]; 0 on the Runge-Kutta path, and
    /// counted also where the series handed the impact over to it). The statistics count them
    /// as accepted steps, and the RHS evaluations of the start steps.
    pub series_steps: u64,
    /// Solver statistics (of every run under [`Settings::e_tol`]).
    pub stats: Stats,
    /// The relative tolerance of the reported run: [`Settings::rtol`], or tighter where
    /// [`Settings::e_tol`] asked for it.
    pub rtol: f64,
    /// Under [`Settings::e_tol`]: the estimate of the error in `e`, the difference from the
    /// check run at 100 times `rtol` (about a hundred times this run's own error where the
    /// error falls in proportion to rtol). `None` for a single run.
    pub e_error: Option<f64>,
    /// As `e_error`, for `t_s` (model time units), where both runs separated.
    pub t_s_error: Option<f64>,
    /// What the check under [`Settings::e_tol`] found.
    pub check: Check,
    /// Under [`Settings::e_tol`]: the tighter run that failed, where one did (the check stopped
    /// there and `e` is the run before it).
    pub tighter_failed: Option<FailedRun>,
    /// Whether the reported run is the double-double one ([`Settings::double_double`]); its
    /// `rtol` is then the double-double run's.
    pub double_double: bool,
    /// Where the check stayed [`Check::Unmet`] under [`Settings::double_double`]: why the
    /// double-double retry reported nothing (`e` is then the double-precision one). `None`
    /// otherwise.
    pub double_double_declined: Option<DdDeclined>,
    /// Whether the result is the phase path's ([`Settings::phase`]): no time steps, so `stats`
    /// count no work and `rtol` is the setting's; `e_error` is the phase path's own estimate.
    pub phase: bool,
}

impl<const N: usize> Impact<N> {
    /// One run's outcome, unchecked ([`Check::Off`]): separated at `t_s` (or not) with `e`,
    /// ending in `state`, at `rtol`, in double precision, neither settled nor stiff, without
    /// series steps. Each path sets what differs by struct update, so that a field added to
    /// the check is added here once.
    pub(crate) fn unchecked(
        (t_s, e, state): (Option<f64>, f64, State<N>),
        stats: Stats,
        rtol: f64,
    ) -> Self {
        Impact {
            t_s,
            e,
            state,
            settled_at: None,
            stiff_from: None,
            series_steps: 0,
            stats,
            rtol,
            e_error: None,
            t_s_error: None,
            check: Check::Off,
            tighter_failed: None,
            double_double: false,
            double_double_declined: None,
            phase: false,
        }
    }

    /// Whether the bodies separated.
    pub fn separated(&self) -> bool {
        self.t_s.is_some()
    }

    /// Contact duration `t_d = t_s - t_0 = t_s`.
    pub fn duration(&self) -> Option<f64> {
        self.t_s
    }

    /// The outcome without the state.
    pub fn cor(&self) -> Cor {
        Cor {
            t_s: self.t_s,
            e: self.e,
            settled_at: self.settled_at,
            stiff_from: self.stiff_from,
            series_steps: self.series_steps,
            stats: self.stats,
            rtol: self.rtol,
            e_error: self.e_error,
            t_s_error: self.t_s_error,
            check: self.check,
            tighter_failed: self.tighter_failed,
            double_double: self.double_double,
            double_double_declined: self.double_double_declined,
            phase: self.phase,
        }
    }
}

/// An impact's outcome without its state: what a CoR evaluation of either model gives
/// ([`crate::impact_at`]). Fields as in [`Impact`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cor {
    /// Separation time in the model's time unit, `None` without separation.
    pub t_s: Option<f64>,
    /// Coefficient of restitution (0 without separation).
    pub e: f64,
    /// Where the contact settled, if it did.
    pub settled_at: Option<f64>,
    /// When the run switched to RODAS4.
    pub stiff_from: Option<f64>,
    /// Steps taken by Taylor series.
    pub series_steps: u64,
    /// Solver statistics.
    pub stats: Stats,
    /// The relative tolerance of the reported run.
    pub rtol: f64,
    /// Estimate of the error in `e` under [`Settings::e_tol`].
    pub e_error: Option<f64>,
    /// Estimate of the error in `t_s` under [`Settings::e_tol`].
    pub t_s_error: Option<f64>,
    /// What the check under [`Settings::e_tol`] found.
    pub check: Check,
    /// The tighter run under [`Settings::e_tol`] that failed, where one did.
    pub tighter_failed: Option<FailedRun>,
    /// Whether the reported run is the double-double one.
    pub double_double: bool,
    /// Why the double-double retry reported nothing, where it was due.
    pub double_double_declined: Option<DdDeclined>,
    /// Whether the result is the phase path's ([`Settings::phase`]).
    pub phase: bool,
}

impl Cor {
    /// Whether the bodies separated.
    pub fn separated(&self) -> bool {
        self.t_s.is_some()
    }
}

/// Which intermediate states to pass to the sink of [`simulate`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Sampling {
    /// None (a CoR evaluation).
    None,
    /// The end of every accepted step.
    Steps,
    /// A uniform grid with spacing `dt` (model time units) through the dense output.
    Grid {
        /// Grid spacing.
        dt: f64,
    },
}

/// The model's non-smooth points, or none.
struct Kinks<'a, M> {
    model: &'a M,
    enabled: bool,
    floor: f64,
}

impl<const N: usize, M: CollisionModel<N>> Switches<N> for Kinks<'_, M> {
    fn count(&self) -> usize {
        if self.enabled {
            2
        } else {
            0
        }
    }
    fn values(&self, t: f64, y: &State<N>) -> Values {
        let k = self.model.kinks(t, y);
        let mut v = [0.0; MAX_FUNCTIONS];
        v[..2].copy_from_slice(&k);
        v
    }
    fn floor(&self) -> Values {
        [self.floor; MAX_FUNCTIONS]
    }
}

/// Integrates one impact from contact to separation, passing sampled states `(t, y)` to `sink`
/// (the initial state first and the separation state last).
///
/// # Errors
/// [`ModelError::InvalidSetting`] for bad settings, [`ModelError::Solver`] when the integration
/// fails (step size underflow, too many steps, non-finite state), with the time and state.
pub fn simulate<M: CollisionModel<N>, const N: usize>(
    model: &M,
    settings: &Settings,
    sampling: Sampling,
    mut sink: impl FnMut(f64, &State<N>),
) -> Result<Impact<N>, ModelError> {
    settings.validate()?;
    if let Sampling::Grid { dt } = sampling {
        check("dt", dt, dt > 0.0, "grid spacing dt > 0")?;
    }
    sink(0.0, &model.initial_state());
    // The Taylor-series path where the settings and the sampling allow it; where the series
    // hand over, the Runge-Kutta path starts from their state with their work.
    let series = sampling == Sampling::None
        && settings.series
        && settings.stiffness != Stiffness::Rosenbrock;
    let run = series
        .then(|| model.series_impact(crate::series::Private(()), settings))
        .flatten();
    let start = match run {
        Some(SeriesRun::Done(out)) => {
            if let Some(t) = out.t_s {
                sink(t, &out.state);
            }
            return Ok(out);
        }
        Some(SeriesRun::HandOver {
            t,
            state,
            stats,
            series_steps,
        }) => Start {
            t,
            y: state,
            done: stats,
            series_steps,
        },
        None => Start {
            t: 0.0,
            y: model.initial_state(),
            done: Stats::default(),
            series_steps: 0,
        },
    };
    by_runge_kutta(model, settings, sampling, start, sink)
}

/// Where the Runge-Kutta path of an impact starts: time, state, and the series' work before.
struct Start<const N: usize> {
    t: f64,
    y: State<N>,
    done: Stats,
    series_steps: u64,
}

/// The impact from `start` on by the Runge-Kutta path, locating the separation (and the kinks
/// where the settings stop at them), sampling into `sink`, until separated, settled or at the
/// horizon.
fn by_runge_kutta<M: CollisionModel<N>, const N: usize>(
    model: &M,
    settings: &Settings,
    sampling: Sampling,
    start: Start<N>,
    mut sink: impl FnMut(f64, &State<N>),
) -> Result<Impact<N>, ModelError> {
    let mut it = runge_kutta(model, settings, start.t, start.y)?;
    // The impact at the solver's state: separated at `t_s`, settled, or at the horizon.
    let finish = |it: &Solver<Rhs<'_, M>, N>, t_s: Option<f64>, state: State<N>, settled_at| {
        let mut stats = it.stats();
        stats += start.done;
        // v(t_s) >= 0 by the definition of t_s; the state of the step retaken to end at t_s may
        // carry a rounding-level negative value, clamped here so that e >= 0.
        let e = t_s.map_or(0.0, |_| {
            model.velocity(&state).max(0.0) / model.impact_speed()
        });
        Impact {
            settled_at,
            stiff_from: it.switched_at(),
            series_steps: start.series_steps,
            ..Impact::unchecked((t_s, e, state), stats, settings.rtol)
        }
    };
    let mut locator = Locator::new(
        Separation(|_t: f64, y: &State<N>| (model.force(y), model.velocity(y))),
        Kinks {
            model,
            enabled: settings.stop_at_kinks,
            floor: 10.0 * settings.atol,
        },
    );
    let t_end = settings.t_max * model.time_scale();
    let mut grid = GridSampler { sampling, next: 1 };
    // Once the input is constant, a state where the right-hand side vanishes is an equilibrium:
    // the contact has settled and will never end.
    let constant_from = model.input_constant_after();
    while it.t() < t_end {
        if settings.stop_at_kinks {
            let clear = CLEARANCE * model.clearance(it.y(), it.derivative(), settings.rtol);
            if it.next_step_size() > clear {
                it.propose_step_size(clear);
            }
        }
        match locator.step(&mut it, t_end)? {
            Step::Event { t, y } => {
                let upto = t.min(it.t());
                grid.emit(&mut it, upto, &mut sink)?;
                sink(t, &y);
                return Ok(finish(&it, Some(t), y, None));
            }
            Step::Continued | Step::Switched { .. } => {
                let upto = it.t();
                grid.emit(&mut it, upto, &mut sink)?;
                if sampling == Sampling::Steps {
                    sink(it.t(), it.y());
                }
                let constant_input = constant_from.is_some_and(|t0| it.t() >= t0);
                if constant_input && at_rest(model, it.derivative(), settings.atol) {
                    return Ok(finish(&it, None, *it.y(), Some(it.t())));
                }
            }
        }
    }
    Ok(finish(&it, None, *it.y(), None))
}

/// The Runge-Kutta solver of the settings from `(t0, y0)`, in the model's units.
fn runge_kutta<'a, M: CollisionModel<N>, const N: usize>(
    model: &'a M,
    settings: &Settings,
    t0: f64,
    y0: State<N>,
) -> Result<Solver<Rhs<'a, M>, N>, ModelError> {
    let options = Options::per_component(
        State::<N>::repeat(settings.rtol),
        model.state_scale() * settings.atol,
    )
    .with_max_step(settings.max_step * model.time_scale())
    .with_max_steps(settings.max_steps);
    let method = match settings.stiffness {
        Stiffness::Ignore => Method::Explicit(settings.method),
        Stiffness::Switch => Method::SwitchWhenStiff(settings.method),
        Stiffness::Rosenbrock => Method::Rosenbrock,
    };
    Ok(Solver::new(Rhs(model), method, t0, y0, options).map_err(bwc_events::Error::from)?)
}

/// A model as the solvers see it: its right-hand side, its Jacobian, autonomous when its input
/// is constant.
struct Rhs<'a, M>(&'a M);

impl<M> Clone for Rhs<'_, M> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<M> Copy for Rhs<'_, M> {}

impl<const N: usize, M: CollisionModel<N>> System<N> for Rhs<'_, M> {
    #[inline]
    fn rhs(&self, t: f64, y: &State<N>) -> State<N> {
        self.0.rhs(t, y)
    }
}

impl<const N: usize, M: CollisionModel<N>> Jacobian<N> for Rhs<'_, M> {
    fn jacobian(&self, t: f64, y: &State<N>) -> Matrix<N> {
        self.0.jacobian(t, y)
    }
    fn is_autonomous(&self) -> bool {
        self.0.input_is_constant()
    }
}

/// Most grid samples one impact may produce (a tiny `dt` must not exhaust memory).
pub const MAX_SAMPLES: usize = 10_000_000;

/// Whether every component of `f` is below `10 atol` in natural units (state scale per time
/// scale): the state is at rest.
pub(crate) fn at_rest<M: CollisionModel<N>, const N: usize>(
    model: &M,
    f: &State<N>,
    atol: f64,
) -> bool {
    let scale = model.state_scale() / model.time_scale();
    f.iter()
        .zip(scale.iter())
        .all(|(d, s)| d.abs() <= 10.0 * atol * s)
}

/// Emits the points of a uniform grid as the integration passes them.
struct GridSampler {
    sampling: Sampling,
    next: usize,
}

impl GridSampler {
    /// Emits the grid points up to `upto` through the dense output of the last step. (After a
    /// stop at a kink that needed several retaken steps, earlier points of the original step are
    /// evaluated on the last retaken step's polynomial, slightly outside its interval.)
    fn emit<T: Stepper<N>, const N: usize>(
        &mut self,
        it: &mut T,
        upto: f64,
        sink: &mut impl FnMut(f64, &State<N>),
    ) -> Result<(), ModelError> {
        let Sampling::Grid { dt } = self.sampling else {
            return Ok(());
        };
        let mut t = self.next as f64 * dt;
        if t > upto {
            return Ok(());
        }
        let dense = it.dense();
        while t <= upto {
            if self.next > MAX_SAMPLES {
                return Err(ModelError::InvalidSetting {
                    name: "dt",
                    value: dt,
                    allowed: "a grid of at most 10,000,000 samples per impact: increase dt",
                });
            }
            sink(t, &dense.eval(t));
            self.next += 1;
            t = self.next as f64 * dt;
        }
        Ok(())
    }
}
