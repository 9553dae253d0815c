//! TOML plumbing shared by scenes ([`crate::scene`]) and identification configs
//! ([`crate::config`]): where a key sits in its file ([`Ctx`]), errors that name the file, the
//! line and the key, and the tables both kinds of file hold (`[input]`, `[solver]`).

mod input;
mod solver;

pub(crate) use input::{signal, RawInput};
pub(crate) use solver::{solver_settings, RawSolver};

use crate::CliError;
use bw_models::{ModelError, ModelKind};
use std::ops::Range;
use std::path::Path;
use toml::Spanned;

/// A number with its place in the file.
pub type Num = Spanned<f64>;

/// A file being parsed: its path and text, for messages.
pub(crate) struct Ctx<'a> {
    pub(crate) path: &'a Path,
    pub(crate) src: &'a str,
}

impl Ctx<'_> {
    pub(crate) fn line(&self, span: &Range<usize>) -> usize {
        let end = span.start.min(self.src.len());
        self.src[..end].matches('\n').count() + 1
    }

    pub(crate) fn invalid(
        &self,
        span: &Range<usize>,
        key: impl Into<String>,
        message: impl Into<String>,
    ) -> CliError {
        CliError::Invalid {
            path: self.path.to_owned(),
            line: self.line(span),
            key: key.into(),
            message: message.into(),
        }
    }

    pub(crate) fn num(&self, v: &Num, key: &str) -> Result<f64, CliError> {
        let x = *v.get_ref();
        if x.is_finite() {
            Ok(x)
        } else {
            Err(self.invalid(&v.span(), key, format!("{x} is not a finite number")))
        }
    }

    pub(crate) fn req(
        &self,
        v: &Option<Num>,
        table: &Range<usize>,
        key: &str,
    ) -> Result<f64, CliError> {
        match v {
            Some(v) => self.num(v, key),
            None => Err(self.invalid(table, key, "missing required key")),
        }
    }

    pub(crate) fn opt(&self, v: &Option<Num>, key: &str) -> Result<Option<f64>, CliError> {
        v.as_ref().map(|v| self.num(v, key)).transpose()
    }

    /// Turns a model-library error into one that names the key and line.
    pub(crate) fn model_error(
        &self,
        e: ModelError,
        table: &str,
        span_of: impl Fn(&str) -> Option<Range<usize>>,
        fallback: &Range<usize>,
    ) -> CliError {
        match e {
            ModelError::InvalidParameter {
                name,
                value,
                allowed,
            }
            | ModelError::InvalidSetting {
                name,
                value,
                allowed,
            } => {
                let span = span_of(name).unwrap_or_else(|| fallback.clone());
                self.invalid(
                    &span,
                    format!("{table}.{name}"),
                    format!("{value} is not admissible: {allowed}"),
                )
            }
            other => self.invalid(fallback, table.to_string(), other.to_string()),
        }
    }
}

/// The text of an input file.
///
/// # Errors
/// [`CliError::Io`] naming the file.
pub(crate) fn read_text(path: &Path) -> Result<String, CliError> {
    std::fs::read_to_string(path).map_err(|source| CliError::Io {
        path: path.to_owned(),
        source,
    })
}

/// A TOML parse error as `file:line:column: message`.
pub(crate) fn syntax_error(ctx: &Ctx, e: &toml::de::Error) -> CliError {
    let src = ctx.src;
    let at = e.span().map_or(0, |s| s.start.min(src.len()));
    let line_start = src[..at].rfind('\n').map_or(0, |i| i + 1);
    CliError::Syntax {
        path: ctx.path.to_owned(),
        line: ctx.line(&(at..at)),
        column: src[line_start..at].chars().count() + 1,
        message: e.message().trim().replace('\n', " "),
    }
}

pub(crate) fn span<T>(v: &Option<Spanned<T>>) -> Option<Range<usize>> {
    v.as_ref().map(|s| s.span())
}

pub(crate) fn model_kind(ctx: &Ctx, v: &Spanned<String>, key: &str) -> Result<ModelKind, CliError> {
    match v.get_ref().as_str() {
        "shccm" => Ok(ModelKind::Shccm),
        "mcm" => Ok(ModelKind::Mcm),
        other => Err(ctx.invalid(
            &v.span(),
            key,
            format!("\"{other}\" is not a model: use \"shccm\" or \"mcm\""),
        )),
    }
}
