//! What a run of a scene gives: one simulated impact ([`Run`]) with its outcome, samples,
//! bounces and provenance, and the setting that would help one that failed.

use crate::impact::scene::{System, SystemSpec};
use bw_models::sequence::Bounce;
use bw_models::sweep::GaveUp;
use bw_models::{
    nondimensionalize, BodyMotion, Cor, ModelError, ModelKind, Nondim, PhysicalParams, Settings,
};

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
    /// Coefficient of restitution (0 without separation, NaN for a failed run).
    pub e: f64,
    /// How the run ended.
    pub outcome: Outcome,
    /// For a failed run: what went wrong and which setting would help.
    pub error: Option<String>,
    /// For a settled contact: where it came to rest.
    pub rest: Option<Rest>,
    /// The time scale `T_c` (s) of the run, for `[physical]`, `[bodies]` and `[base]` scenes
    /// with `T_b`: solver times (`t_max`, `max_step`) are multiples of it.
    pub t_c: Option<f64>,
    /// The nondimensional parameters the run integrated (Table 1 or the base map at `v0`).
    pub nondimensional: Option<Nondim>,
    /// Contact duration in seconds, where a time scale exists.
    pub t_d: Option<f64>,
    /// Unit of `t_s` and of the trajectory's `t`: `"s"` or `"nondimensional"`.
    pub time_unit: &'static str,
    /// How the impact was computed: the CoR evaluation's outcome (statistics, tolerance, the
    /// check under `e_tol` and its error estimates, the path that served it), its times in
    /// the unit of `t_s`; `None` where nothing was simulated (a failed run, an interpolated
    /// row, a sequence, whose contacts are in `bounces`).
    pub solver: Option<Cor>,
    /// Sampled trajectory (only when an output asks for it).
    pub trajectory: Vec<Sample>,
    /// The contacts of a `[sequence]` scene with the displacement (m) at each separation.
    pub bounces: Vec<Bounced>,
    /// For a run of a sweep served by an interpolant (`[sweep] interpolate`): which one; its
    /// solver statistics are then zero. `None` for a simulated run.
    pub interpolation: Option<Interpolation>,
    /// For a simulated run of a sweep that went through the plan: why the plan gave up
    /// interpolating at its speed, where it tried (`bw_models::sweep::GivenUp`).
    pub sweep_gave_up: Option<GaveUp>,
}

/// The interpolant a run's `e` and `t_s` came from (`bw_models::sweep`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Interpolation {
    /// Error estimate: absolute in `e`, relative to the piece's largest `|t_s|` in `t_s`.
    pub estimate: f64,
    /// Degree of the Chebyshev interpolant in `ln v0`.
    pub degree: usize,
    /// The speeds (m/s) its piece spans.
    pub from: f64,
    /// See `from`.
    pub to: f64,
}

/// How a run ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Outcome {
    /// The bodies separated: `t_s = inf{t : F <= 0 <= v}` was reached.
    Separated,
    /// The contact came to rest with the force balancing a constant input: it never ends.
    Settled,
    /// The horizon `[solver].t_max` came first: no separation by then.
    Horizon,
    /// The simulation failed (see [`Run::error`]).
    Failed,
}

impl Outcome {
    /// The name used in tables and JSON: `"separated"`, `"settled"`, `"horizon"`, `"failed"`.
    pub fn name(self) -> &'static str {
        match self {
            Outcome::Separated => "separated",
            Outcome::Settled => "settled",
            Outcome::Horizon => "horizon",
            Outcome::Failed => "failed",
        }
    }
}

/// Where a settled contact came to rest, in the run's units: at rest, `F + u = 0`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rest {
    /// When it was found at rest.
    pub t: f64,
    /// Relative displacement there.
    pub x: f64,
    /// Contact force there.
    pub f: f64,
    /// Input there.
    pub u: f64,
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
    /// A run of `spec` at `v0` that has not happened yet: outcome failed, no results.
    pub fn new(spec: &SystemSpec, v0: Option<f64>, time_unit: &'static str) -> Self {
        Run {
            name: spec.name.clone(),
            model: spec.kind,
            v0,
            t_s: None,
            e: f64::NAN,
            outcome: Outcome::Failed,
            error: None,
            rest: None,
            t_c: None,
            nondimensional: None,
            t_d: None,
            time_unit,
            solver: None,
            trajectory: Vec::new(),
            bounces: Vec::new(),
            interpolation: None,
            sweep_gave_up: None,
        }
    }

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

/// A bounce and the displacement (m) at its separation.
pub type Bounced = (Bounce, f64);

/// The setting that would help a run that failed with `error`.
pub fn hint(error: &ModelError, settings: &Settings) -> String {
    use bwc_ode::Error as Ode;
    let solver = match error {
        ModelError::Solver(bwc_events::Error::Solver(e)) => Some(e),
        _ => None,
    };
    match solver {
        Some(Ode::TooManySteps { max_steps, .. }) => format!(
            "raise [solver].max_steps (now {max_steps}), or loosen [solver].rtol (now {:e}); \
             a stiff contact is cheaper with switch_when_stiff = true or method = \"rosenbrock\"",
            settings.rtol
        ),
        Some(Ode::StepSizeTooSmall { .. }) => format!(
            "the step size collapsed: loosen [solver].rtol (now {:e}) and atol (now {:e}), or \
             use method = \"rosenbrock\" for a stiff contact",
            settings.rtol, settings.atol
        ),
        Some(Ode::NonFiniteState { .. }) => {
            "the state overflowed: check the parameters and the impact speed".into()
        }
        _ => "check the scene's parameters and [solver] settings".into(),
    }
}

/// What the scales of a run give its record: `T_c` (s) where known and the nondimensional
/// parameters integrated.
pub struct Scaling {
    /// `T_c` in s, where the run has a time scale.
    pub t_c: Option<f64>,
    /// The nondimensional parameters integrated.
    pub nondimensional: Nondim,
}

/// `T_c` (where the run has a time scale in s) and the nondimensional parameters of a run:
/// Table 1 for SI systems, the base map at `v0` for `[base]`.
///
/// # Errors
/// As [`nondimensionalize`] and [`bw_models::BaseMap::at`].
pub fn scaling(spec: &SystemSpec, v0: Option<f64>) -> Result<Scaling, ModelError> {
    let v0 = v0.unwrap_or(1.0);
    let table_1 = |params: &PhysicalParams, m: f64, v0: f64| {
        let (nd, scales) = nondimensionalize(params, m, v0)?;
        Ok(Scaling {
            t_c: Some(scales.t_c),
            nondimensional: *nd.get(),
        })
    };
    match &spec.system {
        System::Nondimensional { params, .. } => Ok(Scaling {
            t_c: None,
            nondimensional: *params.get(),
        }),
        System::Base {
            map,
            time_scale_known,
            ..
        } => Ok(Scaling {
            t_c: time_scale_known.then(|| map.time_scale(v0)),
            nondimensional: *map.at(v0)?.0.get(),
        }),
        System::Physical { params, m, .. } => table_1(params, *m, v0),
        System::Bodies { params, bodies } => {
            table_1(params, bodies.effective_mass(), bodies.impact_speed())
        }
    }
}
