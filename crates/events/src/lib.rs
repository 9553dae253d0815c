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
//! `(t_s - t)^p`) are located to the last bit of the interpolant. The step is then retaken to
//! end at the event. Where the retaken state differs from the interpolant's by more than the
//! error tolerance, the crossing is located again on the retaken (shorter) step's
//! interpolant: a long step's interpolant can misplace the root of a flat function by far
//! more than the step's own error. Where the retaken state has not entered the set yet, the
//! event is then put off (once) to the next step. A function that merely
//! *leaves* zero (as the contact force does at `t = 0`) is not a crossing: no event fires at the
//! initial instant. A boundary function that leaves its class and comes back inside one step
//! (equal classes at both ends) is caught by a cubic model of it from its values and rates at
//! the ends, confirmed on the dense output (one extra evaluation of the condition per step;
//! see the `interior` module; a model extremum that only comes near the boundary is checked
//! at the dense output's own extremum, so that a shallow excursion the model misses is seen),
//! and a condition that holds at a switching point where a step stopped is reported there.
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
mod error;
mod functions;
mod interior;
mod locator;
mod root;

pub use error::Error;
pub use functions::{
    Condition, Crossing, Direction, NoSwitches, SwitchAt, Switches, Values, MAX_FUNCTIONS,
};
pub use locator::{Locator, Outcome, Step};
pub use root::{class, find_crossing, Bracket};
