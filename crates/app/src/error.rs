//! The errors of scenes, configs, runs and outputs, each naming the file (and line and key where
//! known); the front ends (the command-line tools, Python) report them.

use std::path::PathBuf;

/// Everything that can stop a command.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum AppError {
    /// A file could not be read or written.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// The file is not valid TOML, or a key has the wrong type or is unknown.
    #[error("{path}:{line}:{column}: {message}")]
    Syntax {
        /// The file.
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// The parser's message.
        message: String,
    },
    /// A key has an inadmissible value, is missing, or conflicts with another.
    #[error("{path}:{line}: `{key}`: {message}")]
    Invalid {
        /// The file.
        path: PathBuf,
        /// 1-based line of the offending key (of its table when the key is missing).
        line: usize,
        /// The key, with its table: `[physical].k`.
        key: String,
        /// What is wrong and what is admissible.
        message: String,
    },
    /// A simulation failed.
    #[error("{path}: run {run}: {source}")]
    Simulation {
        /// The scene.
        path: PathBuf,
        /// Which run (speed or name).
        run: String,
        /// The model error.
        source: bw_models::ModelError,
    },
    /// Writing a CSV file failed.
    #[error("{path}: {source}")]
    Csv {
        /// The file.
        path: PathBuf,
        /// The CSV error.
        source: csv::Error,
    },
    /// Drawing a plot failed.
    #[error("{path}: plotting failed: {message}")]
    Plot {
        /// The file.
        path: PathBuf,
        /// The drawing backend's message.
        message: String,
    },
    /// An identification failed (or its data file is bad).
    #[error("{path}: fit \"{fit}\": {source}")]
    Identify {
        /// The config.
        path: PathBuf,
        /// The fit's name.
        fit: String,
        /// What went wrong.
        source: bwc_identify::IdentifyError,
    },
    /// The `--out` folder cannot be used, or a file in it could not be written.
    #[error("--out {dir}: {}{source}", file.as_ref().map_or(String::new(), |f| format!("writing {f} failed: ")))]
    Output {
        /// The folder given as `--out`.
        dir: PathBuf,
        /// The file being written, if the folder itself was usable.
        file: Option<String>,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// Several mistakes in one file, in file order.
    #[error("{}", .0.iter().map(ToString::to_string).collect::<Vec<_>>().join("\n"))]
    Many(Vec<AppError>),
    /// A command-line argument (or its Python keyword) names nothing the config holds, or asks
    /// what the data cannot give.
    #[error("{argument}: {message}")]
    Argument {
        /// The argument, as typed: `--fit`, `--folds`.
        argument: String,
        /// What is wrong and what is admissible.
        message: String,
    },
    /// The thread pool could not be built.
    #[error("cannot start {threads} threads: {message}")]
    Threads {
        /// Requested threads.
        threads: usize,
        /// Why not.
        message: String,
    },
}
