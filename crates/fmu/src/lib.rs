//! # bwc-fmu: bwc's contact element as an FMI 2.0 Co-Simulation FMU
//!
//! `bwc_contact.fmu` holds one contact element ([`bw_models::ContactElement`]) for FMI
//! importers (OpenModelica, Dymola, Chrono, FMPy, ...). Its parameters are the law's (`k, c,
//! n, p, alpha, beta, gamma, A` of the Bouc-Wen laws, `model` 0 or 1, `policy`, `rtol`,
//! `atol`; `model` 2 and up are the other element laws of [`bw_models::ELEMENT_LAWS`], their
//! parameters named `<law>.<parameter>`: [`law_variables`]), its inputs the penetration
//! `delta` (m, positive while the bodies overlap) and its rate `delta_dot` (m/s, positive while
//! they approach), its outputs the force `force` (N, pushing the bodies apart), the step's
//! `impulse` (N s), the energy `dissipated` and `absorbed` (J), `in_contact` and `contacts`.
//!
//! Each fmi2DoStep from `t` over `h` takes the penetration as quadratic over the step: its
//! value and rate at `t` (the inputs), and the relative acceleration where the importer gives
//! it as the derivative of order 1 of `delta_dot` (fmi2SetRealInputDerivatives;
//! `canInterpolateInputs`). Without it the rate is held over the step, and the coupling is of
//! first order in `h`. The element finds the contact's onsets and separations inside the step.
//! `canGetAndSetFMUstate` lets a master try a step and take it again (a predictor-corrector).
//!
//! Build the FMU with `scripts/build-fmu` (it writes `target/fmu/bwc_contact.fmu`). The crate's
//! own functions, for tests:
//!
//! ```
//! use bwc_contact::Instance;
//! let mut fmu = Instance::new();
//! fmu.enter_initialization().unwrap();
//! fmu.exit_initialization().unwrap();
//! fmu.set_real(30, 1e-5).unwrap(); // delta: 10 um of overlap
//! fmu.set_real(31, 1.0).unwrap(); // delta_dot: approaching at 1 m/s
//! fmu.do_step(0.0, 1e-6).unwrap();
//! assert!(fmu.get_real(40).unwrap() > 0.0); // force
//! // A NaN input is refused and named.
//! assert!(fmu.set_real(30, f64::NAN).unwrap_err().contains("`delta` = NaN"));
//! ```
#![deny(missing_docs)]
// The exported functions carry FMI's names.
#![allow(non_snake_case)]

mod fmi2;
mod instance;
mod variables;

pub use instance::{Instance, Phase};
pub use variables::{law_variables, LawVariable, Type, Variable, BOUC_WEN_MODELS, VARIABLES};

/// The FMU's guid: `modelDescription.xml` carries the same, and fmi2Instantiate checks it.
pub const GUID: &str = "{1d72ba60-be48-4771-b30c-32049f3f42d1}";
