//! A bouncing ball in the user's own loop, with the BWSHCCL contact law as a force element:
//! a baseball (0.145 kg, Table 4's law) dropped from 1 m on a rigid floor. Flights are
//! ballistic; each contact integrates `m v' = F - m g` with the law's `(x, z)` driven by the
//! ball's velocity, from touchdown (law at rest) to the separation `F <= 0 <= v`. The result
//! matches a `[sequence]` scene (the library's `drop_sequence`) to 1e-9.
//!
//! `cargo run --example bouncing_ball`

use bw_models::input::Constant;
use bw_models::sequence::{drop_sequence, Contact, Flight, Policy, SequenceSettings, Start};
use bw_models::Separation;
use bw_models::{impact, Bwshccl, Bwshccm, ContactLaw, ModelKind, PhysicalParams};
use bw_models::{Settings, State};
use bwc_events::{Locator, Outcome, SwitchAt};
use bwc_ode::{Integrator, Options, DOP853};

const M: f64 = 0.145;
const G: f64 = 9.81;
const H0: f64 = 1.0;
const BOUNCES: usize = 4;

/// Table 4's BWSHCCM (Cross's baseball, `bw_models::published`).
fn params() -> Result<PhysicalParams, bw_models::ModelError> {
    PhysicalParams::new(ModelKind::Shccm, bw_models::published::CROSS_BWSHCCM)
}

/// One contact at impact speed `v_in` (m/s): duration (s) and rebound speed (m/s).
fn contact(law: &Bwshccl, v_in: f64) -> Result<(f64, f64), Box<dyn std::error::Error>> {
    // State (x, z, v): the law's displacements (m) and the ball's velocity (m/s, up positive).
    let rhs = |_t: f64, s: &State<3>| {
        let (d, force) = ContactLaw::eval(law, &State::<2>::new(s[0], s[1]), s[2]);
        State::<3>::new(d[0], d[1], force / M - G)
    };
    let force = |_t: f64, s: &State<3>| {
        (
            ContactLaw::eval(law, &State::<2>::new(s[0], s[1]), s[2]).1,
            s[2],
        )
    };
    // Stop exactly where the law is not smooth (its rate and z cross zero).
    let kinks = SwitchAt(|_t: f64, s: &State<3>| law.kinks(&State::<2>::new(s[0], s[1]), s[2]));
    let options = Options::new(1e-12, 1e-17);
    let onset = law.onset();
    let start = State::<3>::new(onset[0], onset[1], -v_in);
    let mut it = Integrator::new(rhs, &DOP853, 0.0, start, options)?;
    match Locator::new(Separation(force), kinks).run(&mut it, 1.0)? {
        Outcome::Event { t, y } => Ok((t, y[2])),
        Outcome::Horizon { .. } => Err("the ball did not separate within 1 s".into()),
    }
}

/// The user's loop: contact onsets (s from release) and rebound speeds (m/s).
fn own_loop() -> Result<Vec<(f64, f64)>, Box<dyn std::error::Error>> {
    let law = Bwshccl::new(&params()?)?;
    let (mut t, mut v_in) = ((2.0 * H0 / G).sqrt(), (2.0 * G * H0).sqrt());
    let mut out = Vec::new();
    for _ in 0..BOUNCES {
        let (t_s, v_out) = contact(&law, v_in)?;
        out.push((t, v_out));
        t += t_s + 2.0 * v_out / G;
        v_in = v_out;
    }
    Ok(out)
}

/// The same sequence from the library, as a `[sequence]` scene runs it.
fn library() -> Result<Vec<(f64, f64)>, Box<dyn std::error::Error>> {
    let params = params()?;
    let settings = SequenceSettings {
        flight: Flight { g: G, drag: 0.0 },
        bounces: BOUNCES,
        policy: Policy::Reset,
    };
    let one = |v_in: f64, _: Option<&()>| {
        let model = Bwshccm::new(&params, M, v_in, Constant(-M * G))?;
        let out = impact(&model, &Settings::default())?;
        Ok(Contact {
            t_s: out.t_s,
            v_out: out.e * v_in,
            settled: out.settled_at.is_some(),
            state: (),
        })
    };
    let bounces = drop_sequence(Start::Height(H0), &settings, one)?;
    Ok(bounces.iter().map(|b| (b.t_contact, b.v_out)).collect())
}

fn run() -> Result<(), Box<dyn std::error::Error>> {
    let (mine, theirs) = (own_loop()?, library()?);
    for (k, ((t, v), (tl, vl))) in mine.iter().zip(&theirs).enumerate() {
        println!(
            "bounce {}: contact at {t:.9} s, rebound {v:.9} m/s (library {tl:.9} s, {vl:.9} m/s)",
            k + 1
        );
        assert!((t - tl).abs() <= 1e-9 * tl && (v - vl).abs() <= 1e-9 * vl);
    }
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    run()
}

#[test]
fn bouncing_ball_example() {
    run().unwrap();
}
