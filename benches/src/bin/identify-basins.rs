//! Where do the search's starts end? For every `[[fit]]` of a config whose name contains
//! FILTER: N starts (alternately a Latin-hypercube point and a particle swarm of the fit's
//! size, as the search makes them), every one polished, no early stop; the share of each kind
//! that ends within 2 % of the best any start reached.
//!
//! `cargo run --release -p bwc-benches --bin identify-basins -- CONFIG [FILTER] [N]`

use bwc_app::fit::config::Config;
use bwc_identify::{minimize, Budget, Objective};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let Some(path) = args.first() else {
        eprintln!("usage: identify-basins CONFIG [FILTER] [N]");
        std::process::exit(2);
    };
    let config = Config::load(std::path::Path::new(path)).unwrap_or_else(|e| {
        eprintln!("{path}: {e}");
        std::process::exit(1)
    });
    let filter = args.get(1).cloned().unwrap_or_default();
    let n = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(40usize);
    bwc_app::out!(
        "| fit | Latin-hypercube starts within 2 % | swarm starts within 2 % | best J | evaluations per start |"
    );
    bwc_app::out!("|---|---:|---:|---:|---:|");
    for f in config.fits.iter().filter(|f| f.name.contains(&filter)) {
        let o = Objective::new(&f.space, &f.data, &f.input, f.settings, f.weights)
            .expect("validated config");
        let budget = Budget {
            starts: n,
            max_starts: n,
            agree: n,
            ..f.budget
        };
        let m = minimize(&o, &budget, 1, None).expect("search");
        let costs = &m.convergence.costs;
        let best = costs.iter().copied().fold(f64::INFINITY, f64::min);
        let within = |kind: usize| {
            let of_kind = costs.iter().skip(kind).step_by(2);
            let reached = of_kind.clone().filter(|c| **c <= 1.02 * best).count();
            format!("{reached}/{}", of_kind.count())
        };
        bwc_app::out!(
            "| {} | {} | {} | {best:.5e} | {} |",
            f.name,
            within(0),
            within(1),
            m.evaluations / n as u64
        );
    }
}
