//! Arbitrary and near-valid inputs: never a panic; every error names the file.
use bwc_app::fit::config::Config;
use bwc_app::impact::scene::Scene;
use proptest::prelude::*;
use proptest::test_runner::RngSeed;
use std::path::{Path, PathBuf};

fn fixtures() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures")
}

fn config(cases: u32) -> ProptestConfig {
    ProptestConfig {
        cases,
        rng_seed: RngSeed::Fixed(0x6277_6321),
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

const SCENES: [&str; 5] = [
    "two_balls_shccm.toml",
    "two_balls_mcm.toml",
    "cross_shccm.toml",
    "cross_mcm.toml",
    "kharaz_curves.toml",
];
const CONFIGS: [&str; 4] = [
    "kharaz.toml",
    "villegas.toml",
    "cross.toml",
    "baseball_wood.toml",
];
const REPLACEMENTS: [&str; 12] = [
    "nan", "inf", "-inf", "1e308", "-1", "0", "\"x\"", "[]", "1e-320", "{}", "true", "-1e308",
];

/// Replaces the `which`-th number of `text` by a hostile value, deletes or duplicates a
/// line, or truncates the text.
fn mutate(text: &str, op: usize, which: usize, with: usize) -> String {
    let lines: Vec<&str> = text.lines().collect();
    match op % 4 {
        0 => {
            let numbers: Vec<(usize, usize)> = {
                let bytes = text.as_bytes();
                let mut spans = Vec::new();
                let mut i = 0;
                while i < bytes.len() {
                    if bytes[i].is_ascii_digit()
                        && (i == 0 || !bytes[i - 1].is_ascii_alphanumeric() && bytes[i - 1] != b'_')
                    {
                        let start = if i > 0 && bytes[i - 1] == b'-' {
                            i - 1
                        } else {
                            i
                        };
                        let mut j = i;
                        while j < bytes.len()
                            && (bytes[j].is_ascii_digit() || b".eE-+".contains(&bytes[j]))
                        {
                            j += 1;
                        }
                        spans.push((start, j));
                        i = j;
                    } else {
                        i += 1;
                    }
                }
                spans
            };
            if numbers.is_empty() {
                return text.to_string();
            }
            let (a, b) = numbers[which % numbers.len()];
            format!(
                "{}{}{}",
                &text[..a],
                REPLACEMENTS[with % REPLACEMENTS.len()],
                &text[b..]
            )
        }
        1 => lines
            .iter()
            .enumerate()
            .filter(|(i, _)| *i != which % lines.len().max(1))
            .map(|(_, l)| *l)
            .collect::<Vec<_>>()
            .join("\n"),
        2 => {
            let mut v = lines.clone();
            let i = which % v.len().max(1);
            v.insert(i, lines[i]);
            v.join("\n")
        }
        _ => {
            let mut cut = which % text.len().max(1);
            while !text.is_char_boundary(cut) {
                cut -= 1;
            }
            text[..cut].to_string()
        }
    }
}

proptest! {
    #![proptest_config(config(256))]

    #[test]
    fn arbitrary_text_never_panics(text in ".{0,400}") {
        let p = Path::new("fuzz.toml");
        if let Err(e) = Scene::parse(p, &text) {
            prop_assert!(e.to_string().contains("fuzz.toml"), "{e}");
        }
        if let Err(e) = Config::parse(p, &text) {
            prop_assert!(e.to_string().contains("fuzz.toml"), "{e}");
        }
        let _ = bwc_identify::Dataset::parse(p, &text);
    }

    /// Mutated fixtures: parsing never panics, errors name the file, and a scene that still
    /// parses runs (with a bounded step budget) without panicking.
    #[test]
    fn mutated_fixtures_never_panic(file in 0usize..9, op in 0usize..4, which in 0usize..10_000, with in 0usize..100) {
        let (name, is_scene) = if file < 5 { (SCENES[file], true) } else { (CONFIGS[file - 5], false) };
        let path = fixtures().join(name);
        let text = std::fs::read_to_string(&path).unwrap();
        let mutated = mutate(&text, op, which, with);
        if is_scene {
            match Scene::parse(&path, &mutated) {
                Err(e) => prop_assert!(e.to_string().contains(name), "{e}"),
                Ok(mut scene) => {
                    scene.settings.max_steps = 20_000;
                    scene.speeds.truncate(3);
                    let _ = bwc_app::impact::simulate::run(&scene, None);
                }
            }
        } else if let Err(e) = Config::parse(&path, &mutated) {
            prop_assert!(e.to_string().contains(name), "{e}");
        }
    }
}
