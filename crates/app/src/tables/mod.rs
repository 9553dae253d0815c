//! TOML plumbing shared by scenes ([`crate::impact::scene`]) and identification configs
//! ([`crate::fit::config`]): where a key sits in its file ([`Ctx`]), errors that name the file, the
//! line and the key, and the tables both kinds of file hold (`[input]`, `[solver]`).

mod context;
mod describe;
mod input;
mod laws;
mod solver;
mod speeds;

pub(crate) use context::{span, Ctx, Num};
pub(crate) use describe::{base_json, settings_json, signal_json};
pub(crate) use input::{signal, RawInput};
pub(crate) use laws::{Mass, RawBase, RawPhysical};
pub(crate) use solver::{solver_settings, RawSolver};
pub use speeds::MAX_SPEEDS;
pub(crate) use speeds::{speeds, RawRange, SeqOrMap, V0};

use crate::AppError;
use bw_models::{ModelKind, Physical, PhysicalParams};
use std::ops::Range;
use std::path::Path;
use toml::Spanned;

/// The contact law of `table` (spanning `span`) for the model `kind`, from its keys `k`, `c`,
/// `n`, `p`, `alpha`, `beta`, `gamma` and `A` (`fields`, in that order), validated: an error
/// names the key of a missing or inadmissible value.
pub(crate) fn contact_law(
    ctx: &Ctx,
    table: &str,
    span: &Range<usize>,
    fields: [&Option<Num>; 8],
    kind: ModelKind,
) -> Result<(Physical, PhysicalParams), AppError> {
    const KEYS: [&str; 8] = ["k", "c", "n", "p", "alpha", "beta", "gamma", "A"];
    let mut values = [0.0; 8];
    for ((value, field), key) in values.iter_mut().zip(fields).zip(KEYS) {
        *value = ctx.req(field, span, &format!("{table}.{key}"))?;
    }
    let [k, c, n, p, alpha, beta, gamma, a] = values;
    let law = Physical {
        k,
        c,
        n,
        p,
        alpha,
        beta,
        gamma,
        a,
    };
    let span_of = |name: &str| {
        KEYS.iter()
            .position(|k| *k == name)
            .and_then(|i| self::span(fields[i]))
    };
    let params =
        PhysicalParams::new(kind, law).map_err(|e| ctx.model_error(e, table, span_of, span))?;
    Ok((law, params))
}

/// The text of an input file.
///
/// # Errors
/// [`AppError::Io`] naming the file.
pub(crate) fn read_text(path: &Path) -> Result<String, AppError> {
    std::fs::read_to_string(path).map_err(|source| AppError::Io {
        path: path.to_owned(),
        source,
    })
}

/// A TOML parse error as `file:line:column: message`; a type error names its key and what the
/// key admits.
pub(crate) fn syntax_error(ctx: &Ctx, e: &toml::de::Error) -> AppError {
    let src = ctx.src;
    let mut at = e.span().map_or(0, |s| s.start.min(src.len()));
    let mut message = e.message().trim().replace('\n', " ");
    if let Some((header, key)) = table_for_value(src, at, &message) {
        let expected = match expected_in_words(&message).as_str() {
            "a borrowed string" => "a value".to_string(),
            words => words.to_string(),
        };
        message = format!("`{key}` expects {expected}, not a table");
        at = header;
    }
    let line_start = src[..at].rfind('\n').map_or(0, |i| i + 1);
    if message.starts_with("invalid type") {
        if let Some(key) = key_at(src, at) {
            let expected = match key.rsplit('.').next() {
                Some("v0") => "a list of impact speeds in m/s, e.g. [1.5], or a range \
                               { from = 0.5, to = 5.0, count = 10 }"
                    .to_string(),
                _ => expected_in_words(&message),
            };
            let found = message
                .split(", expected")
                .next()
                .unwrap_or(&message)
                .to_string();
            message = format!("`{key}` expects {expected} ({found})");
        }
    }
    AppError::Syntax {
        path: ctx.path.to_owned(),
        line: ctx.line(&(at..at)),
        column: src[line_start..at].chars().count() + 1,
        message,
    }
}

/// Where a table stands for a value (`[solver.rtol]` as a table): the byte of its header and
/// its key (`[solver].rtol`). The parser points at the header, or, for a number kept with its
/// span, names the table's key in its own words ("invalid type: string \"rtol\", expected a
/// borrowed string") somewhere inside it.
fn table_for_value(src: &str, at: usize, message: &str) -> Option<(usize, String)> {
    let line_start = src[..at].rfind('\n').map_or(0, |i| i + 1);
    let line = src[line_start..].lines().next().unwrap_or("");
    if message.starts_with("invalid type") {
        if let Some(key) = header_key(line) {
            return Some((line_start, key));
        }
    }
    let name = message
        .strip_prefix("invalid type: string \"")?
        .split_once("\", expected a borrowed string")?
        .0;
    let mut offset = 0;
    for l in src.split('\n') {
        if let Some(key) = header_key(l).filter(|k| k == name || k.ends_with(&format!("].{name}")))
        {
            return Some((offset, key));
        }
        offset += l.len() + 1;
    }
    None
}

/// The key a table header names, with its parent table: `[solver.rtol]` is `[solver].rtol`;
/// `None` for a line that is not a header or an array of tables.
fn header_key(line: &str) -> Option<String> {
    let line = line.split('#').next()?.trim();
    let inner = line.strip_prefix('[')?.strip_suffix(']')?;
    if inner.starts_with('[') {
        return None;
    }
    let parts: Vec<&str> = inner.split('.').map(str::trim).collect();
    let (name, parent) = parts.split_last()?;
    Some(if parent.is_empty() {
        (*name).to_string()
    } else {
        format!("[{}].{name}", parent.join("."))
    })
}

/// The key of the `key = value` on 1-based `line`, with its table.
fn line_key(src: &str, line: usize) -> Option<String> {
    let at: usize = src.split('\n').take(line - 1).map(|l| l.len() + 1).sum();
    key_at(src, at.min(src.len()))
}

/// The key of the `key = value` line holding byte `at`, with its table (`[physical].k`).
fn key_at(src: &str, at: usize) -> Option<String> {
    let line_start = src[..at].rfind('\n').map_or(0, |i| i + 1);
    let line_end = src[at..].find('\n').map_or(src.len(), |i| at + i);
    let (key, _) = src[line_start..line_end].split_once('=')?;
    let key = key.trim().trim_matches('"');
    let table = src[..line_start]
        .lines()
        .rev()
        .map(str::trim)
        .find(|l| l.starts_with('['))
        .map(|l| {
            l.split('#')
                .next()
                .unwrap_or(l)
                .trim()
                .replace("[[", "[")
                .replace("]]", "]")
        });
    Some(match table {
        Some(t) => format!("{t}.{key}"),
        None => key.to_string(),
    })
}

/// serde's "expected f64" and the like, in words.
fn expected_in_words(message: &str) -> String {
    let expected = message.split("expected ").nth(1).unwrap_or("another type");
    match expected.trim() {
        "f64" | "i64" | "u64" | "usize" => "a number".into(),
        "a boolean" | "bool" => "true or false".into(),
        "a string" => "a string in quotes".into(),
        other => other.to_string(),
    }
}

/// Most mistakes reported from one file.
const MOST_ERRORS: usize = 20;

/// Values tried in place of a bad one to see past it: a number in most admissible ranges, a
/// list, a flag, a string; `None` drops the line (an unknown key).
const STAND_INS: [Option<&str>; 10] = [
    Some("1.0"),
    Some("[1.0, 2.0]"),
    Some("0.5"),
    Some("2.0"),
    Some("0.0"),
    Some("10.0"),
    Some("[1.0]"),
    Some("true"),
    Some("\"x\""),
    None,
];

/// Parses `src` with `parse` and, where it fails on a `key = value` line, looks past the
/// mistake by putting stand-in values in its place and parsing again, so that a file with
/// several mistakes reports them all at once, in file order ([`AppError::Many`]).
///
/// # Errors
/// The first error alone, or [`AppError::Many`] with every one found.
pub(crate) fn every_error<T>(
    src: &str,
    parse: impl Fn(&str) -> Result<T, AppError>,
) -> Result<T, AppError> {
    let first = match parse(src) {
        Ok(v) => return Ok(v),
        Err(e) => e,
    };
    let mut text = src.to_string();
    let mut errors = vec![first];
    while errors.len() < MOST_ERRORS {
        let last = errors.last().expect("one error");
        let Some(line) = error_line(last) else { break };
        // A stand-in gets past the mistake if parsing then stops elsewhere, on another key.
        // The values the message names as admissible ("shccm" or "mcm") come first: a line
        // commented out would report its key as missing, which is not a mistake of the file.
        let name = line_key(&text, line).unwrap_or_default();
        let key = format!("`{name}`");
        let named = quoted(&last.to_string());
        // Every stand-in that gets past the line is tried. One that parses means nothing else
        // is wrong; otherwise the error most of them give is the file's, not one of a stand-in's
        // making (`mass = "inf"` makes a wall that must not move), the first of equals first.
        let stand_ins = named.iter().map(|q| Some(q.as_str())).chain(STAND_INS);
        let mut past: Vec<(String, AppError)> = Vec::new();
        let mut parsed = false;
        for v in stand_ins {
            let Some(patched) = with_value(&text, line, v) else {
                continue;
            };
            match parse(&patched) {
                Ok(_) => parsed = true,
                Err(e)
                    if error_line(&e) != Some(line)
                        && !e.to_string().contains(&key)
                        && !missing(&e, &name) =>
                {
                    past.push((patched, e));
                }
                Err(_) => {}
            }
        }
        if parsed || past.is_empty() {
            break;
        }
        let said: Vec<String> = past.iter().map(|(_, e)| e.to_string()).collect();
        let count = |m: &String| said.iter().filter(|o| *o == m).count();
        let best = (0..said.len())
            .max_by_key(|&i| (count(&said[i]), std::cmp::Reverse(i)))
            .unwrap_or(0);
        let (patched, e) = past.swap_remove(best);
        text = patched;
        errors.push(e);
    }
    if errors.len() == 1 {
        return Err(errors.pop().expect("one error"));
    }
    errors.sort_by_key(|e| error_line(e).unwrap_or(usize::MAX));
    Err(AppError::Many(errors))
}

/// The quoted strings of a message (`use "shccm" or "mcm"`), each with its quotes: the values
/// it names as admissible.
fn quoted(message: &str) -> Vec<String> {
    message
        .split('"')
        .skip(1)
        .step_by(2)
        .filter(|q| !q.is_empty() && !q.contains('\\'))
        .map(|q| format!("\"{q}\""))
        .collect()
}

/// Whether `e` reports the key `name` (of any table) as missing.
fn missing(e: &AppError, name: &str) -> bool {
    match e {
        AppError::Invalid { key, message, .. } => {
            // `name` is the line's dotted key (`chain.body.input.kind`), the message's key may
            // name its table otherwise (`[[chain.body]] 0: input.kind`): the last part decides.
            let last = name.rsplit('.').next().unwrap_or(name);
            message.starts_with("missing")
                && (key == name || key == last || key.ends_with(&format!(".{last}")))
        }
        _ => false,
    }
}

/// The line of a file error that a stand-in value could get past (`key = value` errors of the
/// file itself; not a data file's, not a missing key's).
fn error_line(e: &AppError) -> Option<usize> {
    match e {
        AppError::Syntax { line, .. } => Some(*line),
        AppError::Invalid { line, message, .. } if !message.starts_with("missing") => Some(*line),
        _ => None,
    }
}

/// `src` with the value of the `key = value` on 1-based `line` replaced by `value` (the line
/// commented out for `None`), `None` if that line is not a single-line `key = value`.
fn with_value(src: &str, line: usize, value: Option<&str>) -> Option<String> {
    let mut lines: Vec<&str> = src.split('\n').collect();
    let text = lines.get(line.checked_sub(1)?)?;
    let (key, rest) = text.split_once('=')?;
    let inline_table = rest.trim_start().starts_with('{');
    if key.trim().is_empty() || key.trim_start().starts_with('[') || inline_table && value.is_some()
    {
        return None;
    }
    let new = match value {
        Some(v) => format!("{key}= {v}"),
        None => format!("# {text}"),
    };
    lines[line - 1] = &new;
    Some(lines.join("\n"))
}

pub(crate) fn model_kind(ctx: &Ctx, v: &Spanned<String>, key: &str) -> Result<ModelKind, AppError> {
    ModelKind::parse(v.get_ref()).ok_or_else(|| {
        ctx.invalid(
            &v.span(),
            key,
            format!(
                "\"{}\" is not a model: use \"shccm\" or \"mcm\"",
                v.get_ref()
            ),
        )
    })
}
