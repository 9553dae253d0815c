//! Runs the impacts of a scene: one per system and speed, in parallel, in a fixed order.

use crate::scene::{Scene, System, SystemSpec};
use crate::CliError;
use bw_models::input::{Constant, Input, Scaled};
use bw_models::{
    impact, simulate as sim, BodyMotion, Bwmcm, Bwshccm, CollisionModel, Impact, ModelError,
    ModelKind, Ndbwmcm, Ndbwshccm, Sampling, Settings,
};
use bwc_ode::Stats;
use rayon::prelude::*;

/// One simulated impact.
#[derive(Debug, Clone, PartialEq)]
pub struct Run {
    /// Name of the system (from `[[base]]`), if any.
    pub name: Option<String>,
    /// The model.
    pub model: ModelKind,
    /// Impact speed (m/s); `None` for nondimensional scenes.
    pub v0: Option<f64>,
    /// Separation time: nondimensional for `[nondimensional]` scenes (and `[base]` scenes
    /// without `T_b`), seconds otherwise; `None` without separation.
    pub t_s: Option<f64>,
    /// Coefficient of restitution (0 without separation).
    pub e: f64,
    /// Contact duration in seconds, where a time scale exists.
    pub t_d: Option<f64>,
    /// Unit of `t_s` and of the trajectory's `t`: `"s"` or `"nondimensional"`.
    pub time_unit: &'static str,
    /// Solver statistics.
    pub stats: Stats,
    /// When the run switched to RODAS4 because it had become stiff (in the unit of `t_s`).
    pub stiff_from: Option<f64>,
    /// Steps taken by Taylor series (`bw_models::Settings::series`).
    pub series_steps: u64,
    /// Sampled trajectory (only when an output asks for it).
    pub trajectory: Vec<Sample>,
}

/// One sample of a trajectory, in the run's units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// Time.
    pub t: f64,
    /// Relative displacement.
    pub x: f64,
    /// Relative velocity.
    pub v: f64,
    /// Relative input.
    pub u: f64,
    /// Contact force.
    pub f: f64,
    /// The model state (`x, z, v` or `r, y, z, v`).
    pub state: [f64; 4],
    /// Per-body motion (`[bodies]` scenes only).
    pub bodies: Option<BodyMotion>,
}

impl Run {
    /// A label for messages and legends: the name and/or the speed.
    pub fn label(&self) -> String {
        // Speeds to 6 significant digits (log-spaced sweeps have long decimals).
        let speed = |v: f64| format!("{}", format!("{v:.6e}").parse::<f64>().unwrap_or(v));
        match (&self.name, self.v0) {
            (Some(n), Some(v)) => format!("{n}, v0 = {} m/s", speed(v)),
            (Some(n), None) => n.clone(),
            (None, Some(v)) => format!("v0 = {} m/s", speed(v)),
            (None, None) => "run".to_string(),
        }
    }
}

/// Runs every impact of `scene` on the current rayon pool, calling `progress` after each.
///
/// # Errors
/// [`CliError::Simulation`] for the first run that fails.
pub fn run(scene: &Scene, progress: Option<&(dyn Fn() + Sync)>) -> Result<Vec<Run>, CliError> {
    let speeds: Vec<Option<f64>> = if scene.speeds.is_empty() {
        vec![None]
    } else {
        scene.speeds.iter().copied().map(Some).collect()
    };
    let jobs: Vec<(&SystemSpec, Option<f64>)> = scene
        .systems
        .iter()
        .flat_map(|s| speeds.iter().map(move |&v| (s, v)))
        .collect();
    let sampling = (scene.output.trajectory || scene.output.loops).then(|| {
        scene
            .output
            .dt
            .map_or(Sampling::Steps, |dt| Sampling::Grid { dt })
    });
    jobs.par_iter()
        .map(|&(spec, v0)| {
            let r = run_one(spec, v0, &scene.settings, sampling).map_err(|source| {
                CliError::Simulation {
                    path: scene.path.clone(),
                    run: match (&spec.name, v0) {
                        (Some(n), Some(v)) => format!("{n} at v0 = {v}"),
                        (_, Some(v)) => format!("v0 = {v}"),
                        (Some(n), None) => n.clone(),
                        (None, None) => "1".into(),
                    },
                    source,
                }
            });
            if let Some(p) = progress {
                p();
            }
            r
        })
        .collect()
}

fn run_one(
    spec: &SystemSpec,
    v0: Option<f64>,
    settings: &Settings,
    sampling: Option<Sampling>,
) -> Result<Run, ModelError> {
    let mk = |impact: Impact, trajectory, t_scale: Option<f64>, time_unit| {
        let t_s = impact.t_s.map(|t| t * t_scale.unwrap_or(1.0));
        Run {
            name: spec.name.clone(),
            model: spec.kind,
            v0,
            t_s,
            e: impact.e,
            t_d: if t_scale.is_some() { t_s } else { None },
            time_unit,
            stats: impact.stats,
            stiff_from: impact.stiff_from.map(|t| t * t_scale.unwrap_or(1.0)),
            series_steps: impact.series_steps,
            trajectory,
        }
    };
    match &spec.system {
        System::Nondimensional { params, u } => {
            let (imp, tr) = match spec.kind {
                ModelKind::Shccm => drive(
                    &Ndbwshccm::new(params, Constant(*u))?,
                    settings,
                    sampling,
                    1.0,
                )?,
                ModelKind::Mcm => drive(
                    &Ndbwmcm::new(params, Constant(*u))?,
                    settings,
                    sampling,
                    1.0,
                )?,
            };
            Ok(mk(imp, tr, None, "nondimensional"))
        }
        System::Base {
            map,
            input,
            time_scale_known,
        } => {
            let v0v = v0.unwrap_or(1.0);
            let (nd, s) = map.at(v0v)?;
            let u = Scaled {
                inner: input,
                factor: s.factor,
                time_scale: s.time_scale,
            };
            let scale = time_scale_known.then(|| map.time_scale(v0v));
            let (imp, tr) = match spec.kind {
                ModelKind::Shccm => drive(
                    &Ndbwshccm::new(&nd, u)?,
                    settings,
                    sampling,
                    scale.unwrap_or(1.0),
                )?,
                ModelKind::Mcm => drive(
                    &Ndbwmcm::new(&nd, u)?,
                    settings,
                    sampling,
                    scale.unwrap_or(1.0),
                )?,
            };
            Ok(mk(
                imp,
                tr,
                scale,
                if scale.is_some() {
                    "s"
                } else {
                    "nondimensional"
                },
            ))
        }
        System::Physical { params, m, input } => {
            let v0v = v0.unwrap_or(1.0);
            let (imp, tr) = physical(spec.kind, params, *m, v0v, input, settings, sampling)?;
            Ok(mk(imp, tr, Some(1.0), "s"))
        }
        System::Bodies { params, bodies } => {
            let (imp, mut tr) = physical(
                spec.kind,
                params,
                bodies.effective_mass(),
                bodies.impact_speed(),
                bodies.relative_input(),
                settings,
                sampling,
            )?;
            if !tr.is_empty() {
                let mut motion = bodies.motion()?;
                for s in &mut tr {
                    s.bodies = Some(motion.at(s.t, s.x, s.v)?);
                }
            }
            let mut run = mk(imp, tr, Some(1.0), "s");
            run.v0 = Some(bodies.impact_speed());
            Ok(run)
        }
    }
}

fn physical<I: Input>(
    kind: ModelKind,
    params: &bw_models::PhysicalParams,
    m: f64,
    v0: f64,
    input: I,
    settings: &Settings,
    sampling: Option<Sampling>,
) -> Result<(Impact, Vec<Sample>), ModelError> {
    match kind {
        ModelKind::Shccm => drive(
            &Bwshccm::new(params, m, v0, input)?,
            settings,
            sampling,
            1.0,
        ),
        ModelKind::Mcm => drive(&Bwmcm::new(params, m, v0, input)?, settings, sampling, 1.0),
    }
}

/// Simulates one model; samples only when asked. Sample times are multiplied by `t_scale`.
fn drive<M: CollisionModel<N>, const N: usize>(
    model: &M,
    settings: &Settings,
    sampling: Option<Sampling>,
    t_scale: f64,
) -> Result<(Impact, Vec<Sample>), ModelError> {
    let Some(sampling) = sampling else {
        return Ok((impact(model, settings)?, Vec::new()));
    };
    let mut rows = Vec::new();
    let sampling = match sampling {
        Sampling::Grid { dt } => Sampling::Grid { dt: dt / t_scale },
        s => s,
    };
    let out = sim(model, settings, sampling, |t, y| {
        let mut state = [0.0; 4];
        state[..N].copy_from_slice(y.as_slice());
        rows.push(Sample {
            t: t * t_scale,
            x: model.displacement(y),
            v: model.velocity(y),
            u: model.input(t),
            f: model.force(y),
            state,
            bodies: None,
        });
    })?;
    Ok((out, rows))
}
