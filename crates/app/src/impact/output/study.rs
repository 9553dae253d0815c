//! A scene's output folder written as its runs come ([`crate::impact::simulate::stream`]): the rows of
//! `sweep.csv`, `trajectory.csv` and `loop.csv` and the runs of the summary go to their files
//! chunk by chunk, so that memory stays flat however many speeds a study has; the figures are
//! drawn at the end from the runs they show, kept on the way. Every file is written under a
//! temporary name and renamed into place when the study finishes ([`outdir::commit`]): a run
//! that fails or is killed leaves the files of the run before it, complete, or none.

use super::{figures, opt, source, units, SummaryWriter};
use crate::impact::runs::{Outcome, Run};
use crate::impact::scene::{Scene, System};
use crate::impact::simulate::Tally;
use crate::outdir::{self, Staged};
use crate::AppError;
use bw_models::ModelKind;
use std::io::Write;
use std::path::{Path, PathBuf};

/// The most runs of one system a CoR or duration figure draws (evenly spaced in the sweep's
/// order, its last speed included): far more points than a figure has pixels across.
pub const FIGURE_POINTS: usize = 2000;

/// The most runs the time-history and loop figures draw (evenly spaced): each is a line of its
/// own, with a legend entry.
pub const FIGURE_RUNS: usize = 50;

/// Name of the JSON Lines file holding the runs of a study above `[output].summary_runs`.
pub const RUNS_FILE: &str = "runs.jsonl";

/// An output folder being written as a scene's runs come: [`Study::add`] each chunk in
/// [`crate::impact::simulate::stream`]'s order, then [`Study::finish`].
pub struct Study<'a> {
    scene: &'a Scene,
    dir: PathBuf,
    layout: Layout,
    summary: SummaryWriter<Staged>,
    sweep: Option<csv::Writer<Staged>>,
    trajectory: Option<csv::Writer<Staged>>,
    loops: Option<csv::Writer<Staged>>,
    /// The runs the CoR and duration figures draw, without their trajectories.
    points: Vec<Run>,
    /// The runs the time-history and loop figures draw, and every run of a sequence (for
    /// `bounces.csv`).
    traced: Vec<Run>,
    seen: usize,
}

/// What a scene's files hold, decided before its first run.
#[derive(Debug, Clone, Copy)]
struct Layout {
    /// Runs in the whole study.
    total: usize,
    /// Runs of each system.
    per_system: usize,
    several_systems: bool,
    /// `trajectory.csv` with the two bodies' columns.
    bodies: bool,
    /// The first system's model, whose law states `trajectory.csv` carries after `x`
    /// ([`ModelKind::law_states`]: `z`, or `r, y, z`).
    model: ModelKind,
    /// Every `FIGURE_POINTS`-th run of a system drawn in the sweep figures (1: all).
    point_stride: usize,
    /// Every `FIGURE_RUNS`-th run drawn in the time-history and loop figures (1: all).
    run_stride: usize,
}

impl Layout {
    fn of(scene: &Scene) -> Self {
        let total = scene.run_count();
        let per_system = total / scene.systems.len().max(1);
        Layout {
            total,
            per_system,
            several_systems: scene.systems.len() > 1,
            bodies: (scene.systems.iter()).any(|s| matches!(s.system, System::Bodies { .. })),
            model: scene.systems.first().map_or(ModelKind::Shccm, |s| s.kind),
            point_stride: per_system.div_ceil(FIGURE_POINTS).max(1),
            run_stride: total.div_ceil(FIGURE_RUNS).max(1),
        }
    }
}

impl<'a> Study<'a> {
    /// Starts writing the outputs of `scene` into `dir` (a folder [`outdir::prepare`] accepted).
    ///
    /// # Errors
    /// [`AppError::Output`] if a file cannot be created; [`AppError::Csv`] if a header cannot
    /// be written.
    pub fn start(scene: &'a Scene, dir: &Path) -> Result<Self, AppError> {
        let layout = Layout::of(scene);
        let spec = scene.output;
        let csv = |name: &str, header: Vec<&str>| -> Result<_, AppError> {
            let mut w = csv::Writer::from_writer(Staged::create(dir, name)?);
            w.write_record(header).map_err(csv_error(dir, name))?;
            Ok(Some(w))
        };
        let summary = if scene.runs_listed_apart() {
            SummaryWriter::lines(Staged::create(dir, RUNS_FILE)?, scene)
        } else {
            let file = Staged::create(dir, outdir::SUMMARY)?;
            let head = SummaryWriter::array(file, scene);
            head.map_err(|e| AppError::Output {
                dir: dir.to_owned(),
                file: Some(outdir::SUMMARY.into()),
                source: e,
            })?
        };
        let sequence = scene.sequence.is_some();
        Ok(Study {
            scene,
            dir: dir.to_owned(),
            summary,
            sweep: match !sequence && (spec.sweep || scene.speeds.len() > 1) {
                true => csv("sweep.csv", sweep_header(layout))?,
                false => None,
            },
            trajectory: match spec.trajectory && !sequence {
                true => csv("trajectory.csv", trajectory_header(layout))?,
                false => None,
            },
            loops: match spec.loops && !sequence {
                true => csv("loop.csv", loop_header(layout))?,
                false => None,
            },
            layout,
            points: Vec::new(),
            traced: Vec::new(),
            seen: 0,
        })
    }

    /// Writes the next runs of the scene, in [`crate::impact::simulate::stream`]'s order.
    ///
    /// # Errors
    /// [`AppError::Output`] or [`AppError::Csv`] naming the file that could not be written.
    pub fn add(&mut self, runs: Vec<Run>) -> Result<(), AppError> {
        let l = self.layout;
        let dir = &self.dir;
        if let Err(e) = self.summary.add(&runs) {
            return Err(self.summary.sink().error(e));
        }
        if let Some(w) = &mut self.sweep {
            sweep_rows(w, &runs, l).map_err(csv_error(dir, "sweep.csv"))?;
        }
        if let Some(w) = &mut self.trajectory {
            trajectory_rows(w, &runs, l).map_err(csv_error(dir, "trajectory.csv"))?;
        }
        if let Some(w) = &mut self.loops {
            loop_rows(w, &runs, l).map_err(csv_error(dir, "loop.csv"))?;
        }
        let plots = self.scene.output.plots;
        let sequence = self.scene.sequence.is_some();
        let first = self.seen;
        self.seen += runs.len();
        for (k, mut run) in (first..).zip(runs) {
            let j = k % l.per_system;
            let trajectory = std::mem::take(&mut run.trajectory);
            if plots && (j % l.point_stride == 0 || j + 1 == l.per_system) {
                self.points.push(run.clone());
            }
            if sequence || (plots && k % l.run_stride == 0) {
                run.trajectory = trajectory;
                self.traced.push(run);
            }
        }
        Ok(())
    }

    /// Draws the figures, closes the summary (`tally`: of every run added) and renames every
    /// file into place; returns the paths written, `summary.json` first.
    ///
    /// # Errors
    /// [`AppError::Plot`], [`AppError::Csv`] or [`AppError::Output`] naming the file; nothing
    /// of this run is then left in the folder.
    pub fn finish(self, tally: &Tally) -> Result<Vec<PathBuf>, AppError> {
        let dir = self.dir;
        let mut files = Vec::new();
        for w in [self.sweep, self.trajectory, self.loops]
            .into_iter()
            .flatten()
        {
            let name = w.get_ref().name().to_string();
            files.push(w.into_inner().map_err(|e| AppError::Output {
                dir: dir.clone(),
                file: Some(name),
                source: std::io::Error::new(e.error().kind(), e.error().to_string()),
            })?);
        }
        for (name, bytes) in drawn(self.scene, &self.points, &self.traced, &dir)? {
            let mut file = Staged::create(&dir, &name)?;
            file.write_all(&bytes).map_err(|e| file.error(e))?;
            files.push(file);
        }
        let mut names = vec![outdir::SUMMARY.to_string()];
        let lines = self.summary.is_lines();
        if lines {
            names.push(RUNS_FILE.to_string());
        }
        names.extend(files.iter().map(|f| f.name().to_string()));
        let fail = |name: &str, source| AppError::Output {
            dir: dir.clone(),
            file: Some(name.to_string()),
            source,
        };
        let head = if lines {
            let runs =
                (self.summary.finish(self.scene, tally, None)).map_err(|e| fail(RUNS_FILE, e))?;
            files.insert(0, runs);
            let mut head = Staged::create(&dir, outdir::SUMMARY)?;
            let text = pointer(self.scene, tally, &names) + "\n";
            head.write_all(text.as_bytes()).map_err(|e| head.error(e))?;
            head
        } else {
            let mut head = (self.summary.finish(self.scene, tally, Some(&names)))
                .map_err(|e| fail(outdir::SUMMARY, e))?;
            head.write_all(b"\n").map_err(|e| head.error(e))?;
            head
        };
        outdir::commit(&dir, head, files)
    }
}

/// The `summary.json` of a study whose runs are in [`RUNS_FILE`]: the provenance and units of
/// a summary, `"run_count"` and `"runs_file"` in place of `"runs"`, and `"files"`.
fn pointer(scene: &Scene, tally: &Tally, files: &[String]) -> String {
    let mut v = crate::outdir::provenance("bwc-simulate");
    v["run_count"] = tally.runs.into();
    v["runs_file"] = RUNS_FILE.into();
    v["scene"] = scene.describe();
    v["units"] = units(scene, tally.time_unit());
    v["files"] = serde_json::json!(files);
    v.to_string()
}

/// The figures of the runs kept for them (`points` for the CoR and duration, `traced` for the
/// time histories and loops), and `bounces.csv` and `height.svg` of a sequence (`traced`: all
/// its runs).
fn drawn(
    scene: &Scene,
    points: &[Run],
    traced: &[Run],
    dir: &Path,
) -> Result<Vec<(String, Vec<u8>)>, AppError> {
    let spec = scene.output;
    let plot_err = |(name, message): (String, String)| AppError::Plot {
        path: dir.join(name),
        message,
    };
    let mut files = Vec::new();
    if scene.sequence.is_some() {
        let bounces = super::bounces_csv(traced).map_err(csv_error(dir, "bounces.csv"))?;
        files.push(("bounces.csv".to_string(), bounces));
        files.push(figures::height(scene, traced).map_err(plot_err)?);
    }
    if !spec.plots {
        return Ok(files);
    }
    if spec.sweep || scene.speeds.len() > 1 {
        for f in figures::sweep(scene, points) {
            files.push(f.map_err(plot_err)?);
        }
    }
    if spec.trajectory {
        let bodies = (traced.iter()).any(|r| r.trajectory.iter().any(|s| s.bodies.is_some()));
        for f in figures::time_histories(scene, traced, bodies) {
            files.push(f.map_err(plot_err)?);
        }
    }
    if spec.loops {
        files.push(figures::loops(scene, traced).map_err(plot_err)?);
    }
    Ok(files)
}

fn csv_error(dir: &Path, name: &str) -> impl Fn(csv::Error) -> AppError {
    let path = dir.join(name);
    move |source| AppError::Csv {
        path: path.clone(),
        source,
    }
}

/// `sweep.csv`: one row per run (`name` where the scene has several systems).
/// A column of `sweep.csv`: its name, its unit (`None`: the unit of the runs' `t_s`) and its
/// value in a run.
struct SweepColumn {
    name: &'static str,
    unit: Option<&'static str>,
    value: fn(&Run) -> String,
}

/// The columns of `sweep.csv`, in order; `name` only where the scene has several systems.
const SWEEP_COLUMNS: [SweepColumn; 8] = [
    SweepColumn {
        name: "v_0",
        unit: Some("m/s"),
        value: |r| opt(r.v0),
    },
    SweepColumn {
        name: "e",
        unit: Some("1"),
        value: |r| opt(Some(r.e).filter(|e| e.is_finite())),
    },
    SweepColumn {
        name: "t_d",
        unit: Some("s"),
        value: |r| opt(r.t_d),
    },
    SweepColumn {
        name: "t_s",
        unit: None,
        value: |r| opt(r.t_s),
    },
    SweepColumn {
        name: "separated",
        unit: Some("true/false"),
        value: |r| (r.outcome == Outcome::Separated).to_string(),
    },
    SweepColumn {
        name: "name",
        unit: Some("text"),
        value: |r| r.name.clone().unwrap_or_default(),
    },
    SweepColumn {
        name: "outcome",
        unit: Some("text"),
        value: |r| r.outcome.name().to_string(),
    },
    SweepColumn {
        name: "source",
        unit: Some("text"),
        value: |r| source(r).to_string(),
    },
];

/// The columns of `sweep.csv` for a scene of this layout.
fn sweep_columns(l: Layout) -> impl Iterator<Item = &'static SweepColumn> {
    SWEEP_COLUMNS
        .iter()
        .filter(move |c| c.name != "name" || l.several_systems)
}

/// The unit of every column `sweep.csv` may have, `t` that of the runs' `t_s`.
pub(super) fn sweep_units(t: &str) -> serde_json::Value {
    let units = SWEEP_COLUMNS
        .iter()
        .map(|c| (c.name.to_string(), c.unit.unwrap_or(t).into()));
    serde_json::Value::Object(units.collect())
}

fn sweep_header(l: Layout) -> Vec<&'static str> {
    sweep_columns(l).map(|c| c.name).collect()
}

fn sweep_rows<W: Write>(w: &mut csv::Writer<W>, runs: &[Run], l: Layout) -> csv::Result<()> {
    for r in runs {
        w.write_record(sweep_columns(l).map(|c| (c.value)(r)))?;
    }
    Ok(())
}

/// `trajectory.csv`: every sample of every run (`v_0` and `name` where there are several runs;
/// the bodies' columns where a run has two bodies; `r`, `y`, `z` for the MCM, else `z`).
fn trajectory_header(l: Layout) -> Vec<&'static str> {
    let mut header: Vec<&str> = Vec::new();
    if l.total > 1 {
        header.extend(["v_0", "name"]);
    }
    if l.bodies {
        header.extend([
            "t", "x_m_1", "x_m_2", "x_m", "x", "v_m_1", "v_m_2", "v_m", "v", "u_1", "u_2", "u", "F",
        ]);
    } else {
        header.extend(["t", "x", "v", "u", "F"]);
    }
    header.extend(l.model.law_states().iter().filter(|n| **n != "x"));
    header
}

fn trajectory_rows<W: Write>(w: &mut csv::Writer<W>, runs: &[Run], l: Layout) -> csv::Result<()> {
    let nan = f64::NAN;
    for r in runs {
        for s in &r.trajectory {
            let mut rec: Vec<String> = Vec::with_capacity(18);
            if l.total > 1 {
                rec.push(opt(r.v0));
                rec.push(r.name.clone().unwrap_or_default());
            }
            rec.push(s.t.to_string());
            if l.bodies {
                let b = s.bodies;
                let of = |f: fn(&bw_models::BodyMotion) -> f64| b.as_ref().map_or(nan, f);
                rec.extend(
                    [
                        of(|b| b.x_m_1),
                        of(|b| b.x_m_2),
                        of(|b| b.x_m),
                        s.x,
                        of(|b| b.v_m_1),
                        of(|b| b.v_m_2),
                        of(|b| b.v_m),
                        s.v,
                        of(|b| b.u_1),
                        of(|b| b.u_2),
                        s.u,
                        s.f,
                    ]
                    .iter()
                    .map(f64::to_string),
                );
            } else {
                rec.extend([s.x, s.v, s.u, s.f].iter().map(f64::to_string));
            }
            let states = l.model.law_states().iter().enumerate();
            rec.extend(
                states
                    .filter(|(_, n)| **n != "x")
                    .map(|(i, _)| s.state[i].to_string()),
            );
            w.write_record(&rec)?;
        }
    }
    Ok(())
}

/// `loop.csv`: the force against the displacement, every sample of every run.
fn loop_header(l: Layout) -> Vec<&'static str> {
    let mut header = vec!["v_0", "x", "F"];
    if l.several_systems {
        header.push("name");
    }
    header
}

fn loop_rows<W: Write>(w: &mut csv::Writer<W>, runs: &[Run], l: Layout) -> csv::Result<()> {
    for r in runs {
        for s in &r.trajectory {
            let mut rec = vec![opt(r.v0), s.x.to_string(), s.f.to_string()];
            if l.several_systems {
                rec.push(r.name.clone().unwrap_or_default());
            }
            w.write_record(&rec)?;
        }
    }
    Ok(())
}
