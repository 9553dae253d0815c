//! The scene file as written: serde types that keep the span of every value, so that errors can
//! name the line. Unknown keys are rejected by `deny_unknown_fields`.

use serde::de::value::{MapAccessDeserializer, SeqAccessDeserializer};
use serde::de::{MapAccess, SeqAccess, Visitor};
use serde::{Deserialize, Deserializer};
use std::fmt;
use std::marker::PhantomData;
use toml::Spanned;

/// A number with its position in the file.
pub(crate) use crate::tables::Num;
pub(crate) use crate::tables::{Mass, RawBase, RawInput, RawPhysical, RawSolver};

/// A value that is either an array (`S`) or a table (`M`), deserialized without buffering so
/// that spans inside survive.
#[derive(Debug)]
pub enum SeqOrMap<S, M> {
    /// An array.
    Seq(S),
    /// A table.
    Map(M),
}

impl<'de, S: Deserialize<'de>, M: Deserialize<'de>> Deserialize<'de> for SeqOrMap<S, M> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V<S, M>(PhantomData<(S, M)>);
        impl<'de, S: Deserialize<'de>, M: Deserialize<'de>> Visitor<'de> for V<S, M> {
            type Value = SeqOrMap<S, M>;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("an array or a table")
            }
            fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<Self::Value, A::Error> {
                S::deserialize(SeqAccessDeserializer::new(seq)).map(SeqOrMap::Seq)
            }
            fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<Self::Value, A::Error> {
                M::deserialize(MapAccessDeserializer::new(map)).map(SeqOrMap::Map)
            }
        }
        d.deserialize_any(V(PhantomData))
    }
}

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

/// `v0 = { from = 0.1, to = 6.0, count = 40, spacing = "log" }`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawRange {
    pub from: Num,
    pub to: Num,
    pub count: Spanned<i64>,
    pub spacing: Option<Spanned<String>>,
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
