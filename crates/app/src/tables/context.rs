//! Where a value came from: the file being parsed ([`Ctx`]) and the spans of its values, for
//! messages that name the file, line and key.

use crate::AppError;
use bw_models::ModelError;
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
    ) -> AppError {
        AppError::Invalid {
            path: self.path.to_owned(),
            line: self.line(span),
            key: key.into(),
            message: message.into(),
        }
    }

    pub(crate) fn num(&self, v: &Num, key: &str) -> Result<f64, AppError> {
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
    ) -> Result<f64, AppError> {
        match v {
            Some(v) => self.num(v, key),
            None => Err(self.invalid(table, key, "missing required key")),
        }
    }

    pub(crate) fn opt(&self, v: &Option<Num>, key: &str) -> Result<Option<f64>, AppError> {
        v.as_ref().map(|v| self.num(v, key)).transpose()
    }

    /// Turns a model-library error into one that names the key and line.
    pub(crate) fn model_error(
        &self,
        e: ModelError,
        table: &str,
        span_of: impl Fn(&str) -> Option<Range<usize>>,
        fallback: &Range<usize>,
    ) -> AppError {
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

/// The span of an optional value.
pub(crate) fn span<T>(v: &Option<Spanned<T>>) -> Option<Range<usize>> {
    v.as_ref().map(|s| s.span())
}
