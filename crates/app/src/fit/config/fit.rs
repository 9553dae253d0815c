//! One `[[fit]]` table, parsed in named parts: what is fitted ([`head`]), the objectives, the
//! search space ([`space`]), points given in full ([`point`]), the optimizer and the solver.
//! The data file is read only after the whole config has parsed ([`Draft::with_data`]).

use super::search::{optimizer, param_of};
use super::{RawFit, RawPoint, RawQuantities};
use crate::signal::Signal;
use crate::tables::{model_kind, signal, solver_settings, span, Ctx, Num};
use crate::AppError;
use bw_models::{BaseParams, Family, ModelKind, Settings};
use bwc_identify::{
    Budget, Dataset, IdentifyError, KnownMassStiffness, Param, Space, Weights, NAMES,
};
use std::ops::Range;
use std::path::{Path, PathBuf};
use toml::Spanned;

use super::{FitConfig, Reference};

/// A `[[fit]]` validated up to its data.
pub(super) struct Draft {
    fit: FitConfig,
    /// For a drop-test fit, its `[fit.sequence]` (the data are read later).
    setup: Option<bwc_identify::DropSetup>,
    data_path: PathBuf,
    objective_span: Range<usize>,
    pareto_span: Range<usize>,
}

impl Draft {
    /// The fit's name.
    pub(super) fn name(&self) -> &str {
        &self.fit.name
    }

    /// Reads the data file and checks the objectives against it.
    ///
    /// # Errors
    /// [`AppError::Identify`] for the data file's own errors; [`AppError::Invalid`] at
    /// `objectives` for a weight on a quantity the data lack, at `[fit.pareto]` without both.
    pub(super) fn with_data(self, ctx: &Ctx) -> Result<FitConfig, AppError> {
        let mut fit = self.fit;
        if let Some(setup) = self.setup {
            let data = bwc_identify::DropData::load(&self.data_path).map_err(|source| {
                AppError::Identify {
                    path: ctx.path.to_owned(),
                    fit: fit.name.clone(),
                    source,
                }
            })?;
            fit.drops = Some(super::DropFit { data, setup });
            return Ok(fit);
        }
        fit.data = Dataset::load(&self.data_path).map_err(|source| AppError::Identify {
            path: ctx.path.to_owned(),
            fit: fit.name.clone(),
            source,
        })?;
        bwc_identify::Objective::new(&fit.space, &fit.data, &fit.input, fit.settings, fit.weights)
            .map_err(|e| ctx.invalid(&self.objective_span, "[[fit]].objectives", e.to_string()))?;
        if fit.pareto.is_some() && !(fit.data.has_cor() && fit.data.has_durations()) {
            return Err(ctx.invalid(
                &self.pareto_span,
                "[fit.pareto]",
                "a Pareto sweep needs both `e` and `t_d` in the data",
            ));
        }
        Ok(fit)
    }
}

/// Whether `[fit.bounds]` or `[fit.fixed]` give an input scale (`U_b`, `T_b`: the last two of
/// the quantities by name).
fn scales_given(r: &RawFit) -> bool {
    let bounds = r
        .bounds
        .as_ref()
        .map(|b| b.get_ref().by_name()[6..].iter().any(|q| q.is_some()));
    let fixed = r
        .fixed
        .as_ref()
        .map(|b| b.get_ref().by_name()[6..].iter().any(|q| q.is_some()));
    bounds.unwrap_or(false) || fixed.unwrap_or(false)
}

/// Parses `[[fit]]` number `index` (0-based); `dir` is the config's folder.
pub(super) fn parse_fit(
    ctx: &Ctx,
    dir: &Path,
    f: &Spanned<RawFit>,
    index: usize,
) -> Result<Draft, AppError> {
    let t = f.span();
    let r = f.get_ref();
    let (name, kind, data_path) = head(ctx, dir, r, &t, index)?;
    if let Some(family) = r.model.as_ref().and_then(|m| Family::parse(m.get_ref())) {
        return parse_family_fit(ctx, r, (&t, index), (name, family, data_path));
    }
    family_keys_absent(ctx, r)?;
    let drop = header_of(&data_path).is_some_and(|h| bwc_identify::DropData::is_drop_header(&h));
    let weights = if drop {
        drop_objectives(ctx, r)?
    } else {
        objectives(ctx, r)?
    };
    if !drop {
        columns_for(ctx, (r, &t), &data_path, weights)?;
    }
    let known = known(ctx, r)?;
    let (input, uses_input_scales) = input_and_scales(ctx, r, known, weights, drop)?;
    let setup = drop
        .then(|| drop_setup(ctx, r, &t, uses_input_scales))
        .transpose()?;
    let space = space(ctx, r, &t, &name, kind, known, uses_input_scales)?;
    let scales = Scales {
        kind,
        known,
        uses_input_scales,
    };
    let (start, params) = start_and_params(ctx, r, &space, &scales)?;
    let reference = reference(ctx, r, params, &scales)?;
    let hints = mass_hints(ctx, known, setup.as_ref());
    let (budget, seed, settings, pareto) = search(ctx, r, index)?;
    let posterior =
        super::posterior::posterior(ctx, r.posterior.as_ref(), r.prior.as_ref(), &space)?;
    Ok(Draft {
        fit: FitConfig {
            name,
            kind,
            data: Dataset::at_speeds(&data_path, &[]),
            space,
            input,
            weights,
            budget,
            seed,
            settings,
            start,
            params,
            reference,
            uses_input_scales,
            hints,
            pareto,
            drops: None,
            posterior,
            family: None,
        },
        setup,
        data_path,
        objective_span: r.objectives.as_ref().map_or(t.clone(), |o| o.span()),
        pareto_span: r.pareto.as_ref().map_or(t.clone(), |p| p.span()),
    })
}

/// `[fit.input]` (none: zero) and whether the input scales `U_b`, `T_b` matter: under an
/// input, for durations, with a known body, and for drop tests where they are given.
fn input_and_scales(
    ctx: &Ctx,
    r: &RawFit,
    known: Option<KnownMassStiffness>,
    weights: Weights,
    drop: bool,
) -> Result<(Signal, bool), AppError> {
    let input = match &r.input {
        Some(i) => signal(ctx, i, "[fit.input]", known.map(|k| k.m))?,
        None => Signal::zero(),
    };
    let uses_input_scales = !bw_models::input::Input::is_zero(&input)
        || weights.j2 > 0.0
        || known.is_some()
        || (drop && scales_given(r));
    Ok((input, uses_input_scales))
}

/// Notes on masses that look like grams or tonnes where kilograms are expected.
fn mass_hints(
    ctx: &Ctx,
    known: Option<KnownMassStiffness>,
    setup: Option<&bwc_identify::DropSetup>,
) -> Vec<String> {
    let masses = [
        ("[fit.known].m", known.map(|k| k.m)),
        ("[fit.sequence].m", setup.map(|s| s.m)),
    ];
    masses
        .into_iter()
        .filter_map(|(key, m)| crate::plausible::mass_hint(ctx.path, key, m?))
        .collect()
}

/// A `[[fit]]` of a contact-law family ([`super::family`]).
fn parse_family_fit(
    ctx: &Ctx,
    r: &RawFit,
    (t, index): (&Range<usize>, usize),
    (name, family, data_path): (String, Family, PathBuf),
) -> Result<Draft, AppError> {
    if header_of(&data_path).is_some_and(|h| bwc_identify::DropData::is_drop_header(&h)) {
        return Err(ctx.invalid(
            t,
            "[[fit]].data",
            format!(
                "drop-test data (intervals or heights) with model \"{}\": the contact-law \
                 families are fitted to CoRs and durations (v_0, e, t_d)",
                family.name()
            ),
        ));
    }
    let weights = objectives(ctx, r)?;
    columns_for(ctx, (r, t), &data_path, weights)?;
    let space = super::family::family_space(ctx, r, t, family, weights.j2 > 0.0)?;
    let (budget, seed, settings, pareto) = search(ctx, r, index)?;
    let posterior =
        super::posterior::posterior(ctx, r.posterior.as_ref(), r.prior.as_ref(), &space)?;
    Ok(Draft {
        fit: FitConfig {
            name,
            kind: ModelKind::Shccm,
            family: Some(family),
            data: Dataset::at_speeds(&data_path, &[]),
            space,
            input: Signal::zero(),
            weights,
            budget,
            seed,
            settings,
            start: None,
            params: None,
            reference: None,
            uses_input_scales: weights.j2 > 0.0,
            hints: Vec::new(),
            pareto,
            drops: None,
            posterior,
        },
        setup: None,
        data_path,
        objective_span: r.objectives.as_ref().map_or(t.clone(), |o| o.span()),
        pareto_span: r.pareto.as_ref().map_or(t.clone(), |p| p.span()),
    })
}

/// The families' config names, quoted: `"hunt-crossley", "kelvin-voigt", ...`.
fn family_list() -> String {
    let names: Vec<String> = bw_models::FAMILIES
        .iter()
        .map(|f| format!("\"{}\"", f.name()))
        .collect();
    names.join(", ")
}

/// A Bouc-Wen fit names no family parameter.
fn family_keys_absent(ctx: &Ctx, r: &RawFit) -> Result<(), AppError> {
    let family = Family::param_names();
    match r
        .given_quantities()
        .into_iter()
        .find(|(_, n, _)| family.contains(n))
    {
        Some((table, key, span)) => Err(ctx.invalid(
            &span,
            format!("[fit.{table}].{key}"),
            format!(
                "{key} is a parameter of the contact-law families (model = {}), not of the \
                 Bouc-Wen models",
                family_list()
            ),
        )),
        None => Ok(()),
    }
}

/// `[fit.start]` (encoded in the search space) and `[fit.params]`.
fn start_and_params(
    ctx: &Ctx,
    r: &RawFit,
    space: &Space,
    scales: &Scales,
) -> Result<(Option<Vec<f64>>, Option<BaseParams>), AppError> {
    let start = r
        .start
        .as_ref()
        .map(|p| {
            let bp = point(ctx, p, "start", scales)?;
            space
                .encode(&bp)
                .map_err(|e| ctx.invalid(&p.span(), "[fit.start]", e.to_string()))
        })
        .transpose()?;
    let params = r
        .params
        .as_ref()
        .map(|p| point(ctx, p, "params", scales))
        .transpose()?;
    Ok((start, params))
}

/// How the fit searches: `[fit.optimizer]` (budget and seed), `[fit.solver]` (rtol 1e-8 and
/// atol 1e-10 unless it says otherwise) and `[fit.pareto].count`.
fn search(
    ctx: &Ctx,
    r: &RawFit,
    index: usize,
) -> Result<(Budget, u64, Settings, Option<usize>), AppError> {
    let (budget, seed) = optimizer(ctx, &r.optimizer, "[fit.optimizer]", index)?;
    let search = Settings {
        rtol: 1e-8,
        atol: 1e-10,
        e_tol: None,
        ..Settings::default()
    };
    let settings = solver_settings(ctx, &r.solver, "[fit.solver]", search)?;
    let pareto = r
        .pareto
        .as_ref()
        .map(|p| super::search::count(ctx, &p.get_ref().count, "[fit.pareto].count", 2, 1_000, 11))
        .transpose()?
        .map(|n| n as usize);
    Ok((budget, seed, settings, pareto))
}

/// `name`, `model` and `data` (the path, relative to the config's folder).
fn head(
    ctx: &Ctx,
    dir: &Path,
    r: &RawFit,
    t: &Range<usize>,
    index: usize,
) -> Result<(String, ModelKind, PathBuf), AppError> {
    let name = r
        .name
        .as_ref()
        .map_or_else(|| format!("fit {}", index + 1), |n| n.get_ref().clone());
    let kind = match &r.model {
        Some(m) if Family::parse(m.get_ref()).is_some() => ModelKind::Shccm,
        Some(m) => model_kind(ctx, m, "[[fit]].model").map_err(|_| {
            ctx.invalid(
                &m.span(),
                "[[fit]].model",
                format!(
                    "\"{}\" is not a model: use \"shccm\" or \"mcm\" (the Bouc-Wen models), or \
                     a contact-law family: {}",
                    m.get_ref(),
                    family_list()
                ),
            )
        })?,
        None => {
            return Err(ctx.invalid(
                t,
                "[[fit]].model",
                "missing required key: \"shccm\" or \"mcm\"",
            ))
        }
    };
    let data = r.data.as_ref().ok_or_else(|| {
        ctx.invalid(
            t,
            "[[fit]].data",
            "missing required key: a CSV file relative to the config",
        )
    })?;
    Ok((name, kind, dir.join(data.get_ref())))
}

/// `objectives = { J1 = w1, J2 = w2 }` (default: J1 alone).
fn objectives(ctx: &Ctx, r: &RawFit) -> Result<Weights, AppError> {
    Ok(match &r.objectives {
        None => Weights { j1: 1.0, j2: 0.0 },
        Some(o) => {
            let o = o.get_ref();
            Weights {
                j1: ctx.opt(&o.j1, "objectives.J1")?.unwrap_or(0.0),
                j2: ctx.opt(&o.j2, "objectives.J2")?.unwrap_or(0.0),
            }
        }
    })
}

/// A weight on a quantity the data file has no column for, reported before everything that
/// depends on the weights (a `J2` weight makes `U_b` and `T_b` matter): the header is read now,
/// the data after the whole config has parsed. A header without `v_0`, or with neither `e` nor
/// `t_d`, is the data file's own error (it names the columns a dataset needs), as is an empty
/// file.
fn columns_for(
    ctx: &Ctx,
    (r, t): (&RawFit, &Range<usize>),
    data: &Path,
    w: Weights,
) -> Result<(), AppError> {
    let Some(columns) = header_of(data) else {
        // Unreadable: the data file's own error comes with the data.
        return Ok(());
    };
    let has = |c: &str| columns.iter().any(|h| h == c);
    if !has("v_0") || !(has("e") || has("t_d")) {
        return Ok(());
    }
    let (span, given) = match &r.objectives {
        Some(o) => (o.span(), ""),
        None => (
            t.clone(),
            " (the default objectives = { J1 = 1 }: set objectives = { J2 = 1 } to fit the \
             durations alone)",
        ),
    };
    for (weight, name, column, what) in [
        (w.j1, "J1", "e", "CoRs"),
        (w.j2, "J2", "t_d", "contact durations (s)"),
    ] {
        if weight > 0.0 && !has(column) {
            return Err(ctx.invalid(
                &span,
                format!("objectives.{name}"),
                format!(
                    "{name} = {weight} weighs {what}, but {} has no `{column}` column (it has \
                     {}){given}: set {name} = 0 or add the column",
                    data.display(),
                    columns.join(", ")
                ),
            ));
        }
    }
    Ok(())
}

/// The column names of a data file's header (after its `#` comment lines), if it can be read.
fn header_of(path: &Path) -> Option<Vec<String>> {
    let mut reader = csv::ReaderBuilder::new()
        .comment(Some(b'#'))
        .trim(csv::Trim::All)
        .from_path(path)
        .ok()?;
    Some(reader.headers().ok()?.iter().map(String::from).collect())
}

/// A drop-test fit has one cost, `J_drop`: `objectives` must not weigh `J1` or `J2`.
fn drop_objectives(ctx: &Ctx, r: &RawFit) -> Result<Weights, AppError> {
    if let Some(o) = &r.objectives {
        return Err(ctx.invalid(
            &o.span(),
            "[[fit]].objectives",
            "not for drop-test data (intervals or rebound heights): their cost is J_drop",
        ));
    }
    Ok(Weights { j1: 1.0, j2: 0.0 })
}

/// `[fit.sequence]` of a drop-test fit: `m` (kg; required when contacts feel gravity, i.e.
/// with `U_b` and `T_b`), `g` (m/s², default 9.81), `drag` (1/m, default 0).
fn drop_setup(
    ctx: &Ctx,
    r: &RawFit,
    t: &Range<usize>,
    timed: bool,
) -> Result<bwc_identify::DropSetup, AppError> {
    let span = r.sequence.as_ref().map_or(t.clone(), |s| s.span());
    let q = r.sequence.as_ref().map(|s| s.get_ref());
    let value = |v: Option<&Num>,
                 key: &str,
                 ok: fn(f64) -> bool,
                 allowed: &str|
     -> Result<Option<f64>, AppError> {
        let Some(v) = v else { return Ok(None) };
        let x = ctx.num(v, key)?;
        if ok(x) {
            Ok(Some(x))
        } else {
            Err(ctx.invalid(&v.span(), key, format!("{x} is not admissible: {allowed}")))
        }
    };
    let m = value(
        q.and_then(|q| q.m.as_ref()),
        "[fit.sequence].m",
        |x| x > 0.0,
        "m > 0 (kg)",
    )?;
    let g = value(
        q.and_then(|q| q.g.as_ref()),
        "[fit.sequence].g",
        |x| x > 0.0,
        "g > 0 (m/s^2)",
    )?;
    let drag = value(
        q.and_then(|q| q.drag.as_ref()),
        "[fit.sequence].drag",
        |x| x >= 0.0,
        "drag >= 0 (1/m)",
    )?;
    let m = match (m, timed) {
        (Some(m), _) => m,
        (None, false) => 0.0,
        (None, true) => {
            return Err(ctx.invalid(
                &span,
                "[fit.sequence].m",
                "missing: with U_b and T_b the contacts feel gravity -m g: give the mass (kg)",
            ))
        }
    };
    Ok(bwc_identify::DropSetup {
        m: if timed { m } else { m.max(f64::MIN_POSITIVE) },
        flight: bw_models::sequence::Flight {
            g: g.unwrap_or(9.81),
            drag: drag.unwrap_or(0.0),
        },
        timed_contacts: timed,
    })
}

/// `[fit.known]`: `m`, `k`.
fn known(ctx: &Ctx, r: &RawFit) -> Result<Option<KnownMassStiffness>, AppError> {
    r.known
        .as_ref()
        .map(|k| {
            let kr = k.get_ref();
            Ok(KnownMassStiffness {
                m: ctx.req(&kr.m, &k.span(), "[fit.known].m")?,
                k: ctx.req(&kr.k, &k.span(), "[fit.known].k")?,
            })
        })
        .transpose()
}

/// `log = [...]`: which quantities are searched on a log scale.
fn log_flags(ctx: &Ctx, r: &RawFit) -> Result<[bool; 8], AppError> {
    let mut log = [false; 8];
    for item in r.log.as_ref().map_or(&[][..], |l| l.get_ref()) {
        match NAMES.iter().position(|n| n == item.get_ref()) {
            Some(i) => log[i] = true,
            None => {
                return Err(ctx.invalid(
                    &item.span(),
                    "[[fit]].log",
                    format!(
                        "\"{}\" is not a base parameter: use {}",
                        item.get_ref(),
                        NAMES.join(", ")
                    ),
                ))
            }
        }
    }
    Ok(log)
}

/// The search space from `[fit.bounds]`, `[fit.fixed]`, `log` and `[fit.known]`.
fn space(
    ctx: &Ctx,
    r: &RawFit,
    t: &Range<usize>,
    name: &str,
    kind: ModelKind,
    known: Option<KnownMassStiffness>,
    uses_input_scales: bool,
) -> Result<Space, AppError> {
    let empty_b = RawQuantities::default();
    let empty_v = RawQuantities::default();
    let b = r.bounds.as_ref().map_or(&empty_b, |b| b.get_ref());
    let v = r.fixed.as_ref().map_or(&empty_v, |v| v.get_ref());
    let bounds = b.by_name();
    let fixed = v.by_name();
    let log = log_flags(ctx, r)?;
    let mut params = [Param::Fixed(1.0); 8];
    let bounds_span = r.bounds.as_ref().map_or(t.clone(), |b| b.span());
    // Every given bound is checked before the missing ones are reported, all at once.
    let mut missing = Vec::new();
    for i in 0..8 {
        let key = NAMES[i];
        params[i] = match param_of(ctx, "fit", key, bounds[i], fixed[i], log[i])? {
            Some(param) => param,
            None if i == 7 && known.is_some() => Param::Derived,
            // U_b and T_b only matter with an input, a duration objective or a known mass.
            None if i >= 6 && !uses_input_scales => Param::Fixed(1.0),
            None => {
                missing.push(key);
                Param::Fixed(1.0)
            }
        };
    }
    if !missing.is_empty() {
        let keys = missing.join(", ");
        return Err(ctx.invalid(
            &bounds_span,
            format!("[fit.bounds].{}", missing[0]),
            format!("missing {keys}: give each bounds in [fit.bounds] or a value in [fit.fixed]"),
        ));
    }
    Space::new(kind, params, known).map_err(|e| match e {
        IdentifyError::Bounds {
            name,
            lo,
            hi,
            allowed,
        } => {
            let i = NAMES.iter().position(|n| *n == name);
            let (table, s) = match i {
                Some(i) if bounds[i].is_some() => ("[fit.bounds]", span(bounds[i])),
                Some(i) if fixed[i].is_some() => ("[fit.fixed]", span(fixed[i])),
                _ => ("[fit.known]", r.known.as_ref().map(|k| k.span())),
            };
            ctx.invalid(
                &s.unwrap_or(t.clone()),
                format!("{table}.{name}"),
                format!("[{lo}, {hi}] is not admissible: {allowed}"),
            )
        }
        other => ctx.invalid(t, format!("[[fit]] \"{name}\""), other.to_string()),
    })
}

/// The vector to report beside the fit: `[fit.reference]`, or else `[fit.params]` (already
/// parsed as `params`), named by its `label` or else by its table.
fn reference(
    ctx: &Ctx,
    r: &RawFit,
    params: Option<BaseParams>,
    scales: &Scales,
) -> Result<Option<Reference>, AppError> {
    let label = |p: &Spanned<RawPoint>, table: &str| {
        p.get_ref()
            .label
            .as_ref()
            .map_or_else(|| table.to_string(), |l| l.get_ref().clone())
    };
    let Some(p) = &r.reference else {
        return Ok(params.zip(r.params.as_ref()).map(|(params, p)| Reference {
            label: label(p, "[fit.params]"),
            params,
        }));
    };
    let label = label(p, "[fit.reference]");
    Ok(Some(Reference {
        label,
        params: point(ctx, p, "reference", scales)?,
    }))
}

/// What a full parameter point needs: the model, and whether `U_b`, `T_b` are required.
struct Scales {
    kind: ModelKind,
    known: Option<KnownMassStiffness>,
    uses_input_scales: bool,
}

/// `[fit.start]` or `[fit.params]`: a full `P*`, checked by the model.
fn point(
    ctx: &Ctx,
    p: &Spanned<RawPoint>,
    table: &str,
    scales: &Scales,
) -> Result<BaseParams, AppError> {
    let s = p.span();
    let q = p.get_ref();
    let key = |k: &str| format!("[fit.{table}].{k}");
    if let (Some(l), "start") = (&q.label, table) {
        return Err(ctx.invalid(
            &l.span(),
            key("label"),
            "not a key of [fit.start]: only [fit.reference] and [fit.params] have a label",
        ));
    }
    let uf = |v: &Option<Num>, k: &str| -> Result<f64, AppError> {
        if scales.uses_input_scales {
            ctx.req(v, &s, &key(k))
        } else {
            Ok(ctx.opt(v, &key(k))?.unwrap_or(1.0))
        }
    };
    let mut bp = BaseParams {
        b_b: ctx.req(&q.b_b, &s, &key("B_b"))?,
        gamma_b: ctx.req(&q.gamma_b, &s, &key("Gamma_b"))?,
        kappa: ctx.req(&q.kappa, &s, &key("kappa"))?,
        sigma_b: ctx.req(&q.sigma_b, &s, &key("sigma_b"))?,
        n: ctx.req(&q.n, &s, &key("n"))?,
        p: ctx.req(&q.p, &s, &key("p"))?,
        u_b: uf(&q.u_b, "U_b")?,
        t_b: 1.0,
    };
    bp.t_b = match scales.known {
        Some(k) => k.m * bp.u_b,
        None => uf(&q.t_b, "T_b")?,
    };
    bw_models::BaseMap::new(scales.kind, bp).map_err(|e| {
        let span_of = |n: &str| match n {
            "B_b" => span(&q.b_b),
            "Gamma_b" => span(&q.gamma_b),
            "kappa" => span(&q.kappa),
            "sigma_b" => span(&q.sigma_b),
            "n" => span(&q.n),
            "p" => span(&q.p),
            "U_b" => span(&q.u_b),
            "T_b" => span(&q.t_b),
            _ => None,
        };
        ctx.model_error(e, &format!("[fit.{table}]"), span_of, &s)
    })?;
    Ok(bp)
}
