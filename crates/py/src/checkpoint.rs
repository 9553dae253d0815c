//! Checkpoints from Python: `bwc._native.Checkpoint`, the file `bwc-identify --checkpoint`
//! writes, for the studies the package runs a piece at a time (on Dask workers, whose results
//! the client records as they arrive), and the fingerprints of their tasks.

use crate::{chain_scene_of, config_of, error, BwcError};
use bwc_app::fit::checkpoint::fingerprint;
use pyo3::prelude::*;
use std::fmt::Debug;
use std::path::PathBuf;

/// The checkpoint at `path` of a study of `command`, if a path is given.
pub(crate) fn open(
    path: Option<PathBuf>,
    command: &str,
) -> PyResult<Option<bwc_app::fit::checkpoint::Checkpoint>> {
    path.map(|p| bwc_app::fit::checkpoint::Checkpoint::open(&p, command))
        .transpose()
        .map_err(error)
}

/// A study's checkpoint (JSON Lines): the finished tasks it holds, each a text under a key and
/// the fingerprint of what the task depends on, and new ones appended, on the disk when
/// `record` returns.
#[pyclass(module = "bwc._native", frozen)]
pub struct Checkpoint(bwc_app::fit::checkpoint::Checkpoint);

#[pymethods]
impl Checkpoint {
    /// Opens (or creates) the checkpoint at `path` of a study of `command`.
    #[new]
    fn new(path: PathBuf, command: &str) -> PyResult<Self> {
        Ok(Self(open(Some(path), command)?.expect("a path")))
    }

    /// The text recorded for task `key` with this `fingerprint`, or `None`.
    fn get(&self, key: &str, fingerprint: &str) -> Option<String> {
        self.0
            .get(key, fingerprint)
            .and_then(|v| v.as_str().map(String::from))
    }

    /// Records `text`, the result of task `key`.
    fn record(&self, key: &str, fingerprint: &str, text: &str) -> PyResult<()> {
        self.0
            .record(key, fingerprint, serde_json::Value::from(text))
            .map_err(error)
    }

    /// What the study took from the checkpoint, in words, or `None` if it held nothing.
    fn summary(&self) -> Option<String> {
        self.0.summary()
    }
}

/// The fingerprint of a study's tasks on the config (the fits as loaded, their data included;
/// only fit `fit` if given) and `arguments` (a JSON text of the study's other settings).
#[pyfunction]
#[pyo3(signature = (arguments, fit=None, path=None, config_json=None))]
pub fn config_fingerprint(
    arguments: &str,
    fit: Option<&str>,
    path: Option<PathBuf>,
    config_json: Option<&str>,
) -> PyResult<String> {
    let (_, config) = config_of(path, config_json)?;
    let fits: Vec<&dyn Debug> = config
        .fits
        .iter()
        .filter(|f| fit.is_none_or(|n| n == f.name))
        .map(|f| f as &dyn Debug)
        .collect();
    if fits.is_empty() {
        return Err(BwcError::new_err(format!(
            "fit = {fit:?} names no [[fit]] of the config"
        )));
    }
    let loops = config.loop_fits.iter().map(|f| f as &dyn Debug);
    let parts: Vec<&dyn Debug> = [&arguments as &dyn Debug]
        .into_iter()
        .chain(fits)
        .chain(loops)
        .collect();
    Ok(fingerprint(&parts))
}

/// The fingerprint of a `[chain]` scene's run (the scene as loaded).
#[pyfunction]
#[pyo3(signature = (path=None, scene_json=None))]
pub fn scene_fingerprint(path: Option<PathBuf>, scene_json: Option<&str>) -> PyResult<String> {
    let scene = chain_scene_of(path, scene_json, "<scene>")?;
    Ok(fingerprint(&[&scene]))
}
