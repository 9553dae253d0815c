//! `[solver]`-like tables: the integrator and its tolerances.

use super::context::{span, Ctx, Num};
use crate::AppError;
use bw_models::{Settings, Stiffness};
use bwc_ode::{DOP853, DOPRI5, VERN7, VERN9};
use serde::Deserialize;
use toml::Spanned;

/// `[solver]`: method, tolerances, limits.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawSolver {
    pub method: Option<Spanned<String>>,
    pub rtol: Option<Num>,
    pub atol: Option<Num>,
    pub max_step: Option<Num>,
    pub t_max: Option<Num>,
    pub max_steps: Option<Spanned<i64>>,
    pub stop_at_kinks: Option<Spanned<bool>>,
    pub switch_when_stiff: Option<Spanned<bool>>,
    pub series: Option<Spanned<bool>>,
    pub e_tol: Option<Num>,
    pub double_double: Option<Spanned<bool>>,
    pub phase: Option<Spanned<bool>>,
}

/// Parses a `[solver]`-like table (`method`, `rtol`, `atol`, `max_step`, `t_max`, `max_steps`,
/// `stop_at_kinks`, `switch_when_stiff`, `series`, `e_tol`: 0 for one run at `rtol`,
/// `double_double`, `phase`) over `defaults`.
pub(crate) fn solver_settings(
    ctx: &Ctx,
    table: &Option<Spanned<RawSolver>>,
    name: &str,
    defaults: Settings,
) -> Result<Settings, AppError> {
    let mut s = defaults;
    let Some(sv) = table else { return Ok(s) };
    let r = sv.get_ref();
    let key = |k: &str| format!("{name}.{k}");
    if let Some(m) = &r.method {
        set_method(ctx, m, &key("method"), &mut s)?;
    }
    if let Some(v) = &r.switch_when_stiff {
        if s.stiffness != Stiffness::Rosenbrock {
            s.stiffness = if *v.get_ref() {
                Stiffness::Switch
            } else {
                Stiffness::Ignore
            };
        }
    }
    if let Some(v) = ctx.opt(&r.rtol, &key("rtol"))? {
        s.rtol = v;
    }
    if let Some(v) = ctx.opt(&r.atol, &key("atol"))? {
        s.atol = v;
    }
    if let Some(v) = &r.max_step {
        s.max_step = *v.get_ref();
    }
    if let Some(v) = ctx.opt(&r.t_max, &key("t_max"))? {
        s.t_max = v;
    }
    if let Some(v) = &r.max_steps {
        if *v.get_ref() < 1 {
            return Err(ctx.invalid(
                &v.span(),
                key("max_steps"),
                format!("{} is not admissible: >= 1", v.get_ref()),
            ));
        }
        s.max_steps = *v.get_ref() as u64;
    }
    if let Some(v) = &r.stop_at_kinks {
        s.stop_at_kinks = *v.get_ref();
    }
    if let Some(v) = &r.series {
        s.series = *v.get_ref();
    }
    if let Some(v) = &r.double_double {
        s.double_double = *v.get_ref();
    }
    if let Some(v) = &r.phase {
        s.phase = *v.get_ref();
    }
    if let Some(v) = ctx.opt(&r.e_tol, &key("e_tol"))? {
        s.e_tol = (v != 0.0).then_some(v);
    }
    s.validate().map_err(|e| {
        let span_of = |n: &str| match n {
            "rtol" => span(&r.rtol),
            "atol" => span(&r.atol),
            "max_step" => span(&r.max_step),
            "t_max" => span(&r.t_max),
            "e_tol" => span(&r.e_tol),
            _ => None,
        };
        ctx.model_error(e, name, span_of, &sv.span())
    })?;
    Ok(s)
}

/// Sets the Runge-Kutta method of `s` (or Rosenbrock throughout) from its name in `[solver]`.
fn set_method(ctx: &Ctx, m: &Spanned<String>, key: &str, s: &mut Settings) -> Result<(), AppError> {
    match m.get_ref().as_str() {
        "dopri5" => s.method = &DOPRI5,
        "dop853" => s.method = &DOP853,
        "vern7" => s.method = &VERN7,
        "vern9" => s.method = &VERN9,
        "rosenbrock" => s.stiffness = Stiffness::Rosenbrock,
        other => {
            return Err(ctx.invalid(
                &m.span(),
                key,
                format!(
                "\"{other}\": use \"dopri5\", \"dop853\", \"vern7\", \"vern9\" or \"rosenbrock\""
            ),
            ))
        }
    }
    Ok(())
}
