//! A scene file of either kind, read once: a pair scene ([`Scene`]) or a chain
//! ([`ChainScene`]), told apart by its `[chain]` table.

use crate::chain::{is_chain, ChainScene};
use crate::impact::scene::Scene;
use crate::tables::read_text;
use crate::AppError;
use std::path::Path;

/// A validated scene of either kind (a closed set: a front end handles each).
#[derive(Debug)]
pub enum SceneFile {
    /// A pair scene: one or more systems of two bodies.
    Pair(Box<Scene>),
    /// A `[chain]` scene.
    Chain(Box<ChainScene>),
}

impl SceneFile {
    /// Reads the file at `path` once and validates it as the kind of scene it is.
    ///
    /// # Errors
    /// [`AppError::Io`] if it cannot be read; as [`Scene::parse`] or [`ChainScene::parse`].
    pub fn load(path: &Path) -> Result<Self, AppError> {
        let text = read_text(path)?;
        Ok(if is_chain(&text) {
            SceneFile::Chain(Box::new(ChainScene::parse(path, &text)?))
        } else {
            SceneFile::Pair(Box::new(Scene::parse(path, &text)?))
        })
    }
}
