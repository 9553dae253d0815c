//! The keys every fit shares: a quantity's bounds or fixed value and the optimizer's table.

use crate::tables::{Ctx, Num};
use crate::AppError;
use bwc_identify::{Budget, Param};
use serde::Deserialize;
use toml::Spanned;

pub(super) type Pair = Spanned<Vec<Num>>;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawOptimizer {
    particles: Option<Spanned<i64>>,
    iterations: Option<Spanned<i64>>,
    polish: Option<Spanned<i64>>,
    starts: Option<Spanned<i64>>,
    max_starts: Option<Spanned<i64>>,
    agree: Option<Spanned<i64>>,
    tolerance: Option<Num>,
    seed: Option<Spanned<i64>>,
}

pub(super) fn count(
    ctx: &Ctx,
    v: &Option<Spanned<i64>>,
    key: &str,
    min: i64,
    max: i64,
    default: i64,
) -> Result<i64, AppError> {
    match v {
        None => Ok(default),
        Some(x) if (min..=max).contains(x.get_ref()) => Ok(*x.get_ref()),
        Some(x) => Err(ctx.invalid(
            &x.span(),
            key,
            format!("{} is not admissible: {min} <= {key} <= {max}", x.get_ref()),
        )),
    }
}

pub(super) fn optimizer(
    ctx: &Ctx,
    o: &Option<Spanned<RawOptimizer>>,
    table: &str,
    index: usize,
) -> Result<(Budget, u64), AppError> {
    let empty = RawOptimizer {
        particles: None,
        iterations: None,
        polish: None,
        starts: None,
        max_starts: None,
        agree: None,
        tolerance: None,
        seed: None,
    };
    let r = o.as_ref().map_or(&empty, |o| o.get_ref());
    let d = Budget::default();
    let key = |k: &str| format!("{table}.{k}");
    let n = |v: &Option<Spanned<i64>>, k: &str, min: i64, max: i64, default: usize| {
        count(ctx, v, &key(k), min, max, default as i64).map(|x| x as usize)
    };
    let starts = n(&r.starts, "starts", 1, 1_000, d.starts)?;
    // An explicit `starts` alone keeps the old meaning: exactly that many starts.
    let max_default = if r.starts.is_some() && r.max_starts.is_none() {
        starts
    } else {
        d.max_starts.max(starts)
    };
    let max_starts = n(
        &r.max_starts,
        "max_starts",
        starts as i64,
        1_000,
        max_default,
    )?;
    let agree = n(
        &r.agree,
        "agree",
        1,
        max_starts as i64,
        d.agree.min(max_starts),
    )?;
    let tolerance = agreement(ctx, &r.tolerance, &key("tolerance"), d.tolerance)?;
    let budget = Budget {
        particles: n(&r.particles, "particles", 2, 10_000, d.particles)?,
        iterations: n(
            &r.iterations,
            "iterations",
            0,
            1_000_000,
            d.iterations as usize,
        )? as u64,
        polish_iterations: n(
            &r.polish,
            "polish",
            0,
            1_000_000,
            d.polish_iterations as usize,
        )? as u64,
        starts,
        max_starts,
        agree,
        tolerance,
    };
    Ok((
        budget,
        count(ctx, &r.seed, &key("seed"), 0, i64::MAX, index as i64)? as u64,
    ))
}

/// `[fit.optimizer].tolerance`: how close (relative) the costs of starts that agree are.
pub(super) fn agreement(
    ctx: &Ctx,
    v: &Option<Num>,
    key: &str,
    default: f64,
) -> Result<f64, AppError> {
    match ctx.opt(v, key)? {
        None => Ok(default),
        Some(t) if (0.0..=1.0).contains(&t) => Ok(t),
        Some(t) => {
            let span = v.as_ref().map(|x| x.span()).unwrap_or_default();
            Err(ctx.invalid(
                &span,
                key,
                format!("{t} is not admissible: 0 <= tolerance <= 1 (relative)"),
            ))
        }
    }
}

/// A searchable quantity from `[<table>.bounds].key = [lo, hi]` or `[<table>.fixed].key`
/// (`None` when neither is given).
pub(super) fn param_of(
    ctx: &Ctx,
    table: &str,
    key: &str,
    bound: &Option<Pair>,
    fixed: &Option<Num>,
    log: bool,
) -> Result<Option<Param>, AppError> {
    match (bound, fixed) {
        (Some(_), Some(x)) => Err(ctx.invalid(
            &x.span(),
            format!("[{table}.fixed].{key}"),
            "both bounded and fixed: give one",
        )),
        (Some(pair), None) => {
            let name = format!("[{table}.bounds].{key}");
            if pair.get_ref().len() != 2 {
                return Err(ctx.invalid(&pair.span(), name, "give [lower, upper]"));
            }
            let lo = ctx.num(&pair.get_ref()[0], &name)?;
            let hi = ctx.num(&pair.get_ref()[1], &name)?;
            if lo > hi {
                return Err(ctx.invalid(
                    &pair.span(),
                    name,
                    format!("[{lo}, {hi}] is not admissible: lower bound <= upper bound"),
                ));
            }
            Ok(Some(Param::Free { lo, hi, log }))
        }
        (None, Some(x)) => Ok(Some(Param::Fixed(
            ctx.num(x, &format!("[{table}.fixed].{key}"))?,
        ))),
        (None, None) => Ok(None),
    }
}
