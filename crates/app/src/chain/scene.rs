//! `[chain]` scene files: bodies on a line, as arrays or as `[[chain.body]]` tables, a contact
//! law for every pair (`[physical]`) or one per pair (`[[chain.pair]]`), walls as end bodies of
//! infinite mass.

use super::laws::{laws, LawTables, RawChainPair, RawLaw};
use crate::signal::Signal;
use crate::tables::{every_error, RawInput};
use crate::tables::{model_kind, read_text, signal, span, syntax_error, Ctx, Num};
use crate::tables::{Mass, RawBase, RawPhysical};
use crate::AppError;
use bw_models::chain::{ChainBody, ChainSettings, PairLaw, Stop, Walls};
use bw_models::input::Input;
use bw_models::sequence::Policy;
use serde::de::{self, SeqAccess, Visitor};
use serde::{Deserialize, Deserializer};
use std::fmt;
use std::ops::Range;
use std::path::{Path, PathBuf};
use toml::Spanned;

/// A number for every body, or a list with one per body.
#[derive(Debug, Clone)]
enum PerBody<T> {
    All(T),
    Each(Vec<T>),
}

impl<'de> Deserialize<'de> for PerBody<Mass> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = PerBody<Mass>;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a mass in kg or \"inf\", or a list of them")
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<Self::Value, E> {
                Ok(PerBody::All(Mass(v)))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Self::Value, E> {
                Ok(PerBody::All(Mass(v as f64)))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Self::Value, E> {
                Ok(PerBody::All(Mass(v as f64)))
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<Self::Value, E> {
                Mass::deserialize(de::value::StrDeserializer::new(v)).map(PerBody::All)
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Self::Value, A::Error> {
                let mut out = Vec::new();
                while let Some(m) = seq.next_element::<Mass>()? {
                    out.push(m);
                }
                Ok(PerBody::Each(out))
            }
        }
        d.deserialize_any(V)
    }
}

impl<'de> Deserialize<'de> for PerBody<f64> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = PerBody<f64>;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a number, or a list of numbers")
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<Self::Value, E> {
                Ok(PerBody::All(v))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Self::Value, E> {
                Ok(PerBody::All(v as f64))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Self::Value, E> {
                Ok(PerBody::All(v as f64))
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Self::Value, A::Error> {
                let mut out = Vec::new();
                while let Some(x) = seq.next_element::<f64>()? {
                    out.push(x);
                }
                Ok(PerBody::Each(out))
            }
        }
        d.deserialize_any(V)
    }
}

/// The chain scene as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawChainScene {
    model: Option<Spanned<String>>,
    chain: Spanned<RawChain>,
    physical: Option<Spanned<RawPhysical>>,
    base: Option<Spanned<RawBase>>,
    solver: Option<Spanned<RawChainSolver>>,
    output: Option<Spanned<RawChainOutput>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawChain {
    count: Option<Spanned<i64>>,
    mass: Option<Spanned<PerBody<Mass>>>,
    position: Option<Spanned<PerBody<f64>>>,
    gap: Option<Spanned<PerBody<f64>>>,
    velocity: Option<Spanned<PerBody<f64>>>,
    length: Option<Spanned<PerBody<f64>>>,
    g: Option<Num>,
    horizon: Option<Num>,
    until: Option<Spanned<String>>,
    policy: Option<Spanned<String>>,
    body: Option<Vec<Spanned<RawChainBody>>>,
    pair: Option<Vec<Spanned<RawChainPair>>>,
    law: Option<Spanned<RawLaw>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawChainBody {
    mass: Option<Spanned<Mass>>,
    position: Option<Num>,
    gap: Option<Num>,
    velocity: Option<Num>,
    length: Option<Num>,
    input: Option<Spanned<RawInput>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawChainSolver {
    rtol: Option<Num>,
    atol: Option<Num>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawChainOutput {
    dt: Option<Num>,
    plots: Option<Spanned<bool>>,
}

/// A validated `[chain]` scene.
#[derive(Debug, Clone)]
pub struct ChainScene {
    /// The file it came from.
    pub path: PathBuf,
    /// The moving bodies, left to right (walls excluded).
    pub bodies: Vec<ChainBody<Signal>>,
    /// The contact law of every pair, left to right (a left wall's pair first).
    pub laws: Vec<PairLaw>,
    /// The name of each pair's law (`"shccm"`, `"mcm"`, or another element law's).
    pub models: Vec<&'static str>,
    /// The walls.
    pub walls: Walls,
    /// Tolerances and policy.
    pub settings: ChainSettings,
    /// When the run ends.
    pub stop: Stop,
    /// Gravity along `-x` on every body (m/s²), 0 for none.
    pub g: f64,
    /// `[output].dt`: the sampling interval of `chain.csv` (s), if it is written.
    pub dt: Option<f64>,
    /// `[output].plots`: the space-time and ledger figures.
    pub plots: bool,
}

impl ChainScene {
    /// The scene's number of moving body `i` (the bodies as listed, a left wall counted: the
    /// number its outputs carry).
    pub fn body_number(&self, i: usize) -> usize {
        i + usize::from(self.walls.left.is_some())
    }
}

/// Whether the text of a scene describes a chain (has a `[chain]` table).
pub fn is_chain(src: &str) -> bool {
    match src.parse::<toml::Table>() {
        Ok(t) => t.contains_key("chain"),
        // A file with a TOML mistake (a duplicate key) is still a chain scene where it has a
        // `[chain]` table header: its own reader then reports the mistake in its own words.
        Err(_) => src.lines().any(|l| {
            let l = l.trim_start();
            l.starts_with("[chain]") || l.starts_with("[chain.") || l.starts_with("[[chain.")
        }),
    }
}

impl ChainScene {
    /// Reads and validates a chain scene.
    ///
    /// # Errors
    /// As [`crate::impact::scene::Scene::load`].
    pub fn load(path: &Path) -> Result<Self, AppError> {
        Self::parse(path, &read_text(path)?)
    }

    /// Validates a chain scene given as text (`path` only names it in messages).
    ///
    /// # Errors
    /// [`AppError::Syntax`] for TOML errors, wrong types and unknown keys;
    /// [`AppError::Invalid`] naming the line, the key and the body or pair.
    pub fn parse(path: &Path, src: &str) -> Result<Self, AppError> {
        every_error(src, |text| Self::parse_one(path, text))
    }

    fn parse_one(path: &Path, src: &str) -> Result<Self, AppError> {
        let ctx = Ctx { path, src };
        let raw: RawChainScene = toml::from_str(src).map_err(|e| syntax_error(&ctx, &e))?;
        let t = raw.chain.span();
        let c = raw.chain.get_ref();
        let model = raw
            .model
            .as_ref()
            .map(|m| model_kind(&ctx, m, "model"))
            .transpose()?;
        let g = match &c.g {
            Some(g) => ctx.num(g, "[chain].g")?,
            None => 0.0,
        };
        let (bodies, walls) = bodies(&ctx, c, &t, g)?;
        let pairs = bodies.len() - 1
            + usize::from(walls.left.is_some())
            + usize::from(walls.right.is_some());
        let tables = LawTables {
            physical: &raw.physical,
            base: &raw.base,
            pairs: &c.pair,
            law: &c.law,
            chain: t.clone(),
        };
        let (laws, models) = laws(&ctx, &tables, model, &pair_masses(&bodies, walls, pairs))?;
        let settings = settings(&ctx, &raw, c)?;
        let stop = stop(&ctx, c, &t)?;
        let (dt, plots) = output(&ctx, &raw)?;
        let scene = Self {
            path: path.to_owned(),
            bodies,
            laws,
            models,
            walls,
            settings,
            stop,
            g,
            dt,
            plots,
        };
        scene.check(&ctx, &t)?;
        Ok(scene)
    }

    /// The library's own checks (overlaps, masses), reported with the key.
    fn check(&self, ctx: &Ctx, t: &Range<usize>) -> Result<(), AppError> {
        bw_models::chain::Chain::new(
            self.bodies.clone(),
            self.laws.clone(),
            self.walls,
            self.settings,
        )
        .map(|_| ())
        .map_err(|e| ctx.invalid(t, "[chain]", chain_message(&e)))
    }
}

/// A library error about a chain, in the scene's words.
fn chain_message(e: &bw_models::ModelError) -> String {
    match e {
        bw_models::ModelError::InvalidChain {
            part: bw_models::chain::ChainPart::Pair(index),
            name: "gap",
            value,
            ..
        } => format!(
            "pair {index} (between body {index} and the next, walls counted from the left): \
             the bodies overlap by {:e} m; give them a gap >= 0",
            -value
        ),
        other => other.to_string(),
    }
}

/// A list of `n` values of `key` from a number or a list; `None` where the key is missing.
fn per_body<T: Clone>(
    ctx: &Ctx,
    v: &Option<Spanned<PerBody<T>>>,
    n: usize,
    key: &str,
) -> Result<Option<Vec<T>>, AppError> {
    match v {
        None => Ok(None),
        Some(s) => match s.get_ref() {
            PerBody::All(x) => Ok(Some(vec![x.clone(); n])),
            PerBody::Each(list) if list.len() == n => Ok(Some(list.clone())),
            PerBody::Each(list) => Err(ctx.invalid(
                &s.span(),
                key,
                format!(
                    "{} values for {n} bodies: give one per body, or one number for all",
                    list.len()
                ),
            )),
        },
    }
}

/// The number of bodies the arrays give: `count`, or the length of the first list.
fn count(ctx: &Ctx, c: &RawChain, t: &Range<usize>) -> Result<usize, AppError> {
    let empty_masses = c
        .mass
        .as_ref()
        .filter(|m| matches!(m.get_ref(), PerBody::Each(l) if l.is_empty()))
        .map(|m| (m.span(), "mass"));
    let empty = [
        (&c.position, "position"),
        (&c.velocity, "velocity"),
        (&c.length, "length"),
    ]
    .into_iter()
    .find_map(|(v, key)| {
        let s = v.as_ref()?;
        matches!(s.get_ref(), PerBody::Each(l) if l.is_empty()).then(|| (s.span(), key))
    });
    if let Some((s, key)) = empty_masses.or(empty) {
        return Err(ctx.invalid(
            &s,
            format!("[chain].{key}"),
            "an empty list: give one value per body, or one number for all",
        ));
    }
    let lists = [
        c.mass.as_ref().and_then(|m| match m.get_ref() {
            PerBody::Each(l) => Some(l.len()),
            PerBody::All(_) => None,
        }),
        [&c.position, &c.velocity, &c.length]
            .into_iter()
            .find_map(|v| match v.as_ref().map(|s| s.get_ref()) {
                Some(PerBody::Each(l)) => Some(l.len()),
                _ => None,
            }),
    ];
    match (&c.count, lists.into_iter().flatten().next()) {
        (Some(n), _) if *n.get_ref() >= 1 => Ok(*n.get_ref() as usize),
        (Some(n), _) => Err(ctx.invalid(
            &n.span(),
            "[chain].count",
            format!("{} is not admissible: count >= 1", n.get_ref()),
        )),
        (None, Some(n)) => Ok(n),
        (None, None) => Err(ctx.invalid(
            t,
            "[chain].count",
            "missing: the number of bodies (or give mass, position or velocity as lists)",
        )),
    }
}

/// One body as given, before walls are taken out.
struct Given {
    mass: f64,
    position: Option<f64>,
    gap: Option<f64>,
    velocity: f64,
    length: f64,
    input: Signal,
    span: Range<usize>,
    /// Where each value was written, and the key to name (`[chain].gap` for a list,
    /// `[[chain.body]] 2: gap` for a table).
    keys: Keys,
}

/// The place and name of each of a body's values.
#[derive(Clone)]
struct Keys {
    position: (Range<usize>, String),
    gap: (Range<usize>, String),
    velocity: (Range<usize>, String),
    length: (Range<usize>, String),
}

/// The bodies as arrays in `[chain]` or as `[[chain.body]]` tables, not both.
fn given(ctx: &Ctx, c: &RawChain, t: &Range<usize>, g: f64) -> Result<Vec<Given>, AppError> {
    let arrays = [
        span(&c.mass),
        span(&c.position),
        span(&c.gap),
        span(&c.velocity),
        span(&c.length),
        span(&c.count),
    ];
    if let Some(list) = &c.body {
        if let Some(s) = arrays.iter().flatten().next() {
            return Err(ctx.invalid(s, "[chain]", "bodies are given both as [[chain.body]] tables and as lists in [chain]: give one form"));
        }
        return list
            .iter()
            .enumerate()
            .map(|(i, b)| body_table(ctx, b, i, g))
            .collect();
    }
    let n = count(ctx, c, t)?;
    let masses = per_body(ctx, &c.mass, n, "[chain].mass")?.ok_or_else(|| {
        ctx.invalid(
            t,
            "[chain].mass",
            "missing required key (kg, \"inf\" for a wall)",
        )
    })?;
    let velocities = per_body(ctx, &c.velocity, n, "[chain].velocity")?.unwrap_or(vec![0.0; n]);
    let lengths = per_body(ctx, &c.length, n, "[chain].length")?.unwrap_or(vec![0.0; n]);
    let positions = per_body(ctx, &c.position, n, "[chain].position")?;
    let gaps = match &c.gap {
        None => None,
        Some(s) => Some(match s.get_ref() {
            PerBody::All(x) => vec![*x; n.saturating_sub(1)],
            PerBody::Each(l) if l.len() + 1 == n => l.clone(),
            PerBody::Each(l) => {
                return Err(ctx.invalid(&s.span(), "[chain].gap", format!("{} gaps for {n} bodies: give {} (one between each two neighbours), or one number for all", l.len(), n.saturating_sub(1))))
            }
        }),
    };
    let at =
        |v: Option<Range<usize>>, key: &str| (v.unwrap_or(t.clone()), format!("[chain].{key}"));
    let keys = Keys {
        position: at(span(&c.position), "position"),
        gap: at(span(&c.gap), "gap"),
        velocity: at(span(&c.velocity), "velocity"),
        length: at(span(&c.length), "length"),
    };
    Ok((0..n)
        .map(|i| Given {
            mass: masses[i].0,
            position: positions.as_ref().map(|p| p[i]),
            gap: gaps.as_ref().and_then(|gs| i.checked_sub(1).map(|k| gs[k])),
            velocity: velocities[i],
            length: lengths[i],
            input: gravity(masses[i].0, g),
            span: t.clone(),
            keys: keys.clone(),
        })
        .collect())
}

/// `-m g` on a body of mass `m` (none on a wall).
fn gravity(m: f64, g: f64) -> Signal {
    if g == 0.0 || !m.is_finite() {
        Signal::zero()
    } else {
        Signal::Constant(-m * g)
    }
}

/// One `[[chain.body]]` table (body `i`).
fn body_table(ctx: &Ctx, b: &Spanned<RawChainBody>, i: usize, g: f64) -> Result<Given, AppError> {
    let t = b.span();
    let r = b.get_ref();
    let key = |k: &str| format!("[[chain.body]] {i}: {k}");
    let mass = r.mass.as_ref().map(|m| m.get_ref().0).ok_or_else(|| {
        ctx.invalid(
            &t,
            key("mass"),
            "missing required key (kg, \"inf\" for a wall)",
        )
    })?;
    let mut input = gravity(mass, g);
    if let Some(u) = &r.input {
        let own = signal(ctx, u, &key("input"), mass.is_finite().then_some(mass))?;
        input = if input.is_zero() {
            own
        } else {
            Signal::Sum(vec![input, own])
        };
    }
    let at = |v: Option<Range<usize>>, k: &str| (v.unwrap_or(t.clone()), key(k));
    Ok(Given {
        mass,
        position: ctx.opt(&r.position, &key("position"))?,
        gap: ctx.opt(&r.gap, &key("gap"))?,
        velocity: ctx.opt(&r.velocity, &key("velocity"))?.unwrap_or(0.0),
        length: ctx.opt(&r.length, &key("length"))?.unwrap_or(0.0),
        input,
        keys: Keys {
            position: at(span(&r.position), "position"),
            gap: at(span(&r.gap), "gap"),
            velocity: at(span(&r.velocity), "velocity"),
            length: at(span(&r.length), "length"),
        },
        span: t,
    })
}

/// The moving bodies and the walls (end bodies of infinite mass, at rest).
fn bodies(
    ctx: &Ctx,
    c: &RawChain,
    t: &Range<usize>,
    g: f64,
) -> Result<(Vec<ChainBody<Signal>>, Walls), AppError> {
    let given = given(ctx, c, t, g)?;
    let positions = positions(ctx, &given)?;
    let last = given.len() - 1;
    let mut walls = Walls::default();
    let mut bodies = Vec::with_capacity(given.len());
    for (i, (b, x)) in given.into_iter().zip(positions).enumerate() {
        if b.mass.is_nan() || b.mass <= 0.0 {
            return Err(ctx.invalid(
                &b.span,
                format!("[chain] body {i}: mass"),
                format!(
                    "{} is not admissible: mass > 0 (kg), or \"inf\" for a wall at an end",
                    b.mass
                ),
            ));
        }
        if b.mass.is_infinite() {
            if i != 0 && i != last {
                return Err(ctx.invalid(
                    &b.span,
                    format!("[chain] body {i}: mass"),
                    "inf (a wall) is admissible only for the first or the last body",
                ));
            }
            if b.velocity != 0.0 {
                return Err(ctx.invalid(
                    &b.span,
                    format!("[chain] body {i}: velocity"),
                    format!(
                        "{} is not admissible: a wall (mass inf) does not move; give it velocity 0",
                        b.velocity
                    ),
                ));
            }
            if i == 0 {
                walls.left = Some(x + b.length / 2.0);
            } else {
                walls.right = Some(x - b.length / 2.0);
            }
            continue;
        }
        bodies.push(ChainBody::new(b.mass, x, b.velocity, b.length, b.input));
    }
    if bodies.is_empty() {
        return Err(ctx.invalid(
            t,
            "[chain]",
            "no body that moves: walls alone make no chain",
        ));
    }
    if bodies.len() + usize::from(walls.left.is_some()) + usize::from(walls.right.is_some()) < 2 {
        return Err(ctx.invalid(
            t,
            "[chain]",
            "a chain of one body: give at least two bodies, or a wall (mass \"inf\") at an end",
        ));
    }
    Ok((bodies, walls))
}

/// Centres from positions, or from gaps (the first body at 0 unless it has a position).
fn positions(ctx: &Ctx, given: &[Given]) -> Result<Vec<f64>, AppError> {
    let by_gap = given.iter().skip(1).any(|b| b.gap.is_some());
    let mut out = Vec::with_capacity(given.len());
    for (i, b) in given.iter().enumerate() {
        check_values(ctx, b, i)?;
        let x =
            match (b.position, b.gap, i) {
                (Some(_), Some(_), _) => {
                    return Err(ctx.invalid(
                        &b.span,
                        format!("[chain] body {i}"),
                        "both a position and a gap: give one",
                    ))
                }
                (Some(x), None, _) if !by_gap || i == 0 => x,
                (None, None, 0) => 0.0,
                (None, Some(gap), i) if i > 0 => {
                    let prev = &given[i - 1];
                    out[i - 1] + prev.length / 2.0 + gap + b.length / 2.0
                }
                _ => return Err(ctx.invalid(
                    &b.span,
                    format!("[chain] body {i}: position"),
                    "missing: give every body a position, or every body after the first a gap (m)",
                )),
            };
        if !x.is_finite() {
            let (s, key) = &b.keys.gap;
            return Err(ctx.invalid(
                s,
                key,
                format!("body {i}'s position from the gaps is {x}: give gaps that sum to a finite length (m)"),
            ));
        }
        out.push(x);
    }
    Ok(out)
}

/// Body `i`'s own values, each against its admissible set and named by its key: a finite
/// position, a finite gap >= 0 (m), a finite velocity (m/s), a finite length >= 0 (m).
fn check_values(ctx: &Ctx, b: &Given, i: usize) -> Result<(), AppError> {
    let checks = [
        (b.position, &b.keys.position, true, "a finite position (m)"),
        (
            b.gap,
            &b.keys.gap,
            false,
            "a finite gap >= 0 (m): neighbours may touch but not overlap",
        ),
        (
            Some(b.velocity),
            &b.keys.velocity,
            true,
            "a finite velocity (m/s)",
        ),
        (
            Some(b.length),
            &b.keys.length,
            false,
            "a finite length >= 0 (m)",
        ),
    ];
    for (value, (s, key), signed, allowed) in checks {
        let Some(v) = value else { continue };
        if !v.is_finite() || (!signed && v < 0.0) {
            return Err(ctx.invalid(
                s,
                key,
                format!("body {i}: {v} is not admissible: {allowed}"),
            ));
        }
    }
    Ok(())
}

/// Each pair's effective mass (kg): `m_l m_r / (m_l + m_r)`, or the body's mass against a
/// wall.
fn pair_masses(bodies: &[ChainBody<Signal>], walls: Walls, pairs: usize) -> Vec<f64> {
    let shift = usize::from(walls.left.is_some());
    (0..pairs)
        .map(|j| {
            let left = (j >= shift).then(|| bodies[j - shift].mass);
            let right = bodies.get(j + 1 - shift).map(|b| b.mass);
            match (left, right) {
                (Some(a), Some(b)) => a * b / (a + b),
                (Some(m), None) | (None, Some(m)) => m,
                (None, None) => f64::NAN,
            }
        })
        .collect()
}

/// Tolerances from `[solver]` and the policy from `[chain]`.
fn settings(ctx: &Ctx, raw: &RawChainScene, c: &RawChain) -> Result<ChainSettings, AppError> {
    let mut s = ChainSettings::default();
    if let Some(solver) = &raw.solver {
        let r = solver.get_ref();
        // The floors of a single impact's [solver]: no tolerance below the double's rounding.
        let checks = [
            (
                &r.rtol,
                "[solver].rtol",
                f64::EPSILON,
                "finite and > 2.2e-16",
            ),
            (&r.atol, "[solver].atol", 0.0, "finite and > 0 (m)"),
        ];
        for (v, key, floor, allowed) in checks {
            if let Some(x) = ctx.opt(v, key)?.filter(|x| !(*x > floor && x.is_finite())) {
                return Err(ctx.invalid(
                    &span(v).unwrap_or(solver.span()),
                    key,
                    format!("{x:e} is not admissible: {allowed}"),
                ));
            }
        }
        s = s.with_tolerances(
            ctx.opt(&r.rtol, "[solver].rtol")?.unwrap_or(s.rtol),
            ctx.opt(&r.atol, "[solver].atol")?.unwrap_or(s.atol),
        );
    }
    let policy = match c.policy.as_ref().map(|p| (p.get_ref().as_str(), p.span())) {
        None | Some(("reset", _)) => Policy::Reset,
        Some(("carry", _)) => Policy::Carry,
        Some((other, s)) => {
            return Err(ctx.invalid(
                &s,
                "[chain].policy",
                format!("\"{other}\" is not a policy: \"reset\" or \"carry\""),
            ))
        }
    };
    Ok(s.with_policy(policy))
}

/// `[chain].horizon` and `[chain].until`.
fn stop(ctx: &Ctx, c: &RawChain, t: &Range<usize>) -> Result<Stop, AppError> {
    let horizon = ctx.req(&c.horizon, t, "[chain].horizon")?;
    if horizon <= 0.0 {
        return Err(ctx.invalid(
            &span(&c.horizon).unwrap_or(t.clone()),
            "[chain].horizon",
            format!("{horizon} is not admissible: > 0 (s)"),
        ));
    }
    match c.until.as_ref().map(|u| (u.get_ref().as_str(), u.span())) {
        None | Some(("settled", _)) => Ok(Stop::settled(horizon)),
        Some(("horizon", _)) => Ok(Stop::at(horizon)),
        Some((other, s)) => Err(ctx.invalid(&s, "[chain].until", format!("\"{other}\" is not admissible: \"settled\" (all contacts ended and no gap closing, or the horizon) or \"horizon\""))),
    }
}

/// `[output].dt` and `[output].plots`.
fn output(ctx: &Ctx, raw: &RawChainScene) -> Result<(Option<f64>, bool), AppError> {
    let Some(o) = &raw.output else {
        return Ok((None, false));
    };
    let r = o.get_ref();
    let dt = ctx.opt(&r.dt, "[output].dt")?;
    if let Some(dt) = dt.filter(|dt| *dt <= 0.0) {
        return Err(ctx.invalid(
            &span(&r.dt).unwrap_or(o.span()),
            "[output].dt",
            format!("{dt} is not admissible: > 0 (s)"),
        ));
    }
    let plots = r.plots.as_ref().is_some_and(|p| *p.get_ref());
    if plots && dt.is_none() {
        return Err(ctx.invalid(
            &o.span(),
            "[output].dt",
            "missing: the figures plot the samples of chain.csv, taken every dt (s)",
        ));
    }
    Ok((dt, plots))
}
