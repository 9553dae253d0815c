//! Solver settings: tolerances, step-size limits and the step-size controller.

use crate::{Error, State, Tableau};

/// Settings of an adaptive integration. Build with [`Options::new`] and adjust fields or use the
/// `with_*` methods; [`crate::Integrator::new`] validates them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Options<const N: usize> {
    /// Relative tolerance per component (dimensionless), `> 2.2e-16`.
    pub rtol: State<N>,
    /// Absolute tolerance per component (units of the state), `>= 0`.
    pub atol: State<N>,
    /// Initial step; `None` selects Hairer's initial-step heuristic (one extra RHS evaluation).
    pub h0: Option<f64>,
    /// Largest step allowed (`+inf`: no limit).
    pub max_step: f64,
    /// Smallest step allowed before [`Error::StepSizeTooSmall`] (0: only round-off limits it).
    pub min_step: f64,
    /// Most steps (accepted plus rejected) one integration may take.
    pub max_steps: u64,
    /// Step-size controller; `None` uses the method's defaults.
    pub controller: Option<Controller>,
}

/// Hairer's step-size controller: `h_new = h / clamp(err^(1/(q+1) - 0.75 β) / err_old^β / safety)`.
/// With `beta = 0` this is the classical I controller; `beta > 0` gives the PI controller
/// (Lund stabilisation, Hairer & Wanner II Sec. IV.2).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Controller {
    /// Safety factor in `(0, 1)` (Hairer's SAFE, 0.9).
    pub safety: f64,
    /// Smallest ratio `h_new / h` (Hairer's FAC1: 0.2 for DOPRI5, 0.333 for DOP853).
    pub min_ratio: f64,
    /// Largest ratio `h_new / h` (Hairer's FAC2: 10 for DOPRI5, 6 for DOP853).
    pub max_ratio: f64,
    /// PI weight `β` in `[0, 0.2]` (0.04 for DOPRI5, 0 for DOP853).
    pub beta: f64,
}

impl Controller {
    /// Hairer's defaults for a method.
    pub fn for_method(tableau: &Tableau) -> Self {
        if tableau.order <= 5 {
            Self {
                safety: 0.9,
                min_ratio: 0.2,
                max_ratio: 10.0,
                beta: tableau.default_beta,
            }
        } else {
            Self {
                safety: 0.9,
                min_ratio: 0.333,
                max_ratio: 6.0,
                beta: tableau.default_beta,
            }
        }
    }
}

impl<const N: usize> Options<N> {
    /// Scalar tolerances for every component; no step limits; at most 100,000 steps.
    pub fn new(rtol: f64, atol: f64) -> Self {
        Self {
            rtol: State::from_element(rtol),
            atol: State::from_element(atol),
            h0: None,
            max_step: f64::INFINITY,
            min_step: 0.0,
            max_steps: 100_000,
            controller: None,
        }
    }

    /// Per-component tolerances.
    pub fn per_component(rtol: State<N>, atol: State<N>) -> Self {
        Self {
            rtol,
            atol,
            ..Self::new(1e-6, 1e-9)
        }
    }

    /// Sets the largest step.
    pub fn with_max_step(mut self, max_step: f64) -> Self {
        self.max_step = max_step;
        self
    }

    /// Sets the initial step.
    pub fn with_h0(mut self, h0: f64) -> Self {
        self.h0 = Some(h0);
        self
    }

    /// Sets the step limit.
    pub fn with_max_steps(mut self, max_steps: u64) -> Self {
        self.max_steps = max_steps;
        self
    }

    /// Sets the controller.
    pub fn with_controller(mut self, controller: Controller) -> Self {
        self.controller = Some(controller);
        self
    }

    /// Checks every option against its admissible range.
    ///
    /// # Errors
    /// [`Error::InvalidOption`] naming the first offending option.
    pub fn validate(&self) -> Result<(), Error> {
        let bad = |name, value, allowed| {
            Err(Error::InvalidOption {
                name,
                value,
                allowed,
            })
        };
        for &r in self.rtol.iter() {
            if !(r.is_finite() && r > f64::EPSILON) {
                return bad("rtol", r, "finite and > 2.2e-16");
            }
        }
        for &a in self.atol.iter() {
            if !(a.is_finite() && a >= 0.0) {
                return bad("atol", a, "finite and >= 0");
            }
        }
        if let Some(h0) = self.h0 {
            if !(h0.is_finite() && h0 > 0.0) {
                return bad("h0", h0, "finite and > 0");
            }
        }
        if self.max_step.is_nan() || self.max_step <= 0.0 {
            return bad("max_step", self.max_step, "> 0 (may be +inf)");
        }
        if !(self.min_step >= 0.0 && self.min_step < self.max_step) {
            return bad("min_step", self.min_step, ">= 0 and < max_step");
        }
        if self.max_steps == 0 {
            return bad("max_steps", 0.0, ">= 1");
        }
        if let Some(c) = self.controller {
            if !(c.safety > 0.0 && c.safety < 1.0) {
                return bad("controller.safety", c.safety, "in (0, 1)");
            }
            if !(c.min_ratio > 0.0 && c.min_ratio < 1.0) {
                return bad("controller.min_ratio", c.min_ratio, "in (0, 1)");
            }
            if !(c.max_ratio > 1.0 && c.max_ratio.is_finite()) {
                return bad("controller.max_ratio", c.max_ratio, "finite and > 1");
            }
            if !(0.0..=0.2).contains(&c.beta) {
                return bad("controller.beta", c.beta, "in [0, 0.2]");
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn validation_names_the_option() {
        let o = Options::<2>::new(0.0, 1e-9);
        assert!(matches!(
            o.validate(),
            Err(Error::InvalidOption { name: "rtol", .. })
        ));
        let o = Options::<2>::new(1e-6, f64::NAN);
        assert!(matches!(
            o.validate(),
            Err(Error::InvalidOption { name: "atol", .. })
        ));
        let o = Options::<2>::new(1e-6, 1e-9).with_max_step(-1.0);
        assert!(matches!(
            o.validate(),
            Err(Error::InvalidOption {
                name: "max_step",
                ..
            })
        ));
        let o = Options::<2>::new(1e-6, 1e-9).with_h0(0.0);
        assert!(matches!(
            o.validate(),
            Err(Error::InvalidOption { name: "h0", .. })
        ));
        assert!(Options::<2>::new(1e-10, 1e-12).validate().is_ok());
    }
}
