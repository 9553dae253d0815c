//! `[sequence]`: a body dropped from `h0` (or arriving at `v0`) bounces on a fixed surface under
//! gravity, each contact the scene's `[physical]` (or `[base]`, with `[sequence].m`) model with
//! input `u = -m g`.

use super::raw::{RawScene, RawSequence};
use crate::tables::{span, Ctx, Num};
use crate::AppError;
use bw_models::sequence::{Flight, Policy, SequenceSettings, Start};
use std::ops::Range;

/// A validated `[sequence]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SequenceSpec {
    /// Dropped from a height, or arriving at a speed.
    pub start: Start,
    /// Gravity, drag, bounces and policy.
    pub settings: SequenceSettings,
    /// The body's mass (kg) for `[base]` systems (`[physical]` has its own).
    pub m: Option<f64>,
}

/// Most bounces of one sequence.
const MOST_BOUNCES: i64 = 100_000;

/// The scene's `[sequence]`, if any, checked against the rest of the scene.
pub(super) fn sequence(ctx: &Ctx, raw: &RawScene) -> Result<Option<SequenceSpec>, AppError> {
    let Some(seq) = &raw.sequence else {
        return Ok(None);
    };
    let t = seq.span();
    let r = seq.get_ref();
    let m = with_the_scene(ctx, raw, r, &t)?;
    let start = start(ctx, r, &t)?;
    let g = positive(ctx, &r.g, "[sequence].g", "m/s^2")?.unwrap_or(9.81);
    let drag = match &r.drag {
        None => 0.0,
        Some(d) => {
            let v = ctx.num(d, "[sequence].drag")?;
            if v < 0.0 {
                return Err(ctx.invalid(
                    &d.span(),
                    "[sequence].drag",
                    format!("{v} is not admissible: drag >= 0 (1/m)"),
                ));
            }
            v
        }
    };
    let bounces = match &r.bounces {
        None => 10,
        Some(b) if (1..=MOST_BOUNCES).contains(b.get_ref()) => *b.get_ref() as usize,
        Some(b) => {
            return Err(ctx.invalid(
                &b.span(),
                "[sequence].bounces",
                format!(
                    "{} is not admissible: 1 <= bounces <= {MOST_BOUNCES}",
                    b.get_ref()
                ),
            ))
        }
    };
    let policy = match r.policy.as_ref().map(|p| (p.get_ref().as_str(), p.span())) {
        None | Some(("reset", _)) => Policy::Reset,
        Some(("carry", _)) => Policy::Carry,
        Some((other, s)) => {
            return Err(ctx.invalid(
                &s,
                "[sequence].policy",
                format!("\"{other}\" is not a policy: \"reset\" or \"carry\""),
            ))
        }
    };
    Ok(Some(SequenceSpec {
        start,
        settings: SequenceSettings {
            flight: Flight { g, drag },
            bounces,
            policy,
        },
        m,
    }))
}

/// Errors for the scene's tables and keys that a sequence does not take (`[bodies]`,
/// `[nondimensional]`, `v0`, `[input]`); the body's mass where the contact is a `[base]`.
fn with_the_scene(
    ctx: &Ctx,
    raw: &RawScene,
    r: &RawSequence,
    t: &Range<usize>,
) -> Result<Option<f64>, AppError> {
    let conflict = |what: &Option<Range<usize>>, key: &str, why: &str| match what {
        Some(s) => Err(ctx.invalid(s, key, why.to_string())),
        None => Ok(()),
    };
    conflict(
        &span(&raw.bodies),
        "[bodies]",
        "not with [sequence], which drops one body on a fixed surface: describe its contact with \
         [physical]",
    )?;
    conflict(
        &span(&raw.nondimensional),
        "[nondimensional]",
        "not with [sequence], whose flights need SI units: describe the contact with [physical]",
    )?;
    let m = base_mass(ctx, raw, r, t)?;
    conflict(
        &raw.v0.as_ref().map(|v| v.span()),
        "v0",
        "not with [sequence]: give [sequence].h0 (drop height) or [sequence].v0 (first impact \
         speed)",
    )?;
    conflict(
        &span(&raw.input),
        "[input]",
        "not with [sequence]: gravity -m g is the input of every contact ([sequence].g)",
    )?;
    Ok(m)
}

/// A positive value of `key` (in `unit`), if given.
fn positive(ctx: &Ctx, v: &Option<Num>, key: &str, unit: &str) -> Result<Option<f64>, AppError> {
    v.as_ref()
        .map(|x| {
            let value = ctx.num(x, key)?;
            if value > 0.0 {
                Ok(value)
            } else {
                Err(ctx.invalid(
                    &x.span(),
                    key,
                    format!("{value} is not admissible: > 0 ({unit})"),
                ))
            }
        })
        .transpose()
}

/// The start: a drop height `h0` or a first impact speed `v0`, exactly one of them.
fn start(ctx: &Ctx, r: &RawSequence, t: &Range<usize>) -> Result<Start, AppError> {
    match (
        positive(ctx, &r.h0, "[sequence].h0", "m")?,
        positive(ctx, &r.v0, "[sequence].v0", "m/s")?,
    ) {
        (Some(h), None) => Ok(Start::Height(h)),
        (None, Some(v)) => Ok(Start::Speed(v)),
        (None, None) => Err(ctx.invalid(
            t,
            "[sequence].h0",
            "missing: give h0 (drop height, m) or v0 (first impact speed, m/s)",
        )),
        (Some(_), Some(_)) => {
            let s = span(&r.v0).unwrap_or(t.clone());
            Err(ctx.invalid(&s, "[sequence].v0", "give h0 or v0, not both"))
        }
    }
}

/// `[sequence].m` (kg): required with `[base]` (whose contacts feel gravity through `U_b` and
/// last `t_s T_c` seconds, so `U_b` and `T_b` are required too), not used with `[physical]`.
fn base_mass(
    ctx: &Ctx,
    raw: &RawScene,
    r: &RawSequence,
    t: &Range<usize>,
) -> Result<Option<f64>, AppError> {
    use super::raw::SeqOrMap;
    let Some(base) = &raw.base else {
        if let Some(m) = &r.m {
            return Err(ctx.invalid(
                &m.span(),
                "[sequence].m",
                "not with [physical], which has its own m",
            ));
        }
        return Ok(None);
    };
    let entries: Vec<_> = match base.get_ref() {
        SeqOrMap::Map(b) => vec![(b, base.span())],
        SeqOrMap::Seq(list) => list.iter().map(|b| (b.get_ref(), b.span())).collect(),
    };
    for (b, s) in entries {
        for (v, key) in [(&b.u_b, "[base].U_b"), (&b.t_b, "[base].T_b")] {
            if v.is_none() {
                return Err(ctx.invalid(&s, key, "missing: in a [sequence] each contact feels gravity -m g (scaled by U_b) and lasts T_d T_b v^(-(p-1)/(p+1)) s"));
            }
        }
    }
    let Some(m) = &r.m else {
        return Err(ctx.invalid(t, "[sequence].m", "missing: the body's mass (kg), for the gravity -m g of each contact of a [base] system"));
    };
    let value = ctx.num(m, "[sequence].m")?;
    if value <= 0.0 {
        return Err(ctx.invalid(
            &m.span(),
            "[sequence].m",
            format!("{value} is not admissible: m > 0 (kg)"),
        ));
    }
    Ok(Some(value))
}
