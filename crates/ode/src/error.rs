//! Failures of a solve, reported as values with the time and state where they happened.

/// Everything that can go wrong while setting up or running an integration.
///
/// States are carried as `Vec<f64>` so that the error type does not depend on the dimension;
/// they are only built on the failure path, never per step.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A solver option is outside its admissible range.
    #[error("invalid solver option `{name}` = {value}: {allowed}")]
    InvalidOption {
        /// Option name, as in [`crate::Options`].
        name: &'static str,
        /// The rejected value.
        value: f64,
        /// What would have been admissible.
        allowed: &'static str,
    },
    /// The initial time or state is not finite.
    #[error("initial value not finite at t = {t}: y = {state:?}")]
    NonFiniteInitialValue {
        /// Initial time.
        t: f64,
        /// Initial state.
        state: Vec<f64>,
    },
    /// A step was asked to end at or before the current time: the integrators step forward in
    /// time only.
    #[error("t_end = {t_end} is not after t = {t}: the integrators step forward in time only (to integrate backwards, substitute s = -t: solve y' = -f(-s, y) forwards in s)")]
    NotAhead {
        /// Current time.
        t: f64,
        /// The requested end.
        t_end: f64,
    },
    /// A user-supplied tableau is not a usable explicit Runge-Kutta pair.
    #[error("tableau {name}: {reason}")]
    InvalidTableau {
        /// The tableau's name.
        name: &'static str,
        /// What is wrong.
        reason: String,
    },
    /// The step size fell below the minimum step (or below round-off relative to `t`).
    #[error("step size {h:e} too small at t = {t} (state {state:?})")]
    StepSizeTooSmall {
        /// Time at which the step was attempted.
        t: f64,
        /// The step size that was too small.
        h: f64,
        /// State at `t`.
        state: Vec<f64>,
    },
    /// More steps (accepted and rejected) than `max_steps` were needed.
    #[error("more than {max_steps} steps needed; stopped at t = {t} (state {state:?})")]
    TooManySteps {
        /// The limit that was hit.
        max_steps: u64,
        /// Time reached.
        t: f64,
        /// State at `t`.
        state: Vec<f64>,
    },
    /// The right-hand side or the solution became NaN or infinite.
    #[error("non-finite value at t = {t} (state {state:?})")]
    NonFiniteState {
        /// Time at which the non-finite value appeared.
        t: f64,
        /// Last finite state.
        state: Vec<f64>,
    },
    /// A requested instant lies outside the last step.
    #[error("t = {t} lies outside the last step [{t0}, {t1}]")]
    OutsideStep {
        /// Requested instant.
        t: f64,
        /// Start of the step.
        t0: f64,
        /// End of the step.
        t1: f64,
    },
}
