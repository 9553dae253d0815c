//! The `--out` folder of the command-line tools (and of Python's `out`): checked before any work, written atomically file by file,
//! with `summary.json` listing what was written (and where it came from) so that the files an
//! earlier run wrote and this one does not are removed; nothing else in the folder is touched.

use crate::AppError;
use serde_json::{json, Value};
use std::path::{Path, PathBuf};

/// Name of the summary in an output folder.
pub const SUMMARY: &str = "summary.json";

/// Makes sure `dir` can take the outputs before any work is done: creates it and writes and
/// removes a probe file.
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
    let stale_candidates = listed(dir);
    let names: Vec<String> = std::iter::once(SUMMARY.to_string())
        .chain(files.iter().map(|(n, _)| n.clone()))
        .collect();
    summary["files"] = json!(names);
    let text = serde_json::to_string(&summary).expect("summary serializes") + "\n";
    let all = std::iter::once((SUMMARY.to_string(), text.into_bytes())).chain(files);
    std::fs::create_dir_all(dir).map_err(|source| AppError::Output {
        dir: dir.to_owned(),
        file: None,
        source,
    })?;
    let mut written = Vec::new();
    for (name, bytes) in all {
        let path = dir.join(&name);
        let tmp = dir.join(format!(".{name}.{}.tmp", std::process::id()));
        let result = std::fs::write(&tmp, bytes).and_then(|_| std::fs::rename(&tmp, &path));
        if let Err(source) = result {
            let _ = std::fs::remove_file(&tmp);
            return Err(AppError::Output {
                dir: dir.to_owned(),
                file: Some(name),
                source,
            });
        }
        written.push(path);
    }
    for old in stale_candidates.iter().filter(|o| !names.contains(o)) {
        let path = dir.join(old);
        if path.is_file() {
            let _ = std::fs::remove_file(path);
        }
    }
    Ok(written)
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stale_files_of_an_earlier_run_go_and_nothing_else() {
        let dir = std::env::temp_dir().join(format!("bwc-outdir-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        prepare(&dir).unwrap();
        std::fs::write(dir.join("notes.txt"), "mine").unwrap();
        let first = vec![
            ("sweep.csv".to_string(), b"a".to_vec()),
            ("cor.svg".to_string(), b"b".to_vec()),
        ];
        write_all(&dir, json!({"runs": []}), first).unwrap();
        let summary: Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join(SUMMARY)).unwrap()).unwrap();
        assert_eq!(
            summary["files"],
            json!(["summary.json", "sweep.csv", "cor.svg"])
        );
        let second = vec![("sweep.csv".to_string(), b"c".to_vec())];
        write_all(&dir, json!({"runs": []}), second).unwrap();
        assert!(!dir.join("cor.svg").exists());
        assert_eq!(std::fs::read(dir.join("sweep.csv")).unwrap(), b"c");
        assert_eq!(std::fs::read(dir.join("notes.txt")).unwrap(), b"mine");
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn an_unusable_folder_is_refused_before_any_work() {
        let file = std::env::temp_dir().join(format!("bwc-outfile-{}", std::process::id()));
        std::fs::write(&file, "x").unwrap();
        let err = prepare(&file.join("sub")).unwrap_err().to_string();
        assert!(err.starts_with("--out "), "{err}");
        let _ = std::fs::remove_file(&file);
    }
}
