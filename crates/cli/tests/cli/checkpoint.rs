//! Long studies with `--checkpoint`: a coverage study killed part way and run again ends with
//! the replicates an uninterrupted study gives; a posterior resumed from some of its runs (and a
//! line cut by a kill) pools to the posterior of an uninterrupted run; a checkpoint of another
//! command or version is refused with the reason.

use super::*;
use std::process::Stdio;

const FIT: &str = "DSA NDBWSHCCM";

/// `fixtures/kharaz.toml` in `dir` with two starts per fit: what is checked is how a study
/// resumes, which does not depend on the search's budget (a quarter of the default's time).
fn kharaz(dir: &Path) -> String {
    let data = fixtures().join("data");
    let text = std::fs::read_to_string(fixtures().join("kharaz.toml"))
        .unwrap()
        .replace("data = \"data/", &format!("data = \"{}/", data.display()))
        .replace(
            "[fit.bounds]",
            "[fit.optimizer]\nstarts = 2\nmax_starts = 2\n\n[fit.bounds]",
        );
    let path = dir.join("kharaz.toml");
    std::fs::write(&path, text).unwrap();
    path.to_str().unwrap().to_owned()
}

/// The checkpoint at `path` as a kill while writing leaves it: its head, `keep` entries and
/// half of the next line.
fn cut(path: &Path, keep: usize) {
    let text = std::fs::read_to_string(path).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let next = lines[1 + keep];
    let kept = lines[..1 + keep].join("\n");
    std::fs::write(path, format!("{kept}\n{}", &next[..next.len() / 2])).unwrap();
}

/// The list under `key` of the run of `args` (with a checkpoint), which must say it took `taken`
/// finished tasks from it; without the wall times.
fn resumed(args: &[&str], key: &str, taken: usize) -> serde_json::Value {
    let run = identify(args);
    let err = String::from_utf8_lossy(&run.stderr).into_owned();
    let said = format!("{taken} finished tasks taken from the checkpoint");
    assert!(err.contains(&said), "{err}");
    timeless(&run, key)
}

/// The finished entries of a checkpoint (its lines after the first).
fn entries(path: &Path) -> usize {
    let text = std::fs::read_to_string(path).unwrap_or_default();
    text.lines().count().saturating_sub(1)
}

#[test]
fn a_killed_coverage_study_resumes_to_the_uninterrupted_result() {
    let dir = scratch("checkpoint-coverage");
    let checkpoint = dir.join("coverage.jsonl");
    let config = kharaz(&dir);
    let args = [
        "coverage",
        &config,
        "--fit",
        FIT,
        "--replicates",
        "10",
        "--json",
    ];
    let whole = json(&identify(&[&args[..], &["--threads", "2"]].concat()));

    let mut child = Command::new(env!("CARGO_BIN_EXE_bwc-identify"))
        .args(args)
        .args([
            "--threads",
            "1",
            "--checkpoint",
            checkpoint.to_str().unwrap(),
        ])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let waited = std::time::Instant::now();
    while entries(&checkpoint) < 3 && waited.elapsed().as_secs() < 120 {
        std::thread::sleep(std::time::Duration::from_millis(10));
    }
    child.kill().unwrap();
    assert!(!child.wait().unwrap().success(), "finished before the kill");
    let done = entries(&checkpoint);
    assert!((3..10).contains(&done), "{done} replicates before the kill");
    // A line cut by the kill is dropped on resuming.
    let mut text = std::fs::read_to_string(&checkpoint).unwrap();
    text.push_str("{\"key\":\"DSA NDBWSHCCM/9\",\"finger");
    std::fs::write(&checkpoint, text).unwrap();

    let again = identify(&[&args[..], &["--checkpoint", checkpoint.to_str().unwrap()]].concat());
    let err = String::from_utf8_lossy(&again.stderr).into_owned();
    assert!(
        err.contains(&format!("{done} finished tasks taken from the checkpoint")),
        "{err}"
    );
    assert_eq!(json(&again)["coverage"], whole["coverage"]);
    assert_eq!(entries(&checkpoint), 10);
    assert!(std::fs::read_to_string(&checkpoint)
        .unwrap()
        .ends_with('\n'));

    // Run again: everything from the checkpoint, the same study; more replicates extend it.
    let eleven = [&args[..4], &["--replicates", "11", "--json"]].concat();
    let more = identify(&eleven);
    let extended =
        identify(&[&eleven[..], &["--checkpoint", checkpoint.to_str().unwrap()]].concat());
    assert_eq!(json(&extended)["coverage"], json(&more)["coverage"]);
    assert_eq!(entries(&checkpoint), 11);
}

/// The list under `key` of a run's JSON, without what differs between runs (the wall time).
fn timeless(out: &Output, key: &str) -> serde_json::Value {
    let mut v = json(out)[key].take();
    for p in v.as_array_mut().unwrap() {
        p.as_object_mut().unwrap().remove("wall_s");
    }
    v
}

#[test]
fn a_posterior_resumed_from_some_runs_is_the_uninterrupted_posterior() {
    let dir = scratch("checkpoint-posterior");
    let checkpoint = dir.join("posterior.jsonl");
    let config = kharaz(&dir);
    let args = [
        "posterior",
        &config,
        "--fit",
        FIT,
        "--particles",
        "32",
        "--runs",
        "4",
        "--json",
        "--checkpoint",
        checkpoint.to_str().unwrap(),
    ];
    let whole = timeless(&identify(&args), "posteriors");
    // The reference's entry and four runs.
    assert_eq!(entries(&checkpoint), 5);
    // The reference and one run kept, the next line cut.
    cut(&checkpoint, 2);
    assert_eq!(resumed(&args, "posteriors", 2), whole);
    // Every run kept: nothing sampled, the same posterior and evaluation count.
    assert_eq!(resumed(&args, "posteriors", 5), whole);
    // Another seed is another study: nothing taken.
    let other = [&args[..], &["--seed", "3"]].concat();
    assert_ne!(resumed(&other, "posteriors", 0), whole);
}

#[test]
fn a_checkpoint_of_another_command_or_version_is_refused() {
    let dir = scratch("checkpoint-refused");
    let checkpoint = dir.join("c.jsonl");
    let config = kharaz(&dir);
    let path = checkpoint.to_str().unwrap();
    let coverage = [
        "coverage",
        &config,
        "--fit",
        FIT,
        "--replicates",
        "1",
        "--checkpoint",
        path,
    ];
    assert!(identify(&coverage).status.success());
    let posterior = identify(&["posterior", &config, "--fit", FIT, "--checkpoint", path]);
    assert_eq!(posterior.status.code(), Some(1));
    let err = String::from_utf8_lossy(&posterior.stderr);
    assert!(
        err.contains(&format!(
            "{path}:1: `checkpoint`: a checkpoint of `coverage`, not of `posterior`"
        )),
        "{err}"
    );
    std::fs::write(
        &checkpoint,
        "{\"bwc_checkpoint\":1,\"command\":\"coverage\",\"version\":\"0.0.1\"}\n",
    )
    .unwrap();
    let err = String::from_utf8_lossy(&identify(&coverage).stderr).into_owned();
    assert!(err.contains("written by bwc 0.0.1"), "{err}");
    std::fs::write(&checkpoint, "a,b\n1,2\n").unwrap();
    let err = String::from_utf8_lossy(&identify(&coverage).stderr).into_owned();
    assert!(err.contains(&format!("{path}:1: `checkpoint`:")), "{err}");
    assert!(err.contains("remove it to start the study afresh"), "{err}");
    // The refused file is left as it was.
    assert_eq!(std::fs::read_to_string(&checkpoint).unwrap(), "a,b\n1,2\n");
}

#[test]
fn a_run_of_many_fits_resumes_to_the_uninterrupted_fits() {
    let dir = scratch("checkpoint-run");
    let checkpoint = dir.join("run.jsonl");
    let config = kharaz(&dir);
    let plain = ["run", &config, "--json", "--seed", "4"];
    let args = [&plain[..], &["--checkpoint", checkpoint.to_str().unwrap()]].concat();
    let whole = timeless(&identify(&plain), "fits");
    assert_eq!(timeless(&identify(&args), "fits"), whole);
    assert_eq!(entries(&checkpoint), 4);
    // Two searches kept (and a line cut by a kill): two fits searched again.
    cut(&checkpoint, 2);
    assert_eq!(resumed(&args, "fits", 2), whole);
    // Every search taken, on any number of threads; another seed searches every fit again.
    let one_thread = [&args[..], &["--threads", "1"]].concat();
    assert_eq!(resumed(&one_thread, "fits", 4), whole);
    let reseeded = [&["run", &config, "--json", "--seed", "5"][..], &args[5..]].concat();
    let err = String::from_utf8_lossy(&identify(&reseeded).stderr).into_owned();
    assert!(
        err.contains("0 finished tasks taken from the checkpoint; 4 of its entries unused"),
        "{err}"
    );
    // Both seeds' searches stay: each is taken when its seed returns.
    let err = String::from_utf8_lossy(&identify(&args).stderr).into_owned();
    assert!(
        err.contains("4 finished tasks taken from the checkpoint; 4 of its entries unused"),
        "{err}"
    );
}
