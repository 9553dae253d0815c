//! A coefficient of restitution in a few lines: the NDBWSHCCM in its Hunt-Crossley limit
//! (`B = Γ = 0`), checked against the closed form, and a baseball's CoR at 3 m/s from the
//! Table 4 contact law in SI units.
//!
//! `cargo run --example cor`

use bw_models::input::Zero;
use bw_models::{impact, Bwshccm, ModelKind, Ndbwshccm, Nondim, NondimParams};
use bw_models::{PhysicalParams, Settings};

#[path = "support/hunt_crossley.rs"]
mod hunt_crossley;
use hunt_crossley::hunt_crossley_e;

fn run() -> Result<(), Box<dyn std::error::Error>> {
    let nd = Nondim {
        b: 0.0,
        gamma: 0.0,
        kappa: 0.5,
        sigma: 0.5,
        n: 1.0,
        p: 1.5,
    };
    let model = Ndbwshccm::new(&NondimParams::new(ModelKind::Shccm, nd)?, Zero)?;
    let out = impact(&model, &Settings::default())?;
    let exact = hunt_crossley_e(0.5);
    println!(
        "Hunt-Crossley limit: e = {:.15} (closed form {exact:.15}), T_s = {:?}",
        out.e, out.t_s
    );
    assert!((out.e - exact).abs() < 1e-10);

    // Table 4 (Cross's baseball, BWSHCCM): SI parameters (k = 117080063 kg m^(1-p) s^-2,
    // c = 5854003 kg m^-p s^-1, n = 1.1, p = 1.7, alpha = 0.1, beta = 981.05 m^-n,
    // gamma = -961.4 m^-n, A = 0.925), mass 0.145 kg, 3 m/s.
    let params = PhysicalParams::new(ModelKind::Shccm, bw_models::published::CROSS_BWSHCCM)?;
    let ball = impact(
        &Bwshccm::new(&params, 0.145, 3.0, Zero)?,
        &Settings::default(),
    )?;
    println!(
        "baseball at 3 m/s: e = {:.6}, contact {:.3e} s",
        ball.e,
        ball.t_s.unwrap_or(f64::NAN)
    );
    assert!(ball.separated() && ball.e > 0.5 && ball.e < 0.8);
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    run()
}

#[test]
fn cor_example() {
    run().unwrap();
}
