//! Output files: `summary.json`, `sweep.csv`, `trajectory.csv`, `loop.csv` and SVG plots, all
//! rendered in memory first and then written to a temporary name and renamed, so that a failed
//! run leaves no half-written file.

use crate::plot::{self, Series, SeriesLabelPosition};
use crate::scene::{OutputSpec, Scene};
use crate::simulate::Run;
use crate::CliError;
use bw_models::ModelKind;
use serde::Serialize;
use std::path::{Path, PathBuf};

/// One run in the JSON summary. Key names are a fixed contract; keys may be added.
#[derive(Debug, Serialize)]
pub struct RunSummary {
    /// Impact speed (m/s), null for nondimensional scenes.
    pub v0: Option<f64>,
    /// Separation time (nondimensional for nondimensional scenes, s otherwise), null without separation.
    pub t_s: Option<f64>,
    /// Coefficient of restitution.
    pub e: f64,
    /// Contact duration (s), null where no time scale exists.
    pub t_d: Option<f64>,
    /// Whether the bodies separated.
    pub separated: bool,
    /// RHS evaluations.
    pub rhs_evals: u64,
    /// Accepted steps.
    pub accepted: u64,
    /// Rejected steps.
    pub rejected: u64,
    /// Located events.
    pub events: u64,
    /// Jacobian evaluations (RODAS4 steps).
    pub jacobians: u64,
    /// When the run switched to RODAS4 because it had become stiff (unit of `t_s`), or null.
    pub stiff_from: Option<f64>,
    /// Steps taken by Taylor series (0 on the Runge-Kutta path; counted in `accepted`).
    pub series_steps: u64,
    /// `"shccm"` or `"mcm"`.
    pub model: &'static str,
    /// System name, if any.
    pub name: Option<String>,
    /// Unit of `t_s`.
    pub time_unit: &'static str,
}

/// The JSON summary: `{"runs": [...]}`.
#[derive(Debug, Serialize)]
pub struct Summary {
    /// One entry per run, in scene order.
    pub runs: Vec<RunSummary>,
}

impl Summary {
    /// Summarises runs.
    pub fn new(runs: &[Run]) -> Self {
        Summary {
            runs: runs
                .iter()
                .map(|r| RunSummary {
                    v0: r.v0,
                    t_s: r.t_s,
                    e: r.e,
                    t_d: r.t_d,
                    separated: r.t_s.is_some(),
                    rhs_evals: r.stats.rhs_evals,
                    accepted: r.stats.accepted,
                    rejected: r.stats.rejected,
                    events: r.stats.events,
                    jacobians: r.stats.jacobians,
                    stiff_from: r.stiff_from,
                    series_steps: r.series_steps,
                    model: r.model.name(),
                    name: r.name.clone(),
                    time_unit: r.time_unit,
                })
                .collect(),
        }
    }

    /// The summary as one line of JSON.
    pub fn to_json(&self) -> String {
        serde_json::to_string(self).expect("summary serializes")
    }
}

/// Renders every requested output of `runs` into `(file name, bytes)` pairs.
///
/// # Errors
/// [`CliError::Csv`] or [`CliError::Plot`] if rendering fails.
pub fn render(scene: &Scene, runs: &[Run], out: &Path) -> Result<Vec<(String, Vec<u8>)>, CliError> {
    let spec: OutputSpec = scene.output;
    let mut files = vec![(
        "summary.json".to_string(),
        (Summary::new(runs).to_json() + "\n").into_bytes(),
    )];
    let several_systems = scene.systems.len() > 1;
    let several_runs = runs.len() > 1;
    let sweep = spec.sweep || scene.speeds.len() > 1;
    let csv_err = |name: &str| {
        let path = out.join(name);
        move |source: csv::Error| CliError::Csv {
            path: path.clone(),
            source,
        }
    };
    let plot_err = |name: &str| {
        let path = out.join(name);
        move |message: String| CliError::Plot {
            path: path.clone(),
            message,
        }
    };

    if sweep {
        let mut w = csv::Writer::from_writer(Vec::new());
        let mut header = vec!["v_0", "e", "t_d", "t_s", "separated"];
        if several_systems {
            header.push("name");
        }
        w.write_record(&header).map_err(csv_err("sweep.csv"))?;
        for r in runs {
            let mut rec = vec![
                opt(r.v0),
                r.e.to_string(),
                opt(r.t_d),
                opt(r.t_s),
                r.t_s.is_some().to_string(),
            ];
            if several_systems {
                rec.push(r.name.clone().unwrap_or_default());
            }
            w.write_record(&rec).map_err(csv_err("sweep.csv"))?;
        }
        files.push((
            "sweep.csv".into(),
            w.into_inner().expect("in-memory writer"),
        ));
        if spec.plots {
            let by_system = group(runs, |r| (r.v0.unwrap_or(f64::NAN), r.e));
            files.push((
                "cor.svg".into(),
                plot::chart(
                    "Coefficient of restitution",
                    "v0 (m/s)",
                    "e",
                    &by_system,
                    true,
                    SeriesLabelPosition::UpperRight,
                )
                .map_err(plot_err("cor.svg"))?
                .into_bytes(),
            ));
            if runs.iter().any(|r| r.t_d.is_some()) {
                let by_system = group(runs, |r| {
                    (r.v0.unwrap_or(f64::NAN), r.t_d.unwrap_or(f64::NAN))
                });
                files.push((
                    "duration.svg".into(),
                    plot::chart(
                        "Contact duration",
                        "v0 (m/s)",
                        "t_d (s)",
                        &by_system,
                        true,
                        SeriesLabelPosition::UpperRight,
                    )
                    .map_err(plot_err("duration.svg"))?
                    .into_bytes(),
                ));
            }
        }
    }

    if spec.trajectory {
        let bodies = runs
            .iter()
            .any(|r| r.trajectory.iter().any(|s| s.bodies.is_some()));
        let mcm = runs.first().is_some_and(|r| r.model == ModelKind::Mcm);
        let mut header: Vec<&str> = Vec::new();
        if several_runs {
            header.extend(["v_0", "name"]);
        }
        if bodies {
            header.extend([
                "t", "x_m_1", "x_m_2", "x_m", "x", "v_m_1", "v_m_2", "v_m", "v", "u_1", "u_2", "u",
                "F",
            ]);
        } else {
            header.extend(["t", "x", "v", "u", "F"]);
        }
        header.extend(if mcm {
            ["r", "y", "z"].as_slice()
        } else {
            ["z"].as_slice()
        });
        let mut w = csv::Writer::from_writer(Vec::new());
        w.write_record(&header).map_err(csv_err("trajectory.csv"))?;
        for r in runs {
            for s in &r.trajectory {
                let mut rec: Vec<String> = Vec::with_capacity(header.len());
                if several_runs {
                    rec.push(opt(r.v0));
                    rec.push(r.name.clone().unwrap_or_default());
                }
                rec.push(s.t.to_string());
                match &s.bodies {
                    Some(b) if bodies => rec.extend(
                        [
                            b.x_m_1, b.x_m_2, b.x_m, s.x, b.v_m_1, b.v_m_2, b.v_m, s.v, b.u_1,
                            b.u_2, s.u, s.f,
                        ]
                        .iter()
                        .map(f64::to_string),
                    ),
                    _ => rec.extend([s.x, s.v, s.u, s.f].iter().map(f64::to_string)),
                }
                let extra: &[f64] = if mcm { &s.state[..3] } else { &s.state[1..2] };
                rec.extend(extra.iter().map(f64::to_string));
                w.write_record(&rec).map_err(csv_err("trajectory.csv"))?;
            }
        }
        files.push((
            "trajectory.csv".into(),
            w.into_inner().expect("in-memory writer"),
        ));
        if spec.plots {
            files.extend(time_histories(runs, bodies).map_err(plot_err("trajectory plots"))?);
        }
    }

    if spec.loops {
        let mut w = csv::Writer::from_writer(Vec::new());
        let mut header = vec!["v_0", "x", "F"];
        if several_systems {
            header.push("name");
        }
        w.write_record(&header).map_err(csv_err("loop.csv"))?;
        for r in runs {
            for s in &r.trajectory {
                let mut rec = vec![opt(r.v0), s.x.to_string(), s.f.to_string()];
                if several_systems {
                    rec.push(r.name.clone().unwrap_or_default());
                }
                w.write_record(&rec).map_err(csv_err("loop.csv"))?;
            }
        }
        files.push(("loop.csv".into(), w.into_inner().expect("in-memory writer")));
        if spec.plots {
            let si = runs.iter().all(|r| r.time_unit == "s");
            let (xlabel, ylabel, scale) = if si {
                ("|x| (mm)", "F (N)", 1e3)
            } else {
                ("|X|", "F", 1.0)
            };
            let series: Vec<Series> = runs
                .iter()
                .map(|r| Series {
                    label: r.label(),
                    points: r.trajectory.iter().map(|s| (-s.x * scale, s.f)).collect(),
                })
                .collect();
            files.push((
                "loops.svg".into(),
                plot::chart(
                    "Force-compression loops",
                    xlabel,
                    ylabel,
                    &series,
                    false,
                    SeriesLabelPosition::UpperLeft,
                )
                .map_err(plot_err("loops.svg"))?
                .into_bytes(),
            ));
        }
    }
    Ok(files)
}

fn opt(v: Option<f64>) -> String {
    v.map(|x| x.to_string()).unwrap_or_default()
}

/// One series per system: points `f(run)` over its runs.
fn group(runs: &[Run], f: impl Fn(&Run) -> (f64, f64)) -> Vec<Series> {
    let mut out: Vec<Series> = Vec::new();
    for r in runs {
        let label = r.name.clone().unwrap_or_else(|| r.model.name().to_string());
        match out.iter_mut().find(|s| s.label == label) {
            Some(s) => s.points.push(f(r)),
            None => out.push(Series {
                label,
                points: vec![f(r)],
            }),
        }
    }
    out
}

/// The paper's Figs. 3-5: displacements, velocities and forces against time.
fn time_histories(runs: &[Run], bodies: bool) -> Result<Vec<(String, Vec<u8>)>, String> {
    let unit = if runs.iter().all(|r| r.time_unit == "s") {
        "t (s)"
    } else {
        "T"
    };
    let mut disp = Vec::new();
    let mut vel = Vec::new();
    let mut force = Vec::new();
    for r in runs {
        let tag = if runs.len() > 1 {
            format!(" ({})", r.label())
        } else {
            String::new()
        };
        let series = |name: &str, f: &dyn Fn(&crate::simulate::Sample) -> f64| Series {
            label: format!("{name}{tag}"),
            points: r.trajectory.iter().map(|s| (s.t, f(s))).collect(),
        };
        if bodies {
            disp.push(series("x_m_1", &|s| s.bodies.map_or(f64::NAN, |b| b.x_m_1)));
            disp.push(series("x_m_2", &|s| s.bodies.map_or(f64::NAN, |b| b.x_m_2)));
            disp.push(series("x_m", &|s| s.bodies.map_or(f64::NAN, |b| b.x_m)));
            vel.push(series("v_m_1", &|s| s.bodies.map_or(f64::NAN, |b| b.v_m_1)));
            vel.push(series("v_m_2", &|s| s.bodies.map_or(f64::NAN, |b| b.v_m_2)));
            vel.push(series("v_m", &|s| s.bodies.map_or(f64::NAN, |b| b.v_m)));
            force.push(series("u_1", &|s| s.bodies.map_or(f64::NAN, |b| b.u_1)));
            force.push(series("u_2", &|s| s.bodies.map_or(f64::NAN, |b| b.u_2)));
        }
        disp.push(series("x", &|s| s.x));
        vel.push(series("v", &|s| s.v));
        force.push(series("u", &|s| s.u));
        force.push(series("F", &|s| s.f));
    }
    Ok(vec![
        (
            "displacements.svg".into(),
            plot::chart(
                "Displacements",
                unit,
                "displacement",
                &disp,
                false,
                SeriesLabelPosition::LowerRight,
            )?
            .into_bytes(),
        ),
        (
            "velocities.svg".into(),
            plot::chart(
                "Velocities",
                unit,
                "velocity",
                &vel,
                false,
                SeriesLabelPosition::LowerRight,
            )?
            .into_bytes(),
        ),
        (
            "forces.svg".into(),
            plot::chart(
                "Forces",
                unit,
                "force",
                &force,
                false,
                SeriesLabelPosition::MiddleRight,
            )?
            .into_bytes(),
        ),
    ])
}

/// Writes `files` into `dir` (created if needed): each to a temporary name, then renamed.
///
/// # Errors
/// [`CliError::Io`] naming the file that could not be written; temporary files are removed.
pub fn write_all(dir: &Path, files: &[(String, Vec<u8>)]) -> Result<Vec<PathBuf>, CliError> {
    std::fs::create_dir_all(dir).map_err(|source| CliError::Io {
        path: dir.to_owned(),
        source,
    })?;
    let mut written = Vec::new();
    for (name, bytes) in files {
        let path = dir.join(name);
        let tmp = dir.join(format!(".{name}.{}.tmp", std::process::id()));
        let result = std::fs::write(&tmp, bytes).and_then(|_| std::fs::rename(&tmp, &path));
        if let Err(source) = result {
            let _ = std::fs::remove_file(&tmp);
            return Err(CliError::Io { path, source });
        }
        written.push(path);
    }
    Ok(written)
}
