//! Hints at unit slips in a scene: values the models admit whose magnitude suggests another
//! unit than the one asked for. The run still runs; each hint names the likely slip and the
//! fix.
//!
//! | quantity | hint where | likely slip |
//! | --- | --- | --- |
//! | impact speed `v0` | above [`bwc_identify::PLAUSIBLE_SPEED`] = 100 m/s | mm/s for m/s |
//! | mass (`m`, `m1`, `m2`, `[sequence].m`; a config's `[fit.known].m`, `[fit.sequence].m`) | above [`HEAVY`] = 20 kg | g for kg |
//! | stiffness `k` | below [`SOFT`] = 100 N/m^p | N/mm^p or kN/m^p for N/m^p |

use crate::impact::scene::{Scene, System};
use bwc_identify::PLAUSIBLE_SPEED;
use std::path::Path;

/// A mass above this (kg) gets a hint: balls and bodies of contact experiments weigh grams to
/// kilograms, so a value in the hundreds is most likely in grams.
pub const HEAVY: f64 = 20.0;

/// A stiffness below this (N/m^p) gets a hint: the softest contact laws fitted to balls
/// (foam, rubber) have `k` of 1e3 N/m^p and more.
pub const SOFT: f64 = 100.0;

/// The hint for a mass `m` (kg) of key `key` in the file at `path`, if it is heavier than
/// [`HEAVY`].
pub fn mass_hint(path: &Path, key: &str, m: f64) -> Option<String> {
    (m.is_finite() && m > HEAVY).then(|| {
        format!(
            "{}: `{key}` = {m} kg is heavier than the {HEAVY} kg of the bodies these laws are \
             fitted to: if grams were meant, divide by 1000 ({} kg)",
            path.display(),
            m / 1000.0
        )
    })
}

/// The hints of a scene.
pub fn scene_hints(scene: &Scene) -> Vec<String> {
    let file = scene.path.display();
    let mut hints = Vec::new();
    if let Some(v) = scene.speeds.iter().copied().reduce(f64::max) {
        if v > PLAUSIBLE_SPEED {
            hints.push(format!(
                "{file}: `v0` reaches {v} m/s, above the {PLAUSIBLE_SPEED} m/s of any contact \
                 experiment: if mm/s were meant, divide by 1000 ({} m/s)",
                v / 1000.0
            ));
        }
    }
    let mut mass = |key: &str, m: f64| hints.extend(mass_hint(&scene.path, key, m));
    for s in &scene.systems {
        match &s.system {
            System::Physical { m, .. } => mass("[physical].m", *m),
            System::Bodies { bodies, .. } => {
                let (m1, m2) = bodies.masses();
                mass("[bodies].m1", m1);
                mass("[bodies].m2", m2);
            }
            _ => {}
        }
    }
    if let Some(m) = scene.sequence.as_ref().and_then(|q| q.m) {
        mass("[sequence].m", m);
    }
    for s in &scene.systems {
        if let System::Physical { params, .. } | System::Bodies { params, .. } = &s.system {
            let (k, p) = (params.law().k, params.law().p);
            if k < SOFT {
                hints.push(format!(
                    "{file}: `[physical].k` = {k} N/m^{p} is softer than any contact law fitted \
                     to balls (1e3 N/m^p and more): if N/mm^p or kN/m^p were meant, multiply \
                     by {:e} or by 1000",
                    1000f64.powf(p)
                ));
            }
        }
    }
    hints
}
