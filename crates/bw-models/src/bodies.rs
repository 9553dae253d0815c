//! The two-body system of Section 3: effective mass, relative input, impact speed, and the
//! motion of the centre of mass and of each body (computed only when asked for).

use crate::input::Input;
use crate::params::check;
use crate::{ModelError, State};
use bwc_ode::{Integrator, Options, DOP853};

/// Two bodies in a direct collinear impact at `t = 0` (Fig. 1): masses `m1`, `m2` (kg;
/// `m2 = +inf` is a fixed body), velocities `v1`, `v2` (m/s) at impact, distances `l1`, `l2`
/// (m) of the centres of mass from the contact point, external forces `u1(t)`, `u2(t)` (N).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bodies<I1, I2> {
    m1: f64,
    m2: f64,
    v1: f64,
    v2: f64,
    l1: f64,
    l2: f64,
    u1: I1,
    u2: I2,
}

/// Positions (m) and velocities (m/s) of the centres of mass at one instant, with the inputs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyMotion {
    /// Centre of mass of the system `x_m`.
    pub x_m: f64,
    /// Body 1 `x_{m,1}`.
    pub x_m_1: f64,
    /// Body 2 `x_{m,2}`.
    pub x_m_2: f64,
    /// `v_m`.
    pub v_m: f64,
    /// `v_{m,1}`.
    pub v_m_1: f64,
    /// `v_{m,2}`.
    pub v_m_2: f64,
    /// `u_1` (N).
    pub u_1: f64,
    /// `u_2` (N).
    pub u_2: f64,
}

impl<I1: Input, I2: Input> Bodies<I1, I2> {
    /// Validates the system: `m1 > 0` finite, `m2 > 0` (may be `+inf`), `l1, l2 >= 0`, finite
    /// velocities approaching each other (`v0 = v2 - v1 > 0`).
    ///
    /// # Errors
    /// [`ModelError::InvalidParameter`] naming the offending quantity.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        m1: f64,
        m2: f64,
        v1: f64,
        v2: f64,
        l1: f64,
        l2: f64,
        u1: I1,
        u2: I2,
    ) -> Result<Self, ModelError> {
        check("m1", m1, m1 > 0.0, "m1 > 0 (kg)")?;
        if m2.is_nan() || m2 <= 0.0 {
            return Err(ModelError::InvalidParameter {
                name: "m2",
                value: m2,
                allowed: "m2 > 0 (kg), or inf for a fixed body",
            });
        }
        check("l1", l1, l1 >= 0.0, "l1 >= 0 (m)")?;
        check("l2", l2, l2 >= 0.0, "l2 >= 0 (m)")?;
        check("v1", v1, true, "finite (m/s)")?;
        check("v2", v2, true, "finite (m/s)")?;
        check(
            "v0",
            v2 - v1,
            v2 > v1,
            "v0 = v2 - v1 > 0: the bodies must approach each other",
        )?;
        Ok(Self {
            m1,
            m2,
            v1,
            v2,
            l1,
            l2,
            u1,
            u2,
        })
    }

    /// The masses `(m1, m2)` (kg; `m2 = +inf` for a fixed body).
    pub fn masses(&self) -> (f64, f64) {
        (self.m1, self.m2)
    }

    /// The velocities `(v1, v2)` at impact (m/s).
    pub fn velocities(&self) -> (f64, f64) {
        (self.v1, self.v2)
    }

    /// The distances `(l1, l2)` of the centres of mass from the contact point (m).
    pub fn distances(&self) -> (f64, f64) {
        (self.l1, self.l2)
    }

    /// The external forces `(u1, u2)` (N).
    pub fn inputs(&self) -> (&I1, &I2) {
        (&self.u1, &self.u2)
    }

    /// `η = m1 / (m1 + m2)` (0 for a fixed body 2).
    pub fn eta(&self) -> f64 {
        if self.m2.is_infinite() {
            0.0
        } else {
            self.m1 / (self.m1 + self.m2)
        }
    }

    /// Effective mass `m = m1 m2 / (m1 + m2)` (`m1` for a fixed body 2).
    pub fn effective_mass(&self) -> f64 {
        if self.m2.is_infinite() {
            self.m1
        } else {
            self.m1 * self.m2 / (self.m1 + self.m2)
        }
    }

    /// Impact speed `v0 = -(v1 - v2)`.
    pub fn impact_speed(&self) -> f64 {
        self.v2 - self.v1
    }

    /// The relative input `u = (m2 u1 - m1 u2) / (m1 + m2)` (eq:u; `u1` for a fixed body 2).
    pub fn relative_input(&self) -> RelativeInput<'_, I1, I2> {
        RelativeInput {
            eta: self.eta(),
            u1: &self.u1,
            u2: &self.u2,
        }
    }

    /// A tracker of the centre of mass and the bodies along an impact (integrates eq:com).
    ///
    /// # Errors
    /// [`ModelError::Solver`] if the centre-of-mass integration cannot start (non-finite input).
    pub fn motion(&self) -> Result<Motion<'_, I1, I2>, ModelError> {
        let eta = self.eta();
        let x0 = State::<2>::new(
            eta * self.l1 - (1.0 - eta) * self.l2,
            eta * self.v1 + (1.0 - eta) * self.v2,
        );
        let com = ComRhs {
            u1: &self.u1,
            u2: &self.u2,
            total: self.m1 + self.m2,
        };
        let it = Integrator::new(com, &DOP853, 0.0, x0, Options::new(1e-12, 1e-14))
            .map_err(bwc_events::Error::from)?;
        Ok(Motion {
            bodies: self,
            eta,
            com: it,
        })
    }
}

/// `u(t) = η_c u1(t) - η u2(t)` with `η = m1/(m1+m2)`: the input of the relative motion.
#[derive(Debug, Clone, Copy)]
pub struct RelativeInput<'a, I1, I2> {
    eta: f64,
    u1: &'a I1,
    u2: &'a I2,
}

impl<I1: Input, I2: Input> Input for RelativeInput<'_, I1, I2> {
    #[inline]
    fn at(&self, t: f64) -> f64 {
        (1.0 - self.eta) * self.u1.at(t) - self.eta * self.u2.at(t)
    }
    fn is_zero(&self) -> bool {
        self.u1.is_zero() && self.u2.is_zero()
    }
    fn is_constant(&self) -> bool {
        self.u1.is_constant() && self.u2.is_constant()
    }
    fn constant_after(&self) -> Option<f64> {
        Some(self.u1.constant_after()?.max(self.u2.constant_after()?))
    }
    fn at_dd(&self, t: bwc_ode::dd::Dd) -> Option<bwc_ode::dd::Dd> {
        Some(self.u1.at_dd(t)? * (1.0 - self.eta) - self.u2.at_dd(t)? * self.eta)
    }
}

/// Right-hand side of eq:com: `ẋ_m = v_m`, `v̇_m = (u1 + u2) / (m1 + m2)` (0 for a fixed body 2).
#[derive(Debug, Clone, Copy)]
pub struct ComRhs<'a, I1, I2> {
    u1: &'a I1,
    u2: &'a I2,
    total: f64,
}

impl<I1: Input, I2: Input> bwc_ode::System<2> for ComRhs<'_, I1, I2> {
    #[inline]
    fn rhs(&self, t: f64, y: &State<2>) -> State<2> {
        let a = if self.total.is_infinite() {
            0.0
        } else {
            (self.u1.at(t) + self.u2.at(t)) / self.total
        };
        State::<2>::new(y[1], a)
    }
}

/// Centre-of-mass and per-body kinematics along an impact (eq:x_m_1 - eq:v_m_2); query at
/// non-decreasing times.
#[derive(Debug, Clone)]
pub struct Motion<'a, I1, I2> {
    bodies: &'a Bodies<I1, I2>,
    eta: f64,
    com: Integrator<ComRhs<'a, I1, I2>, 2>,
}

impl<I1: Input, I2: Input> Motion<'_, I1, I2> {
    /// The motion at time `t` (s), given the relative displacement `x` (m) and velocity `v`
    /// (m/s) of the collision model there: `x_{m,1} = x_m + η_c x + η_c (l1 + l2)`,
    /// `x_{m,2} = x_m - η x - η (l1 + l2)`, `v_{m,1} = v_m + η_c v`, `v_{m,2} = v_m - η v`.
    ///
    /// # Errors
    /// [`ModelError::Solver`] if the centre-of-mass integration fails.
    pub fn at(&mut self, t: f64, x: f64, v: f64) -> Result<BodyMotion, ModelError> {
        if t > self.com.t() {
            self.com.integrate_to(t).map_err(bwc_events::Error::from)?;
        }
        let (x_m, v_m) = (self.com.y()[0], self.com.y()[1]);
        let (eta, eta_c) = (self.eta, 1.0 - self.eta);
        let l = self.bodies.l1 + self.bodies.l2;
        Ok(BodyMotion {
            x_m,
            x_m_1: x_m + eta_c * x + eta_c * l,
            x_m_2: x_m - eta * x - eta * l,
            v_m,
            v_m_1: v_m + eta_c * v,
            v_m_2: v_m - eta * v,
            u_1: self.bodies.u1.at(t),
            u_2: self.bodies.u2.at(t),
        })
    }
}
