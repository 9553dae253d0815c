//! The contact laws of a `[chain]` scene's pairs: one for every pair in `[physical]` or
//! `[base]`, or one per pair in `[[chain.pair]]`, each given by its SI keys or by base
//! parameters `P*`.
//!
//! A law in base parameters is the one under which its pair, alone, has the CoR and duration
//! that `P*` gives: the law of [`BaseMap::physical`] with `U_b = T_b / m`, `m` the pair's
//! effective mass (`m_l m_r / (m_l + m_r)`, or the body's mass against a wall). `T_b` (default 1)
//! sets the contact's time scale; CoR data alone leave it open.

use crate::tables::{contact_law, model_kind, span, Ctx, Num};
use crate::tables::{RawBase, RawPhysical};
use crate::AppError;
use bw_models::chain::PairLaw;
use bw_models::{BaseMap, BaseParams, ModelKind};
use serde::Deserialize;
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
}

/// Where a scene's laws are given.
pub(super) struct LawTables<'a> {
    pub(super) physical: &'a Option<Spanned<RawPhysical>>,
    pub(super) base: &'a Option<Spanned<RawBase>>,
    pub(super) pairs: &'a Option<Vec<Spanned<RawChainPair>>>,
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
) -> Result<(Vec<PairLaw>, Vec<ModelKind>), AppError> {
    let pairs = masses.len();
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
            Ok((vec![law; pairs], vec![kind; pairs]))
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
            Ok((laws, vec![kind; pairs]))
        }
        (None, None, Some(list)) => {
            if list.len() != pairs {
                let s = list.first().map_or(tables.chain.clone(), |p| p.span());
                return Err(ctx.invalid(&s, "[[chain.pair]]", format!("{} laws for {pairs} pairs (neighbouring bodies, walls included): give one per pair, or one law for all in [physical] or [base]", list.len())));
            }
            let mut laws = Vec::with_capacity(pairs);
            let mut kinds = Vec::with_capacity(pairs);
            for (j, (p, &m)) in list.iter().zip(masses).enumerate() {
                let (law, kind) = pair_law(ctx, p, j, m, model)?;
                laws.push(law);
                kinds.push(kind);
            }
            Ok((laws, kinds))
        }
        (None, None, None) => Err(ctx.invalid(&tables.chain, "[physical]", "missing: the contact law, one for all pairs in [physical] or [base], or one per pair in [[chain.pair]]")),
        _ => {
            let s = tables.physical.as_ref().map(|p| p.span()).or(tables.base.as_ref().map(|b| b.span())).unwrap_or(tables.chain.clone());
            Err(ctx.invalid(&s, "[physical]", "more than one of [physical], [base] and [[chain.pair]]: give one law for all pairs, or one per pair"))
        }
    }
}

/// The law of `[[chain.pair]]` number `j` (effective mass `m`, kg), in SI keys or base
/// parameters.
fn pair_law(
    ctx: &Ctx,
    p: &Spanned<RawChainPair>,
    j: usize,
    m: f64,
    model: Option<ModelKind>,
) -> Result<(PairLaw, ModelKind), AppError> {
    let (t, r) = (p.span(), p.get_ref());
    let table = format!("[[chain.pair]] {j}");
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
        return Ok((base.law(ctx, kind, m)?, kind));
    }
    let fields = [&r.k, &r.c, &r.n, &r.p, &r.alpha, &r.beta, &r.gamma, &r.a];
    let (_, params) = contact_law(ctx, &table, &t, fields, kind)?;
    let law = PairLaw::new(&params).map_err(|e| ctx.invalid(&t, table.clone(), e.to_string()))?;
    Ok((law, kind))
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
