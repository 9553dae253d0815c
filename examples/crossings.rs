//! A custom ODE with dense output and an event crossed several times: the harmonic oscillator
//! `y'' = -y` from `y = 0, y' = 1` (so `y = sin t`), its values between steps from the dense
//! output, and every upward zero crossing (`t = 2π k`) by one locator that steps on past each.
//!
//! `cargo run --example crossings`

use bwc_events::{Crossing, Direction, Locator, NoSwitches, Step};
use bwc_ode::{Integrator, Options, State, DOP853};

fn run() -> Result<Vec<f64>, Box<dyn std::error::Error>> {
    let f = |_t: f64, y: &State<2>| State::<2>::new(y[1], -y[0]);
    let mut it = Integrator::new(
        f,
        &DOP853,
        0.0,
        State::<2>::new(0.0, 1.0),
        Options::new(1e-12, 1e-14),
    )?;
    // Dense output: y at t = 1 from whichever step contains it.
    it.integrate_to(0.5)?;
    while it.t() < 1.0 {
        it.step(10.0)?;
    }
    let y1 = it.dense().eval(1.0);
    println!("y(1) = {:.15} (sin 1 = {:.15})", y1[0], 1f64.sin());
    assert!((y1[0] - 1f64.sin()).abs() < 1e-11);

    // Upward crossings of y = 0 up to t = 20: 2π, 4π, 6π.
    let mut locator = Locator::new(
        Crossing::new(|_t: f64, y: &State<2>| y[0], Direction::Up),
        NoSwitches,
    );
    let mut crossings = Vec::new();
    while it.t() < 20.0 {
        if let Step::Event { t, .. } = locator.step(&mut it, 20.0)? {
            crossings.push(t);
        }
    }
    for (k, t) in crossings.iter().enumerate() {
        let exact = 2.0 * std::f64::consts::PI * (k + 1) as f64;
        println!(
            "crossing {}: t = {t:.12} (2π·{} = {exact:.12})",
            k + 1,
            k + 1
        );
        assert!((t - exact).abs() < 1e-9);
    }
    assert_eq!(crossings.len(), 3);
    Ok(crossings)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    run().map(|_| ())
}

#[test]
fn crossings_example() {
    assert_eq!(run().unwrap().len(), 3);
}
