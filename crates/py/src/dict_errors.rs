//! Errors of descriptions given as Python dicts, told in the dict's terms.
//!
//! A dict reaches the application library as the TOML text a file would hold, so the library's
//! errors cite a line of that text and a key such as `[base].kappa`. A Python user wrote no
//! such file: here each error names the dict key instead (`params["kappa"]` for `bwc.cor`,
//! `config["fit"][1]["bounds"]["n"]` for a config), followed by the library's message.

use bwc_app::AppError;

/// What the dict was: the arguments of `bwc.cor` (a scene built from `model`, `params`, `v0`,
/// `input`, `solver`, `sweep`), or a whole scene or config named as the function's argument.
#[derive(Clone, Copy)]
pub(crate) enum Root {
    /// `bwc.cor`'s arguments.
    Cor,
    /// A dict passed as the argument of this name.
    Dict(&'static str),
}

/// The error lines of `e` (several mistakes one per line), keys named as in the dict that
/// became `toml`.
pub(crate) fn explain(e: &AppError, toml: &str, root: Root) -> String {
    match e {
        AppError::Many(all) => all
            .iter()
            .map(|e| explain(e, toml, root))
            .collect::<Vec<_>>()
            .join("\n"),
        AppError::Invalid {
            line, key, message, ..
        } => match key_path(key, toml, *line, root) {
            Some(path) => format!("{path}: {message}"),
            None => format!("`{key}`: {message}"),
        },
        AppError::Syntax { line, message, .. } => {
            let key = key_at(toml, *line);
            let message = python_words(message);
            match key.and_then(|k| key_path(&k, toml, *line, root)) {
                Some(path) => format!("{path}: {message}"),
                None => message,
            }
        }
        AppError::Simulation { run, source, .. } => format!("run {run}: {source}"),
        other => other.to_string(),
    }
}

/// A library message about a value in Python's words: a table where a value belongs (the
/// library's "`[solver].rtol` expects a number, not a table") is a dict given there, serde's
/// "map" and "sequence" a dict and a list.
fn python_words(message: &str) -> String {
    if let Some((_, expected)) = message
        .strip_suffix(", not a table")
        .and_then(|m| m.split_once("` expects "))
    {
        return format!("a dict given where {expected} belongs");
    }
    message
        .replace("invalid type: map", "a dict given")
        .replace("invalid type: sequence", "a list given")
        .replace("expected f64", "expected a number")
}

/// The key a line of generated TOML sets, with its table: `[base].kappa`; a table's header
/// line names the table (`[solver.rtol]`: `solver.rtol`).
fn key_at(toml: &str, line: usize) -> Option<String> {
    let lines: Vec<&str> = toml.lines().collect();
    let text = lines.get(line.checked_sub(1)?)?;
    if let Some(name) = text.trim().strip_prefix('[') {
        let name = name.trim_start_matches('[').trim_end_matches(']');
        return Some(name.trim().to_string());
    }
    let header = lines[..line]
        .iter()
        .rev()
        .find(|l| l.starts_with('['))
        .map(|h| h.trim());
    let (name, _) = text.split_once('=')?;
    let name = name.trim().trim_matches('"');
    Some(match header {
        Some(h) if !text.starts_with('[') => format!("{h}.{name}"),
        _ => name.to_string(),
    })
}

/// A library key (`[fit.bounds].kappa`, `[[fit]].objectives`, `v0`) at `line` of `toml` as
/// the dict path a Python user wrote; `None` where the key is not of that form.
fn key_path(key: &str, toml: &str, line: usize, root: Root) -> Option<String> {
    let (table, rest) = if let Some(t) = key.strip_prefix("[[") {
        t.split_once("]]")?
    } else if let Some(t) = key.strip_prefix('[') {
        t.split_once(']')?
    } else {
        ("", key)
    };
    let rest = rest.strip_prefix('.').unwrap_or(rest);
    let mut parts: Vec<&str> = table.split('.').filter(|p| !p.is_empty()).collect();
    parts.extend(rest.split('.').filter(|p| !p.is_empty()));
    let valid = |p: &str| p.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    if parts.is_empty() || !parts.iter().all(|p| valid(p)) {
        return None;
    }
    let (mut path, keys) = match root {
        Root::Cor => match parts[0] {
            "nondimensional" | "base" | "physical" => ("params".to_string(), &parts[1..]),
            first => (first.to_string(), &parts[1..]),
        },
        Root::Dict(name) => (name.to_string(), &parts[..]),
    };
    for (i, k) in keys.iter().enumerate() {
        path.push_str(&format!("[\"{k}\"]"));
        // An array of tables (`[[fit]]`): which element, by the headers up to the line.
        if i == 0 && matches!(root, Root::Dict(_)) {
            let header = format!("[[{k}]]");
            let count = toml
                .lines()
                .take(line)
                .filter(|l| l.trim() == header)
                .count();
            if count > 0 {
                path.push_str(&format!("[{}]", count - 1));
            }
        }
    }
    Some(path)
}

#[cfg(test)]
mod tests {
    use super::*;

    const CONFIG: &str = "[[fit]]\nname = \"a\"\n\n[fit.bounds]\nn = [1.0, 6.0]\n\n[[fit]]\nname = \"b\"\n\n[fit.bounds]\nn = [6.0, 1.0]\n";

    #[test]
    fn keys_become_dict_paths() {
        let scene = "model = \"shccm\"\nv0 = [1.0]\n\n[base]\nkappa = 1.5\n";
        assert_eq!(
            key_path("[base].kappa", scene, 5, Root::Cor).as_deref(),
            Some("params[\"kappa\"]")
        );
        assert_eq!(key_path("v0", scene, 2, Root::Cor).as_deref(), Some("v0"));
        assert_eq!(
            key_path("[solver].rtol", scene, 1, Root::Cor).as_deref(),
            Some("solver[\"rtol\"]")
        );
        assert_eq!(
            key_path("[base].kappa", scene, 5, Root::Dict("scene")).as_deref(),
            Some("scene[\"base\"][\"kappa\"]")
        );
        // The second [[fit]]'s bounds, by the headers up to line 11.
        assert_eq!(
            key_path("[fit.bounds].n", CONFIG, 11, Root::Dict("config")).as_deref(),
            Some("config[\"fit\"][1][\"bounds\"][\"n\"]")
        );
        assert_eq!(
            key_path("[[fit]].model", CONFIG, 2, Root::Dict("config")).as_deref(),
            Some("config[\"fit\"][0][\"model\"]")
        );
        assert_eq!(
            key_path("[fit.params] of \"a\"", CONFIG, 1, Root::Cor),
            None
        );
    }

    #[test]
    fn a_line_names_its_key() {
        assert_eq!(key_at(CONFIG, 11).as_deref(), Some("[fit.bounds].n"));
        assert_eq!(key_at(CONFIG, 2).as_deref(), Some("[[fit]].name"));
        assert_eq!(key_at("v0 = \"x\"\n", 1).as_deref(), Some("v0"));
    }
}
