//! A host that drops a ball on a floor and tracks its overlap, holding the contact element
//! (`advance_penetration`), bounces as a `[sequence]` scene of the same law does: the same
//! impact speeds and rebounds, contact after contact, under both policies.
//!
//! The host steps its ball with a predictor-corrector of step `dt` (the velocity from the
//! element's impulse, the height by the trapezoid rule, exact in free flight), so its error is
//! `O(dt²)` of a contact's duration: about 1e-7 relative at `dt` = 1e-6 s against contacts of
//! 0.2-0.6 ms. The scene's bounces are the library's impacts to 1e-10.

use bw_models::sequence::Policy;
use bw_models::{
    Bwmcl, Bwshccl, ContactElement, ContactLaw, ElementSettings, ModelKind, Penetration, Physical,
    PhysicalParams,
};
use bwc_app::impact::scene::Scene;
use std::path::Path;

const M: f64 = 0.145;
const G: f64 = 9.81;
const H0: f64 = 0.1;
const BOUNCES: usize = 3;

/// Table 4's laws (the Cross baseball), as in `fixtures/cross_*.toml`.
fn law(kind: ModelKind) -> Physical {
    bw_models::published::cross_law(kind)
}

/// The scene's bounces: `(v_in, v_out)` per contact.
fn scene_bounces(kind: ModelKind, policy: &str) -> Vec<(f64, f64)> {
    let l = law(kind);
    let src = format!(
        "model = \"{}\"\n[sequence]\nh0 = {H0}\nbounces = {BOUNCES}\npolicy = \"{policy}\"\n\
         [physical]\nm = {M}\nk = {}\nc = {}\nn = {}\np = {}\nalpha = {}\nbeta = {}\n\
         gamma = {}\nA = {}\n",
        kind.name(),
        l.k,
        l.c,
        l.n,
        l.p,
        l.alpha,
        l.beta,
        l.gamma,
        l.a
    );
    let scene = Scene::parse(Path::new("drop.toml"), &src).unwrap();
    let seq = scene.sequence.as_ref().unwrap();
    let bounces =
        bwc_app::impact::sequence::bounces(&scene.systems[0], seq, &scene.settings).unwrap();
    bounces.iter().map(|(b, _)| (b.v_in, b.v_out)).collect()
}

/// The host's bounces: `(v_in, v_out)` per contact.
fn host_bounces<L: ContactLaw<N> + Clone, const N: usize>(
    law: L,
    policy: Policy,
    dt: f64,
) -> Vec<(f64, f64)> {
    let mut settings = ElementSettings::default();
    settings.policy = policy;
    let mut element = ContactElement::new(law, settings).unwrap();
    let (mut y, mut v, mut force) = (H0, 0.0, 0.0);
    let mut out = Vec::new();
    let mut v_in = f64::NAN;
    let end = |y: f64, v: f64| Penetration {
        depth: -y,
        rate: -v,
    };
    while out.len() < BOUNCES {
        let predicted = v + (force / M - G) * dt;
        let trial = element
            .clone()
            .advance_penetration(
                dt,
                end(y, v),
                end(y + 0.5 * dt * (v + predicted), predicted),
            )
            .unwrap();
        let v1 = v + trial.impulse / M - G * dt;
        let y1 = y + 0.5 * dt * (v + v1);
        let step = element
            .advance_penetration(dt, end(y, v), end(y1, v1))
            .unwrap();
        // In free flight before an onset and after a separation the ball's velocity is
        // exact: the impact speed and the rebound follow from the step's ends.
        if let Some(t) = step.began_at {
            v_in = G * t - v;
        }
        if let Some(t) = step.separated_at {
            out.push((v_in, v1 + G * (dt - t)));
        }
        (y, v, force) = (y1, v1, step.force);
    }
    out
}

#[test]
fn a_host_tracking_the_overlap_bounces_as_the_sequence_scene() {
    for kind in [ModelKind::Shccm, ModelKind::Mcm] {
        let params = PhysicalParams::new(kind, law(kind)).unwrap();
        for (policy, name) in [(Policy::Reset, "reset"), (Policy::Carry, "carry")] {
            let reference = scene_bounces(kind, name);
            let host = match kind {
                ModelKind::Shccm => host_bounces(Bwshccl::new(&params).unwrap(), policy, 1e-6),
                ModelKind::Mcm => host_bounces(Bwmcl::new(&params).unwrap(), policy, 1e-6),
            };
            for (i, (h, r)) in host.iter().zip(&reference).enumerate() {
                let err_in = (h.0 - r.0).abs() / r.0;
                let err_out = (h.1 - r.1).abs() / r.1;
                assert!(
                    err_in < 1e-6 && err_out < 1e-6,
                    "{kind:?} {name} contact {}: host {h:?}, scene {r:?}",
                    i + 1
                );
            }
        }
    }
}
