//! Output folders: what a run writes replaces the files of an earlier run and nothing else, and
//! a folder that cannot be one is refused before any work.

use bwc_app::outdir::{prepare, write_all, SUMMARY};
use serde_json::{json, Value};

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
