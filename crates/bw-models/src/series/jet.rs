//! The jets of the series path: Taylor coefficients of the solution of each nondimensional model
//! about the start of a step, in time or in logarithmic time ([`Clock`]), by
//! the recurrences of the powers and Cauchy products ([`super::recurrence`]).

use super::crossing;
use super::polynomial::{Series, ORDER};
use super::recurrence::{clocked, Base, JetPowers, Power, INVERSE};
use super::steps::{step_tolerance, START_TOLERANCE};
use crate::input::Input;
use crate::models::{CollisionModel, NdCoefficients, Ndbwmcm, Ndbwshccm};
use crate::settings::Settings;
use crate::State;

/// The Taylor polynomials of one step.
pub(crate) struct Jet<const N: usize> {
    /// The state components.
    pub(super) state: [Series; N],
    /// The contact force `F`.
    pub(super) force: Series,
    /// The rate across the hysteretic element, whose sign picks the branch: `Y'` of the
    /// NDBWMCM (the NDBWSHCCM's rate is its velocity, `state[2]`, and leaves this unused).
    pub(super) rate: Series,
    /// Scratch of [`Expand::expand`], kept between steps: the bases of the powers and the
    /// powers (each expansion writes every coefficient it reads).
    bases: [Base; 2],
    powers: [Power; 3],
    /// Scratch of a logarithmic expansion: the coefficients of `dT/dσ = Δ e^σ` in reverse
    /// (`clock[ORDER - i] = Δ / i!`), and of the right-hand side of `Z` in time.
    clock: Series,
    z_rhs: Series,
}

/// The independent variable of an expansion.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Clock {
    /// The time `T`.
    Time,
    /// `σ = ln((T - T_a) / Δ)`, about `T = T_a + Δ` (`σ = 0`), where a base vanished at `T_a`:
    /// `dy/dσ = Δ e^σ f(y)`. The solution's branch point at `T_a` (its terms `(T - T_a)^a`
    /// are `Δ^a e^(a σ)`) lies at `σ = -∞`, so the steps in `σ` are not bounded by the
    /// distance to `T_a` as the steps in `T` are.
    Log(f64),
}

impl<const N: usize> Jet<N> {
    pub(super) fn new() -> Self {
        Self {
            state: [[0.0; ORDER + 1]; N],
            force: [0.0; ORDER + 1],
            rate: [0.0; ORDER + 1],
            bases: [Base::ZERO, Base::ZERO],
            powers: [Power::ZERO, Power::ZERO, Power::ZERO],
            clock: [0.0; ORDER + 1],
            z_rhs: [0.0; ORDER + 1],
        }
    }

    /// The coefficients of `Δ e^σ` for a logarithmic expansion of span `Δ`.
    fn set_log_clock(&mut self, span: f64) {
        let mut c = span;
        for i in 0..=ORDER {
            self.clock[ORDER - i] = c;
            c *= INVERSE[i + 1];
        }
    }

    /// The state polynomials at `s` (Estrin's scheme: the state at a step's end is on the
    /// critical path from one expansion to the next, and Estrin's tree is a third of Horner's
    /// chain of dependent operations; -5 % time per CoR evaluation, BENCHMARKS.md).
    pub(super) fn state_at(&self, s: f64) -> [f64; N] {
        self.state_by(&EstrinPowers::of(s))
    }

    fn state_by(&self, powers: &EstrinPowers) -> [f64; N] {
        std::array::from_fn(|i| powers.eval(&self.state[i]))
    }

    /// The state, rate and force polynomials at `s`, the rate taken from the state where it is
    /// the velocity.
    pub(super) fn with_force_at<const RATE_IS_VELOCITY: bool>(
        &self,
        s: f64,
    ) -> ([f64; N], f64, f64) {
        let powers = EstrinPowers::of(s);
        let y = self.state_by(&powers);
        let rate = if RATE_IS_VELOCITY {
            y[N - 1]
        } else {
            powers.eval(&self.rate)
        };
        (y, rate, powers.eval(&self.force))
    }
}

/// `s`, `s^2`, `s^4`, `s^8`, `s^16` for Estrin's scheme.
#[derive(Clone, Copy)]
struct EstrinPowers([f64; 5]);

const _: () = assert!(ORDER == 16, "EstrinPowers::eval is written for order 16");

impl EstrinPowers {
    #[inline(always)]
    fn of(s: f64) -> Self {
        let s2 = s * s;
        let s4 = s2 * s2;
        let s8 = s4 * s4;
        Self([s, s2, s4, s8, s8 * s8])
    }

    /// `Σ_(k <= 16) c_k s^k` by Estrin's scheme: pairs `c_2i + c_(2i+1) s`, then pairs of those
    /// with `s^2`, `s^4`, `s^8`: a tree of depth 5 instead of Horner's chain of 16.
    #[inline(always)]
    fn eval(&self, c: &Series) -> f64 {
        let [s, s2, s4, s8, s16] = self.0;
        let q: [f64; 8] = std::array::from_fn(|i| c[2 * i] + c[2 * i + 1] * s);
        let r: [f64; 4] = std::array::from_fn(|i| q[2 * i] + q[2 * i + 1] * s2);
        let t = [r[0] + r[1] * s4, r[2] + r[3] * s4];
        (t[0] + t[1] * s8) + c[16] * s16
    }
}

/// A nondimensional model whose solution the series path can expand.
pub(crate) trait Expand<const N: usize>: CollisionModel<N> {
    /// Index of the displacement whose power is in the force (`X` or `Y`).
    const BASE: usize;
    /// Index of `Z`.
    const Z: usize;
    /// Whether the rate is the velocity `V` (NDBWSHCCM).
    const RATE_IS_VELOCITY: bool;

    /// The Taylor coefficients of the solution through `y` in the branch where the rate has
    /// sign `rate_sign`, for the constant input `u`; `y[BASE]` and `y[Z]` are nonzero. With
    /// `saturated`, `y[Z]` is the branch's equilibrium ([`Expand::saturation`]) and `Z` is held
    /// there: its series is constant. The series are in the independent variable `clock`.
    fn expand(
        &self,
        y: &State<N>,
        rate_sign: f64,
        saturated: bool,
        u: f64,
        clock: Clock,
        jet: &mut Jet<N>,
    ) {
        match clock {
            Clock::Time => self.expand_in::<false>(y, rate_sign, saturated, u, jet),
            Clock::Log(span) => {
                jet.set_log_clock(span);
                self.expand_in::<true>(y, rate_sign, saturated, u, jet);
            }
        }
    }

    /// [`Expand::expand`] in time, or (`LOG`) in the logarithmic variable whose clock `jet`
    /// holds.
    fn expand_in<const LOG: bool>(
        &self,
        y: &State<N>,
        rate_sign: f64,
        saturated: bool,
        u: f64,
        jet: &mut Jet<N>,
    );

    /// The stable equilibrium `Z*` of the hysteretic variable in the branch of `y` where the
    /// rate has sign `rate_sign`, if it has one: where `c = B sgn(Z) sgn(rate) + Γ > 0` and `Z`
    /// moves with the rate (`sgn(Z) = sgn(rate)`), `Z' = rate (1 - c |Z|^n)` drives `|Z|` to
    /// `c^(-1/n)`, and `Z = Z*` is invariant while the branch lasts.
    fn saturation(&self, y: &State<N>, rate_sign: f64) -> Option<f64> {
        let k = self.coefficients();
        let sz = y[Self::Z].signum();
        let c = k.b * sz * rate_sign + k.gamma;
        (y[Self::Z] != 0.0 && sz == rate_sign && c > 0.0)
            .then(|| sz * c.powf(-1.0 / k.n.exponent()))
    }

    /// The model's nondimensional coefficients.
    fn coefficients(&self) -> &NdCoefficients;

    /// The step off a root of `Z` (`y[Z] = 0`, `y[BASE] != 0`) into the branch where the rate
    /// has sign `s`, under the constant input `u`, where that branch has no hysteresis bracket
    /// (`B + Γ = 0`; [`super::crossing`]); `tol` is the local tolerance. Returns the time the
    /// step takes, the state at its end and whether it ended on a separation (the force's root
    /// with `V >= 0`); `None` elsewhere, or where the step declines: the explicit method's
    /// start step takes over.
    fn crossing_step(
        &self,
        y: &State<N>,
        s: f64,
        u: f64,
        tol: f64,
    ) -> Option<(f64, State<N>, bool)>;

    /// The first step from contact under the constant input `u` where the model's loading has
    /// a series of its own ([`super::contact`]), as the time and state where it ends; `None`
    /// where it has none (the explicit method's start step then leaves contact).
    fn contact_step(&self, _u: f64, _settings: &Settings) -> Option<(f64, State<N>)> {
        None
    }

    /// The time and state just after contact from the leading terms of the loading
    /// ([`super::onset`]), where those left out are at most `tol`, under the constant input `u`.
    fn contact_start(&self, u: f64, tol: f64) -> Option<(f64, State<N>)>;
}

impl<I: Input> Expand<3> for Ndbwshccm<I> {
    const BASE: usize = 0;
    const Z: usize = 1;
    const RATE_IS_VELOCITY: bool = true;

    fn contact_step(&self, u: f64, settings: &Settings) -> Option<(f64, State<3>)> {
        // Loading with Γ = -B and no input is a Hunt-Crossley contact (Z = X).
        if u != 0.0 || self.k.b + self.k.gamma != 0.0 {
            return None;
        }
        let c = super::contact::hunt_crossley_step(self.k.p, self.k.sigma, settings, false)?;
        Some((c.t, State::<3>::new(c.x, c.x, c.v)))
    }

    fn coefficients(&self) -> &NdCoefficients {
        &self.k
    }

    fn contact_start(&self, u: f64, tol: f64) -> Option<(f64, State<3>)> {
        let (t, [x, z, v]) = super::onset::shccm(&self.k, u, tol)?;
        Some((t, State::<3>::new(x, z, v)))
    }

    fn crossing_step(
        &self,
        y: &State<3>,
        s: f64,
        u: f64,
        tol: f64,
    ) -> Option<(f64, State<3>, bool)> {
        let c = crossing::Coefficients::of(&self.k, u)?;
        let end = crossing::shccm(&c, y, s, tol)?;
        let y1 = State::<3>::new(y[0] + s * end.d, s * end.d, end.v);
        Some((end.dt, y1, end.separated))
    }

    fn expand_in<const LOG: bool>(
        &self,
        y: &State<3>,
        sw: f64,
        saturated: bool,
        u: f64,
        jet: &mut Jet<3>,
    ) {
        let k = &self.k;
        let (sx, sz) = (y[0].signum(), y[1].signum());
        // Z' = V - |Z|^n (B sgn(Z) |V| + Γ V) = V - c |Z|^n V in this branch; held at its
        // equilibrium, Z' = 0 (c is not needed then).
        let c = if saturated {
            0.0
        } else {
            k.b * sz * sw + k.gamma
        };
        // Loading with Γ = -B from Z = X: Z' = X' exactly, Z stays X.
        let shared = !saturated && c == 0.0 && y[1] == y[0];
        let kc = 1.0 - k.kappa;
        let Jet {
            state: [x, z, v],
            force,
            bases,
            powers,
            clock,
            z_rhs,
            ..
        } = jet;
        let mut pw = JetPowers::new(k, shared, c, bases, powers);
        (x[0], z[0], v[0]) = (y[0], y[1], y[2]);
        for j in 0..=ORDER {
            let [xp, zp, xpv, znv] = if j == 0 {
                let (xp, zp) = pw.start(sx * x[0], sz * z[0]);
                [xp, zp, xp * v[0], pw.hysteresis_leading() * v[0]]
            } else {
                pw.order_in_branch(j, sx * x[j], sz * z[j], v)
            };
            force[j] = -k.kappa * sx * xp - kc * sz * zp - k.sigma * xpv;
            if j == ORDER {
                break;
            }
            let inv = INVERSE[j + 1];
            let (gx, gv) = if LOG {
                (
                    clocked(v, clock, j),
                    clocked(force, clock, j) + u * clock[ORDER - j],
                )
            } else {
                (v[j], force[j] + if j == 0 { u } else { 0.0 })
            };
            x[j + 1] = gx * inv;
            z[j + 1] = if saturated {
                0.0
            } else if c == 0.0 {
                x[j + 1]
            } else if LOG {
                z_rhs[j] = v[j] - c * znv;
                clocked(z_rhs, clock, j) * inv
            } else {
                (v[j] - c * znv) * inv
            };
            v[j + 1] = gv * inv;
        }
    }
}

impl<I: Input> Expand<4> for Ndbwmcm<I> {
    const BASE: usize = 1;
    const Z: usize = 2;
    const RATE_IS_VELOCITY: bool = false;

    fn contact_step(&self, u: f64, settings: &Settings) -> Option<(f64, State<4>)> {
        // Loading with Γ = -B and no input: Z = Y, F = |Y|^p, V' = F, and X = R + Y with
        // R' = -σ F, so R = -σ (V + 1) and Y = X + σ (V + 1). Where σ is negligible (the paper's
        // DSS (1) fit: σ_b at the edge of its admissible set) this is the undamped Hunt-Crossley
        // contact X'' = |X|^p; the damper moves the force by at most
        // δ = p |X|^(p-1) σ |V + 1| <= p |X|^(p-1) σ, which moves the state by at most
        // δ T² cosh(ω T) / 2 <= δ T² e^(ω T), ω² = p |X|^(p-1) (|X| grows in the loading: its
        // largest value is at the end).
        let k = &self.k;
        if u != 0.0 || k.b + k.gamma != 0.0 || k.p.exponent() < 1.0 {
            return None;
        }
        let c = super::contact::hunt_crossley_step(k.p, 0.0, settings, true)?;
        let lipschitz = k.dpow_p(c.x);
        let bound = lipschitz * k.sigma * c.t * c.t * (lipschitz.sqrt() * c.t).exp();
        let tol = START_TOLERANCE * step_tolerance(&self.initial_state(), settings);
        let r = -k.sigma * (c.v + 1.0);
        let y = c.x - r;
        // The step ends inside the loading branch: Y' = V + σ |Y|^p < 0.
        let rate = c.v + k.sigma * k.p.of_abs(y.abs());
        (bound <= tol && rate < 0.0).then(|| (c.t, State::<4>::new(r, y, y, c.v)))
    }

    fn coefficients(&self) -> &NdCoefficients {
        &self.k
    }

    fn contact_start(&self, u: f64, tol: f64) -> Option<(f64, State<4>)> {
        let (t, [r, y, z, v]) = super::onset::mcm(&self.k, u, tol)?;
        Some((t, State::<4>::new(r, y, z, v)))
    }

    fn crossing_step(
        &self,
        y: &State<4>,
        s: f64,
        u: f64,
        tol: f64,
    ) -> Option<(f64, State<4>, bool)> {
        let c = crossing::Coefficients::of(&self.k, u)?;
        let end = crossing::mcm(&c, y, s, tol)?;
        let y1 = State::<4>::new(y[0] + end.dr, y[1] + s * end.d, s * end.d, end.v);
        Some((end.dt, y1, end.separated))
    }

    fn expand_in<const LOG: bool>(
        &self,
        y: &State<4>,
        sw: f64,
        saturated: bool,
        u: f64,
        jet: &mut Jet<4>,
    ) {
        let k = &self.k;
        let (sy, sz) = (y[1].signum(), y[2].signum());
        // Z' = Y' - c |Z|^n Y' in this branch (rate Y' = V + σ F); held at its equilibrium,
        // Z' = 0.
        let c = if saturated {
            0.0
        } else {
            k.b * sz * sw + k.gamma
        };
        let shared = !saturated && c == 0.0 && y[2] == y[1];
        let kc = 1.0 - k.kappa;
        let Jet {
            state: [r, yy, z, v],
            force,
            rate,
            bases,
            powers,
            clock,
            z_rhs,
        } = jet;
        let mut pw = JetPowers::new(k, shared, c, bases, powers);
        (r[0], yy[0], z[0], v[0]) = (y[0], y[1], y[2], y[3]);
        for j in 0..=ORDER {
            // The passes of the NDBWSHCCM with w = Y' (the product with |Y|^p unused; that with
            // |Z|^n taken with Y'_j = 0, its term |Z|^n_0 Y'_j added once Y'_j is known).
            rate[j] = 0.0;
            let [yp, zp, _, zn_rate] = if j == 0 {
                let (yp, zp) = pw.start(sy * yy[0], sz * z[0]);
                [yp, zp, 0.0, 0.0]
            } else {
                pw.order_in_branch(j, sy * yy[j], sz * z[j], rate)
            };
            force[j] = -k.kappa * sy * yp - kc * sz * zp;
            rate[j] = v[j] + k.sigma * force[j];
            if j == ORDER {
                break;
            }
            let inv = INVERSE[j + 1];
            let (gf, gy, gv) = if LOG {
                let gf = clocked(force, clock, j);
                (gf, clocked(rate, clock, j), gf + u * clock[ORDER - j])
            } else {
                (force[j], rate[j], force[j] + if j == 0 { u } else { 0.0 })
            };
            r[j + 1] = -k.sigma * gf * inv;
            yy[j + 1] = gy * inv;
            z[j + 1] = if saturated {
                0.0
            } else if c == 0.0 {
                yy[j + 1]
            } else {
                // |Z|^n Y' at order j: the pass's sum and the term |Z|^n_0 Y'_j.
                let gz = rate[j] - c * (zn_rate + pw.hysteresis_leading() * rate[j]);
                if LOG {
                    z_rhs[j] = gz;
                    clocked(z_rhs, clock, j) * inv
                } else {
                    gz * inv
                }
            };
            v[j + 1] = gv * inv;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::input::Constant;
    use crate::{ModelKind, Nondim, NondimParams};

    /// Nondimensional parameters with `κ = 0.4` and `n = 1.7`.
    fn nd(kind: ModelKind, b: f64, gamma: f64, sigma: f64, p: f64) -> NondimParams {
        let nd = Nondim {
            b,
            gamma,
            kappa: 0.4,
            sigma,
            n: 1.7,
            p,
        };
        NondimParams::new(kind, nd).unwrap()
    }

    /// The NDBWSHCCM with `σ = 0`, `p = 1` and `Γ = -B` (so `Z = X` and `F = -X`), no input,
    /// loads as `X = -sin T`, `V = -cos T`. Its logarithmic expansion about `T0` (anchor 0) at
    /// `σ` is that solution at `T0 e^σ`, to the Taylor remainder of its terms `a e^(k σ)`,
    /// about `|a| (k σ)^17 / 17!`: the largest are those of `X`'s `T0 e^σ` and of `V`'s
    /// `T0^2 e^(2 σ) / 2` (2.4e-11 at σ = 2), and the rounding.
    #[test]
    fn a_logarithmic_expansion_meets_the_closed_form() {
        let t0: f64 = 1e-3;
        let params = nd(ModelKind::Shccm, 1.5, -1.5, 0.0, 1.0);
        let model = Ndbwshccm::new(&params, Constant(0.0)).unwrap();
        let (x0, v0) = (-t0.sin(), -t0.cos());
        let mut jet = Jet::<3>::new();
        let y = State::<3>::new(x0, x0, v0);
        model.expand(&y, -1.0, false, 0.0, Clock::Log(t0), &mut jet);
        let factorial_17 = (1..=17).map(f64::from).product::<f64>();
        for sigma in [0.5f64, 1.0, 1.5, 2.0] {
            let remainder =
                (t0 * sigma.powi(17) + 0.5 * t0 * t0 * (2.0 * sigma).powi(17)) / factorial_17;
            let t = t0 * f64::exp(sigma);
            let want = [-t.sin(), -t.sin(), -t.cos()];
            let got = jet.state_at(sigma);
            for (g, w) in got.iter().zip(want) {
                let tol = 2.0 * remainder + 1e-13 * w.abs();
                assert!((g - w).abs() <= tol, "σ {sigma}: {got:?} vs {want:?}");
            }
        }
    }

    /// With hysteresis (`B + Γ != 0`), damping and an input, the logarithmic expansion about
    /// `T0 = T_a + Δ` at `σ` and the expansion in time about `T0` at `Δ (e^σ - 1)` are the same
    /// solution: for short spans both series are exact to rounding. A clock whose coefficients
    /// were off would show at order `σ^2` (1e-4 here).
    #[test]
    fn a_logarithmic_expansion_agrees_with_the_expansion_in_time() {
        let (span, u) = (0.3, 0.2);
        let params = |kind| nd(kind, 1.5, -0.7, 0.1, 2.3);
        let shccm = Ndbwshccm::new(&params(ModelKind::Shccm), Constant(u)).unwrap();
        let mcm = Ndbwmcm::new(&params(ModelKind::Mcm), Constant(u)).unwrap();
        let y3 = State::<3>::new(-0.5, -0.3, -0.8);
        let y4 = State::<4>::new(0.02, -0.5, -0.3, -0.8);
        let (mut log3, mut time3, mut log4, mut time4) = (
            Jet::<3>::new(),
            Jet::<3>::new(),
            Jet::<4>::new(),
            Jet::<4>::new(),
        );
        shccm.expand(&y3, -1.0, false, u, Clock::Log(span), &mut log3);
        shccm.expand(&y3, -1.0, false, u, Clock::Time, &mut time3);
        mcm.expand(&y4, -1.0, false, u, Clock::Log(span), &mut log4);
        mcm.expand(&y4, -1.0, false, u, Clock::Time, &mut time4);
        for sigma in [0.01, 0.03, 0.1] {
            let tau = span * f64::exp_m1(sigma);
            let pairs = [
                (log3.state_at(sigma).to_vec(), time3.state_at(tau).to_vec()),
                (log4.state_at(sigma).to_vec(), time4.state_at(tau).to_vec()),
            ];
            for (log, time) in pairs {
                for (a, b) in log.iter().zip(&time) {
                    assert!((a - b).abs() <= 1e-15, "σ {sigma}: {log:?} vs {time:?}");
                }
            }
        }
    }

    #[test]
    fn estrin_sums_the_geometric_series() {
        // Σ_(k<=16) s^k = (1 - s^17) / (1 - s), and the coefficients k (its derivative times s).
        let ones = [1.0; ORDER + 1];
        let ks: Series = std::array::from_fn(|k| k as f64);
        for s in [-1.3, -0.5, 0.0, 1e-3, 0.25, 0.9, 2.0] {
            let p = EstrinPowers::of(s);
            let geometric = if s == 0.0 {
                1.0
            } else {
                (1.0 - s.powi(17)) / (1.0 - s)
            };
            let scale: f64 = (0..=ORDER).map(|k| s.abs().powi(k as i32)).sum();
            assert!((p.eval(&ones) - geometric).abs() <= 8.0 * f64::EPSILON * scale);
            let derivative: f64 = (1..=ORDER).map(|k| k as f64 * s.powi(k as i32)).sum();
            assert!((p.eval(&ks) - derivative).abs() <= 64.0 * f64::EPSILON * scale);
        }
    }
}
