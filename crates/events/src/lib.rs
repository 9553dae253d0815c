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
mod interior;
mod root;

pub use root::{class, find_crossing, Bracket};

use bwc_ode::State;

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

mod locator;
pub use locator::{Locator, Outcome, Step};
