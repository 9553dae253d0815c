//! Scene files: TOML descriptions of impacts, validated into settings for the libraries.
//!
//! ```toml
//! model = "shccm"            # "shccm" | "mcm"
//! v0 = [0.5, 1.0, 2.0]       # m/s, or { from = 0.1, to = 6.0, count = 40, spacing = "log" }
//! [physical]                 # or [nondimensional], [base] / [[base]], or [bodies] + [physical]
//! m = 0.145
//! k = 117080063.0
//! # ...
//! [input]                    # optional: constant | gravity | arctan | table | sum
//! kind = "gravity"
//! [solver]                   # optional: method, rtol, atol, max_step, t_max, max_steps, stop_at_kinks,
//!                            #   switch_when_stiff, series, e_tol (0: off), double_double, phase
//! [output]                   # optional: trajectory, dt, loops, sweep, plots, summary_runs
//! [sweep]                    # optional: interpolate (default true), tolerance (default e_tol / 10)
//! ```

mod bodies;
pub(crate) mod describe;
pub(crate) mod raw;
mod sequence;

use crate::tables::{
    contact_law, model_kind, read_text, signal, solver_settings, span, speeds, syntax_error, Ctx,
};
use bodies::bodies;
pub use sequence::SequenceSpec;

use crate::signal::Signal;
use crate::AppError;
use bw_models::{
    BaseMap, BaseParams, Bodies, ModelKind, Nondim, NondimParams, PhysicalParams, Settings,
};
use raw::{RawBase, RawNondim, RawPhysical, RawScene, SeqOrMap};
use std::collections::BTreeMap;
use std::ops::Range;
use std::path::{Path, PathBuf};
use toml::Spanned;

/// A validated scene.
#[derive(Debug, Clone)]
pub struct Scene {
    /// The file it came from.
    pub path: PathBuf,
    /// The systems to simulate (several for `[[base]]` curves).
    pub systems: Vec<SystemSpec>,
    /// Impact speeds in m/s (empty for nondimensional scenes and `[bodies]`).
    pub speeds: Vec<f64>,
    /// Solver settings.
    pub settings: Settings,
    /// What to write.
    pub output: OutputSpec,
    /// `[sequence]`: repeated impacts under gravity instead of one impact per speed.
    pub sequence: Option<SequenceSpec>,
    /// Values whose magnitude suggests a unit slip, each naming the slip and the fix
    /// ([`crate::plausible`]).
    pub hints: Vec<String>,
    /// `[sweep]`: whether many speeds may be served by interpolants.
    pub sweep: SweepSpec,
    /// `[output.figures.NAME]`: the figures' own titles, axis labels and line styles, by the
    /// figure's file name without `.svg`.
    pub figures: BTreeMap<String, FigureLabels>,
}

/// The names of the figures a scene draws (`[output.figures.NAME]`).
pub const FIGURES: [&str; 7] = [
    "cor",
    "duration",
    "loops",
    "displacements",
    "velocities",
    "forces",
    "height",
];

/// A figure's title, axis labels and line style where the scene gives them (`None`: the
/// figure's own).
#[derive(Debug, Clone, Default, PartialEq)]
#[non_exhaustive]
pub struct FigureLabels {
    /// The title.
    pub title: Option<String>,
    /// The x axis's quantity and unit.
    pub x_label: Option<String>,
    /// The y axis's quantity and unit.
    pub y_label: Option<String>,
    /// Every series as lines, markers or both.
    pub style: Option<crate::plot::Style>,
}

/// One system of a scene.
#[derive(Debug, Clone)]
pub struct SystemSpec {
    /// Optional name (from `[[base]]` entries).
    pub name: Option<String>,
    /// The model.
    pub kind: ModelKind,
    /// Its description.
    pub system: System,
}

/// The four ways to describe a system.
#[derive(Debug, Clone)]
pub enum System {
    /// `[nondimensional]`: parameters and a constant input `U`.
    Nondimensional {
        /// Parameters.
        params: NondimParams,
        /// Constant nondimensional input.
        u: f64,
    },
    /// `[base]`: base parameters and a physical input; `time_scale_known` when `T_b` was given.
    Base {
        /// The map `P(P*, u, v0)`.
        map: BaseMap,
        /// Physical input (N).
        input: Signal,
        /// Whether `T_b` was given (durations in seconds).
        time_scale_known: bool,
    },
    /// `[physical]`: SI parameters, effective mass and input.
    Physical {
        /// Contact-law parameters.
        params: PhysicalParams,
        /// Effective mass (kg).
        m: f64,
        /// Input (N).
        input: Signal,
    },
    /// `[bodies]` with `[physical]` contact-law parameters.
    Bodies {
        /// Contact-law parameters.
        params: PhysicalParams,
        /// The two bodies.
        bodies: Bodies<Signal, Signal>,
    },
}

/// Which outputs the scene asks for.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OutputSpec {
    /// `trajectory.csv` (and the time-history plots).
    pub trajectory: bool,
    /// Trajectory sampling interval in the model's time unit; `None`: every step.
    pub dt: Option<f64>,
    /// `loop.csv` (and the loop plot).
    pub loops: bool,
    /// `sweep.csv` (default: when there is more than one speed).
    pub sweep: bool,
    /// SVG plots of whatever is written.
    pub plots: bool,
    /// The most runs `summary.json` lists under `"runs"`; a study with more lists them in
    /// `runs.jsonl`, one JSON object per line ([`SUMMARY_RUNS`] by default).
    pub summary_runs: usize,
}

pub use crate::tables::MAX_SPEEDS;

/// The default `[output].summary_runs`: a `summary.json` of about 80 MB.
pub const SUMMARY_RUNS: usize = 100_000;

/// `[sweep]`: how the speeds of a sweep are evaluated.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SweepSpec {
    /// Serve the speeds of a sweep from verified Chebyshev interpolants where that saves
    /// simulations (`bw_models::sweep`); every speed is simulated when `false`.
    pub interpolate: bool,
    /// The largest admitted interpolation error: absolute in `e`, relative in `t_s`.
    pub tolerance: f64,
}

impl Scene {
    /// Reads and validates a scene file.
    ///
    /// # Errors
    /// [`AppError::Io`] if the file cannot be read, [`AppError::Syntax`] for TOML errors, wrong
    /// types and unknown keys, [`AppError::Invalid`] for missing, conflicting or inadmissible
    /// values (with line and key).
    pub fn load(path: &Path) -> Result<Self, AppError> {
        Self::parse(path, &read_text(path)?)
    }

    /// Runs the scene makes: one per system and speed (one per system for a sequence).
    pub fn run_count(&self) -> usize {
        let per_system = if self.sequence.is_some() {
            1
        } else {
            self.speeds.len().max(1)
        };
        self.systems.len() * per_system
    }

    /// Whether the scene makes more runs than `[output].summary_runs`, so that its output
    /// folder lists them in `runs.jsonl` rather than in `summary.json`.
    pub fn runs_listed_apart(&self) -> bool {
        self.run_count() > self.output.summary_runs
    }

    /// Validates a scene given as text (`path` is only used in messages).
    ///
    /// # Errors
    /// As [`Scene::load`]; a file with several mistakes reports them all ([`AppError::Many`]).
    pub fn parse(path: &Path, src: &str) -> Result<Self, AppError> {
        crate::tables::every_error(src, |text| Self::parse_one(path, text))
    }

    /// Validates the text, stopping at its first mistake.
    fn parse_one(path: &Path, src: &str) -> Result<Self, AppError> {
        let ctx = Ctx { path, src };
        let raw: RawScene = toml::from_str(src).map_err(|e| syntax_error(&ctx, &e))?;
        let model = match &raw.model {
            Some(m) => Some(model_kind(&ctx, m, "model")?),
            None => None,
        };
        let described = description(&ctx, &raw)?;
        let sequence = sequence::sequence(&ctx, &raw)?;
        let speeds = speeds(&ctx, &raw.v0)?;
        unused_keys(&ctx, &raw, &described, &speeds, sequence.is_some())?;
        let need_model = || {
            model.ok_or_else(|| {
                ctx.invalid(
                    &(0..0),
                    "model",
                    "missing required key: \"shccm\" or \"mcm\"",
                )
            })
        };
        let systems = if let Some(nd) = &raw.nondimensional {
            vec![nondimensional_system(&ctx, nd, need_model()?)?]
        } else if let Some(base) = &raw.base {
            base_systems(&ctx, &raw, base, model)?
        } else {
            let phys = raw.physical.as_ref().ok_or_else(|| {
                ctx.invalid(
                    &described,
                    "[physical]",
                    "missing: [bodies] take their contact-law parameters from [physical]",
                )
            })?;
            vec![physical_system(&ctx, &raw, phys, need_model()?)?]
        };
        let settings = solver_settings(&ctx, &raw.solver, "[solver]", Settings::default())?;
        let mut scene = Scene {
            path: path.to_owned(),
            systems,
            speeds,
            sweep: sweep(&ctx, &raw, &settings)?,
            settings,
            output: output(&ctx, &raw)?,
            figures: figures(&ctx, &raw)?,
            sequence,
            hints: Vec::new(),
        };
        scene.hints = crate::plausible::scene_hints(&scene);
        Ok(scene)
    }
}

/// The span of the scene's one system description; an error for none or several.
fn description(ctx: &Ctx, raw: &RawScene) -> Result<Range<usize>, AppError> {
    let physical = if raw.bodies.is_some() {
        None
    } else {
        span(&raw.physical)
    };
    let descriptions: Vec<(&str, Range<usize>)> = [
        ("[nondimensional]", span(&raw.nondimensional)),
        ("[base]", span(&raw.base)),
        ("[physical]", physical),
        ("[bodies]", span(&raw.bodies)),
    ]
    .into_iter()
    .filter_map(|(n, s)| s.map(|s| (n, s)))
    .collect();
    match descriptions.as_slice() {
        [] => Err(ctx.invalid(
            &(0..0),
            "system",
            "no system description: give one of [nondimensional], [base], [physical], or \
             [bodies] with [physical]",
        )),
        [(_, s)] => Ok(s.clone()),
        [(a, _), (b, sb), ..] => Err(ctx.invalid(
            sb,
            *b,
            format!("two system descriptions ({a} and {b}): give exactly one"),
        )),
    }
}

/// Impact speeds and an `[input]` where the description takes them, and only there.
fn unused_keys(
    ctx: &Ctx,
    raw: &RawScene,
    described: &Range<usize>,
    speeds: &[f64],
    sequence: bool,
) -> Result<(), AppError> {
    let uses_speeds = raw.base.is_some() || (raw.physical.is_some() && raw.bodies.is_none());
    if uses_speeds && speeds.is_empty() && !sequence {
        return Err(ctx.invalid(
            described,
            "v0",
            "missing required key: impact speeds in m/s for [base] and [physical] scenes",
        ));
    }
    if let Some(v) = raw.v0.as_ref().filter(|_| !uses_speeds) {
        let why = if raw.bodies.is_some() {
            "[bodies] scenes take v0 = v2 - v1 from the bodies"
        } else {
            "nondimensional scenes start at V(0) = -1"
        };
        return Err(ctx.invalid(&v.span(), "v0", format!("not used here: {why}")));
    }
    if let Some(w) = raw.sweep.as_ref().filter(|_| !uses_speeds || sequence) {
        return Err(ctx.invalid(
            &w.span(),
            "[sweep]",
            "not used here: it applies to a list of impact speeds v0 ([base] and [physical] \
             scenes without [sequence])",
        ));
    }
    let own_inputs = raw.nondimensional.is_some() || raw.bodies.is_some();
    if let Some(i) = raw.input.as_ref().filter(|_| own_inputs) {
        let why = if raw.bodies.is_some() {
            "use [bodies.u1] and [bodies.u2]"
        } else {
            "use the key U in [nondimensional]"
        };
        return Err(ctx.invalid(&i.span(), "[input]", format!("not used here: {why}")));
    }
    Ok(())
}

/// The system of a `[nondimensional]` table.
fn nondimensional_system(
    ctx: &Ctx,
    nd: &Spanned<RawNondim>,
    kind: ModelKind,
) -> Result<SystemSpec, AppError> {
    let t = nd.span();
    let r = nd.get_ref();
    let p = Nondim {
        b: ctx.req(&r.b, &t, "[nondimensional].B")?,
        gamma: ctx.req(&r.gamma, &t, "[nondimensional].Gamma")?,
        kappa: ctx.req(&r.kappa, &t, "[nondimensional].kappa")?,
        sigma: ctx.req(&r.sigma, &t, "[nondimensional].sigma")?,
        n: ctx.req(&r.n, &t, "[nondimensional].n")?,
        p: ctx.req(&r.p, &t, "[nondimensional].p")?,
    };
    let u = ctx.opt(&r.u, "[nondimensional].U")?.unwrap_or(0.0);
    let span_of = |name: &str| match name {
        "B" => span(&r.b),
        "Gamma" => span(&r.gamma),
        "kappa" => span(&r.kappa),
        "sigma" => span(&r.sigma),
        "n" => span(&r.n),
        "p" => span(&r.p),
        _ => None,
    };
    let params = NondimParams::new(kind, p)
        .map_err(|e| ctx.model_error(e, "[nondimensional]", span_of, &t))?;
    Ok(SystemSpec {
        name: None,
        kind,
        system: System::Nondimensional { params, u },
    })
}

/// The systems of a `[base]` table or array of tables, under the scene's `[input]`.
fn base_systems(
    ctx: &Ctx,
    raw: &RawScene,
    base: &Spanned<SeqOrMap<Vec<Spanned<RawBase>>, RawBase>>,
    model: Option<ModelKind>,
) -> Result<Vec<SystemSpec>, AppError> {
    let entries: Vec<(&RawBase, Range<usize>)> = match base.get_ref() {
        SeqOrMap::Map(b) => vec![(b, base.span())],
        SeqOrMap::Seq(list) => list.iter().map(|b| (b.get_ref(), b.span())).collect(),
    };
    if entries.is_empty() {
        return Err(ctx.invalid(&base.span(), "[base]", "no base parameter vectors"));
    }
    let input = match &raw.input {
        Some(i) => signal(ctx, i, "[input]", None)?,
        None => Signal::zero(),
    };
    entries
        .into_iter()
        .map(|(b, t)| base_system(ctx, b, &t, model, &input))
        .collect()
}

/// The system of a `[physical]` table: one mass under the scene's `[input]`, or the two
/// `[bodies]`.
fn physical_system(
    ctx: &Ctx,
    raw: &RawScene,
    phys: &Spanned<RawPhysical>,
    kind: ModelKind,
) -> Result<SystemSpec, AppError> {
    let t = phys.span();
    let r = phys.get_ref();
    let fields = [&r.k, &r.c, &r.n, &r.p, &r.alpha, &r.beta, &r.gamma, &r.a];
    let (_, params) = contact_law(ctx, "[physical]", &t, fields, kind)?;
    let system = match &raw.bodies {
        None => {
            let m = ctx.req(&r.m, &t, "[physical].m")?;
            if m <= 0.0 {
                return Err(ctx.invalid(
                    &span(&r.m).unwrap_or(t),
                    "[physical].m",
                    format!("{m} is not admissible: m > 0 (kg)"),
                ));
            }
            let input = match &raw.input {
                Some(i) => signal(ctx, i, "[input]", Some(m))?,
                None => Signal::zero(),
            };
            System::Physical { params, m, input }
        }
        Some(b) => {
            if let Some(m) = &r.m {
                return Err(ctx.invalid(
                    &m.span(),
                    "[physical].m",
                    "not used with [bodies]: the effective mass follows from m1 and m2",
                ));
            }
            System::Bodies {
                params,
                bodies: bodies(ctx, b)?,
            }
        }
    };
    Ok(SystemSpec {
        name: None,
        kind,
        system,
    })
}

fn base_system(
    ctx: &Ctx,
    b: &RawBase,
    t: &Range<usize>,
    model: Option<ModelKind>,
    input: &Signal,
) -> Result<SystemSpec, AppError> {
    let kind = match &b.model {
        Some(m) => model_kind(ctx, m, "[base].model")?,
        None => model.ok_or_else(|| {
            ctx.invalid(
                t,
                "model",
                "missing required key: \"shccm\" or \"mcm\" (top level or in [base])",
            )
        })?,
    };
    let has_input = !bw_models::input::Input::is_zero(input);
    let u_b = ctx.opt(&b.u_b, "[base].U_b")?;
    let t_b = ctx.opt(&b.t_b, "[base].T_b")?;
    if has_input && (u_b.is_none() || t_b.is_none()) {
        let key = if u_b.is_none() {
            "[base].U_b"
        } else {
            "[base].T_b"
        };
        return Err(ctx.invalid(
            t,
            key,
            "missing: U_b and T_b are required when there is an [input]",
        ));
    }
    let base = BaseParams {
        b_b: ctx.req(&b.b_b, t, "[base].B_b")?,
        gamma_b: ctx.req(&b.gamma_b, t, "[base].Gamma_b")?,
        kappa: ctx.req(&b.kappa, t, "[base].kappa")?,
        sigma_b: ctx.req(&b.sigma_b, t, "[base].sigma_b")?,
        n: ctx.req(&b.n, t, "[base].n")?,
        p: ctx.req(&b.p, t, "[base].p")?,
        u_b: u_b.unwrap_or(1.0),
        t_b: t_b.unwrap_or(1.0),
    };
    let span_of = |name: &str| match name {
        "B_b" => span(&b.b_b),
        "Gamma_b" => span(&b.gamma_b),
        "kappa" => span(&b.kappa),
        "sigma_b" => span(&b.sigma_b),
        "n" => span(&b.n),
        "p" => span(&b.p),
        "U_b" => span(&b.u_b),
        "T_b" => span(&b.t_b),
        _ => None,
    };
    let map = BaseMap::new(kind, base).map_err(|e| ctx.model_error(e, "[base]", span_of, t))?;
    Ok(SystemSpec {
        name: b.name.as_ref().map(|n| n.get_ref().clone()),
        kind,
        system: System::Base {
            map,
            input: input.clone(),
            time_scale_known: t_b.is_some(),
        },
    })
}

/// `[output.figures.NAME]` tables: `title`, `x_label`, `y_label`, `style` (`"line"`,
/// `"markers"` or `"line+markers"`), for NAME one of [`FIGURES`].
fn figures(ctx: &Ctx, raw: &RawScene) -> Result<BTreeMap<String, FigureLabels>, AppError> {
    use crate::plot::Style;
    let Some(tables) = raw
        .output
        .as_ref()
        .and_then(|o| o.get_ref().figures.as_ref())
    else {
        return Ok(BTreeMap::new());
    };
    let mut out = BTreeMap::new();
    for (name, table) in tables {
        let key = format!("[output.figures.{name}]");
        if !FIGURES.contains(&name.as_str()) {
            return Err(ctx.invalid(
                &table.span(),
                key,
                format!("not a figure: one of {}", FIGURES.join(", ")),
            ));
        }
        let t = table.get_ref();
        let text = |v: &Option<Spanned<String>>| v.as_ref().map(|s| s.get_ref().clone());
        let style = match &t.style {
            None => None,
            Some(s) => Some(match s.get_ref().as_str() {
                "line" => Style::Line,
                "markers" => Style::Markers,
                "line+markers" => Style::LineAndMarkers,
                other => {
                    return Err(ctx.invalid(
                        &s.span(),
                        format!("{key}.style"),
                        format!(
                            "\"{other}\" is not a style: \"line\", \"markers\" or \"line+markers\""
                        ),
                    ))
                }
            }),
        };
        out.insert(
            name.clone(),
            FigureLabels {
                title: text(&t.title),
                x_label: text(&t.x_label),
                y_label: text(&t.y_label),
                style,
            },
        );
    }
    Ok(out)
}

fn output(ctx: &Ctx, raw: &RawScene) -> Result<OutputSpec, AppError> {
    let mut o = OutputSpec {
        trajectory: false,
        dt: None,
        loops: false,
        sweep: false,
        plots: false,
        summary_runs: SUMMARY_RUNS,
    };
    let Some(out) = &raw.output else { return Ok(o) };
    let r = out.get_ref();
    let flag = |v: &Option<Spanned<bool>>| v.as_ref().is_some_and(|b| *b.get_ref());
    o.trajectory = flag(&r.trajectory);
    o.loops = flag(&r.loops);
    o.sweep = flag(&r.sweep);
    o.plots = flag(&r.plots);
    if let Some(dt) = &r.dt {
        let v = ctx.num(dt, "[output].dt")?;
        if v <= 0.0 {
            return Err(ctx.invalid(
                &dt.span(),
                "[output].dt",
                format!("{v} is not admissible: dt > 0"),
            ));
        }
        o.dt = Some(v);
    }
    if let Some(v) = &r.summary_runs {
        o.summary_runs = usize::try_from(*v.get_ref()).map_err(|_| {
            ctx.invalid(
                &v.span(),
                "[output].summary_runs",
                format!("{} is not admissible: a count >= 0", v.get_ref()),
            )
        })?;
    }
    Ok(o)
}

/// A tenth of `t`, reading as written ([`crate::format::tidy`]).
fn tenth(t: f64) -> f64 {
    crate::format::tidy(t / 10.0)
}

/// `[sweep]`, the tolerance by default a tenth of the solver's `e_tol` (1e-11), or its `rtol`
/// without one: about the simulations' own accuracy in `t_s`; a tighter one meets their noise
/// and serves fewer speeds.
fn sweep(ctx: &Ctx, raw: &RawScene, settings: &Settings) -> Result<SweepSpec, AppError> {
    let mut w = SweepSpec {
        interpolate: true,
        tolerance: settings.e_tol.map_or(settings.rtol, tenth),
    };
    let Some(table) = &raw.sweep else {
        return Ok(w);
    };
    let r = table.get_ref();
    if let Some(i) = &r.interpolate {
        w.interpolate = *i.get_ref();
    }
    if let Some(t) = &r.tolerance {
        let v = ctx.num(t, "[sweep].tolerance")?;
        if !(v > 0.0 && v < 1.0) {
            return Err(ctx.invalid(
                &t.span(),
                "[sweep].tolerance",
                format!(
                    "{v} is not admissible: 0 < tolerance < 1 (absolute in e, relative in t_s)"
                ),
            ));
        }
        w.tolerance = v;
    }
    Ok(w)
}
