//! Everything that can go wrong in an identification.

use std::path::PathBuf;

/// Everything that can go wrong in an identification.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum IdentifyError {
    /// A data file could not be read.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// A data file is malformed or holds an inadmissible value.
    #[error("{path}:{line}: {message}")]
    Data {
        /// The file.
        path: PathBuf,
        /// 1-based line.
        line: u64,
        /// What is wrong.
        message: String,
    },
    /// A bound, fixed value or starting point is not admissible.
    #[error("`{name}` in [{lo}, {hi}]: needs {allowed}")]
    Bounds {
        /// The quantity.
        name: &'static str,
        /// Lower bound (or the value).
        lo: f64,
        /// Upper bound (or the value).
        hi: f64,
        /// What is admissible.
        allowed: &'static str,
    },
    /// The constraints cannot be met.
    #[error("infeasible: {reason}")]
    Infeasible {
        /// Why.
        reason: String,
    },
    /// The objectives are not usable with the data.
    #[error("objectives: {reason}")]
    Objectives {
        /// Why.
        reason: String,
    },
    /// The optimizer failed.
    #[error("optimizer: {message}")]
    Optimizer {
        /// argmin's message.
        message: String,
    },
    /// A posterior cannot be sampled as asked.
    #[error("posterior: {reason}")]
    Posterior {
        /// Why, and what setting would help.
        reason: String,
    },
    /// A model could not be built or simulated.
    #[error(transparent)]
    Model(#[from] bw_models::ModelError),
}
