//! A CoR curve over 5,000 impact speeds from a few dozen simulations: `bw_models::sweep::plan`
//! asks for the speeds it needs (simulated here by `impact_at`), and serves the others from
//! verified Chebyshev interpolants in `ln v0`. Checked against the Hunt-Crossley closed form
//! (base parameters with `B_b = Γ_b = 0`, where `σ = σ_b v0`).
//!
//! `cargo run --release --example sweep`

use bw_models::input::Zero;
use bw_models::sweep::{plan, Row, SweepSettings};
use bw_models::{impact_at, BaseMap, BaseParams, ModelKind, Settings};

#[path = "support/hunt_crossley.rs"]
mod hunt_crossley;
use hunt_crossley::hunt_crossley_e;

fn run() -> Result<(), Box<dyn std::error::Error>> {
    let base = BaseParams {
        b_b: 0.0,
        gamma_b: 0.0,
        kappa: 0.5,
        sigma_b: 0.3,
        n: 1.0,
        p: 1.5,
        u_b: 1.0,
        t_b: 1.0,
    };
    let map = BaseMap::new(ModelKind::Shccm, base)?;
    let settings = Settings::default();
    let speeds: Vec<f64> = (0..5_000)
        .map(|i| 0.1 * 60f64.powf(f64::from(i) / 4_999.0))
        .collect();
    // `e` and `t_s` of a separated impact, `None` otherwise (or when the simulation fails).
    let values = |v0: f64| {
        let out = impact_at(&map, Zero, v0, &settings).ok()?;
        Some([out.e, out.t_s?])
    };
    let mut simulations = 0;
    let sweep = plan(&speeds, &SweepSettings { tolerance: 1e-11 }, |batch| {
        simulations += batch.len();
        batch.iter().map(|&v| values(v)).collect()
    });
    let mut worst = 0.0f64;
    for (row, &v0) in sweep.rows.iter().zip(&speeds) {
        let e = match row {
            Row::Interpolated { values, .. } => values[0],
            Row::Simulate => values(v0).ok_or("no separation")?[0],
        };
        worst = worst.max((e - hunt_crossley_e(0.3 * v0)).abs());
    }
    let served = sweep
        .rows
        .iter()
        .filter(|r| matches!(r, Row::Interpolated { .. }))
        .count();
    println!(
        "{} speeds: {served} from {} interpolant(s) after {simulations} simulations; largest \
         error in e against the closed form {worst:.1e}",
        speeds.len(),
        sweep.pieces.len()
    );
    assert!(worst < 1e-11 && served > 4_900 && simulations < 200);
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    run()
}

#[test]
fn sweep_example() {
    run().unwrap();
}
