//! A `[[fit]]` of a contact-law family (`model = "hunt-crossley"` or another of
//! [`bw_models::FAMILIES`]): its parameter ([`Family::param_name`]: `alpha` in s/m, `zeta`,
//! `e_r`, `v_y` in m/s) and `T_b` (s, for durations), each in `[fit.bounds]` or
//! `[fit.fixed]`; the Bouc-Wen quantities, an input, a known mass and drop-test data do not
//! apply.
//!
//! ```toml
//! [[fit]]
//! name = "tennis Hunt-Crossley"
//! model = "hunt-crossley"
//! data = "data/real/tennis_v0_e.csv"
//! [fit.bounds]
//! alpha = [0.0, 2.0]        # s/m; each family's default bounds otherwise
//! ```

use super::search::param_of;
use super::RawFit;
use crate::tables::Ctx;
use crate::AppError;
use bw_models::Family;
use bwc_identify::{IdentifyError, Param, Space};
use std::ops::Range;

/// The default bounds of a family's parameter ([`bw_models::ParamSpec::default_bounds`]).
pub(super) fn default_param(family: Family) -> Param {
    let spec = family.spec().param;
    let (lo, hi) = spec.default_bounds;
    Param::Free {
        lo,
        hi,
        log: spec.default_log,
    }
}

/// The search space of a family's fit; `durations` whether `T_b` matters (a duration
/// objective), then required.
///
/// # Errors
/// [`AppError::Invalid`] naming the key: a Bouc-Wen quantity, an input, a known mass, a start
/// or a parameter vector; bounds the family does not admit; `T_b` missing for durations.
pub(super) fn family_space(
    ctx: &Ctx,
    r: &RawFit,
    t: &Range<usize>,
    family: Family,
    durations: bool,
) -> Result<Space, AppError> {
    foreign_keys_absent(ctx, r, family)?;
    let (param, t_b) = searched(ctx, r, t, family, durations)?;
    Space::family(family, param, t_b).map_err(|e| match e {
        IdentifyError::Bounds {
            name,
            lo,
            hi,
            allowed,
        } => ctx.invalid(
            &r.bounds.as_ref().map_or(t.clone(), |b| b.span()),
            format!("[fit.bounds].{name}"),
            format!("[{lo}, {hi}] is not admissible: {allowed}"),
        ),
        other => ctx.invalid(t, "[[fit]]", other.to_string()),
    })
}

/// A family's fit names none of the Bouc-Wen quantities and none of the tables that belong
/// to the Bouc-Wen models (an input, a known mass, a start, a vector, a drop test).
fn foreign_keys_absent(ctx: &Ctx, r: &RawFit, family: Family) -> Result<(), AppError> {
    let model = family.name();
    let not_here = |span: Range<usize>, key: &str, what: &str| {
        ctx.invalid(
            &span,
            key,
            format!("{what} does not apply to model \"{model}\""),
        )
    };
    let own = [family.param_name(), "T_b"];
    if let Some((table, key, span)) = r
        .given_quantities()
        .into_iter()
        .find(|(_, n, _)| !own.contains(n))
    {
        return Err(not_here(
            span,
            &format!("[fit.{table}].{key}"),
            &format!("{key}: {model} takes {} and T_b", family.param_name()),
        ));
    }
    let tables = [
        (
            r.input.as_ref().map(|x| x.span()),
            "[fit.input]",
            "an input",
        ),
        (
            r.known.as_ref().map(|x| x.span()),
            "[fit.known]",
            "a known mass",
        ),
        (
            r.start.as_ref().map(|x| x.span()),
            "[fit.start]",
            "a Bouc-Wen start",
        ),
        (
            r.params.as_ref().map(|x| x.span()),
            "[fit.params]",
            "a Bouc-Wen vector",
        ),
        (
            r.reference.as_ref().map(|x| x.span()),
            "[fit.reference]",
            "a Bouc-Wen vector",
        ),
        (
            r.sequence.as_ref().map(|x| x.span()),
            "[fit.sequence]",
            "a drop-test sequence",
        ),
    ];
    match tables.into_iter().find(|x| x.0.is_some()) {
        Some((Some(span), key, what)) => Err(not_here(span, key, what)),
        _ => Ok(()),
    }
}

/// The family's parameter (its default bounds where the config gives none) and `T_b`
/// (required where `durations`, held at 1 otherwise), from `[fit.bounds]`, `[fit.fixed]` and
/// `log`.
fn searched(
    ctx: &Ctx,
    r: &RawFit,
    t: &Range<usize>,
    family: Family,
    durations: bool,
) -> Result<(Param, Param), AppError> {
    let (log_param, log_t) = log_flags(ctx, r, family)?;
    let name = family.param_name();
    let b = r.bounds.as_ref().map(|b| b.get_ref());
    let v = r.fixed.as_ref().map(|v| v.get_ref());
    let bound_p = b.and_then(|b| b.family_entry(name).cloned());
    let fixed_p = v.and_then(|v| v.family_entry(name).cloned());
    let param = param_of(ctx, "fit", name, &bound_p, &fixed_p, log_param)?
        .unwrap_or_else(|| default_param(family));
    let bound_t = b.and_then(|b| b.t_b().clone());
    let fixed_t = v.and_then(|v| v.t_b().clone());
    let t_b = match param_of(ctx, "fit", "T_b", &bound_t, &fixed_t, log_t)? {
        Some(p) => p,
        None if !durations => Param::Fixed(1.0),
        None => {
            return Err(ctx.invalid(
                &r.bounds.as_ref().map_or(t.clone(), |b| b.span()),
                "[fit.bounds].T_b",
                "missing: durations need T_b = (m/k)^(1/(p+1)) (s): give bounds or a value",
            ))
        }
    };
    Ok((param, t_b))
}

/// `log = [...]` of a family: its parameter and `T_b`.
fn log_flags(ctx: &Ctx, r: &RawFit, family: Family) -> Result<(bool, bool), AppError> {
    let (mut param, mut t_b) = (false, false);
    for item in r.log.as_ref().map_or(&[][..], |l| l.get_ref()) {
        match item.get_ref().as_str() {
            n if n == family.param_name() => param = true,
            "T_b" => t_b = true,
            other => {
                return Err(ctx.invalid(
                    &item.span(),
                    "[[fit]].log",
                    format!(
                        "\"{other}\" is not a parameter of \"{}\": use {} or T_b",
                        family.name(),
                        family.param_name()
                    ),
                ))
            }
        }
    }
    Ok((param, t_b))
}
