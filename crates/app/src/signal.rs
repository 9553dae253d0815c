//! Input signals described in scene files, evaluated at run time.

use bw_models::input::{Arctan, Input, Table};
use bwc_ode::dd::Dd;

/// An external input `u(t)` built from a scene: a constant (including gravity `-m g`), the
/// paper's arctan ramp, a piecewise-linear table, or a sum of these.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Signal {
    /// `u = value`.
    Constant(f64),
    /// `u = (2/π) m D arctan(ω t)`.
    Arctan(Arctan),
    /// Piecewise-linear in `t`.
    Table(Table),
    /// The sum of the terms.
    Sum(Vec<Signal>),
}

impl Signal {
    /// No input.
    pub fn zero() -> Self {
        Signal::Constant(0.0)
    }
}

impl Input for Signal {
    fn at(&self, t: f64) -> f64 {
        match self {
            Signal::Constant(c) => *c,
            Signal::Arctan(a) => a.at(t),
            Signal::Table(tab) => tab.at(t),
            Signal::Sum(terms) => terms.iter().map(|s| s.at(t)).sum(),
        }
    }

    fn is_zero(&self) -> bool {
        match self {
            Signal::Constant(c) => *c == 0.0,
            Signal::Sum(terms) => terms.iter().all(Input::is_zero),
            _ => false,
        }
    }

    fn is_constant(&self) -> bool {
        match self {
            Signal::Constant(_) => true,
            Signal::Sum(terms) => terms.iter().all(Input::is_constant),
            _ => false,
        }
    }

    /// Every signal has a double-double form.
    fn at_dd(&self, t: Dd) -> Option<Dd> {
        match self {
            Signal::Constant(c) => Some(Dd::from(*c)),
            Signal::Arctan(a) => a.at_dd(t),
            Signal::Table(tab) => tab.at_dd(t),
            Signal::Sum(terms) => terms
                .iter()
                .try_fold(Dd::from(0.0), |acc, s| Some(acc + s.at_dd(t)?)),
        }
    }
}
