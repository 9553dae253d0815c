//! A contact element of any registered law, chosen at run time by name: what the bindings
//! (C, Python, the FMU) hold.
//!
//! The laws are listed once, in the `element_laws!` call below: each entry is a variant, its
//! law type (a [`NamedLaw`]) and its number of states. [`ELEMENT_LAWS`] and every method's
//! dispatch follow from that list.

use crate::element::{ContactElement, ElementSettings, ElementStep, Penetration};
use crate::error::ModelError;
use crate::families::{HuntCrossleyLaw, JacksonGreenLaw, KelvinVoigtLaw, ThorntonLaw};
use crate::law_spec::{law_spec, LawSpec, NamedLaw};
use crate::laws::ContactLaw;
use crate::laws::{Bwmcl, Bwshccl};
use crate::params::{ModelKind, PhysicalParams};
use bwc_ode::State;

macro_rules! element_laws {
    ($($(#[doc = $doc:literal])* $variant:ident($law:ty, $n:literal)),* $(,)?) => {
        /// A [`ContactElement`] of one of the registered laws ([`ELEMENT_LAWS`]).
        ///
        /// ```
        /// use bw_models::{AnyContactElement, ElementSettings};
        /// let hertz = [("k", 1e9), ("alpha", 0.2)];
        /// let mut element = AnyContactElement::of_law("hunt-crossley", &hertz, ElementSettings::default())?;
        /// let step = element.advance(1e-6, -1.0, -1.0)?;
        /// assert!(step.force > 0.0 && element.state().len() == 1);
        /// assert_eq!(element.spec().states, ["x"]);
        /// # Ok::<(), bw_models::ModelError>(())
        /// ```
        #[derive(Debug, Clone)]
        #[non_exhaustive]
        pub enum AnyContactElement {
            $($(#[doc = $doc])* $variant(ContactElement<$law, $n>),)*
        }

        /// Every law an [`AnyContactElement`] can hold, in the order of its variants.
        pub const ELEMENT_LAWS: &[&LawSpec] = &[$(&<$law as NamedLaw<$n>>::SPEC),*];

        /// One of the registered laws ([`ELEMENT_LAWS`]) by value, its state a slice of up to
        /// three displacements (m): what a chain's pair holds.
        #[derive(Debug, Clone, Copy, PartialEq)]
        #[non_exhaustive]
        pub enum AnyLaw {
            $($(#[doc = $doc])* $variant($law),)*
        }

        impl AnyLaw {
            /// The law called `name` with its parameters as (name, value) pairs.
            ///
            /// # Errors
            /// As [`AnyContactElement::of_law`].
            pub fn of_law(name: &str, params: &[(&str, f64)]) -> Result<Self, ModelError> {
                let spec = law_spec(name)?;
                let values = spec.values(params)?;
                $(
                    if spec.name == <$law as NamedLaw<$n>>::SPEC.name {
                        return Ok(Self::$variant(<$law as NamedLaw<$n>>::of_values(&values)?));
                    }
                )*
                Err(ModelError::NotApplicable {
                    reason: "a law in ELEMENT_LAWS without its variant",
                })
            }

            /// The law's description.
            pub fn spec(&self) -> &'static LawSpec {
                match self {
                    $(Self::$variant(_) => &<$law as NamedLaw<$n>>::SPEC,)*
                }
            }

            /// The state rate (zero past the law's states), the force `F` (N) and the
            /// dissipation rate (W) at `s` (the law's states first) with input `u` (m/s).
            #[inline]
            pub fn eval(&self, s: &[f64], u: f64) -> ([f64; 3], f64, f64) {
                match self {
                    $(Self::$variant(law) => {
                        let st = State::<$n>::from_fn(|i, _| s[i]);
                        let (rate, f) = ContactLaw::eval(law, &st, u);
                        let d = ContactLaw::dissipation(law, &st, u, &rate, f);
                        let out = std::array::from_fn(|i| if i < $n { rate[i] } else { 0.0 });
                        (out, f, d)
                    })*
                }
            }

            /// The energy stored at `s` (J) ([`ContactLaw::stored`]).
            #[inline]
            pub fn stored(&self, s: &[f64]) -> f64 {
                match self {
                    $(Self::$variant(law) => {
                        ContactLaw::stored(law, &State::<$n>::from_fn(|i, _| s[i]))
                    })*
                }
            }

            /// The law's non-smooth points at `s` with input `u` ([`ContactLaw::kinks`]).
            #[inline]
            pub fn kinks(&self, s: &[f64], u: f64) -> [f64; 2] {
                match self {
                    $(Self::$variant(law) => {
                        ContactLaw::kinks(law, &State::<$n>::from_fn(|i, _| s[i]), u)
                    })*
                }
            }
        }

        /// `$body` with `$e` bound to the element, whichever law it holds.
        macro_rules! each {
            ($self:expr, $e_:ident => $body_:expr) => {
                match $self {
                    $(AnyContactElement::$variant($e_) => $body_,)*
                }
            };
        }

        impl AnyContactElement {
            /// An element of the law called `name` with its parameters as (name, value)
            /// pairs ([`LawSpec::params`]), out of contact, at rest.
            ///
            /// # Errors
            /// [`ModelError::UnknownName`] for an unknown law or parameter name or a missing
            /// parameter, [`ModelError::InvalidParameter`] for an inadmissible value, and as
            /// [`ContactElement::new`].
            pub fn of_law(
                name: &str,
                params: &[(&str, f64)],
                settings: ElementSettings,
            ) -> Result<Self, ModelError> {
                let spec = law_spec(name)?;
                let values = spec.values(params)?;
                $(
                    if spec.name == <$law as NamedLaw<$n>>::SPEC.name {
                        let law = <$law as NamedLaw<$n>>::of_values(&values)?;
                        return Ok(Self::$variant(ContactElement::new(law, settings)?));
                    }
                )*
                Err(ModelError::NotApplicable {
                    reason: "a law in ELEMENT_LAWS without its variant",
                })
            }

            /// The law's description.
            pub fn spec(&self) -> &'static LawSpec {
                match self {
                    $(Self::$variant(_) => &<$law as NamedLaw<$n>>::SPEC,)*
                }
            }
        }
    };
}

element_laws! {
    /// The Bouc-Wen-Simon-Hunt-Crossley law's element (states x, z).
    Shccm(Bwshccl, 2),
    /// The Bouc-Wen-Maxwell law's element (states r, y, z).
    Mcm(Bwmcl, 3),
    /// Hunt and Crossley's Hertz law's element (state x).
    HuntCrossley(HuntCrossleyLaw, 1),
    /// A linear spring and dashpot's element (state x).
    KelvinVoigt(KelvinVoigtLaw, 1),
    /// Thornton's elastic-perfectly-plastic sphere's element (states x, x_m).
    Thornton(ThorntonLaw, 2),
    /// Jackson and Green's elastic-plastic sphere's element (states x, x_m).
    JacksonGreen(JacksonGreenLaw, 2),
}

impl AnyLaw {
    /// The Bouc-Wen law that validated parameters describe.
    ///
    /// # Errors
    /// None for validated parameters (either model's law is built).
    pub fn new(params: &PhysicalParams) -> Result<Self, ModelError> {
        Ok(match params.kind() {
            ModelKind::Shccm => Self::Shccm(Bwshccl::new(params)?),
            ModelKind::Mcm => Self::Mcm(Bwmcl::new(params)?),
        })
    }
}

impl AnyContactElement {
    /// An element of the Bouc-Wen law that validated parameters describe, out of contact, at
    /// rest.
    ///
    /// ```
    /// use bw_models::{AnyContactElement, ElementSettings, ModelKind, Physical, PhysicalParams};
    /// let law = Physical { k: 1e6, c: 1e3, n: 1.0, p: 1.5, alpha: 0.5, beta: 0.0, gamma: 0.0, a: 1.0 };
    /// let params = PhysicalParams::new(ModelKind::Mcm, law)?;
    /// let mut element = AnyContactElement::new(&params, ElementSettings::default())?;
    /// let step = element.advance(1e-5, -1.0, -1.0)?;
    /// assert!(step.force > 0.0 && element.state().len() == 3);
    /// # Ok::<(), bw_models::ModelError>(())
    /// ```
    ///
    /// # Errors
    /// As [`ContactElement::new`].
    pub fn new(params: &PhysicalParams, settings: ElementSettings) -> Result<Self, ModelError> {
        Ok(match params.kind() {
            ModelKind::Shccm => Self::Shccm(ContactElement::new(Bwshccl::new(params)?, settings)?),
            ModelKind::Mcm => Self::Mcm(ContactElement::new(Bwmcl::new(params)?, settings)?),
        })
    }

    /// [`ContactElement::advance`].
    ///
    /// # Errors
    /// As [`ContactElement::advance`].
    pub fn advance(
        &mut self,
        dt: f64,
        u_start: f64,
        u_end: f64,
    ) -> Result<ElementStep, ModelError> {
        each!(self, e => e.advance(dt, u_start, u_end))
    }

    /// [`ContactElement::advance_penetration`].
    ///
    /// # Errors
    /// As [`ContactElement::advance_penetration`].
    pub fn advance_penetration(
        &mut self,
        dt: f64,
        start: Penetration,
        end: Penetration,
    ) -> Result<ElementStep, ModelError> {
        each!(self, e => e.advance_penetration(dt, start, end))
    }

    /// The force at the end of the last step (N).
    pub fn force(&self) -> f64 {
        each!(self, e => e.force())
    }

    /// The law's state (m), named by [`LawSpec::states`]: `x, z` or `r, y, z` for the
    /// Bouc-Wen laws.
    pub fn state(&self) -> &[f64] {
        each!(self, e => e.state().as_slice())
    }

    /// Whether a contact is under way.
    pub fn in_contact(&self) -> bool {
        each!(self, e => e.in_contact())
    }

    /// [`ContactElement::onset_depth`] (m).
    pub fn onset_depth(&self) -> f64 {
        each!(self, e => e.onset_depth())
    }

    /// [`ContactElement::absorbed`] (J).
    pub fn absorbed(&self) -> f64 {
        each!(self, e => e.absorbed())
    }

    /// [`ContactElement::dissipated`] (J).
    pub fn dissipated(&self) -> f64 {
        each!(self, e => e.dissipated())
    }

    /// Contacts that have ended.
    pub fn contacts(&self) -> u64 {
        each!(self, e => e.contacts())
    }

    /// [`ContactElement::reset`].
    pub fn reset(&mut self) {
        each!(self, e => e.reset())
    }

    /// The settings.
    pub fn settings(&self) -> &ElementSettings {
        each!(self, e => e.settings())
    }
}
