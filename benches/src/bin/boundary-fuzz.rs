//! Generated bad input at every Rust boundary a user reaches (STABILITY.md "Input files"):
//! pair scenes, `[chain]` scenes, identification configs, CSV data and the C ABI. Each case
//! mutates a valid fixture (one to three edits: a number replaced by a hostile value, a key
//! renamed, a line deleted, duplicated or truncated, a value quoted) or, for the C ABI, calls
//! a function with hostile numbers and handles. A case fails where the call panics, where its
//! message is an internal one (a panic's text, serde's or numpy's words without a key), or where
//! an error does not name the file and line (files) or the argument (C).
//!
//! `cargo run --release -p bwc-benches --bin boundary-fuzz -- [CASES] [SEED]` (default 10^6
//! cases per boundary, seed 1); prints per boundary the cases, the inputs refused, the failures
//! (with the first few inputs that failed) and the wall time.

use bwc::*;
use bwc_app::chain::ChainScene;
use bwc_app::fit::config::Config;
use bwc_app::impact::scene::Scene;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use rayon::prelude::*;
use std::ffi::CStr;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Hostile values a number is replaced by.
const HOSTILE: [&str; 16] = [
    "nan",
    "inf",
    "-inf",
    "1e308",
    "-1e308",
    "-1",
    "0",
    "1e-320",
    "\"x\"",
    "[]",
    "{}",
    "true",
    "[nan]",
    "\"inf\"",
    "[1.0, -2.0]",
    "99999999999999999999",
];

/// Words that mark a message as the machinery's rather than the tool's.
const INTERNAL: [&str; 6] = [
    "panicked",
    "called `Option::unwrap()`",
    "called `Result::unwrap()`",
    "not a JSON-like",
    "internal error",
    "index out of bounds",
];

/// A boundary's run over all its cases.
type Boundary<'a> = Box<dyn Fn() -> Tally + 'a>;

/// One boundary's tally.
#[derive(Default)]
struct Tally {
    cases: u64,
    refused: u64,
    failures: Vec<String>,
}

fn fixtures() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../fixtures")
}

/// The spans of the numbers in `text`.
fn numbers(text: &str) -> Vec<(usize, usize)> {
    let b = text.as_bytes();
    let mut spans = Vec::new();
    let mut i = 0;
    while i < b.len() {
        let starts = b[i].is_ascii_digit()
            && (i == 0 || !(b[i - 1].is_ascii_alphanumeric() || b[i - 1] == b'_'));
        if !starts {
            i += 1;
            continue;
        }
        let mut j = i;
        while j < b.len() && (b[j].is_ascii_digit() || b".eE-+".contains(&b[j])) {
            j += 1;
        }
        spans.push((if i > 0 && b[i - 1] == b'-' { i - 1 } else { i }, j));
        i = j;
    }
    spans
}

/// `text` with one to three random edits.
fn mutate(text: &str, rng: &mut StdRng) -> String {
    let mut out = text.to_string();
    for _ in 0..rng.random_range(1..=3) {
        let lines: Vec<&str> = out.lines().collect();
        let n = lines.len().max(1);
        out = match rng.random_range(0..6) {
            0 | 1 => {
                let spans = numbers(&out);
                if spans.is_empty() {
                    continue;
                }
                let (a, b) = spans[rng.random_range(0..spans.len())];
                let with = HOSTILE[rng.random_range(0..HOSTILE.len())];
                format!("{}{}{}", &out[..a], with, &out[b..])
            }
            2 => {
                let skip = rng.random_range(0..n);
                let kept: Vec<&str> = (lines.iter().enumerate())
                    .filter(|(i, _)| *i != skip)
                    .map(|(_, l)| *l)
                    .collect();
                kept.join("\n")
            }
            3 => {
                let mut v = lines.clone();
                let i = rng.random_range(0..n).min(v.len().saturating_sub(1));
                if let Some(l) = lines.get(i) {
                    v.insert(i, l);
                }
                v.join("\n")
            }
            4 => {
                // A key renamed: its first letter doubled.
                let i = rng.random_range(0..n);
                let mut v: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
                if let Some(l) = v.get_mut(i) {
                    if let Some(c) = l.chars().next().filter(|c| c.is_ascii_alphabetic()) {
                        l.insert(0, c);
                    }
                }
                v.join("\n")
            }
            _ => {
                let mut cut = rng.random_range(0..out.len().max(1));
                while !out.is_char_boundary(cut) {
                    cut -= 1;
                }
                out[..cut].to_string()
            }
        };
    }
    out
}

/// Why the message of an error from file `name` fails, if it does.
fn file_message(message: &str, name: &str) -> Option<String> {
    if let Some(w) = INTERNAL.iter().find(|w| message.contains(*w)) {
        return Some(format!("internal words {w:?}"));
    }
    if !message.contains(name) {
        return Some("no file name".into());
    }
    None
}

/// Runs `cases` mutations of the fixtures `files` through `parse` (an `Err` is the message), in
/// parallel, each case seeded by its index.
fn files(
    files: &[&str],
    cases: u64,
    seed: u64,
    parse: impl Fn(&Path, &str) -> Result<(), String> + Sync,
) -> Tally {
    let texts: Vec<(PathBuf, String)> = files
        .iter()
        .map(|f| {
            let path = fixtures().join(f);
            let text = std::fs::read_to_string(&path).expect("fixture");
            (path, text)
        })
        .collect();
    let results: Vec<(bool, Option<String>)> = (0..cases)
        .into_par_iter()
        .map(|i| {
            let mut rng = StdRng::seed_from_u64(seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) ^ i);
            let (path, text) = &texts[rng.random_range(0..texts.len())];
            let mutated = mutate(text, &mut rng);
            let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("");
            match catch_unwind(AssertUnwindSafe(|| parse(path, &mutated))) {
                Err(_) => (true, Some(format!("panic on {name}: {mutated:?}"))),
                Ok(Ok(())) => (false, None),
                Ok(Err(m)) => (
                    true,
                    file_message(&m, name).map(|why| format!("{why}: {m} (input {mutated:?})")),
                ),
            }
        })
        .collect();
    tally(cases, results)
}

fn tally(cases: u64, results: Vec<(bool, Option<String>)>) -> Tally {
    let mut t = Tally {
        cases,
        ..Tally::default()
    };
    for (refused, failure) in results {
        t.refused += u64::from(refused);
        t.failures.extend(failure);
    }
    t
}

/// The C ABI: laws from hostile parameters, impacts and steps with hostile numbers, handles of
/// the wrong kind, freed or made up. Every status other than OK must come with a message that
/// names an argument in backticks.
fn c_abi(cases: u64, seed: u64) -> Tally {
    let hostile = [
        f64::NAN,
        f64::INFINITY,
        -f64::INFINITY,
        -1.0,
        0.0,
        1e-320,
        1e308,
        -1e308,
        0.5,
        2.0,
        1e7,
    ];
    let results: Vec<(bool, Option<String>)> = (0..cases)
        .into_par_iter()
        .map(|i| {
            let mut rng = StdRng::seed_from_u64(seed ^ i.wrapping_mul(0x2545_f491_4f6c_dd1d));
            let mut pick = |good: f64| {
                if rng.random_bool(0.3) {
                    hostile[rng.random_range(0..hostile.len())]
                } else {
                    good
                }
            };
            let params = BwcLawParams {
                model: if i % 7 == 0 { 9 } else { (i % 2) as u32 },
                k: pick(117080063.0),
                c: pick(5854003.0),
                n: pick(1.1),
                p: pick(1.7),
                alpha: pick(0.1),
                beta: pick(981.05),
                gamma: pick(-961.4),
                a: pick(0.925),
            };
            let (dt, u0, u1, m) = (pick(1e-5), pick(-2.0), pick(-1.9), pick(0.145));
            let which = i % 5;
            let call = || unsafe {
                let mut law = 0;
                let s = bwc_law_new(&params, &mut law);
                if s != BwcStatus::Ok {
                    return vec![s];
                }
                let mut contact = 0;
                let mut statuses = vec![bwc_contact_new(law, std::ptr::null(), &mut contact)];
                let mut step = std::mem::zeroed::<BwcStep>();
                let mut impact = std::mem::zeroed::<BwcImpact>();
                statuses.push(match which {
                    0 => bwc_contact_advance(contact, dt, u0, u1, &mut step),
                    1 => bwc_contact_advance(law, dt, u0, u1, &mut step),
                    2 => bwc_impact(law, m, -u0, 0.0, &mut impact),
                    3 => bwc_contact_new(contact, std::ptr::null(), &mut 0),
                    _ => bwc_contact_advance(contact ^ 0x1234, dt, u0, u1, std::ptr::null_mut()),
                });
                bwc_contact_free(contact);
                bwc_law_free(law);
                statuses
            };
            match catch_unwind(AssertUnwindSafe(call)) {
                Err(_) => (true, Some(format!("panic: {params:?} {dt} {u0} {u1} {m}"))),
                Ok(statuses) => {
                    let failed = statuses.last().is_some_and(|s| *s != BwcStatus::Ok);
                    if !failed {
                        return (false, None);
                    }
                    // SAFETY: the library's last error is a NUL-terminated string.
                    let message = unsafe { CStr::from_ptr(bwc_last_error()) }
                        .to_string_lossy()
                        .into_owned();
                    let internal = INTERNAL.iter().any(|w| message.contains(w));
                    let named = message.contains('`');
                    let bad = (internal || !named || statuses.contains(&BwcStatus::Internal))
                        .then(|| format!("{statuses:?}: {message} ({params:?}, {dt}, {u0}, {u1})"));
                    (true, bad)
                }
            }
        })
        .collect();
    tally(cases, results)
}

fn report(name: &str, t: &Tally, wall: f64) {
    bwc_app::out!(
        "{name:<16} {:>9} cases {:>9} refused {:>5} failures {:>8.1} s",
        t.cases,
        t.refused,
        t.failures.len(),
        wall
    );
    for f in t.failures.iter().take(5) {
        bwc_app::out!("    {}", f.chars().take(400).collect::<String>());
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let cases: u64 = args
        .first()
        .and_then(|a| a.parse().ok())
        .unwrap_or(1_000_000);
    let seed: u64 = args.get(1).and_then(|a| a.parse().ok()).unwrap_or(1);
    // A panic is a failure counted here, not a message on stderr per case.
    std::panic::set_hook(Box::new(|_| {}));
    let scenes = [
        "two_balls_shccm.toml",
        "two_balls_mcm.toml",
        "cross_shccm.toml",
        "cross_mcm.toml",
        "kharaz_curves.toml",
        "../docs/src/tutorial/first-drop.toml",
        "../docs/src/tutorial/first-sweep.toml",
    ];
    let chains = [
        "newtons_cradle.toml",
        "ball_stack.toml",
        "granular_chain.toml",
    ];
    let configs = [
        "kharaz.toml",
        "villegas.toml",
        "cross.toml",
        "tennis.toml",
        "golf_drops.toml",
    ];
    let data = [
        "data/kharaz_dss.csv",
        "data/real/tennis_v0_e.csv",
        "data/real/baseball_wood_v0_e.csv",
    ];
    let to_message = |e: bwc_app::AppError| e.to_string();
    let boundaries: [(&str, Boundary); 5] = [
        (
            "scene TOML",
            Box::new(|| {
                files(&scenes, cases, seed, |p, t| {
                    Scene::parse(p, t).map(drop).map_err(to_message)
                })
            }),
        ),
        (
            "chain TOML",
            Box::new(|| {
                files(&chains, cases, seed, |p, t| {
                    ChainScene::parse(p, t).map(drop).map_err(to_message)
                })
            }),
        ),
        (
            "config TOML",
            Box::new(|| {
                files(&configs, cases, seed, |p, t| {
                    Config::parse(p, t).map(drop).map_err(to_message)
                })
            }),
        ),
        (
            "CSV data",
            Box::new(|| {
                files(&data, cases, seed, |p, t| {
                    bwc_identify::Dataset::parse(p, t)
                        .map(drop)
                        .map_err(|e| e.to_string())
                })
            }),
        ),
        ("C ABI", Box::new(|| c_abi(cases, seed))),
    ];
    let mut total = 0;
    for (name, run) in &boundaries {
        let start = Instant::now();
        let t = run();
        report(name, &t, start.elapsed().as_secs_f64());
        total += t.failures.len();
    }
    std::process::exit(i32::from(total > 0));
}
