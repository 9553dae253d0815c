//! The phase path (`bw_models::phase`) on the stress sweep's unforced cases (half the sweep:
//! random admissible parameters of both models over the whole admissible set, `v0` from 1e-4
//! to 1e3 m/s), checked at `tol` 1e-10 against the defaults' CoR (checked to `e_tol` = 1e-10):
//! how many it takes, why it declines the rest, and whether it agrees where both report a met
//! check. Lists every case where the two differ by more than `1e-9 + e_error`.
//!
//! `cargo run --release -p bwc-benches --bin phase-stress -- COUNT SEED`, or `-- case SEED I`
//! for one case: its parameters, the defaults' CoR and the phase path's, checked at several
//! tolerances.

use bw_models::phase::{self, PhaseSettings};
use bw_models::{BaseMap, Check, ModelError};
use bwc_benches::stress::{run, sample, Class};
use rayon::prelude::*;
use std::collections::BTreeMap;

/// What one case gave.
enum Verdict {
    /// The defaults did not report a separated run with a met check.
    NoReference,
    /// The phase path declined, with its reason.
    Declined(String),
    /// The phase path's check did not meet `tol`.
    Unmet { off: f64, estimate: f64 },
    /// Both met: their distance.
    Agreed { off: f64 },
    /// Both met, but farther apart than their estimates allow.
    Disagreed { off: f64, estimate: f64 },
}

fn verdict(seed: u64, i: u64) -> Option<Verdict> {
    let case = sample(seed, i);
    if case.input != (0.0, 0.0, 0.0) {
        return None;
    }
    let reference = run(&case);
    let met = matches!(reference.check, Some(Check::Met));
    let Some((e, Some(_))) = reference
        .result
        .filter(|_| met && reference.class == Class::Separated)
    else {
        return Some(Verdict::NoReference);
    };
    let reference_error = reference.e_error.unwrap_or(0.0);
    let params = BaseMap::new(case.kind, case.base).and_then(|m| m.at(case.v0));
    let Ok((params, _)) = params else {
        return Some(Verdict::NoReference);
    };
    let settings = PhaseSettings {
        tol: 1e-10,
        check: true,
        duration: true,
    };
    Some(match phase::cor(&params, &settings) {
        Err(ModelError::NotApplicable { reason }) => Verdict::Declined(reason.to_string()),
        Err(other) => Verdict::Declined(other.to_string()),
        Ok(cor) => {
            let (off, estimate) = ((cor.e - e).abs(), cor.e_error.unwrap_or(f64::NAN));
            // Both estimates bound their errors, give or take a factor of 2 and the roundings.
            let honest = off <= 2.0 * (estimate + reference_error) + 1e-12;
            match cor.tolerance_met {
                Some(true) if honest => Verdict::Agreed { off },
                Some(true) => Verdict::Disagreed { off, estimate },
                _ => Verdict::Unmet { off, estimate },
            }
        }
    })
}

/// `case SEED I`: one case in full.
fn one_case(seed: u64, i: u64) {
    let case = sample(seed, i);
    println!("{:?} {:?} v0 = {} m/s", case.kind, case.base, case.v0);
    let reference = run(&case);
    println!(
        "defaults: {:?} ({:?}, e_error {:?})",
        reference.result, reference.check, reference.e_error
    );
    let Ok((params, _)) = BaseMap::new(case.kind, case.base).and_then(|m| m.at(case.v0)) else {
        return;
    };
    println!("{:?}", params.get());
    for tol in [1e-6, 1e-8, 1e-10, 1e-12] {
        let settings = PhaseSettings {
            tol,
            check: true,
            duration: true,
        };
        println!(
            "phase at tol {tol:.0e}: {:?}",
            phase::cor(&params, &settings)
        );
    }
}

fn main() {
    let raw: Vec<String> = std::env::args().skip(1).collect();
    if raw.len() == 3 && raw[0] == "case" {
        let number = |s: &String| s.parse().expect("case SEED I");
        return one_case(number(&raw[1]), number(&raw[2]));
    }
    let args: Vec<u64> = std::env::args()
        .skip(1)
        .map(|a| a.parse().expect("COUNT SEED"))
        .collect();
    let (count, seed) = (args[0], args[1]);
    let verdicts: Vec<(u64, Verdict)> = (0..count)
        .into_par_iter()
        .filter_map(|i| verdict(seed, i).map(|v| (i, v)))
        .collect();
    let (mut unforced, mut no_reference, mut agreed, mut largest) = (0, 0, 0, 0.0f64);
    let mut declined: BTreeMap<String, usize> = BTreeMap::new();
    let (mut unmet, mut disagreed) = (Vec::new(), Vec::new());
    for (i, v) in verdicts {
        unforced += 1;
        match v {
            Verdict::NoReference => no_reference += 1,
            Verdict::Declined(why) => *declined.entry(why).or_default() += 1,
            Verdict::Unmet { off, estimate } => unmet.push((i, off, estimate)),
            Verdict::Agreed { off } => {
                agreed += 1;
                largest = largest.max(off);
            }
            Verdict::Disagreed { off, estimate } => disagreed.push((i, off, estimate)),
        }
    }
    println!(
        "seed {seed}, {count} cases: {unforced} unforced, {no_reference} without a met reference"
    );
    println!("agreed: {agreed} (largest distance {largest:.1e})");
    let worst_unmet = unmet.iter().map(|u| u.1).fold(0.0f64, f64::max);
    println!(
        "unmet: {} (largest distance {worst_unmet:.1e})",
        unmet.len()
    );
    for (why, n) in &declined {
        println!("declined, {n}: {why}");
    }
    println!("disagreed: {}", disagreed.len());
    for (i, off, estimate) in disagreed {
        println!("  case {i}: {off:.2e} off (estimate {estimate:.1e})");
    }
}
