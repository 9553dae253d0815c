//! `[chain]` scenes: bodies on a line with a contact law per neighbouring pair
//! ([`bw_models::chain`]), their run, and its outputs: the summary (final velocities, every
//! contact, the energy ledger), `chain.csv` (bodies and pairs over time), `contacts.csv`, the
//! space-time figure of the bodies and the ledger figure.
//!
//! ```
//! use bwc_app::chain::ChainScene;
//! let scene = ChainScene::parse(std::path::Path::new("pair.toml"), r#"
//!     model = "shccm"
//!     [chain]
//!     mass = [0.1, 0.1]
//!     position = [0.0, 0.03]
//!     length = 0.02
//!     velocity = [1.0, 0.0]
//!     horizon = 0.1
//!     [physical]
//!     k = 1.0e7
//!     c = 0.0
//!     n = 1.0
//!     p = 1.5
//!     alpha = 0.5
//!     beta = 0.0
//!     gamma = 0.0
//!     A = 1.0
//! "#)?;
//! let out = bwc_app::chain::run(&scene)?;
//! // Equal masses and an elastic Hertz law (beta = gamma = 0, A = 1): the velocities are
//! // exchanged.
//! assert!((out.run.bodies[1].velocity - 1.0).abs() < 1e-8);
//! # Ok::<(), bwc_app::AppError>(())
//! ```

mod figures;
mod laws;
mod scene;

pub use scene::{is_chain, ChainScene};

use crate::AppError;
use bw_models::chain::{Chain, ChainRun, Ledger};
use serde_json::{json, Value};
use std::path::Path;

/// One row of `chain.csv`: the chain at a sampling instant.
#[derive(Debug, Clone, PartialEq)]
pub struct ChainSample {
    /// Time (s).
    pub t: f64,
    /// Positions of the centres (m).
    pub positions: Vec<f64>,
    /// Velocities (m/s).
    pub velocities: Vec<f64>,
    /// Gaps (m).
    pub gaps: Vec<f64>,
    /// Forces (N).
    pub forces: Vec<f64>,
    /// The ledger.
    pub ledger: Ledger,
}

/// A chain scene's result.
#[derive(Debug, Clone, PartialEq)]
pub struct ChainOutcome {
    /// The run.
    pub run: ChainRun,
    /// The samples every `[output].dt` (empty without it).
    pub samples: Vec<ChainSample>,
}

/// Runs a chain scene.
///
/// # Errors
/// [`AppError::Simulation`] if the integration fails, with the library's reason.
pub fn run(scene: &ChainScene) -> Result<ChainOutcome, AppError> {
    let fail = |source| AppError::Simulation {
        path: scene.path.clone(),
        run: "chain".into(),
        source,
    };
    let chain = Chain::new(
        scene.bodies.clone(),
        scene.laws.clone(),
        scene.walls,
        scene.settings,
    )
    .map_err(fail)?;
    let mut samples = Vec::new();
    let run = chain
        .run(scene.stop, scene.dt, |s| {
            samples.push(ChainSample {
                t: s.t,
                positions: s.positions.to_vec(),
                velocities: s.velocities.to_vec(),
                gaps: s.gaps.to_vec(),
                forces: s.forces.to_vec(),
                ledger: s.ledger,
            })
        })
        .map_err(fail)?;
    Ok(ChainOutcome { run, samples })
}

/// Runs many chain scenes (a parameter study) in parallel on the current rayon pool, each
/// alone: the outcomes in the order of `scenes`, identical on any number of threads (a run has
/// no randomness and does not depend on the others).
pub fn run_many(scenes: &[ChainScene]) -> Vec<Result<ChainOutcome, AppError>> {
    use rayon::prelude::*;
    scenes.par_iter().map(run).collect()
}

fn ledger_json(l: &Ledger) -> Value {
    json!({
        "kinetic_J": l.kinetic,
        "stored_J": l.stored,
        "dissipated_J": l.dissipated,
        "work_J": l.work,
        "initial_J": l.initial,
        "imbalance_J": l.imbalance(),
    })
}

/// The summary of a chain's run: how it ended, the bodies, every contact and the ledger (SI
/// units, in the key names).
pub fn summary(scene: &ChainScene, out: &ChainOutcome) -> Value {
    let r = &out.run;
    let bodies: Vec<Value> = scene
        .bodies
        .iter()
        .zip(&r.bodies)
        .enumerate()
        .map(|(i, (b, f))| {
            json!({
                "body": scene.body_number(i),
                "mass_kg": b.mass,
                "velocity_0_m_s": b.velocity,
                "velocity_m_s": f.velocity,
                "position_0_m": b.position,
                "position_m": f.position,
            })
        })
        .collect();
    let contacts: Vec<Value> = r
        .contacts
        .iter()
        .map(|c| {
            json!({
                "pair": c.pair,
                "onset_s": c.onset,
                "separation_s": c.separation,
                "onset_velocity_m_s": c.onset_velocity,
                "separation_velocity_m_s": c.separation_velocity,
                "rebound": c.rebound(),
                "rebound_note": rebound_note(c),
                "began_at_rest": c.began_at_rest,
                "dissipated_J": c.dissipated,
                "peak_force_N": c.peak_force,
                "peak_at_s": c.peak_at,
            })
        })
        .collect();
    let momentum: f64 = scene
        .bodies
        .iter()
        .zip(&r.bodies)
        .map(|(b, f)| b.mass * f.velocity)
        .sum();
    json!({
        "chain": {
            "outcome": if r.settled { "settled" } else { "horizon" },
            "t_end_s": r.t_end,
            "horizon_s": scene.stop.horizon,
            "policy": format!("{:?}", scene.settings.policy).to_lowercase(),
            "walls": { "left_m": scene.walls.left, "right_m": scene.walls.right },
            "models": scene.models,
            "bodies": bodies,
            "momentum_kg_m_s": momentum,
            "contacts": contacts,
            "ledger": ledger_json(&r.ledger),
            "steps": r.stats.accepted,
            "rhs_evaluations": r.stats.rhs_evals,
            "events": r.stats.events,
        },
        "units": units(),
        "scene": describe(scene),
    })
}

/// Why a contact has no rebound ratio (`None` where it has one).
fn rebound_note(c: &bw_models::chain::ContactRecord) -> Option<&'static str> {
    if c.rebound().is_some() {
        None
    } else if c.separation.is_none() {
        Some("the run ended during the contact")
    } else if c.began_at_rest {
        Some("the contact began at rest (touching, no approach speed): no rebound ratio")
    } else {
        Some("no approach speed at the onset")
    }
}

/// What a chain was run with: the bodies and walls, each pair's model, the tolerances, the
/// policy and scheme, when the run ends, gravity and the sampling.
fn describe(scene: &ChainScene) -> Value {
    json!({
        "path": scene.path.display().to_string(),
        "bodies": scene.bodies.len(),
        "pairs": scene.laws.len(),
        "walls": { "left_m": scene.walls.left, "right_m": scene.walls.right },
        "models": scene.models,
        "solver": {
            "method": "dop853",
            "rtol": scene.settings.rtol,
            "atol_m": scene.settings.atol,
        },
        "policy": format!("{:?}", scene.settings.policy).to_lowercase(),
        "scheme": format!("{:?}", scene.settings.scheme).to_lowercase(),
        "horizon_s": scene.stop.horizon,
        "until": if scene.stop.settled { "settled" } else { "horizon" },
        "g_m_s2": scene.g,
        "dt_s": scene.dt,
        "plots": scene.plots,
    })
}

/// The unit of every key of a chain's summary and every column of its CSV files (the keys
/// carry their units in their names too; `"1"`: dimensionless).
pub fn units() -> Value {
    json!({
        "chain": {
            "t_end_s": "s", "horizon_s": "s", "momentum_kg_m_s": "kg m/s",
            "walls": {"left_m": "m", "right_m": "m"},
            "bodies": {"body": "index", "mass_kg": "kg", "velocity_0_m_s": "m/s",
                "velocity_m_s": "m/s", "position_0_m": "m", "position_m": "m"},
            "contacts": {"pair": "index", "onset_s": "s", "separation_s": "s",
                "onset_velocity_m_s": "m/s", "separation_velocity_m_s": "m/s", "rebound": "1",
                "rebound_note": "text", "began_at_rest": "true or false",
                "dissipated_J": "J", "peak_force_N": "N", "peak_at_s": "s"},
            "ledger": {"kinetic_J": "J", "stored_J": "J", "dissipated_J": "J", "work_J": "J",
                "initial_J": "J", "imbalance_J": "J"},
            "steps": "count", "rhs_evaluations": "count", "events": "count",
        },
        "scene": {"solver": {"rtol": "1", "atol_m": "m"}, "horizon_s": "s", "g_m_s2": "m/s^2",
            "dt_s": "s", "walls": {"left_m": "m", "right_m": "m"}},
        "contacts.csv": {"pair": "index", "onset_s": "s", "separation_s": "s",
            "onset_velocity_m_s": "m/s", "separation_velocity_m_s": "m/s", "rebound": "1",
            "dissipated_J": "J", "peak_force_N": "N", "peak_at_s": "s",
            "began_at_rest": "true or false"},
        "chain.csv": {"t_s": "s", "x_<i>_m": "m", "v_<i>_m_s": "m/s", "gap_<j>_m": "m",
            "F_<j>_N": "N", "kinetic_J": "J", "stored_J": "J", "dissipated_J": "J", "work_J": "J"},
    })
}

/// The files of a chain's run: `chain.csv` (with `[output].dt`), `contacts.csv`, and the
/// figures (with `[output].plots`).
///
/// # Errors
/// [`AppError::Csv`] or [`AppError::Plot`] naming the file.
pub fn render(
    scene: &ChainScene,
    out: &ChainOutcome,
    dir: &Path,
) -> Result<Vec<(String, Vec<u8>)>, AppError> {
    let csv_err = |name: &str| {
        let path = dir.join(name);
        move |source: csv::Error| AppError::Csv {
            path: path.clone(),
            source,
        }
    };
    let mut files = vec![(
        "contacts.csv".to_string(),
        contacts_csv(&out.run).map_err(csv_err("contacts.csv"))?,
    )];
    if scene.dt.is_some() {
        files.push((
            "chain.csv".into(),
            chain_csv(scene, out).map_err(csv_err("chain.csv"))?,
        ));
    }
    if scene.plots {
        for (name, figure) in figures::all(scene, out) {
            let svg = figure.map_err(|message| AppError::Plot {
                path: dir.join(&name),
                message,
            })?;
            files.push((name, svg.into_bytes()));
        }
    }
    Ok(files)
}

fn contacts_csv(run: &ChainRun) -> Result<Vec<u8>, csv::Error> {
    let mut w = csv::Writer::from_writer(Vec::new());
    w.write_record([
        "pair",
        "onset_s",
        "separation_s",
        "onset_velocity_m_s",
        "separation_velocity_m_s",
        "rebound",
        "dissipated_J",
        "peak_force_N",
        "peak_at_s",
        "began_at_rest",
    ])?;
    let opt = |v: Option<f64>| v.map_or(String::new(), |v| format!("{v:e}"));
    for c in &run.contacts {
        w.write_record([
            c.pair.to_string(),
            format!("{:e}", c.onset),
            opt(c.separation),
            format!("{:e}", c.onset_velocity),
            opt(c.separation_velocity),
            opt(c.rebound()),
            format!("{:e}", c.dissipated),
            format!("{:e}", c.peak_force),
            format!("{:e}", c.peak_at),
            c.began_at_rest.to_string(),
        ])?;
    }
    Ok(w.into_inner().expect("in-memory writer"))
}

fn chain_csv(scene: &ChainScene, out: &ChainOutcome) -> Result<Vec<u8>, csv::Error> {
    let mut w = csv::Writer::from_writer(Vec::new());
    let Some(first) = out.samples.first() else {
        w.write_record(["t_s"])?;
        return Ok(w.into_inner().expect("in-memory writer"));
    };
    let (n, p) = (first.positions.len(), first.gaps.len());
    let mut header = vec!["t_s".to_string()];
    let number = |i| scene.body_number(i);
    header.extend((0..n).map(|i| format!("x_{}_m", number(i))));
    header.extend((0..n).map(|i| format!("v_{}_m_s", number(i))));
    header.extend((0..p).map(|j| format!("gap_{j}_m")));
    header.extend((0..p).map(|j| format!("F_{j}_N")));
    header.extend(["kinetic_J", "stored_J", "dissipated_J", "work_J"].map(String::from));
    w.write_record(&header)?;
    let mut row: Vec<String> = Vec::with_capacity(header.len());
    for s in &out.samples {
        row.clear();
        row.push(format!("{:e}", s.t));
        for v in s
            .positions
            .iter()
            .chain(&s.velocities)
            .chain(&s.gaps)
            .chain(&s.forces)
        {
            row.push(format!("{v:e}"));
        }
        let l = &s.ledger;
        for v in [l.kinetic, l.stored, l.dissipated, l.work] {
            row.push(format!("{v:e}"));
        }
        w.write_record(&row)?;
    }
    Ok(w.into_inner().expect("in-memory writer"))
}
