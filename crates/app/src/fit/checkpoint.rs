//! Checkpoints of long studies (coverage replicates, posterior runs, fits, chains over many
//! scenes), so that an interrupted study resumes where it stopped and ends with the results an
//! uninterrupted one gives.
//!
//! A checkpoint is a JSON Lines file. Its first line names the format, the bwc version and the
//! command: `{"bwc_checkpoint": 1, "version": "0.1.0", "command": "coverage"}`. Every further
//! line is one finished task: `{"key": "...", "fingerprint": "...", "value": ...}`. The key
//! names the task within its study (`"kharaz/17"`: fit and seed), the fingerprint is a hash of
//! everything the task's result depends on (the fit as loaded, data included, and the
//! arguments), the value is its result with every number as it was computed (serde_json's
//! `float_roundtrip`). A task is taken from the file only where key and fingerprint both match;
//! entries of other designs of the study (another config, other data, another seed) stay in the
//! file, unused and counted, and are taken again when their design returns. Each line is appended in one write and flushed to the disk before the task counts as
//! done, so a killed run leaves every finished task but the one it was writing, whose partial
//! line the next run removes.
//!
//! ```
//! use bwc_app::fit::checkpoint::Checkpoint;
//! let path = std::env::temp_dir().join(format!("bwc-doc-{}.jsonl", std::process::id()));
//! let c = Checkpoint::open(&path, "coverage").unwrap();
//! c.record("fit/1", "abc", serde_json::json!({"covered": 3})).unwrap();
//! let again = Checkpoint::open(&path, "coverage").unwrap();
//! assert_eq!(again.get("fit/1", "abc").unwrap()["covered"], 3);
//! assert!(again.get("fit/1", "changed").is_none());
//! std::fs::remove_file(&path).unwrap();
//! ```

use crate::AppError;
use serde_json::{json, Value};
use std::collections::HashMap;
use std::fs::{File, OpenOptions};
use std::hash::Hasher;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Mutex, PoisonError};

/// The format's version, the first line's `bwc_checkpoint`.
pub const FORMAT: u64 = 1;

/// An open checkpoint: the finished tasks it holds, and the file new ones are appended to.
#[derive(Debug)]
pub struct Checkpoint {
    path: PathBuf,
    done: HashMap<(String, String), Value>,
    taken: AtomicUsize,
    file: Mutex<File>,
}

impl Checkpoint {
    /// Opens the checkpoint at `path` of a study of `command` (`"coverage"`, `"posterior"`,
    /// ...), creating it when there is none; a partial last line (of a run killed while writing
    /// it) is removed.
    ///
    /// # Errors
    /// [`AppError::Io`] when the file cannot be read, created or written; [`AppError::Invalid`]
    /// when it is not a checkpoint, was written by another bwc version or for another command,
    /// or a complete line is not an entry (naming the line).
    pub fn open(path: &Path, command: &str) -> Result<Self, AppError> {
        let io = |source| AppError::Io {
            path: path.to_owned(),
            source,
        };
        let text = match std::fs::read(path) {
            Ok(bytes) => bytes,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => Vec::new(),
            Err(e) => return Err(io(e)),
        };
        // Only complete lines count: the last one may have been cut by a kill.
        let complete = text.iter().rposition(|&b| b == b'\n').map_or(0, |i| i + 1);
        let text = std::str::from_utf8(&text[..complete]).map_err(|e| invalid(path, 1, e))?;
        let mut lines = text.lines();
        let done = match lines.next() {
            None => HashMap::new(),
            Some(head) => {
                check_head(path, head, command)?;
                entries(path, lines)?
            }
        };
        let file = OpenOptions::new()
            .create(true)
            .truncate(false)
            .write(true)
            .open(path)
            .map_err(io)?;
        file.set_len(complete as u64).map_err(io)?;
        let mut file = OpenOptions::new().append(true).open(path).map_err(io)?;
        if complete == 0 {
            let head = json!({"bwc_checkpoint": FORMAT, "version": env!("CARGO_PKG_VERSION"), "command": command});
            writeln!(file, "{head}").map_err(io)?;
            file.sync_data().map_err(io)?;
        }
        Ok(Self {
            path: path.to_owned(),
            done,
            taken: AtomicUsize::new(0),
            file: Mutex::new(file),
        })
    }

    /// The checkpoint's file.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The result recorded for task `key` with this `fingerprint`, if there is one.
    pub fn get(&self, key: &str, fingerprint: &str) -> Option<&Value> {
        let found = self.done.get(&(key.to_owned(), fingerprint.to_owned()));
        if found.is_some() {
            self.taken.fetch_add(1, Ordering::Relaxed);
        }
        found
    }

    /// What the study took from the checkpoint, for the user: `None` when it held nothing,
    /// else how many finished tasks it gave and how many of its entries went unused (of
    /// another design of the study, or of tasks this run does not have).
    pub fn summary(&self) -> Option<String> {
        let taken = self.taken.load(Ordering::Relaxed);
        let unused = self.done.len().saturating_sub(taken);
        (!self.done.is_empty()).then(|| {
            format!(
                "{}: {taken} finished task{} taken from the checkpoint{}",
                self.path.display(),
                if taken == 1 { "" } else { "s" },
                if unused == 0 {
                    String::new()
                } else {
                    format!(
                        "; {unused} of its entries unused (of another design of the study, or \
                         of tasks this run does not have)"
                    )
                }
            )
        })
    }

    /// Appends the result of task `key`, on the disk when this returns.
    ///
    /// # Errors
    /// [`AppError::Io`] when the line cannot be written or flushed.
    pub fn record(&self, key: &str, fingerprint: &str, value: Value) -> Result<(), AppError> {
        let line = format!(
            "{}\n",
            json!({"key": key, "fingerprint": fingerprint, "value": value})
        );
        let mut file = self.file.lock().unwrap_or_else(PoisonError::into_inner);
        file.write_all(line.as_bytes())
            .and_then(|()| file.sync_data())
            .map_err(|source| AppError::Io {
                path: self.path.clone(),
                source,
            })
    }
}

/// The fingerprint of a task: a 64-bit FNV-1a hash (hex) of `parts`, each the `Debug` text of
/// something the task's result depends on. `Debug` writes every number exactly, so a change
/// of any input changes it.
pub fn fingerprint(parts: &[&dyn std::fmt::Debug]) -> String {
    let mut h = fnv::FnvHasher::default();
    for p in parts {
        h.write(format!("{p:?}").as_bytes());
        h.write_u8(0);
    }
    format!("{:016x}", h.finish())
}

/// `x` as JSON, exactly: a number where finite, else `"inf"`, `"-inf"` or `"nan"`.
pub fn exact(x: f64) -> Value {
    if x.is_finite() {
        json!(x)
    } else {
        json!(x.to_string().to_lowercase())
    }
}

/// The number of [`exact`].
pub fn float_of(v: &Value) -> Option<f64> {
    v.as_f64().or_else(|| v.as_str()?.parse().ok())
}

fn invalid(path: &Path, line: usize, message: impl std::fmt::Display) -> AppError {
    AppError::Invalid {
        path: path.to_owned(),
        line,
        key: "checkpoint".into(),
        message: format!(
            "{message}: not a bwc checkpoint as this version writes; pass another file or \
             remove it to start the study afresh"
        ),
    }
}

fn check_head(path: &Path, head: &str, command: &str) -> Result<(), AppError> {
    let v: Value = serde_json::from_str(head).map_err(|e| invalid(path, 1, e))?;
    if v["bwc_checkpoint"].as_u64() != Some(FORMAT) {
        return Err(invalid(path, 1, "the first line has no `bwc_checkpoint`"));
    }
    let version = v["version"].as_str().unwrap_or("?");
    if version != env!("CARGO_PKG_VERSION") {
        return Err(invalid(
            path,
            1,
            format!(
                "written by bwc {version}, this is {}: results may differ between versions",
                env!("CARGO_PKG_VERSION")
            ),
        ));
    }
    match v["command"].as_str() {
        Some(c) if c == command => Ok(()),
        c => Err(invalid(
            path,
            1,
            format!("a checkpoint of `{}`, not of `{command}`", c.unwrap_or("?")),
        )),
    }
}

fn entries<'a>(
    path: &Path,
    lines: impl Iterator<Item = &'a str>,
) -> Result<HashMap<(String, String), Value>, AppError> {
    let mut done = HashMap::new();
    for (i, line) in lines.enumerate() {
        let mut v: Value = serde_json::from_str(line).map_err(|e| invalid(path, i + 2, e))?;
        let (Some(key), Some(print)) = (v["key"].as_str(), v["fingerprint"].as_str()) else {
            return Err(invalid(
                path,
                i + 2,
                "an entry without `key` or `fingerprint`",
            ));
        };
        let task = (key.to_owned(), print.to_owned());
        done.insert(task, v["value"].take());
    }
    Ok(done)
}
