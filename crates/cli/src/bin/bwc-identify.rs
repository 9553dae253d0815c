//! `bwc-identify`: identify base parameters of the Bouc-Wen collision models from data.

use bwc_app::fit::checkpoint::Checkpoint;
use bwc_app::fit::config::Config;
use bwc_app::fit::identify::{render, render_loops, FitReport, LoopReport};
use bwc_app::outdir;
use bwc_app::AppError;
use bwc_cli::exit;
use clap::{Parser, Subcommand};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "bwc-identify",
    version,
    about = "Identify base parameters P* of the NDBWSHCCM / NDBWMCM from CoR and duration data",
    after_help = "Examples:\n  bwc-identify run fixtures/kharaz.toml --out out/kharaz\n  bwc-identify run fixtures/villegas.toml --json --seed 7\n  bwc-identify eval fixtures/kharaz.toml   # costs at the paper's published vectors\n  bwc-identify coverage fixtures/tennis.toml --replicates 40\n  bwc-identify posterior fixtures/tennis.toml --fit \"Tennis NDBWSHCCM\" --out out/tennis\n  bwc-identify materials fixtures/materials/alumina_on_aluminium.toml"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Fit every [[fit]] of a config from its bounds.
    Run {
        /// The config file (TOML).
        config: PathBuf,
        /// Directory for summary.json and per-fit CSV and SVG files.
        #[arg(long)]
        out: Option<PathBuf>,
        /// Print exactly one JSON object on stdout: {"fits": [...]}.
        #[arg(long)]
        json: bool,
        /// Base seed (combined with each fit's seed).
        #[arg(long, default_value_t = 0)]
        seed: u64,
        /// Record each finished fit's search in this file (JSON Lines, created if absent) and
        /// take the searches it holds: an interrupted run of many fits run again with it
        /// resumes.
        #[arg(long)]
        checkpoint: Option<PathBuf>,
        /// Worker threads (default: all cores, or RAYON_NUM_THREADS).
        #[arg(long, value_parser = clap::value_parser!(u64).range(1..=1024))]
        threads: Option<u64>,
    },
    /// Coverage study of the 95 % band on each CoR-only fit's own design: synthetic data from
    /// [fit.params] (or the fit's optimum) plus Gaussian noise, refitted per replicate.
    Coverage {
        /// The config file (TOML).
        config: PathBuf,
        /// Replicates per fit.
        #[arg(long, default_value_t = 40, value_parser = clap::value_parser!(u64).range(1..=100_000))]
        replicates: u64,
        /// Seed of the first replicate (replicate k has seed first_seed + k).
        #[arg(long, default_value_t = 1)]
        first_seed: u64,
        /// Noise standard deviation of e (default: the truth's residual standard deviation).
        #[arg(long)]
        noise: Option<f64>,
        /// Only the fit with this name.
        #[arg(long)]
        fit: Option<String>,
        /// Record each finished replicate in this file (JSON Lines, created if absent) and take
        /// the replicates it holds: an interrupted study run again with it resumes.
        #[arg(long)]
        checkpoint: Option<PathBuf>,
        /// Print exactly one JSON object on stdout: {"coverage": [...]}.
        #[arg(long)]
        json: bool,
        /// Worker threads (default: all cores, or RAYON_NUM_THREADS).
        #[arg(long, value_parser = clap::value_parser!(u64).range(1..=1024))]
        threads: Option<u64>,
    },
    /// Sample the posterior of each fit's searched quantities (sequential Monte Carlo): weighted
    /// samples, marginal 95 % credible intervals, the log evidence with its Monte Carlo error,
    /// and credible bands of e(v0) and t_d(v0).
    Posterior {
        /// The config file (TOML).
        config: PathBuf,
        /// Directory for summary.json and per-fit CSV and SVG files.
        #[arg(long)]
        out: Option<PathBuf>,
        /// Print exactly one JSON object on stdout: {"posteriors": [...]}.
        #[arg(long)]
        json: bool,
        /// Base seed (combined with each fit's seed).
        #[arg(long, default_value_t = 0)]
        seed: u64,
        /// Only the fit with this name.
        #[arg(long)]
        fit: Option<String>,
        /// Particles per run (default: [fit.posterior].particles, 500).
        #[arg(long, value_parser = clap::value_parser!(u64).range(16..=1_000_000))]
        particles: Option<u64>,
        /// Independent runs (default: [fit.posterior].runs, 4).
        #[arg(long, value_parser = clap::value_parser!(u64).range(2..=10_000))]
        runs: Option<u64>,
        /// Record each finished sampler run in this file (JSON Lines, created if absent) and
        /// take the runs it holds: an interrupted study run again with it resumes.
        #[arg(long)]
        checkpoint: Option<PathBuf>,
        /// Worker threads (default: all cores, or RAYON_NUM_THREADS).
        #[arg(long, value_parser = clap::value_parser!(u64).range(1..=1024))]
        threads: Option<u64>,
    },
    /// Which law the data support: every [[fit]] fitted, and the fits on the same data file
    /// side by side: cost, AIC, BIC, log evidence and the held-out error of k-fold
    /// cross-validation by speed group.
    Compare {
        /// The config file (TOML).
        config: PathBuf,
        /// Print exactly one JSON object on stdout: {"comparisons": [...]}.
        #[arg(long)]
        json: bool,
        /// Base seed (combined with each fit's seed).
        #[arg(long, default_value_t = 0)]
        seed: u64,
        /// Folds of the cross-validation (speed groups dealt in order of speed).
        #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u64).range(2..=1000))]
        folds: u64,
        /// Particles per run of the posteriors (default: [fit.posterior]).
        #[arg(long, value_parser = clap::value_parser!(u64).range(16..=1_000_000))]
        particles: Option<u64>,
        /// Runs of the posteriors (default: [fit.posterior]).
        #[arg(long, value_parser = clap::value_parser!(u64).range(2..=10_000))]
        runs: Option<u64>,
        /// Worker threads (default: all cores, or RAYON_NUM_THREADS).
        #[arg(long, value_parser = clap::value_parser!(u64).range(1..=1024))]
        threads: Option<u64>,
    },
    /// A law from materials and geometry: the [materials] table's two bodies, the Hertz
    /// stiffness, the onset of yield (which body, at what pressure, penetration, force and
    /// impact speed) and Thornton's elastic-plastic law, with its CoR, duration, deepest
    /// penetration and peak force over the table's speeds.
    Materials(MaterialsArgs),
    /// Evaluate the costs at each fit's [fit.params] without optimizing.
    Eval {
        /// The config file (TOML).
        config: PathBuf,
        /// Directory for summary.json and per-fit CSV and SVG files.
        #[arg(long)]
        out: Option<PathBuf>,
        /// Print exactly one JSON object on stdout.
        #[arg(long)]
        json: bool,
    },
}

/// The arguments of `bwc-identify materials`.
#[derive(clap::Args)]
struct MaterialsArgs {
    /// The file with a [materials] table (TOML).
    file: PathBuf,
    /// Print exactly one JSON object on stdout: {"bodies", "derived", "laws", "cor",
    /// "units", "notes"} (and "fits" with --fit).
    #[arg(long)]
    json: bool,
    /// Fit the BWSHCCM and the BWMCM to the reference law's CoR and duration, writing the
    /// dataset (reference.csv) and the config (fit.toml) into --out.
    #[arg(long, requires = "out")]
    fit: bool,
    /// Directory for reference.csv and fit.toml (with --fit).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Seed of the fits.
    #[arg(long, default_value_t = 0)]
    seed: u64,
}

fn main() -> ExitCode {
    let result = match Cli::parse().command {
        Command::Run {
            config,
            out,
            json,
            seed,
            checkpoint,
            threads,
        } => run(
            &config,
            (out.as_deref(), checkpoint.as_deref()),
            json,
            Some(seed),
            threads.map(|t| t as usize),
        ),
        Command::Materials(args) => materials(&args),
        Command::Eval { config, out, json } => {
            run(&config, (out.as_deref(), None), json, None, None)
        }
        Command::Compare {
            config,
            json,
            seed,
            folds,
            particles,
            runs,
            threads,
        } => compare(
            &config,
            json,
            (seed, folds as usize),
            (particles.map(|p| p as usize), runs.map(|r| r as usize)),
            threads.map(|t| t as usize),
        ),
        Command::Posterior {
            config,
            out,
            json,
            seed,
            fit,
            particles,
            runs,
            checkpoint,
            threads,
        } => posterior(
            &config,
            (out.as_deref(), checkpoint.as_deref()),
            json,
            (seed, fit.as_deref()),
            (particles.map(|p| p as usize), runs.map(|r| r as usize)),
            threads.map(|t| t as usize),
        ),
        Command::Coverage {
            config,
            replicates,
            first_seed,
            noise,
            fit,
            checkpoint,
            json,
            threads,
        } => coverage_study(
            &config,
            first_seed..first_seed.saturating_add(replicates),
            (noise, fit.as_deref()),
            checkpoint.as_deref(),
            json,
            threads.map(|t| t as usize),
        ),
    };
    match result {
        Ok(()) => ExitCode::from(exit::OK),
        Err(e) => ExitCode::from(bwc_cli::report(&e, "bwc-identify")),
    }
}

fn run(
    path: &Path,
    (out, checkpoint): (Option<&Path>, Option<&Path>),
    json: bool,
    seed: Option<u64>,
    threads: Option<usize>,
) -> Result<(), AppError> {
    let config = Config::load(path)?;
    if let Some(dir) = out {
        outdir::prepare(dir)?;
    }
    let checkpoint = open_checkpoint(checkpoint, "run")?;
    let bar = progress_bar(&config, json, seed);
    let tick = || bar.inc(1);
    let work = || bwc_app::fit::identify::fit_all(path, &config, seed, &tick, checkpoint.as_ref());
    let (reports, loop_reports) = bwc_app::with_threads(threads, work)?;
    bar.finish_and_clear();
    say_resumed(checkpoint.as_ref());
    warn(&reports, &loop_reports);
    let summary = bwc_app::fit::identify::summary_of(&config, &reports, &loop_reports);
    // The results are printed before the files are written: a failed write loses nothing.
    if json {
        bwc_app::out!("{summary}");
    } else {
        for r in &reports {
            bwc_app::outp!(
                "{}",
                bwc_app::fit::identify::fit_text(r, config_tolerance(&config, &r.name))
            );
        }
        for r in &loop_reports {
            bwc_app::outp!("{}", bwc_app::fit::identify::loop_fit_text(r));
        }
    }
    if let Some(dir) = out {
        let mut files = render(&config.fits, &reports, dir)?;
        for (f, r) in config.loop_fits.iter().zip(&loop_reports) {
            files.extend(render_loops(f, r, dir)?);
        }
        let written = outdir::write_all(dir, summary, files)?;
        if !json {
            for p in written {
                eprintln!("wrote {}", p.display());
            }
        }
    }
    Ok(())
}

/// The progress of a run's evaluations on stderr: hidden for JSON output and without a seed
/// (where the number of evaluations is not planned).
fn materials(args: &MaterialsArgs) -> Result<(), AppError> {
    use bwc_app::materials::{
        fit_to_reference, following_json, following_text, loop_following_text,
    };
    let (json, seed) = (args.json, args.seed);
    let fit = args.out.as_deref().filter(|_| args.fit);
    let spec = bwc_app::materials::MaterialsSpec::load(&args.file)?;
    let report = bwc_app::materials::MaterialsReport::of(&spec)?;
    if let Some(dir) = fit {
        outdir::prepare(dir)?;
    }
    let fits = match fit {
        Some(dir) => Some(fit_to_reference(dir, &spec, &report, seed)?),
        None => None,
    };
    if json {
        let mut v = report.json(&spec);
        if let Some(f) = &fits {
            v["fits"] = f.fits.iter().map(following_json).collect();
            v["loop_fits"] = f.loop_fits.clone().into();
        }
        bwc_app::out!("{v}");
    } else {
        bwc_app::outp!("{}", report.text(&spec));
        for f in fits.iter().flat_map(|f| &f.fits) {
            bwc_app::outp!("{}\n", following_text(f));
        }
        for l in fits.iter().flat_map(|f| &f.loop_fits) {
            bwc_app::outp!("{}\n", loop_following_text(l));
        }
    }
    Ok(())
}

fn progress_bar(config: &Config, json: bool, seed: Option<u64>) -> ProgressBar {
    let total = seed.map_or(0, |_| bwc_app::fit::identify::planned_evaluations(config));
    let target = if json || seed.is_none() {
        ProgressDrawTarget::hidden()
    } else {
        ProgressDrawTarget::stderr()
    };
    let bar = ProgressBar::with_draw_target(Some(total), target);
    bar.set_style(
        ProgressStyle::with_template("{msg:24} {bar:32} {pos}/{len} evaluations, eta {eta}")
            .expect("valid template"),
    );
    let count = config.fits.len() + config.loop_fits.len();
    bar.set_message(format!("{count} fit{}", if count == 1 { "" } else { "s" }));
    bar
}

/// The fits' warnings on stderr.
fn warn(reports: &[FitReport], loop_reports: &[LoopReport]) {
    for w in reports.iter().flat_map(|r| &r.warnings) {
        eprintln!("bwc-identify: warning: {w}");
    }
    for w in loop_reports.iter().flat_map(LoopReport::warnings) {
        eprintln!("bwc-identify: warning: {w}");
    }
}

/// `bwc-identify compare`.
fn compare(
    path: &Path,
    json: bool,
    (seed, folds): (u64, usize),
    sizes: (Option<usize>, Option<usize>),
    threads: Option<usize>,
) -> Result<(), AppError> {
    let config = Config::load(path)?;
    let work = || bwc_app::fit::identify::compare_all(path, &config, seed, folds, sizes);
    let rows = bwc_app::with_threads(threads, work)?;
    if json {
        let mut v = outdir::provenance("bwc-identify");
        v["comparisons"] = bwc_app::fit::identify::compare_summary(&rows)["comparisons"].take();
        bwc_app::out!("{v}");
        return Ok(());
    }
    for (data, members) in bwc_app::fit::identify::groups(&rows) {
        bwc_app::out!("{data}:");
        bwc_app::out!(
            "    {:28} {:14} {:>2} {:>4} {:>10} {:>9} {:>9} {:>16} {:>10}",
            "fit",
            "model",
            "k",
            "n",
            "cost",
            "AIC",
            "BIC",
            "log Z",
            "CV RMSE"
        );
        for r in &members {
            bwc_app::out!(
                "    {:28} {:14} {:>2} {:>4} {:>10.3e} {:>9.1} {:>9.1} {:>9.2} +- {:<4.2} {:>10.3e}",
                r.name,
                r.model,
                r.free,
                r.n,
                r.cost,
                r.aic,
                r.bic,
                r.log_evidence.0,
                r.log_evidence.1,
                r.cv_rmse
            );
        }
        bwc_app::out!("    {}", bwc_app::fit::identify::verdict(&members));
    }
    Ok(())
}

/// `bwc-identify posterior`.
fn posterior(
    path: &Path,
    (out, checkpoint): (Option<&Path>, Option<&Path>),
    json: bool,
    (seed, only): (u64, Option<&str>),
    sizes: (Option<usize>, Option<usize>),
    threads: Option<usize>,
) -> Result<(), AppError> {
    let config = Config::load(path)?;
    if let Some(dir) = out {
        outdir::prepare(dir)?;
    }
    let checkpoint = open_checkpoint(checkpoint, "posterior")?;
    let work = || {
        bwc_app::fit::identify::posterior_all(path, &config, seed, only, sizes, checkpoint.as_ref())
    };
    let reports = bwc_app::with_threads(threads, work)?;
    say_resumed(checkpoint.as_ref());
    for w in reports.iter().flat_map(|r| &r.warnings) {
        eprintln!("bwc-identify: warning: {w}");
    }
    let mut summary = outdir::provenance("bwc-identify");
    summary["posteriors"] =
        bwc_app::fit::identify::posterior_summary(&reports)["posteriors"].take();
    summary["config"] = config.describe();
    // The results are printed before the files are written: a failed write loses nothing.
    if json {
        bwc_app::out!("{summary}");
    } else {
        for r in &reports {
            bwc_app::outp!("{}", bwc_app::fit::identify::posterior_text(r));
        }
    }
    if let Some(dir) = out {
        let mut files = Vec::new();
        for r in &reports {
            let f = config
                .fits
                .iter()
                .find(|f| f.name == r.name)
                .expect("a fit");
            files.extend(bwc_app::fit::identify::render_posterior(f, r, dir)?);
        }
        let written = outdir::write_all(dir, summary, files)?;
        if !json {
            for p in written {
                eprintln!("wrote {}", p.display());
            }
        }
    }
    Ok(())
}

/// `bwc-identify coverage`.
fn coverage_study(
    path: &Path,
    seeds: std::ops::Range<u64>,
    (noise, only): (Option<f64>, Option<&str>),
    checkpoint: Option<&Path>,
    json: bool,
    threads: Option<usize>,
) -> Result<(), AppError> {
    let config = Config::load(path)?;
    let checkpoint = open_checkpoint(checkpoint, "coverage")?;
    let work = || {
        bwc_app::fit::identify::coverage_study(
            path,
            &config,
            noise,
            only,
            seeds,
            checkpoint.as_ref(),
        )
    };
    let reports = bwc_app::with_threads(threads, work)?;
    say_resumed(checkpoint.as_ref());
    if json {
        let mut v = outdir::provenance("bwc-identify");
        v["coverage"] = bwc_app::fit::identify::coverage_summary(&reports)["coverage"].take();
        bwc_app::out!("{v}");
        return Ok(());
    }
    for r in &reports {
        let without = r.replicates.iter().filter(|x| x.error.is_some()).count();
        bwc_app::out!(
            "{}: 95 % band contains the truth at {:.1} % of {} points ({} replicates, noise {:.3e}, truth from {}{})",
            r.name,
            100.0 * bwc_identify::coverage(&r.replicates),
            r.replicates.iter().map(|x| x.points).sum::<usize>(),
            r.replicates.len(),
            r.noise,
            r.truth_from,
            if without > 0 { format!("; {without} without intervals") } else { String::new() }
        );
    }
    Ok(())
}

/// The checkpoint of `--checkpoint`, if given, for `command`.
fn open_checkpoint(path: Option<&Path>, command: &str) -> Result<Option<Checkpoint>, AppError> {
    path.map(|p| Checkpoint::open(p, command)).transpose()
}

/// What a study took from its checkpoint, on stderr.
fn say_resumed(checkpoint: Option<&Checkpoint>) {
    if let Some(s) = checkpoint.and_then(Checkpoint::summary) {
        eprintln!("bwc-identify: {s}");
    }
}

/// The agreement tolerance of the fit named `name`.
fn config_tolerance(config: &Config, name: &str) -> f64 {
    config
        .fits
        .iter()
        .find(|f| f.name == name)
        .map_or(f64::NAN, |f| f.budget.tolerance)
}
