//! Studies larger than a chunk of runs, written as they are computed: the files agree with the
//! one JSON object of `--json` and with the closed form, the runs above `[output].summary_runs`
//! go to `runs.jsonl`, the figures draw a bounded number of points, and a run killed part way
//! leaves the folder's complete files of the run before it or none.

use super::{hunt_crossley_e, json, scratch, simulate};
use std::path::Path;
use std::process::{Command, Stdio};

/// A Hunt-Crossley contact (`B_b = Γ_b = 0`, closed form `e(σ v0)`) at `count` log-spaced
/// speeds, with `extra` appended.
fn hunt_crossley(count: usize, extra: &str) -> String {
    format!(
        "model = \"shccm\"\nv0 = {{ from = 0.1, to = 6.0, count = {count}, spacing = \"log\" }}\n\
         [base]\nB_b = 0.0\nGamma_b = 0.0\nkappa = 0.5\nsigma_b = 0.3\nn = 1.0\np = 1.5\n{extra}"
    )
}

/// The one JSON object `bwc-simulate run SCENE --json --out OUT` prints.
fn json_and_out(scene: &Path, out: &Path) -> serde_json::Value {
    let args = ["run", path(scene), "--json", "--out", path(out)];
    json(&simulate(&args))
}

/// The `summary.json` in `out`.
fn summary_of(out: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap()
}

fn path(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// A study of three chunks (8192 runs each: `bwc_app::impact::simulate::CHUNK`) and a bit, listed in
/// `runs.jsonl` (above `summary_runs = 1000`): every line is the run `--json` prints at its
/// place, `sweep.csv` has a row for each, and every `e` is the closed form's.
#[test]
fn runs_above_summary_runs_go_to_runs_jsonl_in_order_and_match_json() {
    let count = 3 * 8192 + 77;
    let dir = scratch("study-jsonl");
    let scene = dir.join("scene.toml");
    std::fs::write(
        &scene,
        hunt_crossley(count, "[output]\nsummary_runs = 1000\n"),
    )
    .unwrap();
    let out = dir.join("out");
    let run = simulate(&["run", path(&scene), "--json", "--out", path(&out)]);
    let said = String::from_utf8_lossy(&run.stderr);
    assert!(
        said.contains(&format!(
            "the {count} runs are in runs.jsonl, one JSON object per line, not in summary.json: \
             more than [output].summary_runs = 1000"
        )),
        "{said}"
    );
    let printed = json(&run);
    let runs = printed["runs"].as_array().unwrap();
    assert_eq!(runs.len(), count);
    let lines = std::fs::read_to_string(out.join("runs.jsonl")).unwrap();
    let listed: Vec<serde_json::Value> = (lines.lines())
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(&listed, runs);
    for r in runs.iter().step_by(97) {
        let want = hunt_crossley_e(0.3 * r["v0"].as_f64().unwrap());
        assert!((r["e"].as_f64().unwrap() - want).abs() < 1e-10, "{r}");
    }
    let summary = summary_of(&out);
    assert!(summary.get("runs").is_none(), "{summary}");
    assert_eq!(summary["run_count"], count);
    assert_eq!(summary["runs_file"], "runs.jsonl");
    assert_eq!(
        summary["files"],
        serde_json::json!(["summary.json", "runs.jsonl", "sweep.csv"])
    );
    assert_eq!(summary["scene"]["v0"]["count"], count);
    assert_eq!(summary["scene"]["v0"]["first"], runs[0]["v0"]);
    assert_eq!(summary["scene"]["v0"]["last"], runs[count - 1]["v0"]);
    assert_eq!(summary["units"], printed["units"]);
    let csv = std::fs::read_to_string(out.join("sweep.csv")).unwrap();
    let rows: Vec<&str> = csv.lines().collect();
    assert_eq!(rows.len(), count + 1);
    let last: Vec<&str> = rows[count].split(',').collect();
    assert_eq!(last[0].parse::<f64>().unwrap(), 6.0);
    assert_eq!(
        last[1].parse::<f64>().unwrap(),
        runs[count - 1]["e"].as_f64().unwrap()
    );
}

/// At or below `summary_runs`, `summary.json` holds the runs `--json` prints, each speed listed
/// in its scene.
#[test]
fn runs_up_to_summary_runs_stay_in_summary_json() {
    let dir = scratch("study-array");
    let scene = dir.join("scene.toml");
    std::fs::write(
        &scene,
        hunt_crossley(9000, "[output]\nsummary_runs = 9000\n"),
    )
    .unwrap();
    let out = dir.join("out");
    let printed = json_and_out(&scene, &out);
    let mut summary = summary_of(&out);
    assert_eq!(
        summary["files"],
        serde_json::json!(["summary.json", "sweep.csv"])
    );
    assert!(!out.join("runs.jsonl").exists());
    let o = summary.as_object_mut().unwrap();
    o.remove("command");
    o.remove("files");
    assert_eq!(summary, printed);
    assert_eq!(summary["scene"]["v0"].as_array().unwrap().len(), 9000);
}

/// The CoR figure of 20,000 speeds draws at most `FIGURE_POINTS` (2000) of them, the last
/// included: its size stays that of a figure of 2000 speeds.
#[test]
fn figures_of_a_long_sweep_draw_a_bounded_number_of_points() {
    let dir = scratch("study-figure");
    let size = |count: usize| {
        let scene = dir.join(format!("scene-{count}.toml"));
        std::fs::write(&scene, hunt_crossley(count, "[output]\nplots = true\n")).unwrap();
        let out = dir.join(format!("out-{count}"));
        let run = simulate(&[
            "run",
            scene.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(run.status.success());
        std::fs::metadata(out.join("cor.svg")).unwrap().len() as f64
    };
    let (small, large) = (size(2000), size(20_000));
    assert!(large < 1.05 * small, "{small} B against {large} B");
}

/// `bwc-simulate` killed while it writes a study leaves the complete files of the run before
/// it (or none) under their names, and only temporary files of its own, which the next run
/// into the folder removes.
#[test]
fn a_killed_study_leaves_complete_files_or_none() {
    let dir = scratch("study-killed");
    let scene = dir.join("scene.toml");
    let out = dir.join("out");
    std::fs::write(&scene, hunt_crossley(300, "")).unwrap();
    let first = simulate(&[
        "run",
        scene.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(first.status.success());
    let before = std::fs::read(out.join("sweep.csv")).unwrap();
    // Long enough to be killed while it writes: every speed simulated.
    std::fs::write(
        &scene,
        hunt_crossley(400_000, "[sweep]\ninterpolate = false\n"),
    )
    .unwrap();
    let mut child = Command::new(env!("CARGO_BIN_EXE_bwc-simulate"))
        .args([
            "run",
            scene.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let temporary = |dir: &std::path::Path| -> Vec<String> {
        (std::fs::read_dir(dir).unwrap().flatten())
            .map(|e| e.file_name().to_string_lossy().into_owned())
            .filter(|n| n.ends_with(".tmp"))
            .collect()
    };
    // Killed once its files are being written.
    let waited = std::time::Instant::now();
    while temporary(&out).is_empty() && waited.elapsed().as_secs() < 60 {
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    std::thread::sleep(std::time::Duration::from_millis(300));
    child.kill().unwrap();
    let status = child.wait().unwrap();
    assert!(!status.success(), "the study finished before it was killed");
    assert_eq!(std::fs::read(out.join("sweep.csv")).unwrap(), before);
    let summary = summary_of(&out);
    assert_eq!(summary["runs"].as_array().unwrap().len(), 300);
    let left = temporary(&out);
    assert!(!left.is_empty());
    assert!(
        left.iter()
            .all(|n| n.contains(&format!(".{}.", child.id()))),
        "{left:?}"
    );
    // The next run finishes and clears what the killed one left.
    std::fs::write(&scene, hunt_crossley(300, "")).unwrap();
    let again = simulate(&[
        "run",
        scene.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(again.status.success());
    assert!(temporary(&out).is_empty(), "{:?}", temporary(&out));
    assert_eq!(std::fs::read(out.join("sweep.csv")).unwrap(), before);
}
