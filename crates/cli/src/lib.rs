//! # bwc-cli: the command-line front ends of bwc
//!
//! `bwc-simulate run SCENE.toml` simulates the impacts a scene describes and writes tables and
//! plots; `bwc-identify run CONFIG.toml` fits base parameters to data ([`config`],
//! [`identify`]). The crate parses files into validated settings ([`scene`]) and calls the libraries
//! ([`simulate`]); errors ([`CliError`]) are reported once, by the binaries.
//!
//! ```
//! use bwc_cli::scene::Scene;
//! let scene = Scene::parse(std::path::Path::new("example.toml"), r#"
//!     model = "shccm"
//!     [nondimensional]
//!     B = 0.0
//!     Gamma = 0.0
//!     kappa = 0.5
//!     sigma = 0.5
//!     n = 1.0
//!     p = 1.5
//! "#)?;
//! let runs = bwc_cli::simulate::run(&scene, None);
//! assert_eq!(runs[0].outcome, bwc_cli::simulate::Outcome::Separated);
//! assert!((runs[0].e - 0.748434931597434).abs() < 1e-9);
//! # Ok::<(), bwc_cli::CliError>(())
//! ```
#![deny(missing_docs)]

pub mod bounces;
pub mod config;
mod error;
pub mod identify;
pub mod outdir;
pub mod output;
pub mod plot;
pub mod scene;
pub mod signal;
pub mod simulate;
mod tables;

pub use error::CliError;

/// Runs `work` on a rayon pool of `threads` threads, or on the global pool (all cores, or
/// `RAYON_NUM_THREADS`) when `None`. Results do not depend on the choice.
///
/// # Errors
/// [`CliError::Threads`] if the pool cannot start; otherwise `work`'s own error.
pub fn with_threads<T: Send>(
    threads: Option<usize>,
    work: impl FnOnce() -> Result<T, CliError> + Send,
) -> Result<T, CliError> {
    match threads {
        Some(n) => rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .map_err(|e| CliError::Threads {
                threads: n,
                message: e.to_string(),
            })?
            .install(work),
        None => work(),
    }
}

/// `x` to 12 significant digits, so that a tolerance computed from another reads as written
/// (`1e-11`, not the `1.0000000000000001e-11` of `1e-10 / 10`) in summaries and messages.
pub fn tidy(x: f64) -> f64 {
    format!("{x:.11e}").parse().unwrap_or(x)
}

/// `writeln!` to stdout, ignoring errors such as a closed pipe (`bwc-simulate ... | head` must
/// not panic, as `println!` would).
#[macro_export]
macro_rules! out {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!(std::io::stdout().lock(), $($arg)*);
    }};
}

/// [`out!`] without the newline.
#[macro_export]
macro_rules! outp {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let _ = write!(std::io::stdout().lock(), $($arg)*);
    }};
}
