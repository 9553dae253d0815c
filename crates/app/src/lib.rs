//! # bwc-app: scenes and configs, running them, and their outputs
//!
//! The application layer of bwc, between the libraries and the front ends (the command-line
//! tools of `bwc-cli`, the Python package), by feature: a pair's impacts ([`impact`]: scene
//! files, simulation, runs, drop tests, outputs), identification ([`fit`]: configs, fits,
//! posteriors, comparisons) and chains of bodies ([`chain`]); a scene file of either kind is
//! read once ([`scene_file`]). Below them lie what they share: the TOML tables and their
//! line-accurate errors, inputs ([`signal`]), plausibility hints ([`plausible`]), plots
//! ([`plot`]) and output folders written atomically ([`outdir`]). Errors ([`AppError`]) name
//! the file, line and key; the front ends report them once.
//!
//! ```
//! use bwc_app::impact::scene::Scene;
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
//! let runs = bwc_app::impact::simulate::run(&scene, None);
//! assert_eq!(runs[0].outcome, bwc_app::impact::runs::Outcome::Separated);
//! assert!((runs[0].e - 0.748434931597434).abs() < 1e-9);
//! # Ok::<(), bwc_app::AppError>(())
//! ```
#![deny(missing_docs)]

pub mod chain;
mod error;
pub mod fit;
mod format;
pub mod impact;
pub mod materials;
pub mod outdir;
pub mod plausible;
pub mod plot;
pub mod scene_file;
pub mod signal;
mod tables;

pub use error::AppError;
pub use format::tidy;

/// Runs `work` on a rayon pool of `threads` threads, or on the global pool (all cores, or
/// `RAYON_NUM_THREADS`) when `None`. Results do not depend on the choice.
///
/// # Errors
/// [`AppError::Threads`] if the pool cannot start; otherwise `work`'s own error.
pub fn with_threads<T: Send>(
    threads: Option<usize>,
    work: impl FnOnce() -> Result<T, AppError> + Send,
) -> Result<T, AppError> {
    match threads {
        Some(n) => rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .map_err(|e| AppError::Threads {
                threads: n,
                message: e.to_string(),
            })?
            .install(work),
        None => work(),
    }
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

/// The Rust snippets of the README and the user guide (`docs/`), compiled and run as doc tests.
#[cfg(doctest)]
mod guide {
    #[doc = include_str!("../../../README.md")]
    struct ReadMe;
    #[doc = include_str!("../../../docs/src/explanation/identification.md")]
    struct ExplanationIdentification;
    #[doc = include_str!("../../../docs/src/explanation/models.md")]
    struct ExplanationModels;
    #[doc = include_str!("../../../docs/src/explanation/numerics.md")]
    struct ExplanationNumerics;
    #[doc = include_str!("../../../docs/src/howto/dask.md")]
    struct HowtoDask;
    #[doc = include_str!("../../../docs/src/howto/embed.md")]
    struct HowtoEmbed;
    #[doc = include_str!("../../../docs/src/howto/fit-measurements.md")]
    struct HowtoFitMeasurements;
    #[doc = include_str!("../../../docs/src/howto/uncertainty.md")]
    struct HowtoUncertainty;
    #[doc = include_str!("../../../docs/src/introduction.md")]
    struct Introduction;
    #[doc = include_str!("../../../docs/src/reference/commands.md")]
    struct ReferenceCommands;
    #[doc = include_str!("../../../docs/src/reference/config.md")]
    struct ReferenceConfig;
    #[doc = include_str!("../../../docs/src/reference/outputs.md")]
    struct ReferenceOutputs;
    #[doc = include_str!("../../../docs/src/reference/python.md")]
    struct ReferencePython;
    #[doc = include_str!("../../../docs/src/reference/scene.md")]
    struct ReferenceScene;
    #[doc = include_str!("../../../docs/src/reference/warnings.md")]
    struct ReferenceWarnings;
    #[doc = include_str!("../../../docs/src/tutorial/first-cor.md")]
    struct TutorialFirstCor;
    #[doc = include_str!("../../../docs/src/tutorial/first-drop.md")]
    struct TutorialFirstDrop;
    #[doc = include_str!("../../../docs/src/tutorial/first-fit.md")]
    struct TutorialFirstFit;
    #[doc = include_str!("../../../docs/src/tutorial/first-sweep.md")]
    struct TutorialFirstSweep;
}
