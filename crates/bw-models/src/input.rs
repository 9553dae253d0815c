//! External inputs `u(t)` (forces in N, or nondimensional `U(T)`).

use bwc_ode::dd::{self, Dd};

/// A time-dependent input signal.
pub trait Input {
    /// The value at time `t`.
    fn at(&self, t: f64) -> f64;

    /// Whether the input is identically zero (lets a model skip evaluating it).
    fn is_zero(&self) -> bool {
        false
    }

    /// Whether the input is constant in time (then a state at rest is an equilibrium and a
    /// simulation may stop there).
    fn is_constant(&self) -> bool {
        self.is_zero()
    }

    /// A time from which the input is constant, if there is one (`-inf` for a constant input;
    /// the last time of a table). Inputs that only approach a constant, like [`Arctan`], have
    /// none.
    fn constant_after(&self) -> Option<f64> {
        self.is_constant().then_some(f64::NEG_INFINITY)
    }

    /// The value at `t` in double-double arithmetic, for the double-double path of a CoR
    /// evaluation ([`crate::Settings::double_double`]); `None` (the default) where the input
    /// has no such form, and the evaluation stays in double precision.
    fn at_dd(&self, _t: Dd) -> Option<Dd> {
        None
    }
}

/// No input: `u = 0`.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Zero;

impl Input for Zero {
    #[inline]
    fn at(&self, _t: f64) -> f64 {
        0.0
    }
    fn is_zero(&self) -> bool {
        true
    }
    fn at_dd(&self, _t: Dd) -> Option<Dd> {
        Some(Dd::from(0.0))
    }
}

/// A constant input.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Constant(pub f64);

impl Input for Constant {
    #[inline]
    fn at(&self, _t: f64) -> f64 {
        self.0
    }
    fn is_zero(&self) -> bool {
        self.0 == 0.0
    }
    fn is_constant(&self) -> bool {
        true
    }
    fn at_dd(&self, _t: Dd) -> Option<Dd> {
        Some(Dd::from(self.0))
    }
}

/// Gravity on a body of mass `m` along the contact normal: `u = -m g` (N).
pub fn gravity(m: f64, g: f64) -> Constant {
    Constant(-m * g)
}

/// The paper's ramp (Section 6): `u(t) = (2/π) m D arctan(ω t)` (N), rising from 0 to `m D`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Arctan {
    /// Mass `m` (kg).
    pub m: f64,
    /// Final acceleration `D` (m/s²).
    pub d: f64,
    /// Rate `ω` (1/s).
    pub omega: f64,
}

impl Input for Arctan {
    #[inline]
    fn at(&self, t: f64) -> f64 {
        std::f64::consts::FRAC_2_PI * self.m * self.d * (self.omega * t).atan()
    }
    fn at_dd(&self, t: Dd) -> Option<Dd> {
        Some(dd::div(dd::atan(t * self.omega), dd::frac_pi_2()) * (Dd::from(self.m) * self.d))
    }
}

/// The sum of two inputs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sum<A, B>(pub A, pub B);

impl<A: Input, B: Input> Input for Sum<A, B> {
    #[inline]
    fn at(&self, t: f64) -> f64 {
        self.0.at(t) + self.1.at(t)
    }
    fn is_zero(&self) -> bool {
        self.0.is_zero() && self.1.is_zero()
    }
    fn is_constant(&self) -> bool {
        self.0.is_constant() && self.1.is_constant()
    }
    fn constant_after(&self) -> Option<f64> {
        Some(self.0.constant_after()?.max(self.1.constant_after()?))
    }
    fn at_dd(&self, t: Dd) -> Option<Dd> {
        Some(self.0.at_dd(t)? + self.1.at_dd(t)?)
    }
}

/// A sinusoid `u(t) = a + b sin(ω t)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sine {
    /// Mean `a`.
    pub a: f64,
    /// Amplitude `b`.
    pub b: f64,
    /// Angular frequency `ω` (1 / time unit).
    pub omega: f64,
}

impl Input for Sine {
    #[inline]
    fn at(&self, t: f64) -> f64 {
        self.a + self.b * (self.omega * t).sin()
    }
    fn is_zero(&self) -> bool {
        self.a == 0.0 && self.b == 0.0
    }
    fn is_constant(&self) -> bool {
        self.b == 0.0 || self.omega == 0.0
    }
    fn at_dd(&self, t: Dd) -> Option<Dd> {
        Some(dd::sin(t * self.omega) * self.b + self.a)
    }
}

/// `factor * inner(time_scale * t)`: an input seen on another time and force scale (used for
/// the nondimensional input `U(T)` of a physical input `u(t)`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scaled<I> {
    /// The physical input.
    pub inner: I,
    /// Multiplier of the value.
    pub factor: f64,
    /// Multiplier of the time argument.
    pub time_scale: f64,
}

impl<I: Input> Input for Scaled<I> {
    #[inline]
    fn at(&self, t: f64) -> f64 {
        self.factor * self.inner.at(self.time_scale * t)
    }
    fn is_zero(&self) -> bool {
        self.factor == 0.0 || self.inner.is_zero()
    }
    fn is_constant(&self) -> bool {
        self.factor == 0.0 || self.inner.is_constant()
    }
    fn constant_after(&self) -> Option<f64> {
        if self.factor == 0.0 {
            return Some(f64::NEG_INFINITY);
        }
        let t = self.inner.constant_after()?;
        // inner(time_scale * t) is constant for time_scale * t >= t_inner.
        (self.time_scale > 0.0).then(|| t / self.time_scale)
    }
    fn at_dd(&self, t: Dd) -> Option<Dd> {
        Some(self.inner.at_dd(t * self.time_scale)? * self.factor)
    }
}

/// A piecewise-linear table `(t_i, u_i)` with strictly increasing `t_i`, held constant outside
/// its range.
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    t: Vec<f64>,
    u: Vec<f64>,
}

impl Table {
    /// Builds a table from points.
    ///
    /// # Errors
    /// [`crate::ModelError::InvalidTable`] when there are no points, a value is not finite, or
    /// the times do not increase strictly.
    pub fn new(points: &[(f64, f64)]) -> Result<Self, crate::ModelError> {
        if points.is_empty() {
            return Err(crate::ModelError::InvalidTable {
                index: 0,
                reason: "the table has no points",
            });
        }
        for (i, &(t, u)) in points.iter().enumerate() {
            if !t.is_finite() || !u.is_finite() {
                return Err(crate::ModelError::InvalidTable {
                    index: i,
                    reason: "t and u must be finite",
                });
            }
            if i > 0 && t <= points[i - 1].0 {
                return Err(crate::ModelError::InvalidTable {
                    index: i,
                    reason: "times must increase strictly",
                });
            }
        }
        Ok(Self {
            t: points.iter().map(|p| p.0).collect(),
            u: points.iter().map(|p| p.1).collect(),
        })
    }

    /// The points `(t, u)` in time order.
    pub fn points(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.t.iter().copied().zip(self.u.iter().copied())
    }
}

impl Table {
    /// The piece `(t0, t1, u0, u1)` a time lies in, given how many `t_i` it has reached, or
    /// the value held outside the table's range.
    fn piece(&self, reached: usize) -> Result<(f64, f64, f64, f64), f64> {
        match reached {
            0 => Err(self.u[0]),
            i if i == self.t.len() => Err(self.u[i - 1]),
            i => Ok((self.t[i - 1], self.t[i], self.u[i - 1], self.u[i])),
        }
    }
}

impl Input for Table {
    fn at(&self, t: f64) -> f64 {
        match self.piece(self.t.partition_point(|&ti| ti <= t)) {
            Ok((t0, t1, u0, u1)) => u0 + (u1 - u0) * (t - t0) / (t1 - t0),
            Err(held) => held,
        }
    }
    fn at_dd(&self, t: Dd) -> Option<Dd> {
        Some(match self.piece(self.t.partition_point(|&ti| t >= ti)) {
            Ok((t0, t1, u0, u1)) => {
                dd::div((t - t0) * Dd::new_sub(u1, u0), Dd::new_sub(t1, t0)) + u0
            }
            Err(held) => Dd::from(held),
        })
    }
    fn is_constant(&self) -> bool {
        self.u.iter().all(|u| *u == self.u[0])
    }
    fn constant_after(&self) -> Option<f64> {
        Some(if self.is_constant() {
            f64::NEG_INFINITY
        } else {
            self.t[self.t.len() - 1]
        })
    }
}

/// Any closure `Fn(f64) -> f64` is an input.
#[derive(Debug, Clone, Copy)]
pub struct FromFn<F>(pub F);

impl<F: Fn(f64) -> f64> Input for FromFn<F> {
    #[inline]
    fn at(&self, t: f64) -> f64 {
        (self.0)(t)
    }
}

impl<I: Input + ?Sized> Input for &I {
    #[inline]
    fn at(&self, t: f64) -> f64 {
        (**self).at(t)
    }
    fn is_zero(&self) -> bool {
        (**self).is_zero()
    }
    fn is_constant(&self) -> bool {
        (**self).is_constant()
    }
    fn constant_after(&self) -> Option<f64> {
        (**self).constant_after()
    }
    fn at_dd(&self, t: Dd) -> Option<Dd> {
        (**self).at_dd(t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn signals() {
        assert_eq!(gravity(2.0, 9.81).at(5.0), -19.62);
        let r = Arctan {
            m: 2.0,
            d: 250.0,
            omega: 1e3,
        };
        assert_eq!(r.at(0.0), 0.0);
        assert!((r.at(1e9) - 500.0).abs() < 1e-6);
        let tab = Table::new(&[(0.0, 1.0), (1.0, 3.0)]).unwrap();
        assert_eq!(tab.at(-1.0), 1.0);
        assert_eq!(tab.at(0.5), 2.0);
        assert_eq!(tab.at(7.0), 3.0);
        assert!(Table::new(&[(0.0, 1.0), (0.0, 2.0)]).is_err());
        assert!(Table::new(&[]).is_err());
        let s = Scaled {
            inner: Constant(2.0),
            factor: 0.5,
            time_scale: 3.0,
        };
        assert_eq!(s.at(1.0), 1.0);
        assert_eq!(Sum(Constant(1.0), FromFn(|t: f64| t)).at(2.0), 3.0);
        assert!(Sum(Zero, Constant(0.0)).is_zero());
    }

    /// The double-double forms agree with the inputs to rounding, and exactly where both are
    /// exact; an input without one says so.
    #[test]
    fn double_double_forms_match_the_inputs() {
        let sine = Sine {
            a: 0.5,
            b: 2.0,
            omega: 3.0,
        };
        let tab = Table::new(&[(0.0, 1.0), (1.0, 3.0), (2.5, -1.0)]).unwrap();
        let scaled = Scaled {
            inner: sine,
            factor: 0.25,
            time_scale: 1.5,
        };
        let ramp = Arctan {
            m: 2.0,
            d: 250.0,
            omega: 3.0,
        };
        for t in [0.0, 0.3, 1.0, 1.7, 2.5, 9.0] {
            let d = Dd::from(t);
            assert!((ramp.at_dd(d).unwrap().hi() - ramp.at(t)).abs() < 1e-12);
            assert!((sine.at_dd(d).unwrap().hi() - sine.at(t)).abs() < 1e-15);
            assert!((tab.at_dd(d).unwrap().hi() - tab.at(t)).abs() < 1e-15);
            assert!((scaled.at_dd(d).unwrap().hi() - scaled.at(t)).abs() < 1e-15);
        }
        // sin(3 * π/6) = 1 to double-double precision: 0.5 + 2 = 2.5.
        let pi_6 = dd::dd(std::f64::consts::FRAC_PI_6, -5.360408832255455e-17);
        assert!((sine.at_dd(pi_6).unwrap() - 2.5).hi().abs() < 1e-30);
        assert_eq!(tab.at_dd(Dd::from(1.0)).unwrap(), Dd::from(3.0));
        // arctan(1) = π/4: the ramp is at half its final value m D = 500.
        let one_third = Dd::from(1.0) / 3.0;
        assert!((ramp.at_dd(one_third).unwrap() - 250.0).hi().abs() < 1e-28);
        assert_eq!(
            Sum(Constant(1.0), Zero).at_dd(Dd::from(4.0)),
            Some(Dd::from(1.0))
        );
        assert_eq!(FromFn(|t: f64| t).at_dd(Dd::from(1.0)), None);
        assert_eq!(
            Sum(Constant(1.0), FromFn(|t: f64| t)).at_dd(Dd::from(1.0)),
            None
        );
    }

    #[test]
    fn constant_from_some_time() {
        let tab = Table::new(&[(0.0, 1.0), (2.0, 3.0)]).unwrap();
        assert_eq!(tab.constant_after(), Some(2.0));
        let flat = Table::new(&[(0.0, 1.0), (2.0, 1.0)]).unwrap();
        assert_eq!(flat.constant_after(), Some(f64::NEG_INFINITY));
        assert_eq!(Sum(&tab, Constant(1.0)).constant_after(), Some(2.0));
        assert_eq!(Sum(&tab, FromFn(|t: f64| t)).constant_after(), None);
        let s = Scaled {
            inner: &tab,
            factor: 2.0,
            time_scale: 0.5,
        };
        assert_eq!(s.constant_after(), Some(4.0));
        let r = Arctan {
            m: 1.0,
            d: 1.0,
            omega: 1.0,
        };
        assert_eq!(r.constant_after(), None);
        assert_eq!(Zero.constant_after(), Some(f64::NEG_INFINITY));
    }
}
