//! What a contact law says about itself, so that every front end (the C ABI, Python, the
//! reference pages) builds it by name from named values: its name, its parameters with units
//! and admissible sets, and the names of its states.
//!
//! A law registers by implementing [`NamedLaw`] in its own module and taking one line in the
//! list of [`crate::AnyContactElement`]'s laws ([`ELEMENT_LAWS`] follows from it).

use crate::error::ModelError;
use crate::laws::ContactLaw;

pub use crate::any_element::ELEMENT_LAWS;

/// One parameter of a contact law.
#[derive(Debug, Clone, Copy)]
#[non_exhaustive]
pub struct LawParam {
    /// Its name, as the front ends spell it (`"k"`, `"alpha"`, `"A"`).
    pub name: &'static str,
    /// Its SI unit (`"-"` for a pure number).
    pub unit: &'static str,
    /// What it admits on its own, in words. A law may ask more of its parameters together
    /// (`gamma` in `[-beta, beta]`): [`NamedLaw::of_values`] says so.
    pub allowed: &'static str,
    /// Whether a value is admissible on its own.
    pub admits: fn(f64) -> bool,
    /// An admissible value of a typical magnitude: a front end's start value (the FMU's),
    /// and the value of examples.
    pub start: f64,
}

impl LawParam {
    /// A parameter.
    pub const fn new(
        name: &'static str,
        unit: &'static str,
        allowed: &'static str,
        admits: fn(f64) -> bool,
        start: f64,
    ) -> Self {
        Self {
            name,
            unit,
            allowed,
            admits,
            start,
        }
    }
}

/// Everything the front ends need to know about one contact law.
#[derive(Debug, Clone, Copy)]
#[non_exhaustive]
pub struct LawSpec {
    /// The name a front end uses (`"shccm"`, `"hunt-crossley"`).
    pub name: &'static str,
    /// Its name in prose and figures (`"BWSHCCL"`, `"Hunt-Crossley"`).
    pub title: &'static str,
    /// The force law, in the element's terms (`x < 0` in compression, `u` the relative
    /// velocity).
    pub force: &'static str,
    /// Its parameters, in the order [`NamedLaw::of_values`] takes them.
    pub params: &'static [LawParam],
    /// The names of its states (m), in the order of its state vector.
    pub states: &'static [&'static str],
}

impl LawSpec {
    /// The values of `named` (name, value) pairs in the order of [`LawSpec::params`], each
    /// checked on its own.
    ///
    /// # Errors
    /// [`ModelError::UnknownName`] for a name the law has no parameter of or a parameter
    /// missing, and [`ModelError::InvalidParameter`] for a value outside its admissible set.
    pub fn values(&self, named: &[(&str, f64)]) -> Result<Vec<f64>, ModelError> {
        if let Some((name, _)) = named
            .iter()
            .find(|(name, _)| !self.params.iter().any(|p| p.name == *name))
        {
            return Err(self.unknown(name, "is not one of its parameters, which are"));
        }
        self.params
            .iter()
            .map(|p| {
                let value = named
                    .iter()
                    .find(|(name, _)| *name == p.name)
                    .map(|&(_, v)| v)
                    .ok_or_else(|| self.unknown(p.name, "is missing; the law takes"))?;
                if (p.admits)(value) {
                    Ok(value)
                } else {
                    Err(ModelError::InvalidParameter {
                        name: p.name,
                        value,
                        allowed: p.allowed,
                    })
                }
            })
            .collect()
    }

    /// The names of the parameters, comma-separated.
    pub fn param_list(&self) -> String {
        let names: Vec<&str> = self.params.iter().map(|p| p.name).collect();
        names.join(", ")
    }

    fn unknown(&self, name: &str, problem: &'static str) -> ModelError {
        ModelError::UnknownName {
            law: self.name,
            name: name.into(),
            problem,
        }
    }
}

/// The spec of the law called `name`.
///
/// # Errors
/// [`ModelError::UnknownName`] listing the laws there are.
pub fn law_spec(name: &str) -> Result<&'static LawSpec, ModelError> {
    ELEMENT_LAWS
        .iter()
        .copied()
        .find(|s| s.name == name)
        .ok_or_else(|| ModelError::UnknownName {
            law: "",
            name: name.into(),
            problem: "is not one of the laws, which are",
        })
}

/// A contact law the front ends can build by name.
pub trait NamedLaw<const N: usize>: ContactLaw<N> + Sized {
    /// Its description.
    const SPEC: LawSpec;

    /// The law of `values`, in the order of [`LawSpec::params`], each already admissible on
    /// its own.
    ///
    /// # Errors
    /// [`ModelError::InvalidParameter`] for values that are not admissible together.
    fn of_values(values: &[f64]) -> Result<Self, ModelError>;
}

/// `x > 0` and finite.
pub(crate) fn positive(x: f64) -> bool {
    x > 0.0 && x.is_finite()
}

/// `x >= 0` and finite.
pub(crate) fn non_negative(x: f64) -> bool {
    x >= 0.0 && x.is_finite()
}

/// Any finite `x`.
pub(crate) fn finite(x: f64) -> bool {
    x.is_finite()
}
