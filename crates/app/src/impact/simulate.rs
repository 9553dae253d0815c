//! Runs the impacts of a scene: one per system and speed, in parallel, in a fixed order.

use crate::impact::runs::{hint, scaling, Interpolation, Outcome, Rest, Run, Sample, Scaling};
use crate::impact::scene::{Scene, System, SystemSpec};
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
    let mut runs = Vec::with_capacity(scene.systems.len() * scene.speeds.len().max(1));
    let kept: Result<(), std::convert::Infallible> = stream(scene, progress, |chunk| {
        runs.extend(chunk);
        Ok(())
    });
    kept.unwrap_or_else(|never| match never {});
    runs
}

/// The most runs [`stream`] hands over at once: a few megabytes of records, enough to keep
/// every core busy.
pub const CHUNK: usize = 8192;

/// [`run`], handing the runs to `sink` in order, at most [`CHUNK`] at a time, as they are
/// computed: a study of any size holds one chunk of records (a sampled trajectory, where the
/// scene asks for one, is part of its run's record). Stops at the first error of `sink`.
///
/// # Errors
/// The first error `sink` returns.
pub fn stream<E>(
    scene: &Scene,
    progress: Option<&(dyn Fn() + Sync)>,
    mut sink: impl FnMut(Vec<Run>) -> Result<(), E>,
) -> Result<(), E> {
    if let Some(seq) = &scene.sequence {
        let runs = (scene.systems.iter())
            .map(|s| crate::impact::sequence::run(s, seq, &scene.settings))
            .collect();
        return sink(runs);
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
    // Runs per system: one per speed, or one without a speed.
    let per_system = scene.speeds.len().max(1);
    let served = sweep_served(scene);
    let mut first = 0;
    while first < scene.systems.len() {
        if served[first] {
            interpolated(&scene.systems[first], scene, &tick, &mut sink)?;
            first += 1;
            continue;
        }
        // A stretch of systems simulated at every speed, chunked as one list of jobs (a scene
        // of many systems with a speed each keeps its parallelism).
        let end = (first..scene.systems.len())
            .find(|&i| served[i])
            .unwrap_or(scene.systems.len());
        let systems = &scene.systems[first..end];
        let jobs = systems.len() * per_system;
        for start in (0..jobs).step_by(CHUNK) {
            let chunk = (start..jobs.min(start + CHUNK))
                .into_par_iter()
                .map(|k| {
                    let spec = &systems[k / per_system];
                    let v0 = scene.speeds.get(k % per_system).copied();
                    let run = simulated(spec, v0, &scene.settings, sampling);
                    tick();
                    run
                })
                .collect();
            sink(chunk)?;
        }
        first = end;
    }
    Ok(())
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

/// What a scene's runs add up to, gathered as they come (chunk by chunk from [`stream`], in its
/// order): what the notes and warnings after a study say.
#[derive(Debug, Clone, Default)]
pub struct Tally {
    /// Runs seen.
    pub runs: usize,
    /// Failed runs.
    pub failed: usize,
    /// Runs whose `e` and `t_s` came from an interpolant.
    pub interpolated: usize,
    /// The largest error estimate of an interpolated run (0 without one).
    pub largest_estimate: f64,
    /// The unit of `t_s` of the first run and whether every run shares it.
    time_unit: Option<(&'static str, bool)>,
    /// Per system: whether some run was interpolated, and which reasons for giving up its runs
    /// carry.
    systems: Vec<(bool, Vec<GaveUp>)>,
}

impl Tally {
    /// The tally of `runs`, all of a scene's runs in [`run`]'s order.
    pub fn of(scene: &Scene, runs: &[Run]) -> Self {
        let mut tally = Tally::default();
        tally.add(scene, runs);
        tally
    }

    /// Adds the next runs of `scene`, in [`stream`]'s order.
    pub fn add(&mut self, scene: &Scene, runs: &[Run]) {
        let per_system = (scene.run_count() / scene.systems.len().max(1)).max(1);
        self.systems
            .resize(scene.systems.len(), (false, Vec::new()));
        for r in runs {
            let (interpolated, gave_up) = &mut self.systems[self.runs / per_system];
            self.runs += 1;
            self.failed += usize::from(r.outcome == Outcome::Failed);
            if let Some(i) = r.interpolation {
                *interpolated = true;
                self.interpolated += 1;
                self.largest_estimate = self.largest_estimate.max(i.estimate);
            }
            if let Some(why) = r.sweep_gave_up.filter(|w| !gave_up.contains(w)) {
                gave_up.push(why);
            }
            self.time_unit = match self.time_unit {
                None => Some((r.time_unit, true)),
                Some((u, same)) => Some((u, same && u == r.time_unit)),
            };
        }
    }

    /// The unit of `t_s` of every run, for the `units` of a summary: `None` without runs.
    pub fn time_unit(&self) -> Option<&'static str> {
        self.time_unit.map(|(u, same)| {
            if same {
                u
            } else {
                "s or nondimensional (each run's time_unit)"
            }
        })
    }

    /// For each system whose sweep went through the plan but found no interpolant (every speed
    /// simulated, on top of the plan's trials), a note naming the system, why the plan gave up
    /// and the setting that would let it interpolate (`bwc-simulate` prints these on stderr,
    /// `bwc.cor` and `bwc.simulate` issue them as warnings).
    pub fn no_interpolant_notes(&self, scene: &Scene) -> Vec<String> {
        let n = scene.speeds.len();
        let served = sweep_served(scene);
        if n == 0 || !served.contains(&true) {
            return Vec::new();
        }
        (scene.systems.iter().zip(served.iter().zip(&self.systems)))
            .filter(|(_, (&served, (interpolated, _)))| served && !interpolated)
            .map(|(spec, (_, (_, gave_up)))| {
                let causes = [
                    GaveUp::Noise,
                    GaveUp::TooFewSpeeds,
                    GaveUp::NotSmooth,
                    GaveUp::Budget,
                ]
                .into_iter()
                .filter(|why| gave_up.contains(why))
                .map(|why| gave_up_because(scene, n, why))
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
}

/// What giving up for `why` means for a sweep of `speeds` speeds, and the setting that helps.
fn gave_up_because(scene: &Scene, speeds: usize, why: GaveUp) -> String {
    match why {
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
             impact's events changes with v0) for the pieces {speeds} speeds pay for (at least {} \
             speeds each): more speeds let the sweep isolate the change",
            sweep::MIN_SPEEDS
        ),
        GaveUp::NotSmooth => "runs without separation split the speeds into pieces too short \
                              to interpolate"
            .to_string(),
        GaveUp::Budget => "the trials reached their budget, a quarter of the speeds".to_string(),
        other => format!("the sweep gave up interpolating ({})", other.name()),
    }
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

/// The runs of `spec` at the scene's speeds, handed to `sink` a [`CHUNK`] at a time: simulated
/// at the points and checks of [`sweep::plan_lazily`] (kept where they are speeds of the sweep) and
/// wherever it says so, interpolated elsewhere.
fn interpolated<E>(
    spec: &SystemSpec,
    scene: &Scene,
    tick: &(dyn Fn() + Sync),
    sink: &mut impl FnMut(Vec<Run>) -> Result<(), E>,
) -> Result<(), E> {
    let settings = &scene.settings;
    let tolerance = scene.sweep.tolerance;
    // Every simulation the plan asked for, by speed: those at speeds of the sweep are its rows.
    let mut done: HashMap<u64, Run> = HashMap::new();
    let plan = sweep::plan_lazily(&scene.speeds, &SweepSettings { tolerance }, |batch| {
        let runs: Vec<Run> = batch
            .par_iter()
            .map(|&v| simulated(spec, Some(v), settings, None))
            .collect();
        let values = runs.iter().map(smooth_values).collect();
        done.extend(batch.iter().map(|v| v.to_bits()).zip(runs));
        values
    });
    for speeds in scene.speeds.chunks(CHUNK) {
        let chunk = (speeds.par_iter())
            .map(|&v| {
                let run = match plan.row(v) {
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
            .collect();
        sink(chunk)?;
    }
    Ok(())
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
        solver: Some(impact.in_time_unit(scale)),
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
