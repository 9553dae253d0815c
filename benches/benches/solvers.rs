//! Time per solve of each Runge-Kutta method on a fixed problem (one Arenstorf period at
//! rtol = atol = 1e-10). `cargo bench -p bwc-benches --bench solvers`

use bwc_benches::arenstorf_period;
use criterion::{criterion_group, criterion_main, Criterion};

fn solvers(c: &mut Criterion) {
    let mut group = c.benchmark_group("arenstorf_rtol1e-10");
    for tab in bwc_ode::METHODS {
        let (err, evals) = arenstorf_period(tab, 1e-10);
        eprintln!(
            "{}: {evals} RHS evaluations per solve, error {err:.2e}",
            tab.name
        );
        group.bench_function(tab.name, |b| b.iter(|| arenstorf_period(tab, 1e-10)));
    }
    group.finish();
}

criterion_group!(benches, solvers);
criterion_main!(benches);
