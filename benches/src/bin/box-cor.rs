//! CoR evaluations where the fits search: 300 seeded random points of kharaz.toml's box
//! (`B_b` in [0, 5], `g = Γ_b / B_b` in [-1, 1], `κ` in [0.02, 0.98], `σ_b` log-uniform in
//! [1e-5, 0.3], `n` and `p` in [1, 6]) at 0.5, 1.5, 3 and 5 m/s, one model, default settings
//! at one rtol (atol = rtol / 100). Prints the mean time per CoR (the best of three runs of
//! each), the mean RHS evaluations and series steps, and with `check` the error in `e` against
//! the Runge-Kutta path at rtol 1e-13 (max and mean). `slow` lists the 20 slowest CoRs.
//!
//! `cargo run --release -p bwc-benches --bin box-cor -- [shccm|mcm] [RTOL] [check] [slow]`
//! (defaults shccm, 1e-8)

use bw_models::{BaseMap, BaseParams, Cor, ModelKind, Settings};
use bwc_benches::cor;
use rand::{Rng, SeedableRng};
use std::time::Instant;

/// Points of the box.
const POINTS: usize = 300;
/// Impact speeds (m/s).
const SPEEDS: [f64; 4] = [0.5, 1.5, 3.0, 5.0];

/// One timed CoR: its time (us), the result, the point and the speed.
type Row = (f64, Cor, BaseParams, f64);

/// A point of the box.
fn point(rng: &mut rand::rngs::StdRng) -> BaseParams {
    let b = 5.0 * rng.random::<f64>();
    let g = -1.0 + 2.0 * rng.random::<f64>();
    BaseParams {
        b_b: b,
        gamma_b: g * b,
        kappa: 0.02 + 0.96 * rng.random::<f64>(),
        sigma_b: 10f64.powf(-5.0 + (0.3f64.log10() + 5.0) * rng.random::<f64>()),
        n: 1.0 + 5.0 * rng.random::<f64>(),
        p: 1.0 + 5.0 * rng.random::<f64>(),
        u_b: 1.0,
        t_b: 1.0,
    }
}

/// One timed CoR: the best time (us) of three evaluations, and the result.
fn timed(map: &BaseMap, v0: f64, settings: &Settings) -> Option<(f64, Cor)> {
    let mut best = f64::INFINITY;
    let mut out = None;
    for _ in 0..3 {
        let clock = Instant::now();
        let result = cor::evaluate(map, v0, settings);
        best = best.min(clock.elapsed().as_secs_f64() * 1e6);
        out = result.ok();
    }
    out.map(|o| (best, o))
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let kind = match args.first().map(String::as_str) {
        Some("mcm") => ModelKind::Mcm,
        _ => ModelKind::Shccm,
    };
    let rtol: f64 = args.get(1).and_then(|a| a.parse().ok()).unwrap_or(1e-8);
    let (check, slow) = (
        args.iter().any(|a| a == "check"),
        args.iter().any(|a| a == "slow"),
    );
    let settings = Settings {
        rtol,
        atol: rtol / 100.0,
        e_tol: None,
        ..Settings::default()
    };
    let reference = Settings {
        rtol: 1e-13,
        atol: 1e-15,
        series: false,
        e_tol: None,
        ..Settings::default()
    };
    let mut rng = rand::rngs::StdRng::seed_from_u64(12345);
    let mut rows: Vec<Row> = Vec::new();
    let mut errors = Vec::new();
    for _ in 0..POINTS {
        let base = point(&mut rng);
        let Ok(map) = BaseMap::new(kind, base) else {
            continue;
        };
        for v0 in SPEEDS {
            let Some((us, out)) = timed(&map, v0, &settings) else {
                eprintln!("box-cor: no CoR at {base:?}, v0 {v0}");
                continue;
            };
            if check {
                if let Ok(r) = cor::evaluate(&map, v0, &reference) {
                    errors.push((r.e - out.e).abs());
                }
            }
            rows.push((us, out, base, v0));
        }
    }
    let n = rows.len() as f64;
    let mean = |f: &dyn Fn(&Row) -> f64| rows.iter().map(f).sum::<f64>() / n;
    println!(
        "{kind:?} rtol {rtol:e}: {} CoRs, mean {:.2} us, {:.1} RHS evaluations, {:.1} series steps",
        rows.len(),
        mean(&|r| r.0),
        mean(&|r| r.1.stats.rhs_evals as f64),
        mean(&|r| r.1.series_steps as f64),
    );
    if check {
        let max = errors.iter().copied().fold(0.0, f64::max);
        let avg = errors.iter().sum::<f64>() / errors.len() as f64;
        println!(
            "error in e against the Runge-Kutta path at rtol 1e-13: max {max:.3e}, mean {avg:.3e}"
        );
    }
    if slow {
        rows.sort_by(|a, b| b.0.total_cmp(&a.0));
        for (us, out, b, v0) in rows.iter().take(20) {
            println!(
                "{us:7.1} us, {} RHS, {} steps: B_b {:.3} g {:.3} kappa {:.3} sigma_b {:.2e} n {:.3} p {:.3} v0 {v0}",
                out.stats.rhs_evals,
                out.series_steps,
                b.b_b,
                b.gamma_b / b.b_b,
                b.kappa,
                b.sigma_b,
                b.n,
                b.p,
            );
        }
    }
}
