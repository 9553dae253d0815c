//! `bwc-simulate`: simulate the impacts a TOML scene describes.

use bwc_cli::{output, scene::Scene, simulate, CliError};
use clap::{Parser, Subcommand};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
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
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("bwc-simulate: {e}");
            ExitCode::FAILURE
        }
    }
}

fn run(
    path: &std::path::Path,
    out: Option<&std::path::Path>,
    json: bool,
    threads: Option<usize>,
) -> Result<(), CliError> {
    let scene = Scene::load(path)?;
    let total = (scene.systems.len() * scene.speeds.len().max(1)) as u64;
    let bar = ProgressBar::with_draw_target(Some(total), ProgressDrawTarget::hidden());
    bar.set_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} impacts, eta {eta}")
            .expect("valid template"),
    );
    let start = Instant::now();
    let shown = AtomicBool::new(false);
    // Shown only for runs longer than about a second, and never with --json (indicatif stays
    // silent when stderr is not a terminal).
    let tick = || {
        bar.inc(1);
        if !json && !shown.load(Ordering::Relaxed) && start.elapsed() > Duration::from_secs(1) {
            shown.store(true, Ordering::Relaxed);
            bar.set_draw_target(ProgressDrawTarget::stderr());
        }
    };
    let runs = bwc_cli::with_threads(threads, || simulate::run(&scene, Some(&tick)))?;
    bar.finish_and_clear();
    if let Some(dir) = out {
        let files = output::render(&scene, &runs, dir)?;
        let written = output::write_all(dir, &files)?;
        if !json {
            for p in written {
                eprintln!("wrote {}", p.display());
            }
        }
    }
    if json {
        bwc_cli::out!("{}", output::Summary::new(&runs).to_json());
    } else {
        // The first column as wide as the longest label (named bases make long ones).
        let labels: Vec<String> = runs.iter().map(|r| r.label()).collect();
        let width = labels
            .iter()
            .map(|l| l.chars().count())
            .fold(24, usize::max);
        bwc_cli::out!(
            "{:<width$} {:>12} {:>16} {:>14} {:>10}",
            "run",
            "e",
            "t_s",
            "t_d (s)",
            "rhs_evals"
        );
        for (r, label) in runs.iter().zip(&labels) {
            let ts = r
                .t_s
                .map_or("no separation".to_string(), |t| format!("{t:.9e}"));
            let td = r.t_d.map_or("-".to_string(), |t| format!("{t:.6e}"));
            bwc_cli::out!(
                "{:<width$} {:>12.9} {:>16} {:>14} {:>10}",
                label,
                r.e,
                ts,
                td,
                r.stats.rhs_evals
            );
        }
    }
    Ok(())
}
