//! The `--out` folder of the command-line tools (and of Python's `out`): checked before any work, written atomically file by file,
//! with `summary.json` listing what was written (and where it came from) so that the files an
//! earlier run wrote and this one does not are removed; nothing else in the folder is touched.

use crate::AppError;
use serde_json::{json, Value};
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// Name of the summary in an output folder.
pub const SUMMARY: &str = "summary.json";

/// Makes sure `dir` can take the outputs before any work is done: creates it, removes the
/// temporary files of runs killed there before they finished, and writes and removes a probe
/// file.
///
/// # Errors
/// [`AppError::Output`] naming `--out` and what the operating system said.
pub fn prepare(dir: &Path) -> Result<(), AppError> {
    let fail = |source: std::io::Error| AppError::Output {
        dir: dir.to_owned(),
        file: None,
        source,
    };
    std::fs::create_dir_all(dir).map_err(fail)?;
    remove_abandoned(dir);
    let probe = dir.join(format!(".bwc-probe.{}", std::process::id()));
    std::fs::write(&probe, b"").map_err(fail)?;
    std::fs::remove_file(&probe).map_err(fail)
}

/// Where a result came from: the tool, its version and its command line, for `summary.json`
/// (and the `--json` output).
pub fn provenance(tool: &str) -> Value {
    json!({
        "tool": tool,
        "version": env!("CARGO_PKG_VERSION"),
        "command": std::env::args().collect::<Vec<String>>(),
    })
}

/// Adds `"files"` (every file name written, `summary.json` first) to `summary`, serializes it
/// as `summary.json` and writes it with `files` into `dir`: each file to a temporary name, then
/// renamed, so that a failed write leaves no half-written file. Then removes the files that the
/// `summary.json` found in `dir` listed and this run did not write.
///
/// # Errors
/// [`AppError::Output`] naming the folder and the file that could not be written; temporary
/// files are removed.
pub fn write_all(
    dir: &Path,
    mut summary: Value,
    files: Vec<(String, Vec<u8>)>,
) -> Result<Vec<PathBuf>, AppError> {
    let names: Vec<String> = std::iter::once(SUMMARY.to_string())
        .chain(files.iter().map(|(n, _)| n.clone()))
        .collect();
    summary["files"] = json!(names);
    let text = serde_json::to_string(&summary).expect("summary serializes") + "\n";
    std::fs::create_dir_all(dir).map_err(|source| AppError::Output {
        dir: dir.to_owned(),
        file: None,
        source,
    })?;
    let mut staged = Vec::with_capacity(files.len());
    for (name, bytes) in files {
        let mut file = Staged::create(dir, &name)?;
        file.write_all(&bytes).map_err(|e| file.error(e))?;
        staged.push(file);
    }
    let mut head = Staged::create(dir, SUMMARY)?;
    head.write_all(text.as_bytes()).map_err(|e| head.error(e))?;
    commit(dir, head, staged)
}

/// A file of an output folder being written under a temporary name (`.NAME.PID.tmp`) until
/// [`commit`] renames it into place; dropped uncommitted (a failed run), it is removed. A run
/// killed outright leaves its temporary files, which [`prepare`] removes on the next run.
pub struct Staged {
    dir: PathBuf,
    name: String,
    tmp: PathBuf,
    file: Option<BufWriter<File>>,
}

impl Staged {
    /// Creates the temporary file of `name` in `dir`.
    ///
    /// # Errors
    /// [`AppError::Output`] naming the folder and `name`.
    pub fn create(dir: &Path, name: &str) -> Result<Self, AppError> {
        let tmp = dir.join(format!(".{name}.{}.tmp", std::process::id()));
        let fail = |source| AppError::Output {
            dir: dir.to_owned(),
            file: Some(name.to_string()),
            source,
        };
        let file = File::create(&tmp).map_err(fail)?;
        Ok(Staged {
            dir: dir.to_owned(),
            name: name.to_string(),
            tmp,
            file: Some(BufWriter::with_capacity(1 << 16, file)),
        })
    }

    /// The file's final name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// `source` as the [`AppError::Output`] of this file.
    pub fn error(&self, source: std::io::Error) -> AppError {
        AppError::Output {
            dir: self.dir.clone(),
            file: Some(self.name.clone()),
            source,
        }
    }

    /// Flushes the file to disk and renames it into place.
    fn finish(mut self) -> Result<PathBuf, AppError> {
        let path = self.dir.join(&self.name);
        let file = self.file.take().expect("a staged file is finished once");
        let done = file
            .into_inner()
            .map_err(std::io::IntoInnerError::into_error)
            .and_then(|f| f.sync_all())
            .and_then(|()| std::fs::rename(&self.tmp, &path));
        done.map_err(|e| self.error(e))?;
        Ok(path)
    }
}

impl Write for Staged {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.file.as_mut().expect("open until finished").write(buf)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.file.as_mut().expect("open until finished").flush()
    }
}

impl Drop for Staged {
    fn drop(&mut self) {
        if self.file.take().is_some() {
            let _ = std::fs::remove_file(&self.tmp);
        }
    }
}

/// Renames `files` and then `summary` (a `summary.json` listing them) into place in `dir`, so
/// that a summary found there lists only complete files of its own run; then removes the files
/// the summary found there before listed and this run did not write. Returns the paths written,
/// the summary first.
///
/// # Errors
/// [`AppError::Output`] naming the file that could not be flushed or renamed; the temporary
/// files not yet renamed are removed.
pub fn commit(dir: &Path, summary: Staged, files: Vec<Staged>) -> Result<Vec<PathBuf>, AppError> {
    let stale_candidates = listed(dir);
    let names: Vec<String> = std::iter::once(summary.name().to_string())
        .chain(files.iter().map(|f| f.name().to_string()))
        .collect();
    let mut written = Vec::with_capacity(names.len());
    for file in files {
        written.push(file.finish()?);
    }
    written.insert(0, summary.finish()?);
    for old in stale_candidates.iter().filter(|o| !names.contains(o)) {
        let path = dir.join(old);
        if path.is_file() {
            let _ = std::fs::remove_file(path);
        }
    }
    Ok(written)
}

/// Removes the temporary files (`.NAME.PID.tmp`) that runs killed before they finished left
/// in `dir`, where the process that wrote them is known to be gone (Linux's `/proc`; elsewhere
/// nothing is removed).
fn remove_abandoned(dir: &Path) {
    let proc = Path::new("/proc");
    if !proc.join("self").exists() {
        return;
    }
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let name = entry.file_name();
        let Some(pid) = name.to_str().and_then(abandoned_pid) else {
            continue;
        };
        if !proc.join(pid).exists() {
            let _ = std::fs::remove_file(entry.path());
        }
    }
}

/// The process id in a temporary file name `.NAME.PID.tmp`.
fn abandoned_pid(name: &str) -> Option<&str> {
    let stem = name.strip_prefix('.')?.strip_suffix(".tmp")?;
    let (_, pid) = stem.rsplit_once('.')?;
    (!pid.is_empty() && pid.bytes().all(|b| b.is_ascii_digit())).then_some(pid)
}

/// The plain file names the `summary.json` in `dir` lists under `"files"` (none if it is
/// missing or not a bwc summary). Names with a path separator are ignored: a summary never
/// lists a file outside its folder.
fn listed(dir: &Path) -> Vec<String> {
    let Ok(text) = std::fs::read_to_string(dir.join(SUMMARY)) else {
        return Vec::new();
    };
    let Ok(v) = serde_json::from_str::<Value>(&text) else {
        return Vec::new();
    };
    v["files"]
        .as_array()
        .into_iter()
        .flatten()
        .filter_map(Value::as_str)
        .filter(|n| !n.contains(['/', '\\']) && *n != ".." && !n.is_empty())
        .map(String::from)
        .collect()
}
