//! `[bodies]`: two bodies, each with its own input.

use super::raw;
use crate::signal::Signal;
use crate::tables::{signal, span, Ctx};
use crate::AppError;
use bw_models::Bodies;
use toml::Spanned;

pub(super) fn bodies(
    ctx: &Ctx,
    b: &Spanned<raw::RawBodies>,
) -> Result<Bodies<Signal, Signal>, AppError> {
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
