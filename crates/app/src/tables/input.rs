//! `[input]`-like tables: the external force on the contact or on one body.

use super::context::{span, Ctx, Num};
use crate::signal::Signal;
use crate::AppError;
use bw_models::input::{Arctan, Table};
use serde::Deserialize;
use toml::Spanned;

/// An input signal: `kind` and the keys that kind takes.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawInput {
    pub kind: Option<Spanned<String>>,
    pub value: Option<Num>,
    pub m: Option<Num>,
    pub g: Option<Num>,
    #[serde(rename = "D")]
    pub d: Option<Num>,
    pub omega: Option<Num>,
    pub points: Option<Spanned<Vec<Vec<Num>>>>,
    pub terms: Option<Vec<Spanned<RawInput>>>,
}

/// The signal of an input table `table` (`default_m`: the mass a force acts on where the table
/// does not give one).
pub(crate) fn signal(
    ctx: &Ctx,
    raw: &Spanned<RawInput>,
    table: &str,
    default_m: Option<f64>,
) -> Result<Signal, AppError> {
    let t = raw.span();
    let r = raw.get_ref();
    let kind = r.kind.as_ref().ok_or_else(|| {
        ctx.invalid(
            &t,
            format!("{table}.kind"),
            "missing: constant, gravity, arctan, table or sum",
        )
    })?;
    only_its_keys(ctx, raw, table, kind)?;
    let mass = || -> Result<f64, AppError> {
        let m = match ctx.opt(&r.m, &format!("{table}.m"))? {
            Some(m) => m,
            None => default_m.ok_or_else(|| {
                ctx.invalid(
                    &t,
                    format!("{table}.m"),
                    "missing: the mass this force acts on (kg)",
                )
            })?,
        };
        if m > 0.0 {
            Ok(m)
        } else {
            Err(ctx.invalid(
                &span(&r.m).unwrap_or(t.clone()),
                format!("{table}.m"),
                format!("{m} is not admissible: m > 0 (kg)"),
            ))
        }
    };
    Ok(match kind.get_ref().as_str() {
        "constant" => Signal::Constant(ctx.req(&r.value, &t, &format!("{table}.value"))?),
        "gravity" => {
            let g = ctx.opt(&r.g, &format!("{table}.g"))?.unwrap_or(9.81);
            Signal::Constant(-mass()? * g)
        }
        "arctan" => Signal::Arctan(Arctan {
            m: mass()?,
            d: ctx.req(&r.d, &t, &format!("{table}.D"))?,
            omega: ctx.req(&r.omega, &t, &format!("{table}.omega"))?,
        }),
        "table" => Signal::Table(points(ctx, raw, table)?),
        _ => {
            let terms = r.terms.as_ref().ok_or_else(|| {
                ctx.invalid(&t, format!("{table}.terms"), "missing: a list of inputs")
            })?;
            Signal::Sum(
                terms
                    .iter()
                    .map(|term| signal(ctx, term, &format!("{table}.terms"), default_m))
                    .collect::<Result<_, _>>()?,
            )
        }
    })
}

/// An error for an unknown `kind`, or for a key that this kind does not take.
fn only_its_keys(
    ctx: &Ctx,
    raw: &Spanned<RawInput>,
    table: &str,
    kind: &Spanned<String>,
) -> Result<(), AppError> {
    let r = raw.get_ref();
    let allowed: &[&str] = match kind.get_ref().as_str() {
        "constant" => &["value"],
        "gravity" => &["m", "g"],
        "arctan" => &["m", "D", "omega"],
        "table" => &["points"],
        "sum" => &["terms"],
        other => {
            return Err(ctx.invalid(
                &kind.span(),
                format!("{table}.kind"),
                format!(
                    "\"{other}\" is not an input kind: use \"constant\", \"gravity\", \"arctan\", \
                     \"table\" or \"sum\""
                ),
            ))
        }
    };
    let present = [
        ("value", span(&r.value)),
        ("m", span(&r.m)),
        ("g", span(&r.g)),
        ("D", span(&r.d)),
        ("omega", span(&r.omega)),
        ("points", span(&r.points)),
        ("terms", r.terms.as_ref().map(|_| raw.span())),
    ];
    for (key, s) in present {
        if let Some(s) = s.filter(|_| !allowed.contains(&key)) {
            return Err(ctx.invalid(
                &s,
                format!("{table}.{key}"),
                format!(
                    "does not apply to kind \"{}\" (it takes {})",
                    kind.get_ref(),
                    allowed.join(", ")
                ),
            ));
        }
    }
    Ok(())
}

/// The table of a `kind = "table"` input: `points = [[t, u], ...]`.
fn points(ctx: &Ctx, raw: &Spanned<RawInput>, table: &str) -> Result<Table, AppError> {
    let pts = raw.get_ref().points.as_ref().ok_or_else(|| {
        ctx.invalid(
            &raw.span(),
            format!("{table}.points"),
            "missing: [[t, u], ...]",
        )
    })?;
    let mut points = Vec::with_capacity(pts.get_ref().len());
    for p in pts.get_ref() {
        if p.len() != 2 {
            return Err(ctx.invalid(
                &pts.span(),
                format!("{table}.points"),
                "each point is [t, u]",
            ));
        }
        points.push((
            ctx.num(&p[0], &format!("{table}.points"))?,
            ctx.num(&p[1], &format!("{table}.points"))?,
        ));
    }
    Table::new(&points)
        .map_err(|e| ctx.invalid(&pts.span(), format!("{table}.points"), e.to_string()))
}
