//! Impact speeds as a file gives them: `v0 = [0.5, 1.0]` or `v0 = { from = 0.1, to = 6.0,
//! count = 40, spacing = "log" }`, and the array-or-table values that spell them.

use super::{Ctx, Num};
use crate::AppError;
use serde::de::value::{MapAccessDeserializer, SeqAccessDeserializer};
use serde::de::{MapAccess, SeqAccess, Visitor};
use serde::{Deserialize, Deserializer};
use std::fmt;
use std::marker::PhantomData;
use toml::Spanned;

/// The most speeds a range `v0 = { from, to, count }` makes: a study streams its runs, so that
/// only the speeds themselves (8 bytes each, and a sorted copy while a sweep is planned) grow
/// with it.
pub const MAX_SPEEDS: i64 = 100_000_000;

/// A `v0` value: a list of speeds or a range.
pub(crate) type V0 = SeqOrMap<Vec<Num>, RawRange>;

/// A value that is either an array (`S`) or a table (`M`), deserialized without buffering so
/// that spans inside survive.
#[derive(Debug)]
pub(crate) enum SeqOrMap<S, M> {
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

/// `v0 = { from = 0.1, to = 6.0, count = 40, spacing = "log" }`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawRange {
    pub from: Num,
    pub to: Num,
    pub count: Spanned<i64>,
    pub spacing: Option<Spanned<String>>,
}

/// The impact speeds of a `v0` key (m/s): a list, or a range `{ from, to, count, spacing }`;
/// none where the key is absent.
///
/// # Errors
/// [`AppError::Invalid`] naming the key for an empty list, a bad count or spacing, or a speed
/// that is not positive.
pub(crate) fn speeds(ctx: &Ctx, v0: &Option<Spanned<V0>>) -> Result<Vec<f64>, AppError> {
    let Some(v) = v0 else {
        return Ok(Vec::new());
    };
    let speeds = match v.get_ref() {
        SeqOrMap::Seq(list) => {
            if list.is_empty() {
                return Err(ctx.invalid(&v.span(), "v0", "an empty list: give at least one speed"));
            }
            list.iter()
                .map(|s| ctx.num(s, "v0"))
                .collect::<Result<Vec<_>, _>>()?
        }
        SeqOrMap::Map(r) => {
            let (from, to) = (ctx.num(&r.from, "v0.from")?, ctx.num(&r.to, "v0.to")?);
            let count = *r.count.get_ref();
            if !(1..=MAX_SPEEDS).contains(&count) {
                return Err(ctx.invalid(
                    &r.count.span(),
                    "v0.count",
                    format!("{count} is not admissible: 1 <= count <= {MAX_SPEEDS}"),
                ));
            }
            if from <= 0.0 || to < from {
                return Err(ctx.invalid(
                    &r.from.span(),
                    "v0.from",
                    format!("from = {from}, to = {to}: need 0 < from <= to (m/s)"),
                ));
            }
            let log = match r.spacing.as_ref().map(|s| s.get_ref().as_str()) {
                None | Some("linear") => false,
                Some("log") => true,
                Some(other) => {
                    let s = r.spacing.as_ref().map(|s| s.span()).unwrap_or_default();
                    return Err(ctx.invalid(
                        &s,
                        "v0.spacing",
                        format!("\"{other}\": use \"linear\" or \"log\""),
                    ));
                }
            };
            let n = count as usize;
            (0..n)
                .map(|i| {
                    let f = if n == 1 {
                        0.0
                    } else {
                        i as f64 / (n - 1) as f64
                    };
                    if log {
                        from * (to / from).powf(f)
                    } else {
                        from + (to - from) * f
                    }
                })
                .collect()
        }
    };
    if let Some(bad) = speeds.iter().find(|s| **s <= 0.0) {
        return Err(ctx.invalid(
            &v.span(),
            "v0",
            format!("{bad} is not admissible: v0 > 0 (m/s)"),
        ));
    }
    Ok(speeds)
}
