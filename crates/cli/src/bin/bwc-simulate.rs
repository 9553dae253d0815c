//! `bwc-simulate`: simulate the impacts a TOML scene describes.

use bwc_app::chain::ChainScene;
use bwc_app::impact::notes::{self, Note};
use bwc_app::impact::output::{self, SummaryWriter};
use bwc_app::impact::{scene::Scene, simulate};
use bwc_app::outdir;
use bwc_app::scene_file::SceneFile;
use bwc_app::{tidy, AppError};
use bwc_cli::exit;
use clap::{Parser, Subcommand};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

#[derive(Parser)]
#[command(
    name = "bwc-simulate",
    version,
    about = "Simulate binary collisions with the Bouc-Wen collision models (BWSHCCM, BWMCM)",
    after_help = "Examples:\n  bwc-simulate run fixtures/two_balls_shccm.toml --out out/two_balls\n  bwc-simulate run fixtures/kharaz_curves.toml --json > curves.json\n  bwc-simulate run fixtures/cross_mcm.toml --out out/cross --threads 1"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Run a scene: print a summary, write the outputs the scene asks for into --out.
    Run {
        /// The scene file (TOML).
        scene: PathBuf,
        /// Directory for summary.json, sweep.csv, trajectory.csv, loop.csv and SVG plots.
        #[arg(long)]
        out: Option<PathBuf>,
        /// Print exactly one JSON object on stdout: {"runs": [...]}.
        #[arg(long)]
        json: bool,
        /// Worker threads (default: all cores, or RAYON_NUM_THREADS).
        #[arg(long, value_parser = clap::value_parser!(u64).range(1..=1024))]
        threads: Option<u64>,
    },
}

fn main() -> ExitCode {
    let Command::Run {
        scene,
        out,
        json,
        threads,
    } = Cli::parse().command;
    match run(&scene, out.as_deref(), json, threads.map(|t| t as usize)) {
        Ok(status) => ExitCode::from(status),
        Err(e) => ExitCode::from(bwc_cli::report(&e, "bwc-simulate")),
    }
}

/// Runs a scene; returns the exit status ([`exit`]). The runs are printed and written as they
/// come ([`simulate::stream`]), so that memory stays flat however many speeds a study has.
fn run(
    path: &std::path::Path,
    out: Option<&std::path::Path>,
    json: bool,
    threads: Option<usize>,
) -> Result<u8, AppError> {
    let scene = match SceneFile::load(path)? {
        SceneFile::Chain(chain) => return run_chain(&chain, out, json, threads),
        SceneFile::Pair(scene) => scene,
    };
    for hint in &scene.hints {
        eprintln!("bwc-simulate: warning: {hint}");
    }
    let mut study = match out {
        Some(dir) => {
            outdir::prepare(dir)?;
            Some(output::Study::start(&scene, dir)?)
        }
        None => None,
    };
    let progress = Progress::new(
        (scene.systems.len() * scene.speeds.len().max(1)) as u64,
        json,
    );
    let tick = || progress.tick();
    let mut tally = simulate::Tally::default();
    let mut table = Table::default();
    let mut printed = match json {
        true => Some(
            SummaryWriter::array(std::io::BufWriter::new(Stdout), &scene)
                .expect("stdout ignores errors"),
        ),
        false => None,
    };
    // A file that cannot be written stops the folder, not the study: every result is still
    // printed, and the error reported at the end.
    let mut unwritten: Option<AppError> = None;
    bwc_app::with_threads(threads, || {
        simulate::stream(&scene, Some(&tick), |chunk| {
            tally.add(&scene, &chunk);
            report(&scene, &chunk);
            match &mut printed {
                Some(w) => w.add(&chunk).expect("stdout ignores errors"),
                None if scene.sequence.is_some() => bounce_table(&chunk),
                None => table.rows(&chunk),
            }
            if let Some(s) = &mut study {
                if let Err(e) = s.add(chunk) {
                    unwritten = Some(e);
                    study = None;
                }
            }
            Ok(())
        })
    })?;
    progress.bar.finish_and_clear();
    notes(&scene, &tally);
    table.finish();
    if let Some(w) = printed {
        let mut w = w
            .finish(&scene, &tally, None)
            .expect("stdout ignores errors");
        let _ = writeln!(w);
    }
    if let Some(e) = unwritten {
        return Err(e);
    }
    if let Some(study) = study {
        finish_study(study, &scene, &tally, json)?;
    }
    Ok(if tally.failed > 0 {
        exit::SOME_FAILED
    } else {
        exit::OK
    })
}

/// The progress bar of a scene's impacts: drawn only for runs longer than about a second, and
/// never with --json (indicatif stays silent when stderr is not a terminal).
struct Progress {
    bar: ProgressBar,
    start: Instant,
    shown: AtomicBool,
    json: bool,
}

impl Progress {
    fn new(total: u64, json: bool) -> Self {
        let bar = ProgressBar::with_draw_target(Some(total), ProgressDrawTarget::hidden());
        bar.set_style(
            ProgressStyle::with_template("{bar:40} {pos}/{len} impacts, eta {eta}")
                .expect("valid template"),
        );
        Progress {
            bar,
            start: Instant::now(),
            shown: AtomicBool::new(false),
            json,
        }
    }

    /// One impact done.
    fn tick(&self) {
        self.bar.inc(1);
        let late = self.start.elapsed() > Duration::from_secs(1);
        if !self.json && late && !self.shown.load(Ordering::Relaxed) {
            self.shown.store(true, Ordering::Relaxed);
            self.bar.set_draw_target(ProgressDrawTarget::stderr());
        }
    }
}

/// Completes the output folder: its summary and the list of files written (on stderr without
/// --json), and where the runs went if they are listed apart from the summary.
fn finish_study(
    study: output::Study,
    scene: &Scene,
    tally: &simulate::Tally,
    json: bool,
) -> Result<(), AppError> {
    let written = study.finish(tally)?;
    if scene.runs_listed_apart() {
        eprintln!(
            "bwc-simulate: the {} runs are in {}, one JSON object per line, not in {}: \
             more than [output].summary_runs = {}",
            tally.runs,
            output::RUNS_FILE,
            outdir::SUMMARY,
            scene.output.summary_runs
        );
    }
    if !json {
        for p in written {
            eprintln!("wrote {}", p.display());
        }
    }
    Ok(())
}

/// Standard output that ignores errors such as a closed pipe (`bwc-simulate ... | head` must
/// not panic).
struct Stdout;

impl Write for Stdout {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        let _ = std::io::stdout().lock().write_all(buf);
        Ok(buf.len())
    }

    fn flush(&mut self) -> std::io::Result<()> {
        let _ = std::io::stdout().lock().flush();
        Ok(())
    }
}

/// The notes on a whole study, on stderr: how many runs came from interpolants, and why a
/// sweep found none.
fn notes(scene: &Scene, tally: &simulate::Tally) {
    for note in notes::study_notes(scene, tally) {
        eprintln!("bwc-simulate: {note}");
    }
}

/// Says on stderr what is not a plain separation: failures with their reason, horizons with the
/// setting that moves them, settled contacts with their force balance.
fn report(scene: &Scene, runs: &[bwc_app::impact::runs::Run]) {
    for note in simulate::sampling_notes(scene, runs) {
        eprintln!("bwc-simulate: warning: {note}");
    }
    for note in runs.iter().flat_map(|r| notes::run_notes(scene, r)) {
        match note {
            Note::Warning(text) => eprintln!("bwc-simulate: warning: {text}"),
            Note::Info(text) => eprintln!("bwc-simulate: {text}"),
        }
    }
}

/// The human-readable table, with the unit of every column, printed a chunk of runs at a time:
/// the first column as wide as the first chunk's longest label (named bases make long ones).
#[derive(Default)]
struct Table {
    width: Option<usize>,
    /// The labels of the runs in double-double arithmetic.
    precise: Vec<String>,
}

impl Table {
    fn rows(&mut self, runs: &[bwc_app::impact::runs::Run]) {
        let labels: Vec<String> = runs.iter().map(|r| r.label()).collect();
        let width = match self.width {
            Some(w) => w,
            None => {
                let w = (labels.iter().map(|l| l.chars().count())).fold(24, usize::max);
                self.header(runs, w);
                *self.width.insert(w)
            }
        };
        for (r, label) in runs.iter().zip(labels) {
            let e = if r.e.is_finite() {
                format!("{:.9}", r.e)
            } else {
                "-".into()
            };
            // A checked CoR's estimate; an interpolated row's is its interpolant's.
            let estimate = (r.solver.as_ref())
                .and_then(|c| c.e_error)
                .or(r.interpolation.map(|i| i.estimate))
                .map_or("-".to_string(), |d| format!("{d:.1e}"));
            let ts = r.t_s.map_or("-".to_string(), |t| format!("{t:.9e}"));
            let td = r.t_d.map_or("-".to_string(), |t| format!("{t:.6e}"));
            let evals = match r.interpolation {
                Some(_) => "interp.".to_string(),
                None => r.solver.map_or(0, |c| c.stats.rhs_evals).to_string(),
            };
            bwc_app::out!(
                "{:<width$} {:>10} {:>12} {:>11} {:>16} {:>14} {:>10}",
                label,
                r.outcome.name(),
                e,
                estimate,
                ts,
                td,
                evals
            );
            if r.solver.is_some_and(|c| c.double_double) {
                self.precise.push(label);
            }
        }
    }

    /// The header; the unit of `t_s` is that of the first chunk's runs.
    fn header(&self, runs: &[bwc_app::impact::runs::Run], width: usize) {
        let t_unit = match runs.first().map(|r| r.time_unit) {
            Some(u) if runs.iter().all(|r| r.time_unit == u) && u == "s" => "(s)",
            Some(u) if runs.iter().all(|r| r.time_unit == u) => "(T, nondim.)",
            _ => "(s or T)",
        };
        bwc_app::out!(
            "{:<width$} {:>10} {:>12} {:>11} {:>16} {:>14} {:>10}",
            "run",
            "outcome",
            "e (-)",
            "e_error (-)",
            format!("t_s {t_unit}"),
            "t_d (s)",
            "rhs_evals"
        );
    }

    fn finish(self) {
        if !self.precise.is_empty() {
            bwc_app::out!(
                "double-double arithmetic ([solver] double_double), where double precision \
                 could not meet [solver].e_tol: {}",
                self.precise.join("; ")
            );
        }
    }
}

/// The contacts of a sequence, with the unit of every column.
fn bounce_table(runs: &[bwc_app::impact::runs::Run]) {
    bwc_app::out!(
        "{:>4} {:>14} {:>12} {:>12} {:>10} {:>14} {:>12} {:>12} {:>10}",
        "n",
        "t_contact (s)",
        "v_in (m/s)",
        "v_out (m/s)",
        "e (-)",
        "t_s (s)",
        "apex (m)",
        "interval (s)",
        "outcome"
    );
    for (b, _) in runs.iter().flat_map(|r| &r.bounces) {
        let opt =
            |v: Option<f64>, digits: usize| v.map_or("-".to_string(), |x| format!("{x:.digits$e}"));
        bwc_app::out!(
            "{:>4} {:>14.6} {:>12.6} {:>12.6} {:>10.6} {:>14} {:>12.6} {:>12} {:>10}",
            b.n,
            b.t_contact,
            b.v_in,
            b.v_out,
            b.e,
            opt(b.t_s, 6),
            b.apex,
            opt(b.interval, 6),
            match b.end {
                bw_models::sequence::BounceEnd::Separated => "separated",
                bw_models::sequence::BounceEnd::Settled => "settled",
                bw_models::sequence::BounceEnd::Horizon => "horizon",
            }
        );
    }
}

/// Runs a `[chain]` scene: the summary on stdout (a table, or one JSON object with `--json`),
/// the files into `out`.
fn run_chain(
    scene: &ChainScene,
    out: Option<&std::path::Path>,
    json: bool,
    threads: Option<usize>,
) -> Result<u8, AppError> {
    if let Some(dir) = out {
        outdir::prepare(dir)?;
    }
    let outcome = bwc_app::with_threads(threads, || bwc_app::chain::run(scene))?;
    let mut summary = bwc_app::chain::summary(scene, &outcome);
    for (k, v) in outdir::provenance("bwc-simulate")
        .as_object()
        .expect("provenance is an object")
    {
        summary[k] = v.clone();
    }
    if json {
        bwc_app::out!("{summary}");
    } else {
        chain_table(scene, &outcome);
    }
    if let Some(dir) = out {
        let files = bwc_app::chain::render(scene, &outcome, dir)?;
        let written = outdir::write_all(dir, summary, files)?;
        if !json {
            for p in written {
                eprintln!("wrote {}", p.display());
            }
        }
    }
    Ok(exit::OK)
}

/// `x` for a table: 12 significant digits, in scientific notation where it is very small or
/// large.
fn figure(x: f64) -> String {
    if x != 0.0 && !(1e-4..1e6).contains(&x.abs()) {
        format!("{x:.6e}")
    } else {
        tidy(x).to_string()
    }
}

/// The human-readable account of a chain's run, with the unit of every column.
fn chain_table(scene: &ChainScene, out: &bwc_app::chain::ChainOutcome) {
    let r = &out.run;
    let how = if r.settled {
        "settled (no contact active, no gap closing)"
    } else {
        "ended at the horizon"
    };
    bwc_app::out!(
        "chain: {how} at t = {} s, {} contacts",
        figure(r.t_end),
        r.contacts.len()
    );
    bwc_app::out!("{:>6} {:>16} {:>16}", "body", "x (m)", "v (m/s)");
    for (i, b) in r.bodies.iter().enumerate() {
        let n = scene.body_number(i);
        bwc_app::out!(
            "{n:>6} {:>16} {:>16}",
            figure(b.position),
            figure(b.velocity)
        );
    }
    bwc_app::out!(
        "{:>6} {:>14} {:>14} {:>10} {:>14}",
        "pair",
        "onset (s)",
        "separation (s)",
        "rebound",
        "dissipated (J)"
    );
    for c in &r.contacts {
        let shown = |v: Option<f64>| v.map_or("-".to_string(), |v| figure(v).to_string());
        let (sep, e) = (shown(c.separation), shown(c.rebound()));
        bwc_app::out!(
            "{:>6} {:>14} {:>14} {:>10} {:>14}",
            c.pair,
            figure(c.onset),
            sep,
            e,
            figure(c.dissipated)
        );
    }
    let l = &r.ledger;
    bwc_app::out!(
        "energy (J): initial {}, kinetic {}, stored {}, dissipated {}, work of inputs {}; \
         imbalance {:.1e}",
        figure(l.initial),
        figure(l.kinetic),
        figure(l.stored),
        figure(l.dissipated),
        figure(l.work),
        l.imbalance()
    );
}
