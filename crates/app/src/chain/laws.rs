//! The contact laws of a `[chain]` scene's pairs: one for every pair in `[physical]`,
//! `[base]` or `[chain.law]`, or one per pair in `[[chain.pair]]`, each given by its SI keys,
//! by base parameters `P*`, or as any registered element law by name (`law = { model =
//! "thornton", k = ..., delta_y = ... }`).
//!
//! A law in base parameters is the one under which its pair, alone, has the CoR and duration
//! that `P*` gives: the law of [`BaseMap::physical`] with `U_b = T_b / m`, `m` the pair's
//! effective mass (`m_l m_r / (m_l + m_r)`, or the body's mass against a wall). `T_b` (default 1)
//! sets the contact's time scale; CoR data alone leave it open.

use crate::tables::{contact_law, model_kind, span, Ctx, Num};
use crate::tables::{RawBase, RawPhysical};
use crate::AppError;
use bw_models::chain::PairLaw;
use bw_models::{BaseMap, BaseParams, ModelError, ModelKind};
use serde::Deserialize;
use std::collections::BTreeMap;
use std::ops::Range;
use toml::Spanned;

/// A `[[chain.pair]]` table: a model and either the SI keys or the base parameters.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawChainPair {
    model: Option<Spanned<String>>,
    k: Option<Num>,
    c: Option<Num>,
    n: Option<Num>,
    p: Option<Num>,
    alpha: Option<Num>,
    beta: Option<Num>,
    gamma: Option<Num>,
    #[serde(rename = "A")]
    a: Option<Num>,
    #[serde(rename = "B_b")]
    b_b: Option<Num>,
    #[serde(rename = "Gamma_b")]
    gamma_b: Option<Num>,
    kappa: Option<Num>,
    sigma_b: Option<Num>,
    #[serde(rename = "T_b")]
    t_b: Option<Num>,
    law: Option<Spanned<RawLaw>>,
}

/// A law by name: `model` (a registered element law) and its SI parameters by name.
pub(super) type RawLaw = BTreeMap<String, Spanned<toml::Value>>;

/// Where a scene's laws are given.
pub(super) struct LawTables<'a> {
    pub(super) physical: &'a Option<Spanned<RawPhysical>>,
    pub(super) base: &'a Option<Spanned<RawBase>>,
    pub(super) pairs: &'a Option<Vec<Spanned<RawChainPair>>>,
    /// `[chain.law]`: a law by name for every pair.
    pub(super) law: &'a Option<Spanned<RawLaw>>,
    /// The `[chain]` table's span.
    pub(super) chain: Range<usize>,
}

/// Base parameters as read from a table, `U_b` to come from the pair's mass.
struct Base<'a> {
    table: String,
    span: Range<usize>,
    fields: [&'a Option<Num>; 7],
}

const BASE_KEYS: [&str; 7] = ["B_b", "Gamma_b", "kappa", "sigma_b", "n", "p", "T_b"];

impl Base<'_> {
    /// The law of pair mass `m` (kg) for `kind`.
    fn law(&self, ctx: &Ctx, kind: ModelKind, m: f64) -> Result<PairLaw, AppError> {
        let mut v = [0.0; 6];
        for (value, (field, key)) in v.iter_mut().zip(self.fields.iter().zip(BASE_KEYS)) {
            *value = ctx.req(field, &self.span, &format!("{}.{key}", self.table))?;
        }
        let t_b = ctx
            .opt(self.fields[6], &format!("{}.T_b", self.table))?
            .unwrap_or(1.0);
        let [b_b, gamma_b, kappa, sigma_b, n, p] = v;
        let base = BaseParams {
            b_b,
            gamma_b,
            kappa,
            sigma_b,
            n,
            p,
            u_b: t_b / m,
            t_b,
        };
        let span_of = |name: &str| {
            BASE_KEYS
                .iter()
                .position(|k| *k == name)
                .and_then(|i| span(self.fields[i]))
        };
        let error = |e| ctx.model_error(e, &self.table, span_of, &self.span);
        let (params, _) = BaseMap::new(kind, base)
            .and_then(|map| map.physical())
            .map_err(error)?;
        PairLaw::new(&params).map_err(error)
    }
}

/// The law of every pair (`masses`: each pair's effective mass, kg) and its model, from
/// `[physical]` or `[base]` for all, or `[[chain.pair]]` one per pair.
///
/// # Errors
/// [`AppError::Invalid`] naming the table and key: no law or two forms of it, a count of
/// `[[chain.pair]]` tables other than the pairs', a missing model, SI keys beside base
/// parameters, `[physical].m` or `[base].U_b` (the bodies give the masses), or a law the
/// model does not admit.
pub(super) fn laws(
    ctx: &Ctx,
    tables: &LawTables<'_>,
    model: Option<ModelKind>,
    masses: &[f64],
) -> Result<(Vec<PairLaw>, Vec<&'static str>), AppError> {
    let pairs = masses.len();
    if let Some(law) = tables.law {
        if tables.physical.is_some() || tables.base.is_some() || tables.pairs.is_some() {
            return Err(ctx.invalid(&law.span(), "[chain.law]", "beside [physical], [base] or [[chain.pair]]: give one law for all pairs, or one per pair"));
        }
        let law = named_law(ctx, "[chain.law]", law)?;
        return Ok((vec![law; pairs], vec![law.spec().name; pairs]));
    }
    match (tables.physical, tables.base, tables.pairs) {
        (Some(p), None, None) => {
            let (t, r) = (p.span(), p.get_ref());
            if let Some(m) = &r.m {
                return Err(ctx.invalid(&m.span(), "[physical].m", "not used in a chain: each pair's bodies give its masses"));
            }
            let kind = kind_of(ctx, &None, model, &t, "model")?;
            let fields = [&r.k, &r.c, &r.n, &r.p, &r.alpha, &r.beta, &r.gamma, &r.a];
            let (_, params) = contact_law(ctx, "[physical]", &t, fields, kind)?;
            let law = PairLaw::new(&params).map_err(|e| ctx.invalid(&t, "[physical]", e.to_string()))?;
            Ok((vec![law; pairs], vec![kind.name(); pairs]))
        }
        (None, Some(b), None) => {
            let (t, r) = (b.span(), b.get_ref());
            if let Some(u) = &r.u_b {
                return Err(ctx.invalid(&u.span(), "[base].U_b", "not used in a chain: U_b = T_b / m with m each pair's effective mass"));
            }
            if let Some(name) = &r.name {
                return Err(ctx.invalid(&name.span(), "[base].name", "not used in a chain"));
            }
            let kind = kind_of(ctx, &r.model, model, &t, "[base].model")?;
            let base = Base {
                table: "[base]".into(),
                span: t,
                fields: [&r.b_b, &r.gamma_b, &r.kappa, &r.sigma_b, &r.n, &r.p, &r.t_b],
            };
            let laws = masses.iter().map(|&m| base.law(ctx, kind, m)).collect::<Result<_, _>>()?;
            Ok((laws, vec![kind.name(); pairs]))
        }
        (None, None, Some(list)) => {
            if list.len() != pairs {
                let s = list.first().map_or(tables.chain.clone(), |p| p.span());
                return Err(ctx.invalid(&s, "[[chain.pair]]", format!("{} laws for {pairs} pairs (neighbouring bodies, walls included): give one per pair, or one law for all in [physical] or [base]", list.len())));
            }
            let mut laws = Vec::with_capacity(pairs);
            let mut names = Vec::with_capacity(pairs);
            for (j, (p, &m)) in list.iter().zip(masses).enumerate() {
                let law = pair_law(ctx, p, j, m, model)?;
                names.push(law.spec().name);
                laws.push(law);
            }
            Ok((laws, names))
        }
        (None, None, None) => Err(ctx.invalid(&tables.chain, "[physical]", "missing: the contact law, one for all pairs in [physical], [base] or [chain.law], or one per pair in [[chain.pair]]")),
        _ => {
            let s = tables.physical.as_ref().map(|p| p.span()).or(tables.base.as_ref().map(|b| b.span())).unwrap_or(tables.chain.clone());
            Err(ctx.invalid(&s, "[physical]", "more than one of [physical], [base] and [[chain.pair]]: give one law for all pairs, or one per pair"))
        }
    }
}

/// The law of `[[chain.pair]]` number `j` (effective mass `m`, kg), in SI keys, base
/// parameters, or by name (`law`).
fn pair_law(
    ctx: &Ctx,
    p: &Spanned<RawChainPair>,
    j: usize,
    m: f64,
    model: Option<ModelKind>,
) -> Result<PairLaw, AppError> {
    let (t, r) = (p.span(), p.get_ref());
    let table = format!("[[chain.pair]] {j}");
    if let Some(law) = &r.law {
        let others = [
            &r.k, &r.c, &r.n, &r.p, &r.alpha, &r.beta, &r.gamma, &r.a, &r.b_b,
        ]
        .iter()
        .any(|f| f.is_some())
            || r.gamma_b.is_some()
            || r.kappa.is_some()
            || r.sigma_b.is_some()
            || r.t_b.is_some()
            || r.model.is_some();
        if others {
            return Err(ctx.invalid(&t, table, "both `law` and the law's keys beside it: give the law in one form (its model and parameters inside `law = { ... }`)"));
        }
        return named_law(ctx, &format!("{table}.law"), law);
    }
    let kind = kind_of(ctx, &r.model, model, &t, &format!("{table}: model"))?;
    let si = [&r.k, &r.c, &r.alpha, &r.beta, &r.gamma, &r.a];
    let base = [&r.b_b, &r.gamma_b, &r.kappa, &r.sigma_b, &r.t_b];
    let given = |fields: &[&Option<Num>]| fields.iter().any(|f| f.is_some());
    if given(&si) && given(&base) {
        return Err(ctx.invalid(&t, table, "both SI keys (k, c, alpha, beta, gamma, A) and base parameters (B_b, Gamma_b, kappa, sigma_b, T_b): give one form"));
    }
    if given(&base) {
        let base = Base {
            table,
            span: t,
            fields: [&r.b_b, &r.gamma_b, &r.kappa, &r.sigma_b, &r.n, &r.p, &r.t_b],
        };
        return base.law(ctx, kind, m);
    }
    let fields = [&r.k, &r.c, &r.n, &r.p, &r.alpha, &r.beta, &r.gamma, &r.a];
    let (_, params) = contact_law(ctx, &table, &t, fields, kind)?;
    PairLaw::new(&params).map_err(|e| ctx.invalid(&t, table.clone(), e.to_string()))
}

/// A law by name (`table` names it in messages): `model`, a registered element law, and its
/// parameters, each a number under its own name.
fn named_law(ctx: &Ctx, table: &str, raw: &Spanned<RawLaw>) -> Result<PairLaw, AppError> {
    let (t, map) = (raw.span(), raw.get_ref());
    let Some(model) = map.get("model") else {
        return Err(ctx.invalid(
            &t,
            format!("{table}.model"),
            "missing: the law's name, one of the element laws (\"shccm\", \"thornton\", ...)",
        ));
    };
    let Some(name) = model.get_ref().as_str() else {
        return Err(ctx.invalid(
            &model.span(),
            format!("{table}.model"),
            "not a string: the law's name",
        ));
    };
    let mut params = Vec::with_capacity(map.len());
    for (key, value) in map.iter().filter(|(k, _)| k.as_str() != "model") {
        let x = match value.get_ref() {
            toml::Value::Float(x) => *x,
            toml::Value::Integer(i) => *i as f64,
            _ => return Err(ctx.invalid(&value.span(), format!("{table}.{key}"), "not a number")),
        };
        params.push((key.as_str(), x));
    }
    PairLaw::of_law(name, &params).map_err(|e| {
        let at = |key: &str| map.get(key).map_or(t.clone(), |v| v.span());
        match e {
            ModelError::InvalidParameter {
                name: key,
                value,
                allowed,
            } => ctx.invalid(
                &at(key),
                format!("{table}.{key}"),
                format!("{value} is not admissible: {allowed}"),
            ),
            ModelError::UnknownName { law, ref name, .. } => {
                // An unknown law is its `model`'s; an unknown or missing parameter its own.
                let key = if law.is_empty() {
                    "model"
                } else {
                    name.as_ref()
                };
                ctx.invalid(&at(key), format!("{table}.{key}"), e.to_string())
            }
            e => ctx.invalid(&t, table.to_string(), e.to_string()),
        }
    })
}

/// A table's model: its own `given`, else the scene's `model`.
fn kind_of(
    ctx: &Ctx,
    given: &Option<Spanned<String>>,
    model: Option<ModelKind>,
    table: &Range<usize>,
    key: &str,
) -> Result<ModelKind, AppError> {
    match given {
        Some(m) => model_kind(ctx, m, key),
        None => model.ok_or_else(|| {
            ctx.invalid(
                table,
                key,
                "missing: the model of the law, \"shccm\" or \"mcm\" (or the scene's model)",
            )
        }),
    }
}
