//! Work-precision report of the Runge-Kutta methods on the Arenstorf orbit (exact answer: the
//! orbit closes after one period). Prints error vs RHS evaluations vs time per solve.
//!
//! `cargo run --release -p bwc-benches --bin work-precision-ode`

use bwc_benches::{arenstorf_period, median_seconds};

fn main() {
    println!("# Arenstorf orbit, one period; error = |y(T) - y(0)|_inf, atol = rtol");
    println!(
        "{:<8} {:>8} {:>12} {:>10} {:>12}",
        "method", "rtol", "error", "rhs_evals", "time_us"
    );
    for tab in bwc_ode::METHODS {
        for k in 4..=13 {
            let rtol = 10f64.powi(-k);
            let (err, evals) = arenstorf_period(tab, rtol);
            let secs = median_seconds(|| {
                std::hint::black_box(arenstorf_period(tab, rtol));
            });
            println!(
                "{:<8} {:>8.0e} {:>12.3e} {:>10} {:>12.1}",
                tab.name,
                rtol,
                err,
                evals,
                secs * 1e6
            );
        }
    }
}
