//! Repeated CoR evaluations at Table 3's DSS (1), v0 = 2 m/s, with the default settings at a
//! given rtol (atol = rtol / 100, one run: `e_tol` off), or the defaults themselves (RTOL
//! `default`: checked to `e_tol`): the program behind the instruction counts of BENCHMARKS.md.
//! Prints the last e and the mean wall time per evaluation.
//!
//! `valgrind --tool=callgrind target/release/cor-loop [COUNT] [RTOL | default] [shccm|mcm]`
//! (after `cargo build --release -p bwc-benches --bin cor-loop`; defaults 300, 1e-8, shccm)

use bw_models::{ModelKind, Settings};
use bwc_benches::cor;

fn main() {
    let mut args = std::env::args().skip(1);
    let count: u32 = args.next().and_then(|a| a.parse().ok()).unwrap_or(300);
    let rtol = args.next();
    let kind = match args.next().as_deref() {
        Some("mcm") => ModelKind::Mcm,
        _ => ModelKind::Shccm,
    };
    let map = cor::dss1(kind);
    let settings = match rtol.as_deref() {
        Some("default") => Settings::default(),
        r => {
            let rtol = r.and_then(|a| a.parse().ok()).unwrap_or(1e-8);
            Settings {
                rtol,
                atol: rtol / 100.0,
                e_tol: None,
                ..Settings::default()
            }
        }
    };
    let clock = std::time::Instant::now();
    let mut e = f64::NAN;
    for _ in 0..count {
        match cor::evaluate(&map, 2.0, &settings) {
            Ok(out) => e = std::hint::black_box(out.e),
            Err(err) => {
                eprintln!("cor-loop: {err}");
                std::process::exit(1);
            }
        }
    }
    let per = clock.elapsed().as_secs_f64() / f64::from(count.max(1));
    bwc_app::out!("e = {e:.15}, {:.2} us per evaluation", per * 1e6);
}
