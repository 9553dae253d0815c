//! # bwc-py: bwc from Python
//!
//! The native part of the Python package `bwc` (module `bwc._native`): CoR sweeps returned as
//! numpy arrays, scenes and identification configs run exactly as `bwc-simulate` and
//! `bwc-identify` run them (the same parsing, the same messages, the same JSON), with the GIL
//! released while Rust works in parallel. Descriptions arrive as JSON text of a scene or
//! config (the Python side builds it from dicts) and are parsed as the TOML files would be.
//!
//! Errors reach Python once, as `bwc.BwcError` (a `ValueError`) with the CLI's message.
//!
//! Used from Python (`maturin build` in this folder, then `pip install` the wheel; the
//! package's doctest runs this):
//!
//! ```text
//! >>> import bwc
//! >>> out = bwc.cor("shccm", {"B": 0, "Gamma": 0, "kappa": 0.5, "sigma": 0.5, "n": 1, "p": 1.5})
//! >>> round(float(out["e"][0]), 12)   # Hunt-Crossley closed form: 0.748434931597
//! 0.748434931597
//! ```
#![deny(missing_docs)]

mod checkpoint;
mod contact;
mod contacts;
mod dict_errors;

use bwc_app::chain::ChainScene;
use bwc_app::fit::config::Config;
use bwc_app::impact::runs::{Outcome, Run};
use bwc_app::impact::scene::Scene;
use bwc_app::impact::simulate;
use bwc_app::AppError;
use dict_errors::Root;
use numpy::{IntoPyArray, PyArray1};
use pyo3::create_exception;
use pyo3::exceptions::{PyUserWarning, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::{Path, PathBuf};

// Their module is the package's, where users import them from: so they print as
// `bwc.BwcError` and pickle (Dask workers and pytest-xdist carry them between processes).
create_exception!(
    bwc,
    BwcError,
    PyValueError,
    "A bad description or a failed run."
);

create_exception!(
    bwc,
    BwcWarning,
    PyUserWarning,
    "What the command-line tools warn of on stderr about finished runs: a horizon before \
     separation, a CoR that did not meet e_tol, a sweep that found no interpolant."
);

/// Issues what `bwc-simulate` warns of on stderr as `BwcWarning`s, attributed to the caller of
/// the package's Python function (`stacklevel` 2: the native call has no frame of its own):
/// a sweep that found no interpolant, and, one warning a kind for all runs (a sweep may have
/// thousands), runs that met the horizon and CoRs whose check against `e_tol` was not met.
fn warn_notes(py: Python<'_>, scene: &Scene, runs: &[bwc_app::impact::runs::Run]) -> PyResult<()> {
    let notes = bwc_app::impact::notes::kind_notes(scene, runs);
    let category = py.get_type::<BwcWarning>();
    for note in notes {
        // A dict's scene has no file to name.
        let note = note
            .strip_prefix("<scene>: ")
            .map_or(note.clone(), str::to_string);
        let text = std::ffi::CString::new(note).map_err(|e| BwcError::new_err(e.to_string()))?;
        PyErr::warn(py, &category, &text, 2)?;
    }
    Ok(())
}

/// The CLI's error as a `BwcError` (several mistakes one per line, as the CLI prints them).
fn error(e: AppError) -> PyErr {
    let text = match &e {
        AppError::Many(all) => all
            .iter()
            .map(ToString::to_string)
            .collect::<Vec<_>>()
            .join("\n"),
        _ => e.to_string(),
    };
    BwcError::new_err(text)
}

/// A JSON object (text) as the TOML text a file would hold.
fn toml_text(json: &str, what: &str) -> PyResult<String> {
    let value: serde_json::Value = serde_json::from_str(json)
        .map_err(|e| BwcError::new_err(format!("{what}: not a JSON-like dict: {e}")))?;
    toml::to_string(&value).map_err(|e| BwcError::new_err(format!("{what}: {e}")))
}

/// A scene from a path or from the JSON text of a dict shaped like a scene file (`root`
/// says how the dict's keys are named in errors).
fn scene_of(path: Option<PathBuf>, json: Option<&str>, root: Root) -> PyResult<Scene> {
    match (path, json) {
        (Some(p), _) => Scene::load(&p).map_err(error),
        (None, Some(j)) => {
            let text = toml_text(j, "scene")?;
            Scene::parse(Path::new("<scene>"), &text)
                .map_err(|e| BwcError::new_err(dict_errors::explain(&e, &text, root)))
        }
        (None, None) => Err(BwcError::new_err("a scene needs a path or a dict")),
    }
}

/// The outcomes in the order of the codes `cor` returns.
const OUTCOMES: [&str; 4] = ["separated", "settled", "horizon", "failed"];

/// What each CoR's check against `e_tol` found, in the order of the codes `cor` returns
/// (`"none"`: nothing simulated, an interpolated speed).
const CHECKS: [&str; 5] = ["off", "met", "unmet", "unverified", "none"];

/// Why the double-double retry of an unmet check reported nothing
/// (`bw_models::DdDeclined::name`), in the order of the codes `cor` returns (`"none"`: it
/// was not due, or it settled the CoR).
const DECLINED: [&str; 6] = [
    "none",
    "stiff",
    "no-path",
    "failed",
    "steps-grew",
    "disagreed",
];

/// Why a sweep simulated a speed it tried to interpolate (`bw_models::sweep::GaveUp::name`),
/// in the order of the codes `cor` returns (`"none"`: interpolated, or not tried).
const GAVE_UP: [&str; 5] = ["none", "noise", "too-few-speeds", "not-smooth", "budget"];

/// `bwc.cor`: one impact per speed (or the one nondimensional impact) of the scene given as
/// JSON text; a dict of numpy arrays `e`, `t_s`, `t_d` (NaN where absent), `separated`,
/// `e_error` (a checked CoR's estimate of its error in `e`, `[solver] e_tol`; NaN where none),
/// `check` (codes into `CHECKS`), `tighter_failed_rtol` (the rtol of a tighter run under
/// `e_tol` that failed; NaN where none did), `tighter_out_of_steps` (whether it ran out of
/// `max_steps`), `double_double` (whether the reported run is the double-double one,
/// `[solver] double_double`), `double_double_declined` (codes into `DECLINED`), `phase`
/// (whether the phase path served it, `[solver] phase`), `rhs_evals`, `interpolated` (whether `e` and `t_s` came from
/// a sweep's interpolant), `sweep_gave_up` (codes into `GAVE_UP`) and `outcome` (codes into `"separated"`, `"settled"`, `"horizon"`,
/// `"failed"`).
#[pyfunction]
#[pyo3(signature = (scene_json, threads=None))]
fn cor<'py>(
    py: Python<'py>,
    scene_json: &str,
    threads: Option<usize>,
) -> PyResult<Bound<'py, PyDict>> {
    let scene = scene_of(None, Some(scene_json), Root::Cor)?;
    let runs = py
        .allow_threads(|| bwc_app::with_threads(threads, || Ok(simulate::run(&scene, None))))
        .map_err(error)?;
    if let Some(failed) = runs.iter().find(|r| r.outcome == Outcome::Failed) {
        return Err(BwcError::new_err(format!(
            "run {}: {}",
            failed.label(),
            failed.error.as_deref().unwrap_or("failed")
        )));
    }
    warn_notes(py, &scene, &runs)?;
    cor_columns(py, &runs)
}

/// The columns of `bwc.cor`, one per quantity of the runs, in the order its documentation
/// lists them: floats (NaN where absent), flags, and codes into the lists above.
fn cor_columns<'py>(py: Python<'py>, runs: &[Run]) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    let floats = |name: &str, f: &dyn Fn(&Run) -> Option<f64>| {
        let v: Vec<f64> = runs.iter().map(|r| f(r).unwrap_or(f64::NAN)).collect();
        out.set_item(name, v.into_pyarray(py))
    };
    let flags = |name: &str, f: &dyn Fn(&Run) -> bool| {
        out.set_item(name, PyArray1::from_vec(py, runs.iter().map(f).collect()))
    };
    let codes = |name: &str, list: &[&str], f: &dyn Fn(&Run) -> &'static str| {
        let code = |r: &Run| list.iter().position(|n| *n == f(r)).unwrap_or(0) as u8;
        out.set_item(
            name,
            runs.iter().map(code).collect::<Vec<u8>>().into_pyarray(py),
        )
    };
    let solver = |r: &Run| r.solver;
    floats("e", &|r| Some(r.e))?;
    floats("t_s", &|r| r.t_s)?;
    floats("t_d", &|r| r.t_d)?;
    flags("separated", &|r| r.outcome == Outcome::Separated)?;
    floats("e_error", &|r| solver(r).and_then(|c| c.e_error))?;
    codes("check", &CHECKS, &|r| {
        solver(r).map_or("none", |c| c.check.name())
    })?;
    let failed = |r: &Run| solver(r).and_then(|c| c.tighter_failed);
    floats("tighter_failed_rtol", &|r| {
        failed(r).map(|f| bwc_app::tidy(f.rtol))
    })?;
    flags("tighter_out_of_steps", &|r| {
        failed(r).is_some_and(|f| f.out_of_steps)
    })?;
    flags("double_double", &|r| {
        solver(r).is_some_and(|c| c.double_double)
    })?;
    flags("phase", &|r| solver(r).is_some_and(|c| c.phase))?;
    codes("double_double_declined", &DECLINED, &|r| {
        let declined = solver(r).and_then(|c| c.double_double_declined);
        declined.map_or("none", |d| d.name())
    })?;
    let evals: Vec<u64> = runs
        .iter()
        .map(|r| solver(r).map_or(0, |c| c.stats.rhs_evals))
        .collect();
    out.set_item("rhs_evals", evals.into_pyarray(py))?;
    flags("interpolated", &|r| r.interpolation.is_some())?;
    codes("sweep_gave_up", &GAVE_UP, &|r| {
        r.sweep_gave_up.map_or("none", |g| g.name())
    })?;
    // Codes into OUTCOMES (the Python side makes the string array without per-run objects).
    codes("outcome", &OUTCOMES, &|r| r.outcome.name())?;
    Ok(out)
}

/// `bwc.simulate`: the JSON text `bwc-simulate run --json` prints for the scene, and per run
/// its trajectory as numpy arrays (`t`, `x`, `v`, `u`, `F` and the model's states `z` or
/// `r, y, z`, in the run's units) where the scene asks for one (`[output] trajectory` or
/// `loops`), else `None`.
#[pyfunction]
#[pyo3(signature = (path=None, scene_json=None, threads=None))]
fn simulate_json<'py>(
    py: Python<'py>,
    path: Option<PathBuf>,
    scene_json: Option<&str>,
    threads: Option<usize>,
) -> PyResult<(String, Vec<Option<Bound<'py, PyDict>>>)> {
    let scene = scene_of(path, scene_json, Root::Dict("scene"))?;
    pair_result(py, &scene, threads)
}

/// The summary text and trajectories of a pair scene's runs, as [`simulate_json`] gives them.
fn pair_result<'py>(
    py: Python<'py>,
    scene: &Scene,
    threads: Option<usize>,
) -> PyResult<(String, Vec<Option<Bound<'py, PyDict>>>)> {
    let runs = py
        .allow_threads(|| bwc_app::with_threads(threads, || Ok(simulate::run(scene, None))))
        .map_err(error)?;
    warn_notes(py, scene, &runs)?;
    let summary = bwc_app::impact::output::Summary::new(&runs, scene.sequence.is_some());
    let text = summary.provenance_json(scene, &runs);
    let sampled = scene.output.trajectory || scene.output.loops;
    let trajectories = runs
        .iter()
        .map(|r| sampled.then(|| trajectory(py, r)).transpose())
        .collect::<PyResult<_>>()?;
    Ok((text, trajectories))
}

/// `bwc.simulate` of a scene file, read once: whether it is a `[chain]` scene, the summary as
/// JSON text, and the trajectories of a pair scene's runs (a list) or a chain's samples (a
/// dict or `None`), as [`simulate_json`] and [`simulate_chain_json`] give them.
#[pyfunction]
#[pyo3(signature = (path, threads=None))]
fn simulate_file_json(
    py: Python<'_>,
    path: PathBuf,
    threads: Option<usize>,
) -> PyResult<(bool, String, PyObject)> {
    match bwc_app::scene_file::SceneFile::load(&path).map_err(error)? {
        bwc_app::scene_file::SceneFile::Pair(scene) => {
            let (text, trajectories) = pair_result(py, &scene, threads)?;
            Ok((
                false,
                text,
                trajectories.into_pyobject(py)?.into_any().unbind(),
            ))
        }
        bwc_app::scene_file::SceneFile::Chain(scene) => {
            let out = py
                .allow_threads(|| bwc_app::with_threads(threads, || bwc_app::chain::run(&scene)))
                .map_err(error)?;
            let (text, samples) = chain_result(py, &scene, &out, "bwc.simulate")?;
            Ok((true, text, samples.into_pyobject(py)?.into_any().unbind()))
        }
    }
}

/// `bwc.simulate` of a `[chain]` scene: the summary as JSON text (with the provenance) and,
/// where `[output].dt` is given, the samples as a dict of numpy arrays: `t` (s), `x`, `v`
/// (samples x bodies; m, m/s), `gap`, `F` (samples x pairs; m, N), and the ledger's
/// `kinetic`, `stored`, `dissipated`, `work` (J).
#[pyfunction]
#[pyo3(signature = (path=None, scene_json=None, threads=None))]
fn simulate_chain_json<'py>(
    py: Python<'py>,
    path: Option<PathBuf>,
    scene_json: Option<&str>,
    threads: Option<usize>,
) -> PyResult<(String, Option<Bound<'py, PyDict>>)> {
    let scene = chain_scene_of(path, scene_json, "<scene>")?;
    let out = py
        .allow_threads(|| bwc_app::with_threads(threads, || bwc_app::chain::run(&scene)))
        .map_err(error)?;
    chain_result(py, &scene, &out, "bwc.simulate")
}

/// `bwc.simulate_many`: many `[chain]` scenes, each a path or JSON text (`paths[i]` or
/// `scene_jsons[i]`; `indices[i]` its place in the caller's list, if given), run in parallel;
/// per scene the summary as JSON text and its samples, as [`simulate_chain_json`] gives them.
#[pyfunction]
#[pyo3(signature = (paths, scene_jsons, threads=None, indices=None))]
#[allow(clippy::type_complexity)]
fn simulate_chains_json<'py>(
    py: Python<'py>,
    paths: Vec<Option<PathBuf>>,
    scene_jsons: Vec<Option<String>>,
    threads: Option<usize>,
    indices: Option<Vec<usize>>,
) -> PyResult<Vec<(String, Option<Bound<'py, PyDict>>)>> {
    // Errors name a scene by its place in the caller's list (`indices`, for a part of it).
    let index = |i: usize| {
        indices
            .as_ref()
            .and_then(|x| x.get(i).copied())
            .unwrap_or(i)
    };
    let scenes = paths
        .into_iter()
        .zip(&scene_jsons)
        .enumerate()
        .map(|(i, (path, json))| {
            chain_scene_of(path, json.as_deref(), &format!("<scenes[{}]>", index(i)))
        })
        .collect::<PyResult<Vec<_>>>()?;
    let outs = py
        .allow_threads(|| bwc_app::with_threads(threads, || Ok(bwc_app::chain::run_many(&scenes))));
    let outs = outs.map_err(error)?;
    scenes
        .iter()
        .zip(outs)
        .map(|(scene, out)| chain_result(py, scene, &out.map_err(error)?, "bwc.simulate_many"))
        .collect()
}

/// A chain's summary as JSON text, with the provenance of the `origin` call, and its samples
/// where the scene asks for them.
fn chain_result<'py>(
    py: Python<'py>,
    scene: &ChainScene,
    out: &bwc_app::chain::ChainOutcome,
    origin: &str,
) -> PyResult<(String, Option<Bound<'py, PyDict>>)> {
    let mut summary = bwc_app::chain::summary(scene, out);
    for (k, v) in bwc_app::outdir::provenance(origin)
        .as_object()
        .expect("provenance is an object")
    {
        summary[k] = v.clone();
    }
    let samples = scene.dt.map(|_| chain_samples(py, out)).transpose()?;
    Ok((summary.to_string(), samples))
}

/// A chain's samples as a dict of numpy arrays (see [`simulate_chain_json`]).
fn chain_samples<'py>(
    py: Python<'py>,
    out: &bwc_app::chain::ChainOutcome,
) -> PyResult<Bound<'py, PyDict>> {
    use numpy::PyArray2;
    let d = PyDict::new(py);
    let s = &out.samples;
    let rows = |f: &dyn Fn(&bwc_app::chain::ChainSample) -> &Vec<f64>| {
        s.iter().map(|x| f(x).clone()).collect::<Vec<Vec<f64>>>()
    };
    let matrix = |m: Vec<Vec<f64>>, width: usize| -> PyResult<Bound<'py, PyArray2<f64>>> {
        if m.is_empty() {
            return Ok(numpy::PyArray2::zeros(py, [0, width], false));
        }
        PyArray2::from_vec2(py, &m).map_err(|e| BwcError::new_err(e.to_string()))
    };
    let (n, p) = (out.run.bodies.len(), s.first().map_or(0, |x| x.gaps.len()));
    d.set_item(
        "t",
        s.iter().map(|x| x.t).collect::<Vec<_>>().into_pyarray(py),
    )?;
    d.set_item("x", matrix(rows(&|x| &x.positions), n)?)?;
    d.set_item("v", matrix(rows(&|x| &x.velocities), n)?)?;
    d.set_item("gap", matrix(rows(&|x| &x.gaps), p)?)?;
    d.set_item("F", matrix(rows(&|x| &x.forces), p)?)?;
    let ledger = |f: &dyn Fn(&bw_models::chain::Ledger) -> f64| {
        s.iter().map(|x| f(&x.ledger)).collect::<Vec<f64>>()
    };
    d.set_item("kinetic", ledger(&|l| l.kinetic).into_pyarray(py))?;
    d.set_item("stored", ledger(&|l| l.stored).into_pyarray(py))?;
    d.set_item("dissipated", ledger(&|l| l.dissipated).into_pyarray(py))?;
    d.set_item("work", ledger(&|l| l.work).into_pyarray(py))?;
    Ok(d)
}

/// A run's samples as a dict of numpy arrays.
fn trajectory<'py>(
    py: Python<'py>,
    r: &bwc_app::impact::runs::Run,
) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    let column = |f: &dyn Fn(&bwc_app::impact::runs::Sample) -> f64| {
        r.trajectory.iter().map(f).collect::<Vec<f64>>()
    };
    out.set_item("t", column(&|s| s.t).into_pyarray(py))?;
    out.set_item("x", column(&|s| s.x).into_pyarray(py))?;
    out.set_item("v", column(&|s| s.v).into_pyarray(py))?;
    out.set_item("u", column(&|s| s.u).into_pyarray(py))?;
    out.set_item("F", column(&|s| s.f).into_pyarray(py))?;
    for (i, name) in r
        .model
        .law_states()
        .iter()
        .enumerate()
        .filter(|(_, n)| **n != "x")
    {
        out.set_item(*name, column(&|s| s.state[i]).into_pyarray(py))?;
    }
    Ok(out)
}

/// `bwc.materials`: the JSON text `bwc-identify materials --json` prints for a file or a dict
/// with a `[materials]` table.
#[pyfunction]
#[pyo3(signature = (path=None, materials_json=None, out=None, seed=0))]
fn materials_json(
    py: Python<'_>,
    path: Option<PathBuf>,
    materials_json: Option<&str>,
    out: Option<PathBuf>,
    seed: u64,
) -> PyResult<String> {
    use bwc_app::materials::{fit_to_reference, following_json, MaterialsReport, MaterialsSpec};
    let spec = match (path, materials_json) {
        (Some(p), _) => MaterialsSpec::load(&p).map_err(error)?,
        (None, Some(j)) => {
            let text = toml_text(j, "materials")?;
            MaterialsSpec::parse(Path::new("<materials>"), &text).map_err(|e| {
                BwcError::new_err(dict_errors::explain(&e, &text, Root::Dict("materials")))
            })?
        }
        (None, None) => return Err(BwcError::new_err("materials: give a path or a dict")),
    };
    let report = py
        .allow_threads(|| MaterialsReport::of(&spec))
        .map_err(error)?;
    let mut json = report.json(&spec);
    if let Some(dir) = out {
        let fits = py
            .allow_threads(|| {
                bwc_app::outdir::prepare(&dir)?;
                fit_to_reference(&dir, &spec, &report, seed)
            })
            .map_err(error)?;
        json["fits"] = fits.fits.iter().map(following_json).collect();
        json["loop_fits"] = fits.loop_fits.into();
    }
    Ok(json.to_string())
}

/// `bwc.identify`: the JSON text `bwc-identify run --json` prints for the config (with
/// `seed`; without, the evaluation at each fit's `[fit.params]`, as `bwc-identify eval`).
#[pyfunction]
#[pyo3(signature = (path=None, config_json=None, seed=None, threads=None, checkpoint=None))]
fn identify_json(
    py: Python<'_>,
    path: Option<PathBuf>,
    config_json: Option<&str>,
    seed: Option<u64>,
    threads: Option<usize>,
    checkpoint: Option<PathBuf>,
) -> PyResult<String> {
    let (file, config) = config_of(path, config_json)?;
    let checkpoint = checkpoint::open(checkpoint, "run")?;
    let (reports, loops) = py
        .allow_threads(|| {
            bwc_app::with_threads(threads, || {
                let c = checkpoint.as_ref();
                bwc_app::fit::identify::fit_all(&file, &config, seed, &|| {}, c)
            })
        })
        .map_err(error)?;
    Ok(bwc_app::fit::identify::summary_of(&config, &reports, &loops).to_string())
}

/// `bwc.coverage`: the JSON text `bwc-identify coverage --json` prints for the config over the
/// replicates with seeds `first_seed .. first_seed + replicates`.
#[pyfunction]
#[pyo3(signature = (path=None, config_json=None, replicates=40, first_seed=1, noise=None, fit=None, threads=None, checkpoint=None))]
#[allow(clippy::too_many_arguments)]
fn coverage_json(
    py: Python<'_>,
    path: Option<PathBuf>,
    config_json: Option<&str>,
    replicates: u64,
    first_seed: u64,
    noise: Option<f64>,
    fit: Option<&str>,
    threads: Option<usize>,
    checkpoint: Option<PathBuf>,
) -> PyResult<String> {
    let (file, config) = config_of(path, config_json)?;
    let seeds = first_seed..first_seed.saturating_add(replicates);
    let checkpoint = checkpoint::open(checkpoint, "coverage")?;
    let reports = py
        .allow_threads(|| {
            bwc_app::with_threads(threads, || {
                let c = checkpoint.as_ref();
                bwc_app::fit::identify::coverage_study(&file, &config, noise, fit, seeds, c)
            })
        })
        .map_err(error)?;
    let mut v = bwc_app::outdir::provenance("bwc-identify");
    v["coverage"] = bwc_app::fit::identify::coverage_summary(&reports)["coverage"].take();
    Ok(v.to_string())
}

/// `bwc.posterior`: the JSON text `bwc-identify posterior --json` prints for the config, each
/// posterior with its weighted sample under `"samples"`.
#[pyfunction]
#[pyo3(signature = (path=None, config_json=None, seed=0, fit=None, particles=None, runs=None, threads=None, checkpoint=None))]
#[allow(clippy::too_many_arguments)]
fn posterior_json(
    py: Python<'_>,
    path: Option<PathBuf>,
    config_json: Option<&str>,
    seed: u64,
    fit: Option<&str>,
    particles: Option<usize>,
    runs: Option<usize>,
    threads: Option<usize>,
    checkpoint: Option<PathBuf>,
) -> PyResult<String> {
    let (file, config) = config_of(path, config_json)?;
    let sizes = posterior_sizes(particles, runs)?;
    let checkpoint = checkpoint::open(checkpoint, "posterior")?;
    let reports = py
        .allow_threads(|| {
            bwc_app::with_threads(threads, || {
                let c = checkpoint.as_ref();
                bwc_app::fit::identify::posterior_all(&file, &config, seed, fit, sizes, c)
            })
        })
        .map_err(error)?;
    Ok(posterior_text(&config, &reports))
}

/// The JSON of posteriors with their samples.
fn posterior_text(config: &Config, reports: &[bwc_app::fit::identify::PosteriorReport]) -> String {
    let mut v = bwc_app::outdir::provenance("bwc-identify");
    v["posteriors"] = bwc_app::fit::identify::posterior_summary(reports)["posteriors"].take();
    for (p, r) in v["posteriors"]
        .as_array_mut()
        .into_iter()
        .flatten()
        .zip(reports)
    {
        p["samples"] = bwc_app::fit::identify::samples_json(r);
    }
    v["config"] = config.describe();
    v.to_string()
}

/// Particles and runs as the command line admits them.
fn posterior_sizes(
    particles: Option<usize>,
    runs: Option<usize>,
) -> PyResult<(Option<usize>, Option<usize>)> {
    if particles.is_some_and(|p| !(16..=1_000_000).contains(&p)) {
        return Err(BwcError::new_err(format!(
            "particles = {}: needs 16 <= particles <= 1000000",
            particles.unwrap_or(0)
        )));
    }
    if runs.is_some_and(|r| !(2..=10_000).contains(&r)) {
        return Err(BwcError::new_err(format!(
            "runs = {}: needs 2 <= runs <= 10000 (their spread is the evidence's error)",
            runs.unwrap_or(0)
        )));
    }
    Ok((particles, runs))
}

/// The fit named `name` of a config (or an error listing the names).
fn fit_named<'a>(config: &'a Config, name: &str) -> PyResult<&'a bwc_app::fit::config::FitConfig> {
    config.fits.iter().find(|f| f.name == name).ok_or_else(|| {
        let names: Vec<&str> = config.fits.iter().map(|f| f.name.as_str()).collect();
        BwcError::new_err(format!("fit = {name:?} names no [[fit]]: one of {names:?}"))
    })
}

/// The names of a config's `[[fit]]` tables, in file order.
#[pyfunction]
#[pyo3(signature = (path=None, config_json=None))]
fn fit_names(path: Option<PathBuf>, config_json: Option<&str>) -> PyResult<Vec<String>> {
    let (_, config) = config_of(path, config_json)?;
    Ok(config.fits.iter().map(|f| f.name.clone()).collect())
}

/// The runs `[fit.posterior]` of fit `fit` asks for.
#[pyfunction]
#[pyo3(signature = (fit, path=None, config_json=None))]
fn posterior_runs(fit: &str, path: Option<PathBuf>, config_json: Option<&str>) -> PyResult<usize> {
    let (_, config) = config_of(path, config_json)?;
    Ok(fit_named(&config, fit)?.posterior.runs)
}

/// One run (number `index`) of the posterior sampler of fit `fit`, as JSON text: what a worker
/// of `bwc.dask.posterior` computes.
#[pyfunction]
#[pyo3(signature = (fit, index, path=None, config_json=None, seed=0, particles=None, runs=None))]
#[allow(clippy::too_many_arguments)]
fn posterior_run_json(
    py: Python<'_>,
    fit: &str,
    index: usize,
    path: Option<PathBuf>,
    config_json: Option<&str>,
    seed: u64,
    particles: Option<usize>,
    runs: Option<usize>,
) -> PyResult<String> {
    let (file, config) = config_of(path, config_json)?;
    let sizes = posterior_sizes(particles, runs)?;
    let f = fit_named(&config, fit)?;
    let run = py
        .allow_threads(|| {
            bwc_app::with_threads(Some(1), || {
                bwc_app::fit::identify::posterior_run(&file, f, seed, sizes, index)
            })
        })
        .map_err(error)?;
    Ok(bwc_app::fit::identify::run_json(&run).to_string())
}

/// Pools the runs (JSON texts of `posterior_run_json`) of each fit named in `fits` into the JSON
/// text `posterior_json` gives.
#[pyfunction]
#[pyo3(signature = (fits, runs_json, path=None, config_json=None, seed=0, threads=None))]
fn posterior_pool_json(
    py: Python<'_>,
    fits: Vec<String>,
    runs_json: Vec<Vec<String>>,
    path: Option<PathBuf>,
    config_json: Option<&str>,
    seed: u64,
    threads: Option<usize>,
) -> PyResult<String> {
    let (file, config) = config_of(path, config_json)?;
    let mut reports = Vec::new();
    for (name, texts) in fits.iter().zip(&runs_json) {
        let f = fit_named(&config, name)?;
        let runs = texts
            .iter()
            .map(|t| {
                let v: serde_json::Value = serde_json::from_str(t)
                    .map_err(|e| BwcError::new_err(format!("a posterior run's JSON: {e}")))?;
                bwc_app::fit::identify::run_of_json(&v).map_err(error)
            })
            .collect::<PyResult<Vec<_>>>()?;
        let report = py
            .allow_threads(|| {
                bwc_app::with_threads(threads, || {
                    bwc_app::fit::identify::posterior_from_runs(&file, f, seed, runs)
                })
            })
            .map_err(error)?;
        reports.push(report);
    }
    Ok(posterior_text(&config, &reports))
}

/// A `[chain]` scene from a path or from the JSON text of a dict, which errors call `label`
/// (`<scene>`, `<scenes[3]>`).
fn chain_scene_of(path: Option<PathBuf>, json: Option<&str>, label: &str) -> PyResult<ChainScene> {
    match (path, json) {
        (Some(p), _) => ChainScene::load(&p).map_err(error),
        (None, Some(j)) => {
            let text = toml_text(j, "scene")?;
            ChainScene::parse(Path::new(label), &text).map_err(|e| {
                BwcError::new_err(dict_errors::explain(&e, &text, Root::Dict("scene")))
            })
        }
        (None, None) => Err(BwcError::new_err(format!(
            "{label}: a scene needs a path or a dict"
        ))),
    }
}

/// A config from a path or from the JSON text of a dict shaped like a config file (data paths
/// relative to the working directory).
fn config_of(path: Option<PathBuf>, json: Option<&str>) -> PyResult<(PathBuf, Config)> {
    match (path, json) {
        (Some(p), _) => Ok((p.clone(), Config::load(&p).map_err(error)?)),
        (None, Some(j)) => {
            let file = PathBuf::from("<config>");
            let text = toml_text(j, "config")?;
            let config = Config::parse(&file, &text).map_err(|e| {
                BwcError::new_err(dict_errors::explain(&e, &text, Root::Dict("config")))
            })?;
            Ok((file, config))
        }
        (None, None) => Err(BwcError::new_err("a config needs a path or a dict")),
    }
}

/// The native module `bwc._native`.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("BwcError", m.py().get_type::<BwcError>())?;
    m.add("BwcWarning", m.py().get_type::<BwcWarning>())?;
    m.add_function(wrap_pyfunction!(cor, m)?)?;
    m.add_function(wrap_pyfunction!(materials_json, m)?)?;
    m.add_function(wrap_pyfunction!(simulate_json, m)?)?;
    m.add_function(wrap_pyfunction!(simulate_file_json, m)?)?;
    m.add_function(wrap_pyfunction!(simulate_chain_json, m)?)?;
    m.add_function(wrap_pyfunction!(simulate_chains_json, m)?)?;
    m.add_function(wrap_pyfunction!(identify_json, m)?)?;
    m.add_function(wrap_pyfunction!(coverage_json, m)?)?;
    m.add_function(wrap_pyfunction!(posterior_json, m)?)?;
    m.add_function(wrap_pyfunction!(posterior_run_json, m)?)?;
    m.add_function(wrap_pyfunction!(posterior_pool_json, m)?)?;
    m.add_function(wrap_pyfunction!(fit_names, m)?)?;
    m.add_function(wrap_pyfunction!(posterior_runs, m)?)?;
    m.add_class::<checkpoint::Checkpoint>()?;
    m.add_function(wrap_pyfunction!(checkpoint::config_fingerprint, m)?)?;
    m.add_function(wrap_pyfunction!(checkpoint::scene_fingerprint, m)?)?;
    m.add_class::<contact::Contact>()?;
    m.add_class::<contact::Step>()?;
    m.add_class::<contacts::Contacts>()?;
    Ok(())
}
