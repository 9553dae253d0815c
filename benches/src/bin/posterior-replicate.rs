//! One replicate of `posterior-coverage` taken apart: the NDBWMCM's fixed truth on the baseball
//! design (`BWC_INTERIOR=1`'s), synthetic data of seed `SEED`, the noise sampled, and the
//! posterior at `PARTICLES` x `RUNS`: each run's log evidence, the pooled marginals, the
//! posterior mass at `B_b < 0.1` (the truth's corner), and the band against the true curve at
//! each speed. Larger populations tell a sampling error from what the posterior is.
//!
//! `cargo run --release -p bwc-benches --bin posterior-replicate -- SEED PARTICLES [RUNS]`

use bw_models::input::Zero;
use bw_models::{BaseParams, Settings};
use bwc_app::fit::config::Config;
use bwc_identify::{
    fit, marginals, posterior_band, sample, Dataset, NoiseScale, Objective, PosteriorProblem,
    PosteriorSpec, SmcSettings, Weights,
};
use rand::SeedableRng;
use rand_distr::{Distribution, Normal};

fn main() {
    let arg = |i: usize, default: u64| {
        std::env::args()
            .nth(i)
            .and_then(|a| a.parse().ok())
            .unwrap_or(default)
    };
    let (seed, particles, runs) = (arg(1, 10), arg(2, 300) as usize, arg(3, 4) as usize);
    let config = Config::load(std::path::Path::new("fixtures/baseball_wood.toml"))
        .expect("run from the repository root");
    let (t, noise) = bwc_benches::baseball_truths()[1];
    let truth = BaseParams {
        kappa: t.kappa.max(0.06),
        n: t.n.min(3.0),
        p: t.p.min(3.0),
        ..t
    };
    let f = &config.fits[1];
    let map = f.space.map(&truth).expect("truth");
    let truth_at = |v0: f64| map.impact(Zero, v0, &Settings::default()).expect("truth").e;
    // The data exactly as posterior_replicate draws them.
    let mut rng = rand::rngs::StdRng::seed_from_u64(seed);
    let normal = Normal::new(0.0, noise).expect("noise");
    let mut csv = String::from("v_0,e,e_std\n");
    for p in &f.data.points {
        csv += &format!(
            "{},{},{noise}\n",
            p.v0,
            truth_at(p.v0) + normal.sample(&mut rng)
        );
    }
    let data = Dataset::parse(std::path::Path::new("synthetic.csv"), &csv).expect("data");
    let mut spec = PosteriorSpec::new(&data, Weights { j1: 1.0, j2: 0.0 });
    spec.e_noise = NoiseScale::Sampled { lo: 1e-4, hi: 0.5 };
    let problem =
        PosteriorProblem::new(&f.space, &data, &Zero, f.settings, &spec).expect("problem");
    let objective = Objective::new(&f.space, &data, &Zero, f.settings, spec.weights).expect("cost");
    let optimum = fit(&objective, &f.budget, seed, None).expect("fit");
    let reference = problem.reference_at(&optimum.point, &optimum.costs);
    let post = sample(
        &problem,
        &SmcSettings::new(particles, runs),
        &reference,
        seed,
    )
    .expect("smc");
    println!(
        "seed {seed}, {particles} x {runs}: log evidence {:.3} ± {:.3}, {} evaluations",
        post.log_evidence, post.log_evidence_error, post.evaluations
    );
    for r in &post.runs {
        println!(
            "  run {}: log evidence {:.3}, {} stages",
            r.index,
            r.log_evidence,
            r.stages.len()
        );
    }
    for m in marginals(&problem, &post) {
        println!(
            "  {}: median {:.4e}, 95 % [{:.4e}, {:.4e}]",
            m.name, m.median, m.interval[0], m.interval[1]
        );
    }
    let corner: f64 = post
        .particles
        .iter()
        .zip(&post.weights)
        .filter(|(p, _)| problem.values(p)[0] < 0.1)
        .map(|(_, w)| w)
        .sum();
    println!("  mass at B_b < 0.1: {corner:.3}");
    let mut speeds: Vec<f64> = data.points.iter().map(|p| p.v0).collect();
    speeds.sort_by(f64::total_cmp);
    speeds.dedup();
    let band = posterior_band(&problem, &post, &speeds, (400, seed), noise).expect("band");
    let mut covered = 0;
    println!("| v0 (m/s) | true e | 2.5 % | median | 97.5 % | covered |");
    for b in &band {
        let e = truth_at(b.v0);
        let inside = b.e[1] <= e && e <= b.e[2];
        covered += usize::from(inside);
        println!(
            "| {:.2} | {e:.4} | {:.4} | {:.4} | {:.4} | {inside} |",
            b.v0, b.e[1], b.e[0], b.e[2]
        );
    }
    println!("covered {covered} of {}", band.len());
}
