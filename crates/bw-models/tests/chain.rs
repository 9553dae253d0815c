//! Chains of bodies against what is known about them: two bodies are the paper's two-body
//! system (Section 3: the relative motion with the effective mass and the relative input), and
//! without inputs or walls the total momentum and the energy ledger are conserved.

use bw_models::chain::{
    Chain, ChainBody, ChainPart, ChainRun, ChainSettings, PairLaw, Scheme, Stop, Walls,
};
use bw_models::input::{Arctan, Constant, Input};
use bw_models::sequence::Policy;
use bw_models::{
    impact, Bodies, Bwmcm, Bwshccm, ModelError, ModelKind, Physical, PhysicalParams, Settings,
};

/// The contact law of the paper's application example (Table 2; `c` in the units of the
/// model).
fn table2(kind: ModelKind) -> PhysicalParams {
    let law = Physical {
        k: 1.0e6,
        c: 1.0e3,
        n: 1.5,
        p: 1.5,
        alpha: 0.5,
        beta: 1.0e4,
        gamma: -5.0e3,
        a: 1.0,
    };
    PhysicalParams::new(kind, law).unwrap()
}

/// An input of either kind the application example uses.
#[derive(Debug, Clone, Copy)]
enum Force {
    Constant(Constant),
    Arctan(Arctan),
}

impl Input for Force {
    fn at(&self, t: f64) -> f64 {
        match self {
            Force::Constant(c) => c.at(t),
            Force::Arctan(a) => a.at(t),
        }
    }
    fn is_zero(&self) -> bool {
        matches!(self, Force::Constant(c) if c.0 == 0.0)
    }
    fn is_constant(&self) -> bool {
        matches!(self, Force::Constant(_))
    }
}

/// The Hunt-Crossley law `F = k |x|^(3/2) + c |x|^(3/2) (-ẋ)` (N; `k` in N/m^1.5, `c` in
/// N s/m^2.5): the BWSHCCL with `β = γ = 0` and `A = 1`, so that `z = x` for any `α`.
fn hunt_crossley(k: f64, c: f64) -> PairLaw {
    let law = Physical::hertz_damped(k, c);
    PairLaw::new(&PhysicalParams::new(ModelKind::Shccm, law).unwrap()).unwrap()
}

/// The elastic Hertz law `F = k |x|^(3/2)`: Hunt-Crossley without damping.
fn elastic_hertz(k: f64) -> PairLaw {
    hunt_crossley(k, 0.0)
}

fn tight() -> ChainSettings {
    ChainSettings::default().with_tolerances(1e-12, 1e-17)
}

/// The application example (Section 6) as a chain of two touching balls, ball 2 on the left
/// rising at 1.5 m/s under the arctan push, ball 1 on the right falling at 0.5 m/s under
/// gravity: the rebound ratio and contact duration are the two-body model's `e` and `t_s`
/// (impact at `t = 0`, effective mass, relative input) to 1e-9, for both laws.
#[test]
fn two_bodies_are_the_two_body_model() {
    // Balls of radius 0.05 m and densities 3000 and 1000 kg/m³.
    let ball = |rho: f64| 4.0 / 3.0 * std::f64::consts::PI * rho * 0.05f64.powi(3);
    let (m1, m2) = (ball(3000.0), ball(1000.0));
    let u1 = Force::Constant(Constant(-m1 * 9.81));
    let u2 = Force::Arctan(Arctan {
        m: m2,
        d: 250.0,
        omega: 1000.0,
    });
    let pair = Bodies::new(m1, m2, -0.5, 1.5, 0.05, 0.05, u1, u2).unwrap();
    for kind in [ModelKind::Shccm, ModelKind::Mcm] {
        let params = table2(kind);
        let (m, v0) = (pair.effective_mass(), pair.impact_speed());
        let settings = Settings::default();
        let reference = match kind {
            ModelKind::Shccm => {
                let model = Bwshccm::new(&params, m, v0, pair.relative_input()).unwrap();
                let out = impact(&model, &settings).unwrap();
                (out.e, out.t_s.unwrap())
            }
            ModelKind::Mcm => {
                let model = Bwmcm::new(&params, m, v0, pair.relative_input()).unwrap();
                let out = impact(&model, &settings).unwrap();
                (out.e, out.t_s.unwrap())
            }
        };
        let bodies = vec![
            ChainBody::new(m2, 0.0, 1.5, 0.1, u2),
            ChainBody::new(m1, 0.1, -0.5, 0.1, u1),
        ];
        let law = PairLaw::new(&params).unwrap();
        let chain = Chain::new(bodies, vec![law], Walls::default(), tight()).unwrap();
        let run = chain
            .run(Stop::at(2.0 * reference.1), None, |_| {})
            .unwrap();
        let contact = run.contacts[0];
        assert_eq!(contact.onset, 0.0);
        let e = contact.rebound().unwrap();
        let t_s = contact.separation.unwrap();
        assert!(
            (e - reference.0).abs() <= 1e-9,
            "{kind:?}: e {e} vs {}",
            reference.0
        );
        assert!(
            (t_s - reference.1).abs() <= 1e-9 * reference.1,
            "{kind:?}: t_s {t_s} vs {}",
            reference.1
        );
    }
}

/// Five bodies (masses in kg, velocities in m/s, centres in m, each 0.1 m long) whose gaps and
/// velocities make them collide many times.
const COLLIDING_FIVE: ([f64; 5], [f64; 5], [f64; 5]) = (
    [0.3, 0.1, 0.25, 0.05, 0.4],
    [2.0, 0.0, -0.5, 1.0, -1.5],
    [0.0, 0.1, 0.2005, 0.301, 0.402],
);

/// The colliding five without inputs or walls: the total momentum stays what it was to 1e-12 (relative), and the
/// ledger closes to 1e-9 of the initial kinetic energy, under both policies.
#[test]
fn momentum_and_energy_are_conserved() {
    let (masses, velocities, positions) = COLLIDING_FIVE;
    for (kind, policy) in [
        (ModelKind::Mcm, Policy::Reset),
        (ModelKind::Shccm, Policy::Carry),
    ] {
        let bodies: Vec<_> = (0..5)
            .map(|i| ChainBody::new(masses[i], positions[i], velocities[i], 0.1, Constant(0.0)))
            .collect();
        let p0: f64 = (0..5).map(|i| masses[i] * velocities[i]).sum();
        let law = PairLaw::new(&table2(kind)).unwrap();
        let settings = tight().with_policy(policy);
        let chain = Chain::new(bodies, vec![law], Walls::default(), settings).unwrap();
        let mut worst: f64 = 0.0;
        let run = chain
            .run(Stop::settled(1.0), Some(1e-4), |s| {
                worst = worst.max(s.ledger.imbalance().abs());
            })
            .unwrap();
        assert!(run.settled, "{kind:?}");
        assert!(run.contacts.len() >= 4, "{kind:?}: {:?}", run.contacts);
        let p: f64 = (0..5).map(|i| masses[i] * run.bodies[i].velocity).sum();
        let scale: f64 = (0..5).map(|i| (masses[i] * velocities[i]).abs()).sum();
        assert!((p - p0).abs() <= 1e-12 * scale, "{kind:?}: {p} vs {p0}");
        let l = run.ledger;
        assert!(l.dissipated > 0.0 && l.stored >= 0.0);
        assert!(l.imbalance().abs() <= 1e-9 * l.initial, "{kind:?}: {l:?}");
        assert!(
            worst <= 1e-9 * l.initial,
            "{kind:?}: sampled imbalance {worst}"
        );
        // Settled: every gap opening, in order of the velocities.
        for w in run.bodies.windows(2) {
            assert!(w[1].velocity >= w[0].velocity, "{kind:?}: {:?}", run.bodies);
        }
        // A pair's rebound ratio may pass 1 where a third body pushes during the contact; its
        // dissipation is positive all the same.
        for c in &run.contacts {
            assert!(c.separation.is_some() && c.dissipated > 0.0, "{c:?}");
        }
    }
}

/// A ball dropped on a wall under gravity bounces, each contact with the law of a
/// `[sequence]` scene; the ledger closes with the work of gravity.
#[test]
fn a_ball_bounces_on_a_wall_under_gravity() {
    let m = 0.05;
    let g = 9.81;
    let bodies = vec![ChainBody::new(m, 0.1 + 0.02, 0.0, 0.04, Constant(-m * g))];
    let law = PairLaw::new(&table2(ModelKind::Shccm)).unwrap();
    let walls = Walls::new(Some(0.0), None);
    let chain = Chain::new(bodies, vec![law], walls, tight()).unwrap();
    let run = chain.run(Stop::at(0.6), None, |_| {}).unwrap();
    assert!(run.contacts.len() >= 2, "{:?}", run.contacts);
    // Free fall from 0.1 m: the first contact at sqrt(2 h / g), at sqrt(2 g h).
    let first = run.contacts[0];
    assert!(
        (first.onset - (0.2f64 / g).sqrt()).abs() < 1e-9,
        "{first:?}"
    );
    assert!((first.onset_velocity + (2.0 * g * 0.1f64).sqrt()).abs() < 1e-9);
    let l = run.ledger;
    assert!(l.work > 0.0);
    assert!(l.imbalance().abs() <= 1e-9 * (l.work + l.initial), "{l:?}");
}

/// Bad chains are errors naming the body or pair.
#[test]
fn bad_chains_name_the_body_or_pair() {
    let law = PairLaw::new(&table2(ModelKind::Shccm)).unwrap();
    let body = |m: f64, x: f64| ChainBody::new(m, x, 0.0, 0.1, Constant(0.0));
    let build = |bodies, laws, walls| Chain::new(bodies, laws, walls, ChainSettings::default());
    let part = |r: Result<Chain<Constant>, ModelError>| match r.unwrap_err() {
        ModelError::InvalidChain { part, name, .. } => (part, name),
        e => panic!("{e}"),
    };
    assert_eq!(
        part(build(vec![body(1.0, 0.0)], vec![law], Walls::default())),
        (ChainPart::Chain, "bodies")
    );
    assert_eq!(
        part(build(
            vec![body(1.0, 0.0), body(1.0, 0.2), body(1.0, 0.25)],
            vec![law],
            Walls::default()
        )),
        (ChainPart::Pair(1), "gap")
    );
    assert_eq!(
        part(build(
            vec![body(1.0, 0.0), body(0.0, 0.2)],
            vec![law],
            Walls::default()
        )),
        (ChainPart::Body(1), "mass")
    );
    assert_eq!(
        part(build(
            vec![body(1.0, 0.0), body(1.0, 0.2)],
            vec![law, law],
            Walls::default()
        )),
        (ChainPart::Chain, "laws")
    );
    // A wall overlapping its body.
    assert_eq!(
        part(build(
            vec![body(1.0, 0.0), body(1.0, 0.2)],
            vec![law],
            Walls::new(Some(0.01), None)
        )),
        (ChainPart::Pair(0), "gap")
    );
    let one = build(vec![body(1.0, 0.1)], vec![law], Walls::new(Some(0.0), None));
    assert!(one.is_ok());
}

/// A long chain of touching steel beads with the elastic Hertz law struck at one end (`c = 0`,
/// `p = 3/2`, and `β = γ = 0`, `A = 1`: then `z = x`, and the law is `F = k |x|^(3/2)` for any
/// `α`, the limit `α = 1` of the admissible `0 < α < 1`) carries a solitary wave whose speed grows as the sixth root of
/// its force amplitude (Nesterenko, *Dynamics of Heterogeneous Materials*, 2001, ch. 1:
/// `V_s ∝ F_m^(1/6)`). Two striker speeds a decade apart: the ratio of the wave speeds (from
/// the times of peak force at pairs 20 and 40) equals the ratio of the mean peak forces there
/// to the power 1/6. The Hertz chain is self-similar (velocities `λ v` give forces
/// `λ^(6/5) F` on times `λ^(-1/5) t`), so the law holds to the integration's accuracy, not only
/// asymptotically: 1e-6 here, against Nesterenko's 2 %.
#[test]
fn the_hertz_chain_carries_nesterenko_solitary_waves() {
    let r = 0.005;
    let m = 7850.0 * 4.0 / 3.0 * std::f64::consts::PI * r * r * r;
    // Two identical spheres: F = (2/3) E / (1 - ν²) √(R/2) δ^(3/2), E = 200 GPa, ν = 0.3.
    let k = 2.0 / 3.0 * 200e9 / (1.0 - 0.09) * (r / 2.0f64).sqrt();
    let law = elastic_hertz(k);
    let wave = |striker: f64| {
        let bodies: Vec<_> = (0..60)
            .map(|i| {
                let v = if i == 0 { striker } else { 0.0 };
                ChainBody::new(m, 2.0 * r * i as f64, v, 2.0 * r, Constant(0.0))
            })
            .collect();
        let settings = ChainSettings::default().with_tolerances(1e-10, 1e-15);
        let chain = Chain::new(bodies, vec![law], Walls::default(), settings).unwrap();
        let run = chain.run(Stop::at(4e-3), None, |_| {}).unwrap();
        // Each pair's first contact carries the wave.
        let first = |j: usize| run.contacts.iter().find(|c| c.pair == j).copied().unwrap();
        let (a, b) = (first(20), first(40));
        let speed = 20.0 * 2.0 * r / (b.peak_at - a.peak_at);
        let force = (20..=40).map(|j| first(j).peak_force).sum::<f64>() / 21.0;
        (speed, force)
    };
    let (slow, weak) = wave(0.1);
    let (fast, strong) = wave(1.0);
    let predicted = (strong / weak).powf(1.0 / 6.0);
    assert!(
        ((fast / slow) / predicted - 1.0).abs() < 1e-6,
        "speeds {slow} and {fast} m/s, forces {weak} and {strong} N: ratio {} against {predicted}",
        fast / slow
    );
}

/// The hard-sphere limit: `masses` (left to right, a wall on the left at 0 when `wall`) with
/// centres `x` and velocities `v`, each collision instantaneous and elastic, in the order the
/// gaps (faces `length / 2` from the centres) close; the velocities once no gap closes.
fn hard_spheres(masses: &[f64], x: &[f64], v: &[f64], length: f64, wall: bool) -> Vec<f64> {
    let (mut x, mut v) = (x.to_vec(), v.to_vec());
    for _ in 0..1000 {
        // The next pair to touch: (time, left body or None for the wall, right body).
        let mut next: Option<(f64, Option<usize>, usize)> = None;
        let mut consider = |t: f64, l: Option<usize>, r: usize| {
            if t >= 0.0 && next.is_none_or(|(best, _, _)| t < best) {
                next = Some((t, l, r));
            }
        };
        if wall && v[0] < 0.0 {
            consider((x[0] - length / 2.0) / -v[0], None, 0);
        }
        for i in 0..masses.len() - 1 {
            let closing = v[i] - v[i + 1];
            if closing > 0.0 {
                consider((x[i + 1] - x[i] - length) / closing, Some(i), i + 1);
            }
        }
        let Some((t, l, r)) = next else { return v };
        for (xi, vi) in x.iter_mut().zip(&v) {
            *xi += vi * t;
        }
        match l {
            None => v[r] = -v[r],
            Some(l) => {
                let (m1, m2, u1, u2) = (masses[l], masses[r], v[l], v[r]);
                v[l] = ((m1 - m2) * u1 + 2.0 * m2 * u2) / (m1 + m2);
                v[r] = ((m2 - m1) * u2 + 2.0 * m1 * u1) / (m1 + m2);
            }
        }
    }
    panic!("no end to the hard-sphere collisions");
}

/// The ideal-elastic limits: a stack of three balls arriving together at a wall, 10 mm apart,
/// and Newton's cradle with 0.1 mm gaps, both with the elastic Hertz law and no gravity. As
/// the law stiffens (k from 1e5 to 1e9 N/m^1.5) the contacts shorten and stop overlapping,
/// and the final velocities approach those of instantaneous elastic collisions in sequence
/// (computed above): the error falls with every step of k until it is the integration's own
/// (below 1e-9 of the striking speed: once the contacts no longer overlap, an elastic contact
/// gives the hard-sphere velocities exactly).
#[test]
fn stiff_elastic_chains_approach_the_hard_sphere_limit() {
    let elastic = elastic_hertz;
    let cases: [(&[f64], f64, f64, bool); 2] = [
        // The stack: heavy to light from the wall, all at -4.43 m/s, 10 mm apart.
        (&[0.6, 0.145, 0.057], 0.05, 0.01, true),
        // The cradle: five equal balls, the first at 1 m/s, 0.1 mm apart.
        (&[0.0642; 5], 0.025, 1e-4, false),
    ];
    for (masses, length, gap, wall) in cases {
        let n = masses.len();
        let x: Vec<f64> = (0..n)
            .map(|i| 0.1 + length / 2.0 + i as f64 * (length + gap))
            .collect();
        let v: Vec<f64> = if wall {
            vec![-4.43; n]
        } else {
            (0..n).map(|i| if i == 0 { 1.0 } else { 0.0 }).collect()
        };
        let ideal = hard_spheres(masses, &x, &v, length, wall);
        let speed = v.iter().fold(0.0f64, |a, b| a.max(b.abs()));
        let mut errors = Vec::new();
        for k in [1e5, 1e6, 1e7, 1e8, 1e9] {
            let bodies: Vec<_> = (0..n)
                .map(|i| ChainBody::new(masses[i], x[i], v[i], length, Constant(0.0)))
                .collect();
            let walls = Walls::new(wall.then_some(0.0), None);
            let chain = Chain::new(bodies, vec![elastic(k)], walls, tight()).unwrap();
            // Settled, or at rest to the tolerance (balls left drifting at 1e-12 m/s).
            let run = chain.run(Stop::settled(1.0), None, |_| {}).unwrap();
            let error = run
                .bodies
                .iter()
                .zip(&ideal)
                .map(|(b, i)| (b.velocity - i).abs())
                .fold(0.0f64, f64::max);
            errors.push(error / speed);
        }
        let floor = 1e-9;
        assert!(
            errors.windows(2).all(|w| w[1] < w[0] || w[1] < floor)
                && errors[0] > 1e3 * floor
                && errors[errors.len() - 1] < floor,
            "wall {wall}: errors {errors:?} against {ideal:?}"
        );
    }
}

/// A chain run twice: integrating only the bodies in contact (the default) and every body.
fn both_schemes(chain: &Chain<Constant>, stop: Stop) -> [ChainRun; 2] {
    [Scheme::Contacts, Scheme::Whole].map(|scheme| {
        let settings = chain.settings().with_scheme(scheme);
        let again = Chain::new(
            chain.bodies().to_vec(),
            chain.laws().to_vec(),
            chain.walls(),
            settings,
        )
        .unwrap();
        again.run(stop, None, |_| {}).unwrap()
    })
}

/// Bodies in no contact fly in closed form and the onsets of free pairs are predicted in closed
/// form; that gives the answer of integrating every body, to the integration's tolerance: on
/// the colliding bodies of the momentum test (both policies), a stack dropped on a wall under
/// gravity, a struck Hertz chain and a gas of 30 bodies between two walls. Final positions and
/// velocities within 1e-9 of their scales, every contact's onset (but where touching beads begin
/// at rest) and separation within 1e-9 of the run's length, and the same number of contacts.
#[test]
fn integrating_only_the_bodies_in_contact_changes_nothing() {
    let law = |kind| PairLaw::new(&table2(kind)).unwrap();
    let body = |m: f64, x: f64, v: f64, l: f64, u: f64| ChainBody::new(m, x, v, l, Constant(u));
    let mut scenes: Vec<(&str, Chain<Constant>, Stop)> = Vec::new();
    let (masses, velocities, positions) = COLLIDING_FIVE;
    for (kind, policy) in [
        (ModelKind::Mcm, Policy::Reset),
        (ModelKind::Shccm, Policy::Carry),
    ] {
        let bodies = (0..5)
            .map(|i| body(masses[i], positions[i], velocities[i], 0.1, 0.0))
            .collect();
        let settings = tight().with_policy(policy);
        let chain = Chain::new(bodies, vec![law(kind)], Walls::default(), settings).unwrap();
        scenes.push(("colliding five", chain, Stop::settled(1.0)));
    }
    let stack = [0.6, 0.145, 0.057]
        .iter()
        .enumerate()
        .map(|(i, &m)| body(m, 0.2 + 0.06 * i as f64, 0.0, 0.05, -9.81 * m))
        .collect();
    let walls = Walls::new(Some(0.0), None);
    let chain = Chain::new(stack, vec![law(ModelKind::Shccm)], walls, tight()).unwrap();
    scenes.push(("stack", chain, Stop::at(0.5)));
    let r = 0.005;
    let beads = (0..40)
        .map(|i| {
            body(
                4.1092e-3,
                2.0 * r * i as f64,
                f64::from(u8::from(i == 0)),
                2.0 * r,
                0.0,
            )
        })
        .collect();
    let settings = ChainSettings::default().with_tolerances(1e-11, 1e-16);
    let chain = Chain::new(
        beads,
        vec![elastic_hertz(7.326e9)],
        Walls::default(),
        settings,
    );
    scenes.push(("Hertz chain", chain.unwrap(), Stop::at(2e-3)));
    // A gas: 30 bodies 0.05 m long between walls, gaps and velocities from a fixed recipe.
    let mut x = 0.0;
    let gas = (0..30)
        .map(|i| {
            let f = f64::from(i);
            x += 0.05 + 0.01 * (1.0 + (1.7 * f).sin());
            body(0.1 + 0.05 * (0.3 * f).cos(), x, (2.3 * f).sin(), 0.05, 0.0)
        })
        .collect();
    let walls = Walls::new(Some(0.0), Some(x + 0.1));
    let chain = Chain::new(gas, vec![law(ModelKind::Shccm)], walls, tight()).unwrap();
    scenes.push(("gas", chain, Stop::at(0.5)));
    for (name, chain, stop) in &scenes {
        let [contacts, whole] = both_schemes(chain, *stop);
        assert_eq!(contacts.contacts.len(), whole.contacts.len(), "{name}");
        assert!(
            contacts.contacts.len() >= 3,
            "{name}: {:?}",
            contacts.contacts
        );
        let scale = chain
            .bodies()
            .iter()
            .map(|b| b.velocity)
            .chain(whole.bodies.iter().map(|b| b.velocity))
            .fold(0.0f64, |a, v| a.max(v.abs()));
        for (a, b) in contacts.bodies.iter().zip(&whole.bodies) {
            assert!(
                (a.velocity - b.velocity).abs() <= 1e-9 * scale,
                "{name}: {a:?} {b:?}"
            );
            assert!(
                (a.position - b.position).abs() <= 1e-9,
                "{name}: {a:?} {b:?}"
            );
        }
        let t = whole.t_end;
        for (a, b) in contacts.contacts.iter().zip(&whole.contacts) {
            assert_eq!(a.pair, b.pair, "{name}");
            // Touching beads begin as the wave's precursor reaches them, at relative velocities
            // of 1e-300 m/s whose sign is the integration's rounding: those onsets are not
            // compared, their contacts' separations are.
            if a.onset_velocity < -1e-6 * scale {
                assert!((a.onset - b.onset).abs() <= 1e-9 * t, "{name}: {a:?} {b:?}");
            }
            let (sa, sb) = (a.separation.unwrap_or(t), b.separation.unwrap_or(t));
            assert!((sa - sb).abs() <= 1e-9 * t, "{name}: {a:?} {b:?}");
        }
        let (la, lb) = (contacts.ledger, whole.ledger);
        assert!((la.dissipated - lb.dissipated).abs() <= 1e-9 * (la.initial + la.work.abs()));
        assert!(
            la.imbalance().abs() <= 1e-9 * (la.initial + la.work.abs()),
            "{name}: {la:?}"
        );
        // The point of it: fewer right-hand-side evaluations of fewer bodies.
        assert!(
            contacts.stats.accepted <= 2 * whole.stats.accepted,
            "{name}"
        );
    }
}

/// The largest force of a damped contact lies inside a step, before the maximal compression:
/// two bodies under the Hunt-Crossley law `F = k |x|^1.5 (1 + (c/k) (-ẋ))` (the BWSHCCL with
/// `β = γ = 0`, `A = 1`) reach the peak force of an independent fixed-step RK4 integration of
/// the relative motion `m_e ẍ = F` (step 1e-6 of the contact, the peak refined by a parabola
/// through the largest sample and its neighbours) to 1e-9 relative.
#[test]
fn a_damped_contacts_peak_force_is_found_inside_a_step() {
    let (m1, m2, k, c, v0) = (0.1, 0.3, 1.0e7, 3.0e6, 1.0);
    let pair = hunt_crossley(k, c);
    let bodies = vec![
        ChainBody::new(m1, 0.0, v0, 0.1, Constant(0.0)),
        ChainBody::new(m2, 0.1, 0.0, 0.1, Constant(0.0)),
    ];
    let chain = Chain::new(bodies, vec![pair], Walls::default(), tight()).unwrap();
    let run = chain.run(Stop::at(1e-2), None, |_| {}).unwrap();
    let contact = run.contacts[0];
    // The reference: x < 0 in compression, u = ẋ the relative velocity.
    let m_e = m1 * m2 / (m1 + m2);
    let force = |x: f64, u: f64| {
        let xp = x.abs().powf(1.5);
        if x < 0.0 {
            k * xp - c * xp * u
        } else {
            0.0
        }
    };
    let rhs = |x: f64, u: f64| (u, force(x, u) / m_e);
    let t_d = contact.separation.unwrap() - contact.onset;
    let h = 1e-6 * t_d;
    let (mut x, mut u) = (0.0f64, -v0);
    let mut samples = vec![0.0];
    while x <= 0.0 {
        let k1 = rhs(x, u);
        let k2 = rhs(x + 0.5 * h * k1.0, u + 0.5 * h * k1.1);
        let k3 = rhs(x + 0.5 * h * k2.0, u + 0.5 * h * k2.1);
        let k4 = rhs(x + h * k3.0, u + h * k3.1);
        x += h / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0);
        u += h / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1);
        samples.push(force(x, u));
    }
    let i = (1..samples.len() - 1)
        .max_by(|&a, &b| samples[a].total_cmp(&samples[b]))
        .unwrap();
    let (a, b, d) = (samples[i - 1], samples[i], samples[i + 1]);
    let peak = b + (d - a).powi(2) / (8.0 * (2.0 * b - a - d));
    let relative = (contact.peak_force - peak).abs() / peak;
    assert!(
        relative < 1e-9,
        "peak {} against {peak}: {relative:e}",
        contact.peak_force
    );
    // Before the maximal compression, where the damping still adds to the spring force.
    let t_peak = i as f64 * h;
    assert!((contact.peak_at - contact.onset - t_peak).abs() < 2.0 * h);
}

/// A pair of any registered law: two equal balls, one at rest, the other meeting it at `v`,
/// joined by Thornton's law (by name). In the centre-of-mass frame the impact is a body of
/// the effective mass `m/2` meeting the law at `v`, so the relative rebound speed is
/// Thornton's closed form at `r = v_y / v`, `(5/4) (m/2) v_y² = k δ_y^(5/2)`.
#[test]
fn a_pair_of_a_law_by_name_rebounds_at_its_closed_form() {
    let (m, v, k, r) = (0.01f64, 1.0f64, 1e9f64, 0.2f64);
    let delta_y = (1.25 * 0.5 * m * (r * v).powi(2) / k).powf(0.4);
    let law = PairLaw::of_law("thornton", &[("k", k), ("delta_y", delta_y)]).unwrap();
    assert_eq!(law.spec().states, ["x", "x_m"]);
    let bodies = vec![
        ChainBody::new(m, 0.0, v, 0.01, Constant(0.0)),
        ChainBody::new(m, 0.01, 0.0, 0.01, Constant(0.0)),
    ];
    let chain = Chain::new(bodies, vec![law], Walls::default(), tight()).unwrap();
    let run = chain.run(Stop::at(1e-3), None, |_| {}).unwrap();
    let e = run.contacts[0].rebound().unwrap();
    let want = (6.0 * 3f64.sqrt() / 5.0).sqrt()
        * (1.0 - r * r / 6.0).sqrt()
        * (r / (r + 2.0 * (1.2 - 0.2 * r * r).sqrt())).powf(0.25);
    assert!((e - want).abs() < 1e-8, "e {e} vs Thornton {want}");
}
