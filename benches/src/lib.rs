//! Problems with known answers shared by the benchmarks and the work-precision reports.
#![allow(clippy::excessive_precision)] // reference values keep their published digits

use bwc_ode::{Integrator, Options, State, Tableau};
use std::time::Instant;

/// Mass ratio of the restricted three-body problem (Hairer, Nørsett & Wanner I, Sec. II.0).
pub const ARENSTORF_MU: f64 = 0.012277471;
/// Period of the Arenstorf orbit.
pub const ARENSTORF_PERIOD: f64 = 17.0652165601579625588917206249;
/// Initial state of the Arenstorf orbit `(x, y, x', y')`.
pub fn arenstorf_y0() -> State<4> {
    State::<4>::new(0.994, 0.0, 0.0, -2.00158510637908252240537862224)
}

/// Right-hand side of the Arenstorf orbit.
pub fn arenstorf(_t: f64, y: &State<4>) -> State<4> {
    let mu = ARENSTORF_MU;
    let mu1 = 1.0 - mu;
    let d1 = ((y[0] + mu).powi(2) + y[1].powi(2)).powf(1.5);
    let d2 = ((y[0] - mu1).powi(2) + y[1].powi(2)).powf(1.5);
    State::<4>::new(
        y[2],
        y[3],
        y[0] + 2.0 * y[3] - mu1 * (y[0] + mu) / d1 - mu * (y[0] - mu1) / d2,
        y[1] - 2.0 * y[2] - mu1 * y[1] / d1 - mu * y[1] / d2,
    )
}

/// One Arenstorf period at tolerance `rtol` (atol = rtol): returns the error `|y(T) - y(0)|_inf`
/// and the RHS evaluations.
pub fn arenstorf_period(tab: &'static Tableau, rtol: f64) -> (f64, u64) {
    let y0 = arenstorf_y0();
    match Integrator::new(
        arenstorf,
        tab,
        0.0,
        y0,
        Options::new(rtol, rtol).with_max_steps(10_000_000),
    )
    .and_then(|mut it| it.integrate_to(ARENSTORF_PERIOD).map(|_| it))
    {
        Ok(it) => ((it.y() - y0).amax(), it.stats().rhs_evals),
        Err(_) => (f64::NAN, 0),
    }
}

/// Median wall time per call of `f` in seconds: batches of calls lasting about 20 ms each.
pub fn median_seconds(mut f: impl FnMut()) -> f64 {
    let start = Instant::now();
    f();
    let once = start.elapsed().as_secs_f64().max(1e-9);
    let reps = ((0.02 / once) as usize).clamp(1, 1_000_000);
    let mut samples: Vec<f64> = (0..7)
        .map(|_| {
            let s = Instant::now();
            for _ in 0..reps {
                f();
            }
            s.elapsed().as_secs_f64() / reps as f64
        })
        .collect();
    samples.sort_by(f64::total_cmp);
    samples[samples.len() / 2]
}
