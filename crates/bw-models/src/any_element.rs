//! A contact element of either law, chosen at run time: what bindings (C, Python) hold.

use crate::element::{ContactElement, ElementSettings, ElementStep, Penetration};
use crate::error::ModelError;
use crate::laws::{Bwmcl, Bwshccl};
use crate::params::{ModelKind, PhysicalParams};

/// A [`ContactElement`] of the law that validated parameters describe.
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
#[derive(Debug, Clone)]
#[non_exhaustive]
pub enum AnyContactElement {
    /// The Bouc-Wen-Simon-Hunt-Crossley law's element (states x, z).
    Shccm(ContactElement<Bwshccl, 2>),
    /// The Bouc-Wen-Maxwell law's element (states r, y, z).
    Mcm(ContactElement<Bwmcl, 3>),
}

/// `$body` with `$e` bound to the element, whichever law it holds.
macro_rules! each {
    ($self:expr, $e:ident => $body:expr) => {
        match $self {
            AnyContactElement::Shccm($e) => $body,
            AnyContactElement::Mcm($e) => $body,
        }
    };
}

impl AnyContactElement {
    /// An element of the law of `params`, out of contact, at rest.
    ///
    /// # Errors
    /// As [`ContactElement::new`].
    pub fn new(params: &PhysicalParams, settings: ElementSettings) -> Result<Self, ModelError> {
        Ok(match params.kind() {
            ModelKind::Shccm => Self::Shccm(ContactElement::new(Bwshccl::new(params)?, settings)?),
            ModelKind::Mcm => Self::Mcm(ContactElement::new(Bwmcl::new(params)?, settings)?),
        })
    }

    /// The law's model.
    pub fn kind(&self) -> ModelKind {
        match self {
            Self::Shccm(_) => ModelKind::Shccm,
            Self::Mcm(_) => ModelKind::Mcm,
        }
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

    /// The law's state (m): `x, z` or `r, y, z`.
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
