//! One interface over the explicit and the Rosenbrock integrators, and a solver that starts
//! explicit and switches to RODAS4 when Hairer's stiffness test fires.

use crate::control::Stats;
use crate::integrator::{Dense, Trial};
use crate::{Error, Integrator, Jacobian, Options, Rosenbrock, State, Tableau};

/// What event location needs from an adaptive integrator (implemented by [`Integrator`],
/// [`Rosenbrock`] and [`Solver`]). See [`Integrator`] for the meaning of each method.
pub trait Stepper<const N: usize> {
    /// Current time.
    fn t(&self) -> f64;
    /// Current state.
    fn y(&self) -> &State<N>;
    /// `f(t, y)` at the current point.
    fn derivative(&self) -> &State<N>;
    /// Statistics so far.
    fn stats(&self) -> Stats;
    /// Counts one located event.
    fn record_event(&mut self);
    /// Proposed size of the next step.
    fn next_step_size(&self) -> f64;
    /// Proposes the size of the next step.
    fn propose_step_size(&mut self, h: f64);
    /// How many error tolerances a difference `dy` from the current state spans (the largest
    /// `|dy_i| / (atol_i + rtol_i |y_i|)`; infinite where the tolerances are not known).
    fn tolerances(&self, dy: &State<N>) -> f64 {
        let _ = dy;
        f64::INFINITY
    }
    /// One accepted step ending at `t_end` at the latest, rejected trials aimed by `aim`.
    ///
    /// # Errors
    /// As [`Integrator::step`].
    fn step_aiming(
        &mut self,
        t_end: f64,
        aim: &mut dyn FnMut(&Trial<'_, N>) -> Option<f64>,
    ) -> Result<(), Error>;
    /// The continuous extension of the last accepted step.
    fn dense(&mut self) -> Dense<N>;
    /// Retakes the last step to end exactly at `t_stop` inside it.
    ///
    /// # Errors
    /// As [`Integrator::retake_to`].
    fn retake_to(&mut self, t_stop: f64) -> Result<(), Error>;
    /// One accepted adaptive step, ending at `t_end` at the latest.
    ///
    /// # Errors
    /// As [`Integrator::step`].
    fn step(&mut self, t_end: f64) -> Result<(), Error> {
        self.step_aiming(t_end, &mut |_| None)
    }
    /// Steps until `t = t_end` exactly (nothing if `t_end` is not ahead).
    ///
    /// # Errors
    /// As [`Integrator::step`].
    fn integrate_to(&mut self, t_end: f64) -> Result<(), Error> {
        while self.t() < t_end {
            self.step(t_end)?;
        }
        Ok(())
    }
}

macro_rules! delegate_stepper {
    ($ty:ident, $bound:ident) => {
        impl<F: crate::$bound<N>, const N: usize> Stepper<N> for $ty<F, N> {
            fn t(&self) -> f64 {
                $ty::t(self)
            }
            fn y(&self) -> &State<N> {
                $ty::y(self)
            }
            fn derivative(&self) -> &State<N> {
                $ty::derivative(self)
            }
            fn stats(&self) -> Stats {
                $ty::stats(self)
            }
            fn record_event(&mut self) {
                $ty::record_event(self)
            }
            fn next_step_size(&self) -> f64 {
                $ty::next_step_size(self)
            }
            fn propose_step_size(&mut self, h: f64) {
                $ty::propose_step_size(self, h)
            }
            fn tolerances(&self, dy: &State<N>) -> f64 {
                $ty::tolerances(self, dy)
            }
            fn step_aiming(
                &mut self,
                t_end: f64,
                aim: &mut dyn FnMut(&Trial<'_, N>) -> Option<f64>,
            ) -> Result<(), Error> {
                $ty::step_aiming(self, t_end, aim)
            }
            fn dense(&mut self) -> Dense<N> {
                $ty::dense(self)
            }
            fn retake_to(&mut self, t_stop: f64) -> Result<(), Error> {
                $ty::retake_to(self, t_stop)
            }
        }
    };
}

delegate_stepper!(Integrator, System);
delegate_stepper!(Rosenbrock, Jacobian);

/// Which integrator a [`Solver`] uses.
#[derive(Debug, Clone, Copy)]
#[non_exhaustive]
pub enum Method {
    /// An explicit method throughout (stiffness is ignored: the run may crawl).
    Explicit(&'static Tableau),
    /// An explicit method until Hairer's stiffness test fires, then RODAS4 from that point on.
    SwitchWhenStiff(&'static Tableau),
    /// RODAS4 throughout.
    Rosenbrock,
}

/// An integration by the [`Method`] chosen, switching from explicit to RODAS4 when the problem
/// turns out to be stiff.
///
/// ```
/// use bwc_ode::{Jacobian, Matrix, Method, Options, Solver, State, Stepper, System, DOP853};
/// // y' = -1e5 (y - cos t) - sin t, y = cos t: stiff (Prothero-Robinson).
/// #[derive(Clone, Copy)]
/// struct Stiff;
/// impl System<1> for Stiff {
///     fn rhs(&self, t: f64, y: &State<1>) -> State<1> {
///         State::<1>::new(-1e5 * (y[0] - t.cos()) - t.sin())
///     }
/// }
/// impl Jacobian<1> for Stiff {
///     fn jacobian(&self, _t: f64, _y: &State<1>) -> Matrix<1> {
///         Matrix::<1>::new(-1e5)
///     }
/// }
/// let mut s = Solver::new(Stiff, Method::SwitchWhenStiff(&DOP853), 0.0, State::<1>::new(1.0),
///     Options::new(1e-8, 1e-10))?;
/// while s.t() < 10.0 {
///     s.step_aiming(10.0, &mut |_| None)?;
/// }
/// assert!(s.switched_at().is_some());
/// assert!((s.y()[0] - 10.0f64.cos()).abs() < 1e-7);
/// assert!(s.stats().rhs_evals < 20_000); // DOP853 alone: 10^6 / 6.1 steps of 12 evaluations
/// # Ok::<(), bwc_ode::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct Solver<F, const N: usize> {
    inner: Inner<F, N>,
    switch: bool,
    options: Options<N>,
    switched_at: Option<f64>,
}

#[derive(Debug, Clone)]
enum Inner<F, const N: usize> {
    Explicit(Integrator<F, N>),
    Rosenbrock(Rosenbrock<F, N>),
}

impl<F: Jacobian<N> + Clone, const N: usize> Solver<F, N> {
    /// Starts an integration at `(t0, y0)`.
    ///
    /// # Errors
    /// As [`Integrator::new`].
    pub fn new(
        f: F,
        method: Method,
        t0: f64,
        y0: State<N>,
        options: Options<N>,
    ) -> Result<Self, Error> {
        let (inner, switch) = match method {
            Method::Explicit(tab) => (
                Inner::Explicit(Integrator::new(f, tab, t0, y0, options)?),
                false,
            ),
            Method::SwitchWhenStiff(tab) => (
                Inner::Explicit(Integrator::new(f, tab, t0, y0, options)?),
                true,
            ),
            Method::Rosenbrock => (
                Inner::Rosenbrock(Rosenbrock::new(f, t0, y0, options)?),
                false,
            ),
        };
        Ok(Self {
            inner,
            switch,
            options,
            switched_at: None,
        })
    }

    /// When the solver switched from the explicit method to RODAS4, if it did.
    pub fn switched_at(&self) -> Option<f64> {
        self.switched_at
    }

    /// Switches to RODAS4 at the current point if the explicit method found the problem stiff.
    fn switch_if_stiff(&mut self) -> Result<(), Error> {
        if let Inner::Explicit(it) = &self.inner {
            if self.switch && it.is_stiff() {
                let rb = Rosenbrock::resume(
                    it.system().clone(),
                    it.t(),
                    *it.y(),
                    it.next_step_size(),
                    self.options,
                    it.stats(),
                )?;
                self.switched_at = Some(it.t());
                self.inner = Inner::Rosenbrock(rb);
            }
        }
        Ok(())
    }
}

macro_rules! both {
    ($self:expr, $it:ident => $e:expr) => {
        match $self {
            Inner::Explicit($it) => $e,
            Inner::Rosenbrock($it) => $e,
        }
    };
}

impl<F: Jacobian<N> + Clone, const N: usize> Stepper<N> for Solver<F, N> {
    fn t(&self) -> f64 {
        both!(&self.inner, it => it.t())
    }
    fn y(&self) -> &State<N> {
        both!(&self.inner, it => it.y())
    }
    fn derivative(&self) -> &State<N> {
        both!(&self.inner, it => it.derivative())
    }
    fn stats(&self) -> Stats {
        both!(&self.inner, it => it.stats())
    }
    fn record_event(&mut self) {
        both!(&mut self.inner, it => it.record_event())
    }
    fn next_step_size(&self) -> f64 {
        both!(&self.inner, it => it.next_step_size())
    }
    fn propose_step_size(&mut self, h: f64) {
        both!(&mut self.inner, it => it.propose_step_size(h))
    }
    fn tolerances(&self, dy: &State<N>) -> f64 {
        both!(&self.inner, it => it.tolerances(dy))
    }
    fn step_aiming(
        &mut self,
        t_end: f64,
        aim: &mut dyn FnMut(&Trial<'_, N>) -> Option<f64>,
    ) -> Result<(), Error> {
        self.switch_if_stiff()?;
        both!(&mut self.inner, it => it.step_aiming(t_end, aim))
    }
    fn dense(&mut self) -> Dense<N> {
        both!(&mut self.inner, it => it.dense())
    }
    fn retake_to(&mut self, t_stop: f64) -> Result<(), Error> {
        both!(&mut self.inner, it => it.retake_to(t_stop))
    }
}
