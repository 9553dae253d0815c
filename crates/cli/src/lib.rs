//! # bwc-cli: the command-line tools `bwc-simulate` and `bwc-identify`
//!
//! Thin binaries over [`bwc_app`]: they parse arguments (clap), show progress (indicatif), print
//! results and map errors to exit statuses. Everything they compute and write is `bwc_app`'s;
//! this library holds only what both binaries share: the exit statuses ([`exit`]) and the one
//! place an error is reported ([`report`]).
//!
//! ```
//! use bwc_app::AppError;
//! let err = AppError::Threads { threads: 0, message: "no threads".into() };
//! assert_eq!(bwc_cli::report(&err, "bwc-simulate"), bwc_cli::exit::ERROR);
//! ```
#![deny(missing_docs)]

use bwc_app::AppError;

/// Exit statuses of `bwc-simulate` and `bwc-identify` (the user guide's reference, "Exit status").
pub mod exit {
    /// Everything asked for was done (runs that ended on the horizon or settled included).
    pub const OK: u8 = 0;
    /// Nothing was computed: bad input, unreadable file, unusable `--out`, thread pool.
    pub const ERROR: u8 = 1;
    /// The command line itself is wrong (clap's status).
    pub const USAGE: u8 = 2;
    /// Some runs or fits failed; the others were printed and written.
    pub const SOME_FAILED: u8 = 3;
    /// The results were printed, but writing them into `--out` failed.
    pub const NOT_WRITTEN: u8 = 4;
}

/// Prints `error` on stderr as `tool: message`, one line per mistake of an
/// [`AppError::Many`], and returns the exit status it stands for ([`exit`]): `NOT_WRITTEN`
/// where only writing a result into `--out` failed, `ERROR` otherwise.
pub fn report(error: &AppError, tool: &str) -> u8 {
    match error {
        AppError::Many(all) => {
            eprintln!("{tool}: {} mistakes:", all.len());
            for one in all {
                eprintln!("{tool}: {one}");
            }
        }
        _ => eprintln!("{tool}: {error}"),
    }
    match error {
        AppError::Output { file: Some(_), .. } => exit::NOT_WRITTEN,
        _ => exit::ERROR,
    }
}

#[cfg(test)]
mod tests {
    use super::{exit, report};
    use bwc_app::AppError;

    fn output(file: Option<&str>) -> AppError {
        AppError::Output {
            dir: "out".into(),
            file: file.map(str::to_string),
            source: std::io::Error::from(std::io::ErrorKind::PermissionDenied),
        }
    }

    #[test]
    fn only_a_result_that_could_not_be_written_has_its_own_status() {
        assert_eq!(
            report(&output(Some("summary.json")), "test"),
            exit::NOT_WRITTEN
        );
        assert_eq!(report(&output(None), "test"), exit::ERROR);
        let many = AppError::Many(vec![output(None), output(Some("a.csv"))]);
        assert_eq!(report(&many, "test"), exit::ERROR);
    }
}
