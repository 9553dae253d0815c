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
pub fn median_seconds(f: impl FnMut()) -> f64 {
    side_by_side(&mut [Box::new(f)])[0]
}

/// Median wall time per call of each of `fs` in seconds, timed side by side: seven rounds, each
/// a batch of calls (about 20 ms) of every closure in turn, so that a machine whose speed drifts
/// during a run slows all of them alike and their ratios hold.
pub fn side_by_side(fs: &mut [Box<dyn FnMut() + '_>]) -> Vec<f64> {
    let reps: Vec<usize> = fs
        .iter_mut()
        .map(|f| {
            let start = Instant::now();
            f();
            let once = start.elapsed().as_secs_f64().max(1e-9);
            ((0.02 / once) as usize).clamp(1, 1_000_000)
        })
        .collect();
    let mut samples = vec![Vec::with_capacity(7); fs.len()];
    for _ in 0..7 {
        for ((f, &n), out) in fs.iter_mut().zip(&reps).zip(&mut samples) {
            let s = Instant::now();
            for _ in 0..n {
                f();
            }
            out.push(s.elapsed().as_secs_f64() / n as f64);
        }
    }
    samples
        .into_iter()
        .map(|mut s| {
            s.sort_by(f64::total_cmp);
            s[s.len() / 2]
        })
        .collect()
}

pub mod cor {
    //! One CoR evaluation of the paper's Table 3 models (DSS (1) and DSA (1)), the unit of work
    //! of the identification.
    use bw_models::{impact_at, input::Zero, BaseMap, Cor, ModelError, ModelKind, Settings};

    pub use bw_models::published::{DSA1_MCM, DSA1_SHCCM, DSS1_MCM, DSS1_SHCCM};

    /// The base map of a model at DSS (1).
    pub fn dss1(kind: ModelKind) -> BaseMap {
        let base = match kind {
            ModelKind::Shccm => DSS1_SHCCM,
            ModelKind::Mcm => DSS1_MCM,
        };
        BaseMap::new(kind, base).expect("published parameters are admissible")
    }

    /// The base map of a model at DSA (1).
    pub fn dsa1(kind: ModelKind) -> BaseMap {
        let base = match kind {
            ModelKind::Shccm => DSA1_SHCCM,
            ModelKind::Mcm => DSA1_MCM,
        };
        BaseMap::new(kind, base).expect("published parameters are admissible")
    }

    /// One run per CoR at `rtol` (`atol = rtol / 100`, no check): the series path by default.
    pub fn one_run(rtol: f64) -> Settings {
        Settings {
            rtol,
            atol: rtol / 100.0,
            e_tol: None,
            ..Settings::default()
        }
    }

    /// The plain path the speed figures are measured against, one run per CoR: `[solver] series = false, stop_at_kinks =
    /// false, method = "dop853"` (and no switch to RODAS4).
    pub fn plain(rtol: f64) -> Settings {
        Settings {
            method: &bwc_ode::DOP853,
            stop_at_kinks: false,
            stiffness: bw_models::Stiffness::Ignore,
            series: false,
            ..one_run(rtol)
        }
    }

    /// One CoR evaluation at impact speed `v0` (m/s).
    pub fn evaluate(map: &BaseMap, v0: f64, settings: &Settings) -> Result<Cor, ModelError> {
        impact_at(map, Zero, v0, settings)
    }
}

pub mod stress;
#[cfg(test)]
mod stress_sample;

/// The truths of the coverage studies on the baseball design (`fixtures/baseball_wood.toml`):
/// the default fits of the NDBWSHCCM and the NDBWMCM to the measured data (BENCHMARKS.md) and
/// their residual standard deviations, `u = 0`.
pub fn baseball_truths() -> [(bw_models::BaseParams, f64); 2] {
    let base = bw_models::BaseParams::unforced;
    [
        (
            base(0.041289, 0.013128, 0.02, 6.930122e-4, 3.43861, 4.0),
            0.0215,
        ),
        (
            base(0.015323, 0.015323, 0.074151, 4.162404e-2, 4.0, 4.0),
            0.0222,
        ),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::cell::Cell;

    #[test]
    fn side_by_side_times_every_closure_in_every_round() {
        // A cheap and a dearer closure: each is called once to size its batch, then in seven
        // rounds of batches; the medians come back in the closures' order.
        let (cheap, dear) = (Cell::new(0u64), Cell::new(0u64));
        let times = side_by_side(&mut [
            Box::new(|| cheap.set(cheap.get() + 1)),
            Box::new(|| {
                dear.set(dear.get() + 1);
                std::thread::sleep(std::time::Duration::from_millis(2));
            }),
        ]);
        assert_eq!(times.len(), 2);
        assert!(dear.get() >= 8 && cheap.get() > dear.get());
        // The sleeping closure takes at least its 2 ms per call.
        assert!(times[1] >= 2e-3 && times[0] > 0.0 && times[0] < times[1]);
    }
}
