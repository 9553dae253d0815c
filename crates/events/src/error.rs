//! Failures of an integration with events.

/// Failures of an integration with events.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
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
        /// [`MAX_FUNCTIONS`](crate::MAX_FUNCTIONS).
        max: usize,
    },
}
