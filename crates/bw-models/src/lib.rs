//! # bw-models: Bouc-Wen collision models
//!
//! The models of binary direct collinear impacts with external forces from Milehins & Marghitu,
//! *Incremental Collision Laws Based on the Bouc-Wen Model: Improved Collision Models and
//! Further Results* (equation labels refer to its LaTeX source):
//!
//! * the collision laws as force elements: [`Bwshccl`] (x, z) and [`Bwmcl`] (r, y, z), and a
//!   [`ContactElement`] that carries one law's state between a host simulator's steps
//!   ([`AnyContactElement`]: of either law, chosen at run time);
//! * the models with input `u(t)`: [`Bwshccm`] (x, z, v), [`Bwmcm`] (r, y, z, v) in SI units and
//!   their nondimensional forms [`Ndbwshccm`], [`Ndbwmcm`] with input `U(T)`; the earlier
//!   BWMCM forms [`BwmcmEarlier`], [`NdbwmcmEarlier`];
//! * parameters validated against the admissible sets ([`PhysicalParams`], [`NondimParams`]),
//!   Table 1 both ways ([`nondimensionalize`], [`Scales`]), base parameters `P*` and the map
//!   `P(P*, u, v0)` ([`BaseParams`], [`base_params`], [`BaseMap`]);
//! * inputs ([`input`]) and the two-body system of Section 3 ([`Bodies`]);
//! * chains of bodies on a line with a law per neighbouring pair, walls at either end, any
//!   number of contacts at once ([`chain`]);
//! * one impact ([`impact`], [`simulate`]): separation `t_s = inf{t > 0 : F <= 0 <= v}`,
//!   `e = v(t_s)/v0` (0 without separation) and `t_d = t_s`; by default CoR evaluations under
//!   a constant input (of the SI models through their nondimensional form) by Taylor series of
//!   order 16 between the non-smooth points ([`Settings::series`]; a private part of the
//!   crate), everything else by DOP853 with stops at the kinks, switching to RODAS4 with the model's Jacobian ([`CollisionModel::jacobian`])
//!   when the run turns stiff ([`Stiffness`]), and stopping early once a contact under a
//!   constant input has settled ([`Impact::settled_at`]);
//! * by default every CoR checked to [`Settings::e_tol`]: runs at other tolerances estimate the
//!   error in `e` ([`Impact::e_error`], [`Impact::check`]), and one whose check stays unmet is
//!   computed again in double-double arithmetic ([`Settings::double_double`],
//!   [`Impact::double_double`]; [`Impact::double_double_declined`] says why not, where not);
//! * sweeps of many impact speeds served by verified Chebyshev interpolants in `ln v0`
//!   ([`sweep`]);
//! * a CoR without time steps for the nondimensional models with no input, as quadratures in
//!   phase space ([`phase`]; opt-in, up to twice as fast as the series path at equal error).
//!
//! Conventions: `x < 0` is compression, `F > 0` pushes the bodies apart, `v(0) = -v0`.
//!
//! ```
//! use bw_models::{impact, input::Zero, ModelKind, Ndbwshccm, Nondim, NondimParams, Settings};
//! // Hunt-Crossley limit (B = Γ = 0): e solves σ - ln(1+σ) = -σe - ln(1-σe); σ = 0.5 → 0.7484...
//! let p = NondimParams::new(ModelKind::Shccm, Nondim { b: 0.0, gamma: 0.0, kappa: 0.5, sigma: 0.5, n: 1.0, p: 1.5 })?;
//! let model = Ndbwshccm::new(&p, Zero)?;
//! let out = impact(&model, &Settings::default())?;
//! assert!((out.e - 0.748434931597434).abs() < 1e-9);
//! println!("T_s = {:?}, {} RHS evaluations", out.t_s, out.stats.rhs_evals);
//! # Ok::<(), bw_models::ModelError>(())
//! ```
#![deny(missing_docs)]

mod any_element;
mod bodies;
pub mod chain;
mod clearance;
mod cor;
mod double_double;
mod element;
mod error;
mod families;
mod fast_paths;
pub mod input;
pub mod law_spec;
mod laws;
pub mod materials;
mod models;
mod outcome;
mod params;
pub mod phase;
mod power;
pub mod published;
mod scaling;
mod separation;
pub mod sequence;
mod series;
mod settings;
mod simulate;
pub mod sweep;

pub use any_element::{AnyContactElement, AnyLaw};
pub use bodies::{Bodies, BodyMotion, ComRhs, Motion, RelativeInput};
pub use cor::{impact, impact_at, impact_double_double};
pub use element::{ContactElement, ElementSettings, ElementStep, Penetration, Remedy};
pub use error::ModelError;
pub use families::{
    family_impact, Family, FamilyParams, FamilySpec, HuntCrossleyLaw, JacksonGreenLaw,
    KelvinVoigtLaw, Ndkv, Ndthornton, ParamSpec, ThorntonLaw, FAMILIES,
};
pub use law_spec::{law_spec, LawParam, LawSpec, NamedLaw, ELEMENT_LAWS};
pub use laws::{Bwmcl, Bwshccl, ContactLaw, LawJacobian};
pub use models::{
    Bwmcm, BwmcmEarlier, Bwshccm, CollisionModel, Ndbwmcm, NdbwmcmEarlier, Ndbwshccm,
};
pub use outcome::{Check, Cor, DdDeclined, DdFailure, FailedRun, Impact};
pub use params::{
    BaseParams, ModelKind, Nondim, NondimParams, Physical, PhysicalParams, MODEL_KINDS,
};
pub use power::Pow;
pub use scaling::{base_params, nondimensionalize, BaseMap, InputScaling, Scales};
pub use separation::{separated, Separation};
pub use settings::{Ladder, Settings, Stiffness, LADDER};
pub use simulate::{simulate, Sampling, MAX_SAMPLES};

/// A model state on the stack.
pub use bwc_ode::State;
