//! The synthetic design of the credible band's coverage study: an NDBWSHCCM with `κ = 0.6` and
//! `σ_b = 0.03` searched (the rest fixed) at five speeds, noise 0.01, 150 particles x 4 runs per
//! posterior. Shared by the identification tests and the benchmark `posterior-band`.

use bw_models::{BaseParams, ModelKind, Settings};
use bwc_identify::{Budget, Param, PosteriorTask, SmcSettings, Space};

/// The synthetic truth of the identification tests: a NDBWSHCCM with loading branch
/// `Γ_b = -B_b`.
pub const TRUTH: BaseParams = BaseParams {
    b_b: 1.0,
    gamma_b: -1.0,
    kappa: 0.6,
    sigma_b: 0.03,
    n: 1.5,
    p: 1.5,
    u_b: 1.0,
    t_b: 1.0,
};

/// The design, the noise told to the likelihood (`given_noise`) or sampled with the parameters.
pub fn task(given_noise: bool) -> PosteriorTask {
    let truth = TRUTH;
    let fixed = Param::Fixed;
    let space = Space::new(
        ModelKind::Shccm,
        [
            fixed(1.0),
            fixed(-1.0),
            Param::Free {
                lo: 0.1,
                hi: 0.9,
                log: false,
            },
            Param::Free {
                lo: 1e-4,
                hi: 0.3,
                log: true,
            },
            fixed(1.5),
            fixed(1.5),
            fixed(1.0),
            fixed(1.0),
        ],
        None,
    )
    .unwrap();
    PosteriorTask {
        space,
        truth,
        speeds: vec![0.2, 0.5, 1.0, 2.0, 4.0],
        noise: 0.01,
        given_noise,
        from_prior: false,
        smc: SmcSettings::new(150, 4),
        budget: Budget {
            particles: 10,
            iterations: 10,
            ..Budget::default()
        },
        draws: 300,
        settings: Settings {
            rtol: 1e-8,
            atol: 1e-10,
            ..Settings::default()
        },
    }
}
