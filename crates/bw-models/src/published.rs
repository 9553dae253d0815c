//! Laws published with the paper, for examples, tests and as starting points:
//!
//! * Table 4 (tab:RCross): the BWSHCCM and the BWMCM of Cross's baseball (Cross 2011,
//!   Fig. 9.5) of mass [`CROSS_MASS`] on a flat surface, in SI units (k in kg m^(1-p) s^-2, c
//!   in kg m^-p s^-1 for the BWSHCCM and kg s^-1 for the BWMCM, β and γ in m^-n);
//!   `fixtures/cross_shccm.toml` and `fixtures/cross_mcm.toml` are the same laws as scenes;
//! * Table 3 (tab:DSSDSA_param), columns DSS (1) and DSA (1): the base parameters identified
//!   from Kharaz & Gorham's alumina sphere on steel and on an aluminium alloy, unforced (`U_b`
//!   and `T_b` do not matter and are 1 here, [`BaseParams::unforced`]).
//!
//! ```
//! use bw_models::published::{cross, CROSS_MASS};
//! use bw_models::ModelKind;
//! let law = cross(ModelKind::Shccm);
//! assert_eq!((law.law().k, CROSS_MASS), (117080063.0, 0.145));
//! ```

use crate::params::{BaseParams, ModelKind, Physical, PhysicalParams};

/// The baseball's mass (kg).
pub const CROSS_MASS: f64 = 0.145;

/// Table 4's BWSHCCM.
pub const CROSS_BWSHCCM: Physical = Physical {
    k: 117080063.0,
    c: 5854003.0,
    n: 1.1,
    p: 1.7,
    alpha: 0.1,
    beta: 981.05,
    gamma: -961.4,
    a: 0.925,
};

/// Table 4's BWMCM.
pub const CROSS_BWMCM: Physical = Physical {
    k: 253000000.0,
    c: 2811.0,
    n: 1.2,
    p: 1.8,
    alpha: 0.15,
    beta: 1200.0,
    gamma: -1200.0,
    a: 1.01,
};

/// Table 4's law of `kind`.
pub fn cross_law(kind: ModelKind) -> Physical {
    match kind {
        ModelKind::Shccm => CROSS_BWSHCCM,
        ModelKind::Mcm => CROSS_BWMCM,
    }
}

/// Table 4's law of `kind`, validated.
pub fn cross(kind: ModelKind) -> PhysicalParams {
    PhysicalParams::new(kind, cross_law(kind)).expect("Table 4's laws are admissible")
}

/// Table 3, DSS (1), NDBWSHCCM.
pub const DSS1_SHCCM: BaseParams = BaseParams::unforced(2.38, -2.38, 0.677, 0.0348, 2.93, 2.62);

/// Table 3, DSA (1), NDBWSHCCM.
pub const DSA1_SHCCM: BaseParams = BaseParams::unforced(1.04, -1.02, 0.362, 0.017, 1.01, 1.67);

/// Table 3, DSS (1), NDBWMCM.
pub const DSS1_MCM: BaseParams = BaseParams::unforced(0.966, -0.966, 0.531, 2.22e-16, 1.57, 1.75);

/// Table 3, DSA (1), NDBWMCM.
pub const DSA1_MCM: BaseParams = BaseParams::unforced(0.521, -0.521, 0.168, 0.0144, 1.0, 2.04);
