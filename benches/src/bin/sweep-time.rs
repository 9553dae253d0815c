//! In-process time of a scene's sweep on one thread (`simulate::run`, no output): the Rust side
//! of the Python overhead comparison in BENCHMARKS.md. Prints the median of `rounds` runs.
//!
//! `target/release/sweep-time SCENE.toml [ROUNDS]`

fn main() {
    let mut args = std::env::args().skip(1);
    let path = args.next().unwrap_or_else(|| {
        eprintln!("sweep-time: usage: sweep-time SCENE.toml [ROUNDS]");
        std::process::exit(2)
    });
    let rounds: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(5);
    let scene =
        bwc_app::impact::scene::Scene::load(std::path::Path::new(&path)).unwrap_or_else(|e| {
            eprintln!("sweep-time: {e}");
            std::process::exit(1)
        });
    let mut times: Vec<f64> = (0..rounds)
        .map(|_| {
            let clock = std::time::Instant::now();
            let runs =
                bwc_app::with_threads(Some(1), || Ok(bwc_app::impact::simulate::run(&scene, None)))
                    .expect("one thread");
            std::hint::black_box(runs);
            clock.elapsed().as_secs_f64()
        })
        .collect();
    times.sort_by(f64::total_cmp);
    bwc_app::out!(
        "{} runs, median {:.4} s over {rounds} rounds",
        scene.speeds.len(),
        times[rounds / 2]
    );
}
