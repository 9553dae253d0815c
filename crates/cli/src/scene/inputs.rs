//! The inputs of a scene: `[input]`-like tables (the external force on the contact or on one
//! body) and `[bodies]` (two bodies, each with its own input).

use super::{raw, span, Ctx};
use crate::signal::Signal;
use crate::CliError;
use bw_models::input::{Arctan, Table};
use bw_models::Bodies;
use raw::RawInput;
use toml::Spanned;

pub(super) fn bodies(
    ctx: &Ctx,
    b: &Spanned<raw::RawBodies>,
) -> Result<Bodies<Signal, Signal>, CliError> {
    let t = b.span();
    let r = b.get_ref();
    let m1 = ctx.req(&r.m1, &t, "[bodies].m1")?;
    let m2 = match &r.m2 {
        Some(m) if m.get_ref().0.is_nan() => {
            return Err(ctx.invalid(&m.span(), "[bodies].m2", "NaN is not a mass"))
        }
        Some(m) => m.get_ref().0,
        None => {
            return Err(ctx.invalid(
                &t,
                "[bodies].m2",
                "missing required key (a mass in kg or \"inf\")",
            ))
        }
    };
    let u1 =
        r.u1.as_ref()
            .map(|u| signal(ctx, u, "[bodies.u1]", Some(m1)))
            .transpose()?
            .unwrap_or_else(Signal::zero);
    let u2 =
        r.u2.as_ref()
            .map(|u| signal(ctx, u, "[bodies.u2]", m2.is_finite().then_some(m2)))
            .transpose()?
            .unwrap_or_else(Signal::zero);
    let (v1, v2) = (
        ctx.req(&r.v1, &t, "[bodies].v1")?,
        ctx.req(&r.v2, &t, "[bodies].v2")?,
    );
    let (l1, l2) = (
        ctx.opt(&r.l1, "[bodies].l1")?.unwrap_or(0.0),
        ctx.opt(&r.l2, "[bodies].l2")?.unwrap_or(0.0),
    );
    Bodies::new(m1, m2, v1, v2, l1, l2, u1, u2).map_err(|e| {
        let span_of = |name: &str| match name {
            "m1" => span(&r.m1),
            "m2" => span(&r.m2),
            "v1" | "v0" => span(&r.v1),
            "v2" => span(&r.v2),
            "l1" => span(&r.l1),
            "l2" => span(&r.l2),
            _ => None,
        };
        ctx.model_error(e, "[bodies]", span_of, &t)
    })
}

pub(crate) fn signal(
    ctx: &Ctx,
    raw: &Spanned<RawInput>,
    table: &str,
    default_m: Option<f64>,
) -> Result<Signal, CliError> {
    let t = raw.span();
    let r = raw.get_ref();
    let kind = r.kind.as_ref().ok_or_else(|| {
        ctx.invalid(
            &t,
            format!("{table}.kind"),
            "missing: constant, gravity, arctan, table or sum",
        )
    })?;
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
                format!("\"{other}\": use constant, gravity, arctan, table or sum"),
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
        ("terms", r.terms.as_ref().map(|_| t.clone())),
    ];
    for (key, s) in present {
        if let Some(s) = s {
            if !allowed.contains(&key) {
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
    }
    let mass = |ctx: &Ctx| -> Result<f64, CliError> {
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
            Signal::Constant(-mass(ctx)? * g)
        }
        "arctan" => Signal::Arctan(Arctan {
            m: mass(ctx)?,
            d: ctx.req(&r.d, &t, &format!("{table}.D"))?,
            omega: ctx.req(&r.omega, &t, &format!("{table}.omega"))?,
        }),
        "table" => {
            let pts = r.points.as_ref().ok_or_else(|| {
                ctx.invalid(&t, format!("{table}.points"), "missing: [[t, u], ...]")
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
            Signal::Table(
                Table::new(&points).map_err(|e| {
                    ctx.invalid(&pts.span(), format!("{table}.points"), e.to_string())
                })?,
            )
        }
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
