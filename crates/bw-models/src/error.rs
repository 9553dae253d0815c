//! Everything that can go wrong when building or simulating a model.

/// Everything that can go wrong when building or simulating a model.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ModelError {
    /// A model parameter is outside its admissible set.
    #[error("parameter `{name}` = {value} is not admissible: {allowed}")]
    InvalidParameter {
        /// Parameter name as in the paper (`"kappa"`, `"B_b"`, ...).
        name: &'static str,
        /// The rejected value.
        value: f64,
        /// The admissible range.
        allowed: &'static str,
    },
    /// A simulation setting is out of range.
    #[error("setting `{name}` = {value} is not admissible: {allowed}")]
    InvalidSetting {
        /// Setting name as in [`Settings`](crate::Settings).
        name: &'static str,
        /// The rejected value.
        value: f64,
        /// The admissible range.
        allowed: &'static str,
    },
    /// Parameters of one model were given to the other.
    #[error("parameters of the {found} model given where the {expected} model was expected")]
    WrongModel {
        /// The model expected.
        expected: &'static str,
        /// The model the parameters belong to.
        found: &'static str,
    },
    /// A piecewise-linear input table is malformed.
    #[error("input table point {index}: {reason}")]
    InvalidTable {
        /// Index of the offending point.
        index: usize,
        /// What is wrong.
        reason: &'static str,
    },
    /// A method was asked for a model or parameters it does not cover.
    #[error("not applicable: {reason}")]
    NotApplicable {
        /// What the method covers, or why it gave up.
        reason: &'static str,
    },
    /// The integration failed.
    #[error("simulation failed: {0}")]
    Solver(#[from] bwc_events::Error),
}
