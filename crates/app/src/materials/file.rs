//! The `[materials]` table as written, validated into two [`Body`]s and the speeds to tabulate.

use crate::tables::{read_text, speeds, syntax_error, Ctx, Num, V0};
use crate::AppError;
use bw_models::materials::{material, material_names, Body, Material, MaterialPair};
use bw_models::ModelError;
use serde::Deserialize;
use std::ops::Range;
use std::path::{Path, PathBuf};
use toml::Spanned;

/// A file holding a `[materials]` table (other tables are the scene's or the config's). The
/// table keeps no span: toml cannot give one to a table only its sub-tables define
/// (`[materials.body1]` without `[materials]`).
#[derive(Debug, Deserialize)]
struct RawFile {
    materials: Option<RawMaterials>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawMaterials {
    v0: Option<Spanned<V0>>,
    body1: Option<Spanned<RawBody>>,
    body2: Option<Spanned<RawBody>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawBody {
    material: Option<Spanned<String>>,
    youngs_modulus: Option<Num>,
    poisson: Option<Num>,
    density: Option<Num>,
    yield_strength: Option<Num>,
    yield_pressure: Option<Num>,
    radius: Option<Num>,
    mass: Option<Num>,
}

/// One body as the file describes it, with where its values came from.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct BodySpec {
    /// The body.
    pub body: Body,
    /// The material's name in the table, if the body names one.
    pub material: Option<String>,
    /// The table's source of the material's values, if it names one.
    pub source: Option<&'static str>,
    /// The keys the file gives over the table's values.
    pub own: Vec<&'static str>,
}

/// A validated `[materials]` table.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct MaterialsSpec {
    /// The file it came from.
    pub path: PathBuf,
    /// The two bodies.
    pub bodies: [BodySpec; 2],
    /// Their pair's law.
    pub pair: MaterialPair,
    /// The impact speeds to tabulate (m/s): the file's `v0`, or 12 from `v_y / 2` to
    /// `100 v_y` on a log scale (0.1 to 10 m/s where the contact does not yield).
    pub speeds: Vec<f64>,
}

impl MaterialsSpec {
    /// Reads and validates the `[materials]` table of the file at `path`.
    ///
    /// # Errors
    /// [`AppError::Io`], [`AppError::Syntax`], and [`AppError::Invalid`] naming the file, line
    /// and key of a missing table, an unknown material (listing the known ones) or an
    /// inadmissible value.
    pub fn load(path: &Path) -> Result<Self, AppError> {
        Self::parse(path, &read_text(path)?)
    }

    /// As [`MaterialsSpec::load`], from the file's text.
    ///
    /// # Errors
    /// As [`MaterialsSpec::load`].
    pub fn parse(path: &Path, src: &str) -> Result<Self, AppError> {
        let ctx = Ctx { path, src };
        let raw: RawFile = toml::from_str(src).map_err(|e| syntax_error(&ctx, &e))?;
        let Some(m) = raw.materials else {
            return Err(ctx.invalid(&(0..0), "materials", "missing table [materials]"));
        };
        let table = src.find("[materials").map_or(0..0, |at| at..at);
        let body = |b: &Option<Spanned<RawBody>>, key: &'static str| match b {
            Some(b) => body(&ctx, b.get_ref(), &b.span(), key),
            None => Err(ctx.invalid(&table, format!("materials.{key}"), "missing table")),
        };
        let bodies = [body(&m.body1, "body1")?, body(&m.body2, "body2")?];
        let pair = MaterialPair::new(&bodies[0].body, &bodies[1].body)
            .map_err(|e| pair_error(&ctx, e, &m, &table))?;
        let mut speeds = speeds(&ctx, &m.v0)?;
        if speeds.is_empty() {
            let (from, to) = pair.v_y.map_or((0.1, 10.0), |v| (0.5 * v, 100.0 * v));
            speeds = (0..12)
                .map(|i| from * (to / from).powf(f64::from(i) / 11.0))
                .collect();
        }
        Ok(Self {
            path: path.to_owned(),
            bodies,
            pair,
            speeds,
        })
    }
}

/// One body: the named material's values, each overridden by the file's own.
fn body(ctx: &Ctx, b: &RawBody, span: &Range<usize>, key: &str) -> Result<BodySpec, AppError> {
    let entry = match &b.material {
        Some(name) => Some(material(name.get_ref()).ok_or_else(|| {
            ctx.invalid(
                &name.span(),
                format!("materials.{key}.material"),
                format!(
                    "\"{}\" is not a known material: {}; or give youngs_modulus, poisson, \
                     density and yield_strength",
                    name.get_ref(),
                    material_names()
                ),
            )
        })?),
        None => None,
    };
    let base = entry.map(|e| e.material);
    let mut own = Vec::new();
    let mut pick = |v: &Option<Num>, name: &'static str, table: Option<f64>| {
        let given = ctx.opt(v, &format!("materials.{key}.{name}"))?;
        if given.is_some() {
            own.push(name);
        }
        match given.or(table) {
            Some(x) => Ok(x),
            None => Err(ctx.invalid(
                span,
                format!("materials.{key}.{name}"),
                "missing: give it, or a `material` from the table that has it",
            )),
        }
    };
    let material = Material {
        youngs_modulus: pick(
            &b.youngs_modulus,
            "youngs_modulus",
            base.map(|m| m.youngs_modulus),
        )?,
        poisson: pick(&b.poisson, "poisson", base.map(|m| m.poisson))?,
        density: pick(&b.density, "density", base.map(|m| m.density))?,
        yield_strength: match &b.yield_strength {
            Some(_) => Some(pick(&b.yield_strength, "yield_strength", None)?),
            None => base.and_then(|m| m.yield_strength),
        },
    };
    let radius = match &b.radius {
        Some(r) => {
            own.push("radius");
            *r.get_ref()
        }
        None => f64::INFINITY,
    };
    let mass = ctx.opt(&b.mass, &format!("materials.{key}.mass"))?;
    let mut body = match (mass, radius.is_finite()) {
        (Some(m), _) => Body::new(material, radius, Some(m)),
        (None, true) => Body::sphere(material, radius),
        (None, false) => Body::flat(material),
    };
    if let Some(p) = ctx.opt(
        &b.yield_pressure,
        &format!("materials.{key}.yield_pressure"),
    )? {
        body = body.with_yield_pressure(p);
    }
    Ok(BodySpec {
        body,
        material: b.material.as_ref().map(|n| n.get_ref().clone()),
        source: entry.map(|e| e.source),
        own,
    })
}

/// A pair's error at the key of the body and quantity it names.
fn pair_error(ctx: &Ctx, e: ModelError, m: &RawMaterials, table: &Range<usize>) -> AppError {
    let ModelError::InvalidMaterial {
        body,
        name,
        value,
        allowed,
    } = e
    else {
        return ctx.invalid(table, "materials", e.to_string());
    };
    let raw = match body {
        1 => m.body1.as_ref(),
        2 => m.body2.as_ref(),
        _ => None,
    };
    let key = match body {
        0 => "materials".to_string(),
        i => format!("materials.body{i}.{name}"),
    };
    let span = raw
        .and_then(|b| value_span(b.get_ref(), name).or(Some(b.span())))
        .unwrap_or_else(|| table.clone());
    let from_table = raw.is_some_and(|b| value_span(b.get_ref(), name).is_none());
    let whence = if from_table {
        " (the material table's value)"
    } else {
        ""
    };
    ctx.invalid(
        &span,
        key,
        format!("{value}{whence} is not admissible: {allowed}"),
    )
}

fn value_span(b: &RawBody, name: &str) -> Option<Range<usize>> {
    let v = match name {
        "youngs_modulus" => &b.youngs_modulus,
        "poisson" => &b.poisson,
        "density" => &b.density,
        "yield_strength" => &b.yield_strength,
        "yield_pressure" => &b.yield_pressure,
        "radius" => &b.radius,
        "mass" => &b.mass,
        _ => return None,
    };
    v.as_ref().map(|v| v.span())
}
