//! One run of an impact ([`simulate`]): integrate a model from the instant of contact to
//! separation `t_s = inf{t > 0 : F <= 0 <= v}` and report `t_s`, `e = v(t_s) / v0` and
//! `t_d = t_s`, by the Taylor series where they apply and the Runge-Kutta path (with stops at
//! the non-smooth points, a switch to RODAS4 when the run turns stiff, and an early stop where
//! the contact settles) from where they hand over.

use crate::error::ModelError;
use crate::fast_paths;
use crate::models::{at_rest, CollisionModel};
use crate::outcome::Impact;
use crate::params::check;
use crate::separation::Separation;
use crate::series::SeriesRun;
use crate::settings::{Settings, Stiffness};
use bwc_events::{Locator, Step, Switches, Values, MAX_FUNCTIONS};
use bwc_ode::{Jacobian, Matrix, Method, Options, Solver, State, Stats, Stepper, System};

/// The largest step of the Runge-Kutta path with [`Settings::stop_at_kinks`], as a fraction of
/// the time to the next point where the right-hand side is not analytic
/// ([`CollisionModel::clearance`]).
const CLEARANCE: f64 = 0.5;

/// Which intermediate states to pass to the sink of [`simulate`].
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
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
        .then(|| fast_paths::series(model, settings))
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
        Impact::unchecked((t_s, e, state), stats, settings.rtol).with(|c| {
            c.settled_at = settled_at;
            c.stiff_from = it.switched_at();
            c.series_steps = start.series_steps;
        })
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
