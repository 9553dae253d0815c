//! The scene file as written: serde types that keep the span of every value, so that errors can
//! name the line. Unknown keys are rejected by `deny_unknown_fields`.

use serde::Deserialize;
use toml::Spanned;

/// A number with its position in the file.
pub(crate) use crate::tables::Num;
pub(crate) use crate::tables::{Mass, RawBase, RawInput, RawPhysical, RawSolver};
pub(crate) use crate::tables::{RawRange, SeqOrMap};

/// The whole scene.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawScene {
    pub model: Option<Spanned<String>>,
    pub v0: Option<Spanned<SeqOrMap<Vec<Num>, RawRange>>>,
    pub nondimensional: Option<Spanned<RawNondim>>,
    pub base: Option<Spanned<SeqOrMap<Vec<Spanned<RawBase>>, RawBase>>>,
    pub physical: Option<Spanned<RawPhysical>>,
    pub bodies: Option<Spanned<RawBodies>>,
    pub input: Option<Spanned<RawInput>>,
    pub solver: Option<Spanned<RawSolver>>,
    pub output: Option<Spanned<RawOutput>>,
    pub sequence: Option<Spanned<RawSequence>>,
    pub sweep: Option<Spanned<RawSweep>>,
}

/// `[sweep]`: how the speeds of a sweep are evaluated.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawSweep {
    pub interpolate: Option<Spanned<bool>>,
    pub tolerance: Option<Num>,
}

/// `[sequence]`: repeated impacts of a body dropped on a fixed surface.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawSequence {
    pub h0: Option<Num>,
    pub v0: Option<Num>,
    pub g: Option<Num>,
    pub bounces: Option<Spanned<i64>>,
    pub drag: Option<Num>,
    pub policy: Option<Spanned<String>>,
    pub m: Option<Num>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawNondim {
    #[serde(rename = "B")]
    pub b: Option<Num>,
    #[serde(rename = "Gamma")]
    pub gamma: Option<Num>,
    pub kappa: Option<Num>,
    pub sigma: Option<Num>,
    pub n: Option<Num>,
    pub p: Option<Num>,
    #[serde(rename = "U")]
    pub u: Option<Num>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawBodies {
    pub m1: Option<Num>,
    pub m2: Option<Spanned<Mass>>,
    pub v1: Option<Num>,
    pub v2: Option<Num>,
    pub l1: Option<Num>,
    pub l2: Option<Num>,
    pub u1: Option<Spanned<RawInput>>,
    pub u2: Option<Spanned<RawInput>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawOutput {
    pub trajectory: Option<Spanned<bool>>,
    pub dt: Option<Num>,
    pub loops: Option<Spanned<bool>>,
    pub sweep: Option<Spanned<bool>>,
    pub plots: Option<Spanned<bool>>,
    pub summary_runs: Option<Spanned<i64>>,
    pub figures: Option<std::collections::BTreeMap<String, Spanned<RawFigure>>>,
}

/// `[output.figures.NAME]`: a figure's own title, axis labels and line style.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawFigure {
    pub title: Option<Spanned<String>>,
    pub x_label: Option<Spanned<String>>,
    pub y_label: Option<Spanned<String>>,
    pub style: Option<Spanned<String>>,
}
