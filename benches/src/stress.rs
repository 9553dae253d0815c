//! Stress sweep: random admissible parameter sets of both models, including the edges of the
//! admissible sets, each run classified (STABILITY.md, "The stress sweep").

use bw_models::input::{Constant, Scaled, Sine};
use bw_models::{
    impact_at, impact_double_double, BaseMap, BaseParams, Check, DdDeclined, DdFailure, FailedRun,
    Impact, ModelError, ModelKind, Ndbwmcm, Ndbwshccm, Settings,
};
use bwc_ode::Stats;
use rand::{Rng, SeedableRng};
use rayon::prelude::*;
use std::time::Instant;

/// One sampled case.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Case {
    /// The model.
    pub kind: ModelKind,
    /// Base parameters.
    pub base: BaseParams,
    /// Impact speed (m/s).
    pub v0: f64,
    /// Input `u(t) = a + b sin(w t)` (N), scaled to `U(T)` by the base map.
    pub input: (f64, f64, f64),
}

/// How a run ended.
#[derive(Debug, Clone, PartialEq)]
pub enum Class {
    /// Separated with finite `T_s` and `e`.
    Separated,
    /// Separated with `e > 1 + 1e-9` although `u = 0`: energy was created (a bug).
    EnergyCreated(f64),
    /// No separation by the horizon (`e = 0`).
    NoSeparation,
    /// The base map left the admissible set at this speed (overflow of `v0^(2n/(p+1))`).
    Inadmissible,
    /// Step size underflow.
    StepSizeTooSmall,
    /// Step limit reached (typically stiffness: large `sigma` in the MCM).
    TooManySteps,
    /// NaN or infinity in the state.
    NonFinite,
    /// Anything else (should not happen).
    Other(String),
}

impl Class {
    /// Short name.
    pub fn name(&self) -> &'static str {
        match self {
            Class::Separated => "separated",
            Class::EnergyCreated(_) => "energy created (BUG)",
            Class::NoSeparation => "no separation by the horizon",
            Class::Inadmissible => "inadmissible at this speed",
            Class::StepSizeTooSmall => "step size underflow",
            Class::TooManySteps => "too many steps",
            Class::NonFinite => "non-finite state",
            Class::Other(_) => "other failure",
        }
    }
}

/// The outcome of one case.
#[derive(Debug, Clone)]
pub struct Outcome {
    /// The case.
    pub case: Case,
    /// Its class.
    pub class: Class,
    /// Wall time (s).
    pub seconds: f64,
    /// RHS evaluations (0 when not simulated).
    pub rhs_evals: u64,
    /// Whether the run switched to RODAS4 (stiffness detected).
    pub switched: bool,
    /// Whether the Taylor-series path finished the run (`Settings::series`).
    pub series: bool,
    /// Coefficient of restitution and separation time of a run that ended without a failure.
    pub result: Option<(f64, Option<f64>)>,
    /// The run's estimate of its error in `e` (`Settings::e_tol`), if it made one.
    pub e_error: Option<f64>,
    /// What the run's check against `Settings::e_tol` found, for a run that ended.
    pub check: Option<Check>,
    /// The tighter run under `Settings::e_tol` that failed, where one did.
    pub tighter_failed: Option<FailedRun>,
    /// Whether the result is the double-double run's (`Settings::double_double`).
    pub double_double: bool,
    /// Why the double-double retry of an unmet check reported nothing, where it was due.
    pub double_double_declined: Option<DdDeclined>,
}

fn log_uniform(rng: &mut impl Rng, lo: f64, hi: f64) -> f64 {
    lo * (hi / lo).powf(rng.random::<f64>())
}

/// Case `i` of the sweep with seed `seed` (independent of any other case: parallel and
/// sequential sweeps sample the same cases).
pub fn sample(seed: u64, i: u64) -> Case {
    let mut rng = rand::rngs::StdRng::seed_from_u64(seed ^ i.wrapping_mul(0x9E37_79B9_7F4A_7C15));
    let kind = if rng.random::<bool>() {
        ModelKind::Shccm
    } else {
        ModelKind::Mcm
    };
    let edge = |rng: &mut rand::rngs::StdRng, lo: f64, hi: f64| match rng.random_range(0..10) {
        0 => lo,
        1 => hi,
        _ => lo + (hi - lo) * rng.random::<f64>(),
    };
    let n = edge(&mut rng, 1.0, 10.0);
    let p = edge(&mut rng, 1.0, 10.0);
    let b_b = if rng.random_range(0..10) == 0 {
        0.0
    } else {
        log_uniform(&mut rng, 1e-3, 1e3)
    };
    let gamma_b = match rng.random_range(0..10) {
        0 => -b_b,
        1 => b_b,
        _ => b_b * (2.0 * rng.random::<f64>() - 1.0),
    };
    let logit = 13.8 * (2.0 * rng.random::<f64>() - 1.0); // kappa in [1e-6, 1 - 1e-6]
    let kappa = (1.0 / (1.0 + (-logit).exp())).clamp(1e-6, 1.0 - 1e-6);
    let sigma_b = match (kind, rng.random_range(0..20)) {
        (ModelKind::Shccm, 0..=1) => 0.0,
        (ModelKind::Mcm, 0) => 1e-16,
        _ => log_uniform(&mut rng, 1e-6, 1e3),
    };
    let v0 = log_uniform(&mut rng, 1e-4, 1e3);
    // Input: none (half the cases), a constant push or pull, or a sign-changing one.
    let input = match rng.random_range(0..4) {
        0 | 1 => (0.0, 0.0, 0.0),
        2 => (20.0 * rng.random::<f64>() - 10.0, 0.0, 0.0),
        _ => (
            0.0,
            10.0 * rng.random::<f64>(),
            log_uniform(&mut rng, 0.1, 10.0),
        ),
    };
    Case {
        kind,
        base: BaseParams::unforced(b_b, gamma_b, kappa, sigma_b, n, p),
        v0,
        input,
    }
}

/// The sweep's settings: the defaults (CoRs checked to `e_tol` = 1e-10) with horizon 100
/// (nondimensional) and at most 200,000 steps.
pub fn settings() -> Settings {
    Settings {
        t_max: 100.0,
        max_steps: 200_000,
        ..Settings::default()
    }
}

/// The sweep's [`settings`] with the library's step limit (`Settings::default().max_steps`) in
/// place of the sweep's 200,000: what a user of the defaults gets.
pub fn library_settings() -> Settings {
    Settings {
        max_steps: Settings::default().max_steps,
        ..settings()
    }
}

/// The arguments `SEED RTOL[,RTOL...] CASE [CASE...]` of the single-case tools (`tool` names
/// the tool in the usage message, printed with exit status 2 where they do not parse).
pub fn cases_args(tool: &str) -> (u64, Vec<f64>, Vec<u64>) {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let parsed = (|| -> Option<(u64, Vec<f64>, Vec<u64>)> {
        let seed = args.first()?.parse().ok()?;
        let rtols = args.get(1)?.split(',').map(|r| r.parse().ok());
        let cases = args.get(2..)?.iter().map(|c| c.parse().ok());
        Some((
            seed,
            rtols.collect::<Option<_>>()?,
            cases.collect::<Option<_>>()?,
        ))
    })();
    match parsed.filter(|(_, r, c)| !r.is_empty() && !c.is_empty()) {
        Some(parsed) => parsed,
        None => {
            eprintln!("usage: {tool} SEED RTOL[,RTOL...] CASE [CASE...] (SEED, CASE integers)");
            std::process::exit(2);
        }
    }
}

/// Runs one case with the sweep's [`settings`].
pub fn run(case: &Case) -> Outcome {
    run_with(case, &settings())
}

/// The case's input `u(t) = a + b sin(w t)` divided by `factor`, the base map's `U_factor` at
/// the case's speed: a nondimensional input of magnitude `|U| <= 10` at every speed.
pub fn input(case: &Case, factor: f64) -> Sine {
    let (a, b, w) = case.input;
    Sine {
        a: a / factor,
        b: b / factor,
        omega: w,
    }
}

/// `(e, T_s, statistics)` of the case by the library's double-double path at `rtol`
/// ([`impact_double_double`], `settings` for its limits), `None` where the case is
/// inadmissible or its model has no such path.
pub fn double_double_reference(
    case: &Case,
    rtol: f64,
    settings: &Settings,
) -> Option<Result<(f64, f64, Stats), DdFailure>> {
    let map = BaseMap::new(case.kind, case.base).ok()?;
    let (nd, scales) = map.at(case.v0).ok()?;
    // The sweep's input as `impact_at` scales it.
    let u = Scaled {
        inner: input(case, scales.factor),
        factor: scales.factor,
        time_scale: scales.time_scale,
    };
    fn parts<const N: usize>(i: Impact<N>) -> (f64, f64, Stats) {
        (i.e, i.t_s.unwrap_or(f64::NAN), i.stats)
    }
    Some(match case.kind {
        ModelKind::Shccm => {
            impact_double_double(&Ndbwshccm::new(&nd, u).ok()?, rtol, settings)?.map(parts)
        }
        ModelKind::Mcm => {
            impact_double_double(&Ndbwmcm::new(&nd, u).ok()?, rtol, settings)?.map(parts)
        }
    })
}

/// Runs one case with `settings`.
pub fn run_with(case: &Case, settings: &Settings) -> Outcome {
    let clock = Instant::now();
    let (a, b, _) = case.input;
    let unforced = a == 0.0 && b == 0.0;
    let (mut switched, mut series) = (false, false);
    let mut result = None;
    let mut e_error = None;
    let mut check = None;
    let mut tighter_failed = None;
    let mut double_double = false;
    let mut double_double_declined = None;
    let (class, evals) = match BaseMap::new(case.kind, case.base)
        .and_then(|map| {
            let (_, s) = map.at(case.v0)?;
            if b == 0.0 {
                impact_at(&map, Constant(a / s.factor), case.v0, settings)
            } else {
                impact_at(&map, input(case, s.factor), case.v0, settings)
            }
        })
        .inspect(|out| {
            switched = out.stiff_from.is_some();
            series = out.series_steps > 0;
            result = Some((out.e, out.t_s));
            e_error = out.e_error;
            check = Some(out.check);
            tighter_failed = out.tighter_failed;
            double_double = out.double_double;
            double_double_declined = out.double_double_declined;
        }) {
        Ok(out) if out.separated() && out.e.is_finite() && out.e >= 0.0 => {
            if unforced && out.e > 1.0 + 1e-9 {
                (Class::EnergyCreated(out.e), out.stats.rhs_evals)
            } else {
                (Class::Separated, out.stats.rhs_evals)
            }
        }
        Ok(out) if !out.separated() => (Class::NoSeparation, out.stats.rhs_evals),
        Ok(out) => (
            Class::Other(format!("non-finite e = {}", out.e)),
            out.stats.rhs_evals,
        ),
        Err(ModelError::InvalidParameter { .. }) => (Class::Inadmissible, 0),
        Err(ModelError::Solver(bwc_events::Error::Solver(e))) => (
            match e {
                bwc_ode::Error::StepSizeTooSmall { .. } => Class::StepSizeTooSmall,
                bwc_ode::Error::TooManySteps { .. } => Class::TooManySteps,
                bwc_ode::Error::NonFiniteState { .. }
                | bwc_ode::Error::NonFiniteInitialValue { .. } => Class::NonFinite,
                other => Class::Other(other.to_string()),
            },
            0,
        ),
        Err(other) => (Class::Other(other.to_string()), 0),
    };
    Outcome {
        case: *case,
        class,
        seconds: clock.elapsed().as_secs_f64(),
        rhs_evals: evals,
        switched,
        series,
        result,
        e_error,
        check,
        tighter_failed,
        double_double,
        double_double_declined,
    }
}

/// Runs cases `0..count` of seed `seed` in parallel (results in case order).
pub fn sweep(seed: u64, count: u64) -> Vec<Outcome> {
    sweep_with(seed, count, &settings())
}

/// As [`sweep`], with `settings`.
pub fn sweep_with(seed: u64, count: u64, settings: &Settings) -> Vec<Outcome> {
    (0..count)
        .into_par_iter()
        .map(|i| run_with(&sample(seed, i), settings))
        .collect()
}
