//! Whether the sweeps' interpolants keep their tolerance (`bw_models::sweep`, BENCHMARKS.md,
//! "Sweeps from verified interpolants"): random base parameter sets of both models over the
//! fits' search box (every other one under a random constant input, -1 to 0.3 N with
//! `U_b = T_b = 1`), each swept over 400 (or COUNT) log-spaced speeds from 0.1 to 10 m/s with the default
//! settings, once served by interpolants and once simulating every speed, against a reference
//! simulating every speed at rtol 1e-13. Differences in the tolerance's terms (absolute in `e`,
//! relative to the sweep's largest `t_s` in `t_s`): an interpolated row against the simulation
//! of its speed, and both against the reference.
//!
//! `target/release/sweep-check [CASES] [SEED] [COUNT]` (defaults 200, 1, 400)

use bwc_app::impact::runs::Run;
use bwc_app::impact::scene::Scene;
use bwc_app::impact::simulate;
use rand::{Rng, SeedableRng};
use rayon::prelude::*;
use std::path::Path;

fn log_uniform(rng: &mut impl Rng, lo: f64, hi: f64) -> f64 {
    lo * (hi / lo).powf(rng.random::<f64>())
}

/// Case `i` with `extra` tables: one base parameter set, drawn as the fits search them, at
/// `count` speeds.
fn scene(seed: u64, i: u64, count: usize, extra: &str) -> Scene {
    let mut rng = rand::rngs::StdRng::seed_from_u64(seed ^ i.wrapping_mul(0x9E37_79B9_7F4A_7C15));
    let model = if rng.random::<bool>() { "shccm" } else { "mcm" };
    let b = log_uniform(&mut rng, 0.01, 10.0);
    let g = if rng.random::<bool>() {
        -1.0
    } else {
        rng.random_range(-1.0..=1.0)
    };
    let mut text = format!(
        "model = \"{model}\"\nv0 = {{ from = 0.1, to = 10.0, count = {count}, spacing = \"log\" }}\n\
         {extra}[base]\nB_b = {b}\nGamma_b = {}\nkappa = {}\nsigma_b = {}\nn = {}\np = {}\n",
        g * b,
        rng.random_range(0.05..0.95),
        log_uniform(&mut rng, 1e-3, 1.0),
        rng.random_range(1.0..3.0),
        rng.random_range(1.0..3.0),
    );
    // Every other case under a constant input (N): a push (negative) can make slow impacts
    // settle instead of separating, a change of outcome within the sweep.
    if i % 2 == 1 {
        let u = rng.random_range(-1.0..0.3);
        text += &format!("U_b = 1.0\nT_b = 1.0\n[input]\nkind = \"constant\"\nvalue = {u}\n");
    }
    Scene::parse(Path::new("sweep-check.toml"), &text).expect("admissible parameters")
}

/// The largest error of the rows of `runs` marked in `rows` against `reference`, in the
/// tolerance's terms (infinite where a run did not separate like its reference); 0 for none.
fn worst(runs: &[Run], reference: &[Run], rows: &[bool]) -> f64 {
    let scale = reference
        .iter()
        .filter_map(|r| r.t_s)
        .fold(0.0f64, |m, t| m.max(t.abs()));
    let marked = runs.iter().zip(reference).zip(rows).filter(|(_, &m)| m);
    let errors = marked.map(|((r, q), _)| {
        let dt = match (r.t_s, q.t_s) {
            (Some(a), Some(b)) => (a - b).abs() / scale,
            (None, None) => 0.0,
            _ => f64::INFINITY,
        };
        (r.e - q.e).abs().max(dt)
    });
    errors.fold(0.0, f64::max)
}

/// One case: the interpolated rows, and as multiples of the tolerance their largest difference
/// from the simulations of their speeds, their largest error against the reference, and the
/// simulations' largest error there; and whether the reference's outcome changes within the
/// sweep.
fn case(seed: u64, i: u64, count: usize) -> (usize, [f64; 3], bool) {
    let fast = scene(seed, i, count, "");
    let tolerance = fast.sweep.tolerance;
    let every = scene(seed, i, count, "[sweep]\ninterpolate = false\n");
    let reference = scene(
        seed,
        i,
        count,
        "[sweep]\ninterpolate = false\n[solver]\nrtol = 1e-13\natol = 1e-15\n",
    );
    let (a, b, r) = (
        simulate::run(&fast, None),
        simulate::run(&every, None),
        simulate::run(&reference, None),
    );
    let rows: Vec<bool> = a.iter().map(|x| x.interpolation.is_some()).collect();
    let count = rows.iter().filter(|&&x| x).count();
    let errors = [
        worst(&a, &b, &rows),
        worst(&a, &r, &rows),
        worst(&b, &r, &rows),
    ];
    let changes = r.windows(2).any(|w| w[0].outcome != w[1].outcome);
    (count, errors.map(|e| e / tolerance), changes)
}

fn main() {
    let mut args = std::env::args().skip(1);
    let cases: u64 = args.next().and_then(|a| a.parse().ok()).unwrap_or(200);
    let seed: u64 = args.next().and_then(|a| a.parse().ok()).unwrap_or(1);
    let count: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(400);
    let results: Vec<(usize, [f64; 3], bool)> = (0..cases)
        .into_par_iter()
        .map(|i| case(seed, i, count))
        .collect();
    let rows: usize = results.iter().map(|r| r.0).sum();
    let changes = results.iter().filter(|r| r.2).count();
    let none = results.iter().filter(|r| r.0 == 0).count();
    let max = |k: usize| results.iter().map(|r| r.1[k]).fold(0.0, f64::max);
    let over = results.iter().filter(|r| r.1[0] > 1.0).count();
    bwc_app::out!(
        "{cases} sweeps of {count} speeds ({changes} with a change of outcome): {rows} rows \
         interpolated ({none} sweeps with none)\n\
         largest difference of an interpolated row from its speed's simulation: {:.3} \
         tolerances ({over} sweeps above 1)\n\
         largest error against rtol 1e-13: interpolated rows {:.3}, the simulations at the same \
         speeds {:.3} tolerances",
        max(0),
        max(1),
        max(2)
    );
    for (i, r) in results.iter().enumerate().filter(|(_, r)| r.1[0] > 1.0) {
        bwc_app::out!(
            "  case {i}: {} rows; difference {:.3}, errors {:.3} (interpolated), {:.3} \
             (simulated) tolerances",
            r.0,
            r.1[0],
            r.1[1],
            r.1[2]
        );
    }
}
