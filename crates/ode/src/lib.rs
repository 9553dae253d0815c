//! # bwc-ode: embedded Runge-Kutta and Rosenbrock solvers for small fixed-size systems
//!
//! Explicit embedded Runge-Kutta pairs as data ([`Tableau`]) driven by one stepping engine
//! ([`Integrator`]), on stack-allocated states `State<N> = nalgebra::SVector<f64, N>`:
//!
//! * [`DOPRI5`]: Dormand-Prince 5(4) with Hairer's 4th-order dense output;
//! * [`DOP853`]: Hairer's 8(5,3) with its 7th-order dense output (3 extra stages, lazily);
//! * [`VERN7`]: Verner's efficient 7(6) with its 7th-order interpolant (6 extra stages, lazily);
//! * [`VERN9`]: Verner's efficient 9(8) with an 8th-order interpolant (5 extra stages, lazily).
//!
//! Step control follows Hairer (scaled RMS error norm with `sc_i = atol_i + rtol_i max(|y_i|,
//! |y1_i|)`, DOP853's combined 5th/3rd-order norm, Hairer's initial step, I or PI controller),
//! and so does the stiffness test ([`Integrator::is_stiff`]).
//!
//! For stiff problems, [`Rosenbrock`] is RODAS4 (L-stable, order 4(3), 3rd-order dense output)
//! with the system's [`Jacobian`]; [`Solver`] starts with an explicit method and switches to it
//! when the stiffness test fires ([`Method`]). All three implement [`Stepper`], the interface
//! event location works on.
//! Both integrators carry the rounding error of each update of the state into the next step
//! (compensated summation) and take steps the time takes exactly, so that rounding errors do
//! not add up over the hundreds of thousands of steps of a long integration at tight tolerances.
//! Nothing is allocated per step or per solve; failures are values ([`Error`]) carrying the time
//! and state where they happened. Integration can stop at any instant inside a step
//! ([`Integrator::retake_to`]) and restart ([`Integrator::restart`]): the `bwc-events` crate
//! builds event location on these.
//!
//! For systems whose size is known only when the integration starts (a chain of many bodies),
//! [`FlatIntegrator`] is the same explicit engine on flat heap buffers allocated once, with the
//! error in the maximum norm and the dense output per component.
//!
//! Beyond double precision, [`Extrapolation`] is Gragg-Bulirsch-Stoer extrapolation on
//! double-double states ([`dd`]), for the rare integrations whose answer rounding errors of
//! 1e-16 decide.
//!
//! ```
//! use bwc_ode::{Integrator, Options, State, VERN7};
//! // Harmonic oscillator x'' = -x: after a full period the state returns to (1, 0).
//! let f = |_t: f64, y: &State<2>| State::<2>::new(y[1], -y[0]);
//! let mut it = Integrator::new(f, &VERN7, 0.0, State::<2>::new(1.0, 0.0), Options::new(1e-12, 1e-14))?;
//! it.integrate_to(2.0 * std::f64::consts::PI)?;
//! assert!((it.y() - State::<2>::new(1.0, 0.0)).norm() < 1e-10);
//! println!("{} RHS evaluations", it.stats().rhs_evals);
//! # Ok::<(), bwc_ode::Error>(())
//! ```
#![deny(missing_docs)]

mod control;
pub mod dd;
mod error;
mod extrapolation;
mod flat;
mod integrator;
mod methods;
mod options;
mod rosenbrock;
mod stepper;
mod system;
pub mod tableau;

pub use control::Stats;
pub use error::Error;
pub use extrapolation::{DdSystem, DdTrial, Extrapolation};
pub use flat::{FlatIntegrator, FlatOptions, FlatSystem};
pub use integrator::{Dense, Integrator, Trial};
pub use methods::{DOP853, DOPRI5, METHODS, VERN7, VERN9};
pub use options::{Controller, Options};
pub use rosenbrock::{Jacobian, Matrix, Rosenbrock};
pub use stepper::{Method, Solver, Stepper};
pub use system::{State, System};
pub use tableau::{Tableau, MAX_STAGES};
