//! Runs the impacts of a scene: one per system and speed, in parallel, in a fixed order.

use crate::runs::{hint, scaling, Interpolation, Outcome, Rest, Run, Sample, Scaling};
use crate::scene::{Scene, System, SystemSpec};
use bw_models::input::{Constant, Input, Scaled};
use bw_models::sweep::{self, GaveUp, Row, SweepSettings, Values};
use bw_models::{
    impact, simulate as sim, Bwmcm, Bwshccm, CollisionModel, Cor, ModelError, ModelKind, Ndbwmcm,
    Ndbwshccm, NondimParams, PhysicalParams, Sampling, Settings,
};
use rayon::prelude::*;
use std::collections::HashMap;

/// Runs every impact of `scene` on the current rayon pool, calling `progress` after each. Each
/// run stands alone: one that fails is returned with [`Outcome::Failed`] and its error, and the
/// others are unaffected. The speeds of a sweep are served by verified interpolants where that
/// saves simulations (`[sweep] interpolate`, see [`Run::interpolation`]).
pub fn run(scene: &Scene, progress: Option<&(dyn Fn() + Sync)>) -> Vec<Run> {
    if let Some(seq) = &scene.sequence {
        return scene
            .systems
            .iter()
            .map(|s| crate::sequence::run(s, seq, &scene.settings))
            .collect();
    }
    let sampling = (scene.output.trajectory || scene.output.loops).then(|| {
        scene
            .output
            .dt
            .map_or(Sampling::Steps, |dt| Sampling::Grid { dt })
    });
    let tick = || {
        if let Some(p) = progress {
            p();
        }
    };
    let speeds: Vec<Option<f64>> = if scene.speeds.is_empty() {
        vec![None]
    } else {
        scene.speeds.iter().copied().map(Some).collect()
    };
    let served = sweep_served(scene);
    // Every simulated run of every other system in one parallel pass (a scene of many systems
    // with a speed each keeps its parallelism).
    let jobs: Vec<(&SystemSpec, Option<f64>)> = (scene.systems.iter().zip(&served))
        .filter(|(_, &served)| !served)
        .flat_map(|(s, _)| speeds.iter().map(move |&v| (s, v)))
        .collect();
    let mut simulated_runs = jobs
        .par_iter()
        .map(|&(spec, v0)| {
            let run = simulated(spec, v0, &scene.settings, sampling);
            tick();
            run
        })
        .collect::<Vec<Run>>()
        .into_iter();
    let mut runs = Vec::with_capacity(scene.systems.len() * speeds.len());
    for (spec, &served) in scene.systems.iter().zip(&served) {
        if served {
            runs.extend(interpolated(spec, scene, &tick));
        } else {
            runs.extend(simulated_runs.by_ref().take(speeds.len()));
        }
    }
    runs
}

/// For each system of `scene`, whether its speeds go through the sweep's plan (verified
/// interpolants): `[sweep] interpolate`, at least `sweep::MIN_SPEEDS` speeds, no trajectories
/// or loops, no impact sequence, and runs smooth in the speed.
pub fn sweep_served(scene: &Scene) -> Vec<bool> {
    let interpolate = scene.sweep.interpolate
        && scene.sequence.is_none()
        && !(scene.output.trajectory || scene.output.loops)
        && scene.speeds.len() >= sweep::MIN_SPEEDS;
    (scene.systems.iter())
        .map(|spec| interpolate && smooth_in_speed(spec))
        .collect()
}

/// Fewest samples of a contact a sampled trajectory is expected to have before it is called
/// too coarse.
pub const FEW_SAMPLES: usize = 20;

/// Notes for runs whose `[output].dt` samples the contact fewer than [`FEW_SAMPLES`] times
/// (`dt` is in the run's time unit: s in SI and `[base]` scenes, natural time in
/// `[nondimensional]` ones), with the `dt` that would give 100 samples.
pub fn sampling_notes(scene: &Scene, runs: &[Run]) -> Vec<String> {
    let Some(dt) = scene.output.dt else {
        return Vec::new();
    };
    if !(scene.output.trajectory || scene.output.loops) || scene.sequence.is_some() {
        return Vec::new();
    }
    runs.iter()
        .filter_map(|r| {
            let t_s = r.t_s?;
            let inside = r.trajectory.iter().filter(|s| s.t <= t_s).count();
            (inside < FEW_SAMPLES).then(|| {
                let label = match r.label().as_str() {
                    "run" => "the run".to_string(),
                    l => format!("run {l}"),
                };
                format!(
                    "{label}: [output].dt = {dt:e} {unit} samples the contact ({t_s:.3e} {unit}) \
                     {inside} times: dt is in {unit_name}; dt = {better:.1e} gives about 100 \
                     samples",
                    unit = r.time_unit,
                    unit_name = if r.time_unit == "s" {
                        "seconds in an SI or [base] scene"
                    } else {
                        "natural time in a [nondimensional] scene"
                    },
                    better = t_s / 100.0,
                )
            })
        })
        .collect()
}

/// For each system whose sweep went through the plan but found no interpolant (every speed
/// simulated, on top of the plan's trials), a note naming the system, why the plan gave up
/// and the setting that would let it interpolate (`bwc-simulate` prints these on stderr,
/// `bwc.cor` and `bwc.simulate` issue them as warnings). `runs` are [`run`]'s, in its order.
pub fn no_interpolant_notes(scene: &Scene, runs: &[Run]) -> Vec<String> {
    let n = scene.speeds.len();
    let served = sweep_served(scene);
    if n == 0 || !served.contains(&true) {
        return Vec::new();
    }
    (scene.systems.iter().zip(served.iter().zip(runs.chunks(n))))
        .filter(|(_, (&served, runs))| served && runs.iter().all(|r| r.interpolation.is_none()))
        .map(|(spec, (_, runs))| {
            let causes = [
                GaveUp::Noise,
                GaveUp::TooFewSpeeds,
                GaveUp::NotSmooth,
                GaveUp::Budget,
            ]
            .iter()
            .filter_map(|&why| gave_up_because(scene, runs, why))
            .collect::<Vec<_>>()
            .join("; ");
            format!(
                "{}: no interpolant held to [sweep].tolerance {:e}, so all {n} speeds were \
                 simulated, after up to {} trial simulations: {causes}; [sweep] interpolate = \
                 false skips the trials",
                spec.name.as_deref().unwrap_or("the sweep"),
                scene.sweep.tolerance,
                n / 4
            )
        })
        .collect()
}

/// What giving up for `why` means for the runs of one system's sweep, and the setting that
/// helps, where some of its runs were given up for it.
fn gave_up_because(scene: &Scene, runs: &[Run], why: GaveUp) -> Option<String> {
    if !runs.iter().any(|r| r.sweep_gave_up == Some(why)) {
        return None;
    }
    Some(match why {
        GaveUp::Noise => {
            // Without the stops at kinks and the series, the error in `e` is far above rtol.
            let error = if scene.settings.series {
                ""
            } else {
                " (with series = false, up to 1000 times rtol)"
            };
            format!(
                "e(v0) is smooth only to the simulations' own error{error}: a \
                 [sweep].tolerance above that error lets the sweep interpolate"
            )
        }
        GaveUp::TooFewSpeeds => format!(
            "e(v0) or t_s(v0) changes too sharply (a kink, such as where the order of the \
             impact's events changes with v0) for the pieces {} speeds pay for (at least {} \
             speeds each): more speeds let the sweep isolate the change",
            runs.len(),
            sweep::MIN_SPEEDS
        ),
        GaveUp::NotSmooth => "runs without separation split the speeds into pieces too short \
                              to interpolate"
            .to_string(),
        GaveUp::Budget => "the trials reached their budget, a quarter of the speeds".to_string(),
        other => format!("the sweep gave up interpolating ({})", other.name()),
    })
}

/// Whether a system's runs are smooth in the impact speed wherever the outcome holds: a
/// `[base]` or `[physical]` system under a constant input. A time-varying input can make
/// narrow windows of speeds end differently (a grazing contact, an input's peak), which
/// points between them could miss, so its speeds are always simulated.
fn smooth_in_speed(spec: &SystemSpec) -> bool {
    match &spec.system {
        System::Base { input, .. } | System::Physical { input, .. } => input.is_constant(),
        System::Nondimensional { .. } | System::Bodies { .. } => false,
    }
}

/// The run of `spec` at `v0`, failed or not.
fn simulated(
    spec: &SystemSpec,
    v0: Option<f64>,
    settings: &Settings,
    sampling: Option<Sampling>,
) -> Run {
    run_one(spec, v0, settings, sampling).unwrap_or_else(|e| failed(spec, v0, &e, settings))
}

/// The runs of `spec` at the scene's speeds: simulated at the points and checks of
/// [`sweep::plan`] (kept where they are speeds of the sweep) and wherever it says so,
/// interpolated elsewhere.
fn interpolated(spec: &SystemSpec, scene: &Scene, tick: &(dyn Fn() + Sync)) -> Vec<Run> {
    let settings = &scene.settings;
    let tolerance = scene.sweep.tolerance;
    // Every simulation the plan asked for, by speed: those at speeds of the sweep are its rows.
    let mut done: HashMap<u64, Run> = HashMap::new();
    let plan = sweep::plan(&scene.speeds, &SweepSettings { tolerance }, |batch| {
        let runs: Vec<Run> = batch
            .par_iter()
            .map(|&v| simulated(spec, Some(v), settings, None))
            .collect();
        let values = runs.iter().map(smooth_values).collect();
        done.extend(batch.iter().map(|v| v.to_bits()).zip(runs));
        values
    });
    scene
        .speeds
        .par_iter()
        .zip(&plan.rows)
        .map(|(&v, row)| {
            let run = match *row {
                Row::Interpolated {
                    values,
                    estimate,
                    piece,
                } => {
                    let p = &plan.pieces[piece];
                    let how = Interpolation {
                        estimate,
                        degree: p.degree,
                        from: p.from,
                        to: p.to,
                    };
                    from_interpolant(spec, v, values, how, settings)
                }
                Row::Simulate => {
                    let mut run = match done.get(&v.to_bits()) {
                        Some(r) => r.clone(),
                        None => simulated(spec, Some(v), settings, None),
                    };
                    // The innermost range holding the speed: ranges given up later lie
                    // within those given up before them.
                    run.sweep_gave_up = (plan.given_up.iter().rev())
                        .find(|g| g.from <= v && v <= g.to)
                        .map(|g| g.why);
                    run
                }
            };
            tick();
            run
        })
        .collect()
}

/// `[e, t_s]` of a separated run, the values a sweep interpolates.
fn smooth_values(r: &Run) -> Option<Values> {
    match (r.outcome, r.t_s) {
        (Outcome::Separated, Some(t_s)) if r.e.is_finite() => Some([r.e, t_s]),
        _ => None,
    }
}

/// The record of `spec` at `v0` with `[e, t_s]` from an interpolant: separated, its scales
/// computed at `v0`, its solver statistics zero.
fn from_interpolant(
    spec: &SystemSpec,
    v0: f64,
    [e, t_s]: Values,
    how: Interpolation,
    settings: &Settings,
) -> Run {
    let scaling = match scaling(spec, Some(v0)) {
        Ok(s) => s,
        Err(error) => return failed(spec, Some(v0), &error, settings),
    };
    let mut run = Run::new(spec, Some(v0), time_unit(spec));
    run.e = e;
    run.t_s = Some(t_s);
    run.t_d = (run.time_unit == "s").then_some(t_s);
    run.outcome = Outcome::Separated;
    run.t_c = scaling.t_c;
    run.nondimensional = Some(scaling.nondimensional);
    run.interpolation = Some(how);
    run
}

/// The record of a run that failed with `error`.
fn failed(spec: &SystemSpec, v0: Option<f64>, error: &ModelError, settings: &Settings) -> Run {
    let scaling = scaling(spec, v0).ok();
    let v0 = match &spec.system {
        System::Bodies { bodies, .. } => Some(bodies.impact_speed()),
        _ => v0,
    };
    let mut run = Run::new(spec, v0, time_unit(spec));
    run.error = Some(format!("{error}; {}", hint(error, settings)));
    run.t_c = scaling.as_ref().and_then(|s| s.t_c);
    run.nondimensional = scaling.map(|s| s.nondimensional);
    run
}

/// The unit of the times of a system's runs.
fn time_unit(spec: &SystemSpec) -> &'static str {
    match &spec.system {
        System::Nondimensional { .. } => "nondimensional",
        System::Base {
            time_scale_known, ..
        } if !time_scale_known => "nondimensional",
        _ => "s",
    }
}

fn run_one(
    spec: &SystemSpec,
    v0: Option<f64>,
    settings: &Settings,
    sampling: Option<Sampling>,
) -> Result<Run, ModelError> {
    let scaling = scaling(spec, v0)?;
    let record = |driven, t_scale| record(spec, v0, &scaling, driven, t_scale);
    match &spec.system {
        System::Nondimensional { params, u } => {
            let driven = drive_nd(spec.kind, params, Constant(*u), settings, sampling, 1.0)?;
            Ok(record(driven, None))
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
            let driven = drive_nd(spec.kind, &nd, u, settings, sampling, scale.unwrap_or(1.0))?;
            Ok(record(driven, scale))
        }
        System::Physical { params, m, input } => {
            let v0v = v0.unwrap_or(1.0);
            let driven = physical(spec.kind, params, *m, v0v, input, settings, sampling)?;
            Ok(record(driven, Some(1.0)))
        }
        System::Bodies { params, bodies } => {
            let (m, v0b) = (bodies.effective_mass(), bodies.impact_speed());
            let input = bodies.relative_input();
            let mut driven = physical(spec.kind, params, m, v0b, input, settings, sampling)?;
            if !driven.trajectory.is_empty() {
                let mut motion = bodies.motion()?;
                for s in &mut driven.trajectory {
                    s.bodies = Some(motion.at(s.t, s.x, s.v)?);
                }
            }
            let mut run = record(driven, Some(1.0));
            run.v0 = Some(v0b);
            Ok(run)
        }
    }
}

/// The nondimensional model of `kind` with parameters `nd` under `input`, driven
/// ([`drive`]; `t_scale`: seconds per unit of its time).
fn drive_nd<I: Input>(
    kind: ModelKind,
    nd: &NondimParams,
    input: I,
    settings: &Settings,
    sampling: Option<Sampling>,
    t_scale: f64,
) -> Result<Driven, ModelError> {
    match kind {
        ModelKind::Shccm => drive(&Ndbwshccm::new(nd, input)?, settings, sampling, t_scale),
        ModelKind::Mcm => drive(&Ndbwmcm::new(nd, input)?, settings, sampling, t_scale),
    }
}

/// The record of a driven run at `v0` of the system `spec`: its times in s where the run has a
/// time scale (`t_scale`, s per unit), in its own unit otherwise.
fn record(
    spec: &SystemSpec,
    v0: Option<f64>,
    scaling: &Scaling,
    driven: Driven,
    t_scale: Option<f64>,
) -> Run {
    let Driven {
        impact,
        trajectory,
        rest,
    } = driven;
    let scale = t_scale.unwrap_or(1.0);
    let t_s = impact.t_s.map(|t| t * scale);
    let outcome = if impact.t_s.is_some() {
        Outcome::Separated
    } else if impact.settled_at.is_some() {
        Outcome::Settled
    } else {
        Outcome::Horizon
    };
    Run {
        name: spec.name.clone(),
        model: spec.kind,
        v0,
        t_s,
        e: impact.e,
        outcome,
        error: None,
        rest: rest.map(|r| Rest {
            t: r.t * scale,
            ..r
        }),
        t_c: scaling.t_c,
        nondimensional: Some(scaling.nondimensional),
        t_d: if t_scale.is_some() { t_s } else { None },
        time_unit: time_unit(spec),
        stats: impact.stats,
        stiff_from: impact.stiff_from.map(|t| t * scale),
        series_steps: impact.series_steps,
        rtol: Some(impact.rtol),
        e_error: impact.e_error,
        t_s_error: impact.t_s_error.map(|t| t * scale),
        check: Some(impact.check),
        tighter_failed: impact.tighter_failed,
        double_double: impact.double_double,
        double_double_declined: impact.double_double_declined,
        phase: impact.phase,
        trajectory,
        bounces: Vec::new(),
        interpolation: None,
        sweep_gave_up: None,
    }
}

/// What [`drive`] returns: the impact, its samples, and where a settled contact came to rest.
struct Driven {
    impact: Cor,
    trajectory: Vec<Sample>,
    rest: Option<Rest>,
}

fn physical<I: Input>(
    kind: ModelKind,
    params: &PhysicalParams,
    m: f64,
    v0: f64,
    input: I,
    settings: &Settings,
    sampling: Option<Sampling>,
) -> Result<Driven, ModelError> {
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
) -> Result<Driven, ModelError> {
    let mut rows = Vec::new();
    let impact = match sampling {
        None => impact(model, settings)?,
        Some(sampling) => {
            let sampling = match sampling {
                Sampling::Grid { dt } => Sampling::Grid { dt: dt / t_scale },
                s => s,
            };
            sim(model, settings, sampling, |t, y| {
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
            })?
        }
    };
    let rest = impact.settled_at.map(|t| {
        let y = impact.state;
        Rest {
            t,
            x: model.displacement(&y),
            f: model.force(&y),
            u: model.input(t),
        }
    });
    Ok(Driven {
        impact: impact.cor(),
        trajectory: rows,
        rest,
    })
}
