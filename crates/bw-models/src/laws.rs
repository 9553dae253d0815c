//! The collision laws as force elements driven by a relative-velocity input `u` (m/s), for
//! embedding in other simulators: BWSHCCL (eq:BWSHCCL, states x, z) and BWMCL (eq:BWMCL,
//! states r, y, z). Output: the contact force `F` (N), positive when pushing the bodies apart.

use crate::law_spec::{finite, non_negative, positive, LawParam, LawSpec, NamedLaw};
use crate::params::{ModelKind, Physical, PhysicalParams};
use crate::power::{Pow, Powers};
use crate::published::{CROSS_BWMCM, CROSS_BWSHCCM};
use crate::{ModelError, State};
use bwc_ode::Matrix;

/// Bouc-Wen hysteresis `ż = A w - β |z|^(n-1) z |w| - γ |z|^n w`, with `zn()` giving `|z|^n`.
///
/// `β |z|^(n-1) z |w| = β sgn(z) |z|^n |w|`, so `ż = A w - |z|^n (β sgn(z) |w| + γ w)`; the
/// bracket is exactly 0 on the branch `sgn(z) = sgn(w)` when `γ = -β` (loading in all of the
/// paper's fits), and then `|z|^n` is not computed (the result is the same bit for bit).
#[inline]
pub(crate) fn hysteresis(
    a: f64,
    beta: f64,
    gamma: f64,
    z: f64,
    w: f64,
    zn: impl FnOnce() -> f64,
) -> f64 {
    let m = (beta * w.abs()).copysign(z) + gamma * w;
    if m == 0.0 {
        a * w
    } else {
        a * w - zn() * m
    }
}

fn expect(params: &PhysicalParams, kind: ModelKind) -> Result<(), ModelError> {
    if params.kind() == kind {
        Ok(())
    } else {
        Err(ModelError::WrongModel {
            expected: kind.name(),
            found: params.kind().name(),
        })
    }
}

/// The contact-law parameters both laws use, with the exponents classified once.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Coefficients {
    pub(crate) k: f64,
    pub(crate) c: f64,
    pub(crate) alpha: f64,
    pub(crate) beta: f64,
    pub(crate) gamma: f64,
    pub(crate) a: f64,
    pub(crate) n: Pow,
    pub(crate) p: Pow,
}

impl Coefficients {
    fn new(params: &PhysicalParams, kind: ModelKind) -> Result<Self, ModelError> {
        expect(params, kind)?;
        let l = params.law();
        Ok(Self {
            k: l.k,
            c: l.c,
            alpha: l.alpha,
            beta: l.beta,
            gamma: l.gamma,
            a: l.a,
            n: Pow::new(l.n),
            p: Pow::new(l.p),
        })
    }
}

/// The Bouc-Wen-Simon-Hunt-Crossley collision law: a nonlinear dashpot in parallel with a
/// Bouc-Wen element, `ẋ = u`, `ż = A u - β|z|^(n-1) z |u| - γ|z|^n u`,
/// `F = -α k |x|^(p-1) x - (1-α) k |z|^(p-1) z - c |x|^p u`.
///
/// Units and signs: `x`, `z` in m (`x < 0` in compression), `u` in m/s (the relative velocity,
/// negative while the bodies approach), `F` in N (positive pushes them apart).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bwshccl(pub(crate) Coefficients);

impl Bwshccl {
    /// The law with validated SHCCM parameters.
    ///
    /// # Errors
    /// [`ModelError::WrongModel`] for MCM parameters.
    pub fn new(params: &PhysicalParams) -> Result<Self, ModelError> {
        Coefficients::new(params, ModelKind::Shccm).map(Self)
    }

    /// State derivative `(ẋ, ż)` and force `F` at state `(x, z)` with input `u`.
    #[inline]
    pub fn eval(&self, s: &State<2>, u: f64) -> (State<2>, f64) {
        let c = &self.0;
        let (x, z) = (s[0], s[1]);
        let xp = c.p.of_abs(x.abs());
        let mut zpow = Powers::of(z.abs());
        let zp = zpow.get(c.p);
        let f =
            -c.alpha * c.k * xp.copysign(x) - (1.0 - c.alpha) * c.k * zp.copysign(z) - c.c * xp * u;
        (
            State::<2>::new(u, hysteresis(c.a, c.beta, c.gamma, z, u, || zpow.get(c.n))),
            f,
        )
    }
}

/// The Bouc-Wen-Maxwell collision law: a linear dashpot in series with a Bouc-Wen element,
/// `ṙ = (k/c)(α |y|^(p-1) y + (1-α) |z|^(p-1) z)`, `ẏ = u - ṙ`,
/// `ż = A ẏ - β|z|^(n-1) z |ẏ| - γ|z|^n ẏ`, `F = -c ṙ`.
///
/// Units and signs: `r`, `y`, `z` in m (`x = r + y < 0` in compression), `u` in m/s (the
/// relative velocity, negative while the bodies approach), `F` in N (positive pushes them
/// apart).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bwmcl(pub(crate) Coefficients);

impl Bwmcl {
    /// The law with validated MCM parameters.
    ///
    /// # Errors
    /// [`ModelError::WrongModel`] for SHCCM parameters.
    pub fn new(params: &PhysicalParams) -> Result<Self, ModelError> {
        Coefficients::new(params, ModelKind::Mcm).map(Self)
    }

    /// State derivative `(ṙ, ẏ, ż)` and force `F` at state `(r, y, z)` with input `u`.
    #[inline]
    pub fn eval(&self, s: &State<3>, u: f64) -> (State<3>, f64) {
        let c = &self.0;
        let (y, z) = (s[1], s[2]);
        let mut zpow = Powers::of(z.abs());
        let zp = zpow.get(c.p);
        let f = -c.k * (c.alpha * c.p.signed(y) + (1.0 - c.alpha) * zp.copysign(z));
        let rdot = -f / c.c;
        let ydot = u - rdot;
        let zdot = hysteresis(c.a, c.beta, c.gamma, z, ydot, || zpow.get(c.n));
        (State::<3>::new(rdot, ydot, zdot), f)
    }
}

/// The derivatives of a law's state rate `ṡ` and force `F` with respect to its state `s` and
/// its input `u` (units of `ṡ`, `F` per unit of `s`, `u`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LawJacobian<const N: usize> {
    /// `∂ṡ/∂s`.
    pub rate_state: Matrix<N>,
    /// `∂ṡ/∂u`.
    pub rate_input: State<N>,
    /// `∂F/∂s`.
    pub force_state: State<N>,
    /// `∂F/∂u`.
    pub force_input: f64,
}

/// A collision law as a force element another simulator can hold: a state `s` of `N`
/// displacements (m), driven by the relative velocity `u` (m/s, negative while the bodies
/// approach), giving the contact force `F` (N, positive pushing the bodies apart). A contact
/// starts from [`ContactLaw::onset`] and ends where [`crate::separated`] holds for `F` and the
/// relative velocity.
pub trait ContactLaw<const N: usize> {
    /// The state at the onset of a contact: the law at rest, all displacements zero.
    fn onset(&self) -> State<N> {
        State::<N>::zeros()
    }

    /// The state derivative `ṡ` (m/s) and the force `F` (N) at state `s` with input `u`.
    fn eval(&self, s: &State<N>, u: f64) -> (State<N>, f64);

    /// The energy stored in the law's elastic elements at state `s` (J): what a release to
    /// rest would give back. The rest of the work done on the law has been dissipated. The
    /// default is 0 (a law without springs, or one that does not say: then all the work
    /// counts as dissipated); the built-in laws override it.
    fn stored(&self, _s: &State<N>) -> f64 {
        0.0
    }

    /// The rate at which the law dissipates energy at state `s` with input `u` (W), given
    /// what [`ContactLaw::eval`] returned there (`rate`, `force`): the power the bodies put
    /// in, `-F u`, less the rate of [`ContactLaw::stored`]. The default is `-F u` (consistent
    /// with the default `stored` of 0); the built-in laws override it with their closed
    /// forms, which are `>= 0` on their admissible sets.
    fn dissipation(&self, _s: &State<N>, u: f64, _rate: &State<N>, force: f64) -> f64 {
        -force * u
    }

    /// Functions whose zeros are the non-smooth points of [`ContactLaw::eval`]: the rate
    /// across the hysteretic element (m/s) and `z` (m). An integrator that stops exactly at
    /// them keeps its order (`bwc_events::Switches`).
    fn kinks(&self, s: &State<N>, u: f64) -> [f64; 2];

    /// The derivatives of `ṡ` and `F` at `(s, u)`, by forward differences with steps
    /// `√ε max(|v|, 1e-9)` (relative accuracy about 1e-8; the laws are not differentiable at
    /// their kinks).
    fn jacobian(&self, s: &State<N>, u: f64) -> LawJacobian<N> {
        let (rate, force) = self.eval(s, u);
        let step = |v: f64| f64::EPSILON.sqrt() * v.abs().max(1e-9);
        let mut rate_state = Matrix::<N>::zeros();
        let mut force_state = State::<N>::zeros();
        for c in 0..N {
            let mut sc = *s;
            sc[c] += step(s[c]);
            let h = sc[c] - s[c];
            let (r, f) = self.eval(&sc, u);
            rate_state.set_column(c, &((r - rate) / h));
            force_state[c] = (f - force) / h;
        }
        let du = (u + step(u)) - u;
        let (r, f) = self.eval(s, u + du);
        LawJacobian {
            rate_state,
            rate_input: (r - rate) / du,
            force_state,
            force_input: (f - force) / du,
        }
    }
}

impl Coefficients {
    /// The energy of the elastic spring at displacement `x` and of the Bouc-Wen element at
    /// `z` (J): `α k |x|^(p+1) / (p+1) + (1-α) k |z|^(p+1) / ((p+1) A)`. The second term is
    /// the work that drives `z` from 0 where the element does not yield (`β = γ = 0`, so
    /// `ż = A` times its rate): all of it comes back on the way to `z = 0`.
    fn stored(&self, x: f64, z: f64) -> f64 {
        let p1 = self.p.exponent() + 1.0;
        let spring = |d: f64| self.k * d.abs().powf(p1) / p1;
        self.alpha * spring(x) + (1.0 - self.alpha) * spring(z) / self.a
    }

    /// The Bouc-Wen element's dissipation (W) at `z` whose rate across is `w` (m/s):
    /// `(1-α) k / A |z|^(p+n) (β |w| + γ sgn(z) w)`, the work it takes, `(1-α) k |z|^p sgn(z)
    /// w`, less the rate of its stored energy, `(1-α) k |z|^p sgn(z) ż / A`.
    fn hysteretic(&self, z: f64, w: f64) -> f64 {
        let za = z.abs();
        let m = self.beta * w.abs() + self.gamma * w * z.signum();
        if m == 0.0 || za == 0.0 {
            return 0.0;
        }
        (1.0 - self.alpha) * self.k / self.a * self.p.of_abs(za) * self.n.of_abs(za) * m
    }
}

impl ContactLaw<2> for Bwshccl {
    fn eval(&self, s: &State<2>, u: f64) -> (State<2>, f64) {
        Bwshccl::eval(self, s, u)
    }
    /// `α k |x|^(p+1) / (p+1) + (1-α) k |z|^(p+1) / ((p+1) A)` (J).
    fn stored(&self, s: &State<2>) -> f64 {
        self.0.stored(s[0], s[1])
    }
    /// `c |x|^p u² + (1-α) k / A |z|^(p+n) (β |u| + γ sgn(z) u)` (W).
    fn dissipation(&self, s: &State<2>, u: f64, _rate: &State<2>, _force: f64) -> f64 {
        let c = &self.0;
        c.c * c.p.of_abs(s[0].abs()) * u * u + c.hysteretic(s[1], u)
    }
    fn kinks(&self, s: &State<2>, u: f64) -> [f64; 2] {
        [u, s[1]]
    }
}

impl ContactLaw<3> for Bwmcl {
    fn eval(&self, s: &State<3>, u: f64) -> (State<3>, f64) {
        Bwmcl::eval(self, s, u)
    }
    /// `α k |y|^(p+1) / (p+1) + (1-α) k |z|^(p+1) / ((p+1) A)` (J): the dashpot stores
    /// nothing.
    fn stored(&self, s: &State<3>) -> f64 {
        self.0.stored(s[1], s[2])
    }
    /// `F² / c + (1-α) k / A |z|^(p+n) (β |ẏ| + γ sgn(z) ẏ)` (W): the dashpot's and the
    /// Bouc-Wen element's, `ẏ` the rate across it.
    fn dissipation(&self, s: &State<3>, _u: f64, rate: &State<3>, force: f64) -> f64 {
        force * force / self.0.c + self.0.hysteretic(s[2], rate[1])
    }
    fn kinks(&self, s: &State<3>, u: f64) -> [f64; 2] {
        [Bwmcl::eval(self, s, u).0[1], s[2]]
    }
}

/// The parameters of a Bouc-Wen law, `k, c, n, p, alpha, beta, gamma, A`, as
/// [`PhysicalParams::new`] checks them, with the damping `c` (whose unit and admissible set
/// differ between the laws) given, and Table 4's law `$t` as start values.
macro_rules! bouc_wen_params {
    ($t:expr, $c_unit:expr, $c_allowed:expr, $c_admits:expr) => {
        &[
            LawParam::new("k", "kg m^(1-p) s^-2", "k > 0", positive, $t.k),
            LawParam::new("c", $c_unit, $c_allowed, $c_admits, $t.c),
            LawParam::new("n", "-", "n >= 1", |n| n >= 1.0 && n.is_finite(), $t.n),
            LawParam::new("p", "-", "p >= 1", |p| p >= 1.0 && p.is_finite(), $t.p),
            LawParam::new(
                "alpha",
                "-",
                "0 < alpha < 1",
                |a| a > 0.0 && a < 1.0,
                $t.alpha,
            ),
            LawParam::new("beta", "m^-n", "beta >= 0", non_negative, $t.beta),
            LawParam::new("gamma", "m^-n", "-beta <= gamma <= beta", finite, $t.gamma),
            LawParam::new("A", "-", "A > 0", positive, $t.a),
        ]
    };
}

/// The validated parameters of `kind` from `k, c, n, p, alpha, beta, gamma, A`.
fn physical(kind: ModelKind, v: &[f64]) -> Result<PhysicalParams, ModelError> {
    let &[k, c, n, p, alpha, beta, gamma, a] = v else {
        return Err(ModelError::NotApplicable {
            reason: "a Bouc-Wen law takes 8 values: k, c, n, p, alpha, beta, gamma, A",
        });
    };
    let law = Physical {
        k,
        c,
        n,
        p,
        alpha,
        beta,
        gamma,
        a,
    };
    PhysicalParams::new(kind, law)
}

impl NamedLaw<2> for Bwshccl {
    const SPEC: LawSpec = LawSpec {
        name: "shccm",
        title: "BWSHCCL",
        force: "-alpha k |x|^(p-1) x - (1-alpha) k |z|^(p-1) z - c |x|^p u",
        params: bouc_wen_params!(
            CROSS_BWSHCCM,
            "kg m^-p s^-1",
            "c >= 0 for the BWSHCCM",
            non_negative
        ),
        states: &["x", "z"],
    };
    fn of_values(values: &[f64]) -> Result<Self, ModelError> {
        Self::new(&physical(ModelKind::Shccm, values)?)
    }
}

impl NamedLaw<3> for Bwmcl {
    const SPEC: LawSpec = LawSpec {
        name: "mcm",
        title: "BWMCL",
        force: "-k (alpha |y|^(p-1) y + (1-alpha) |z|^(p-1) z) = -c r'",
        params: bouc_wen_params!(CROSS_BWMCM, "kg s^-1", "c > 0 for the BWMCM", positive),
        states: &["r", "y", "z"],
    };
    fn of_values(values: &[f64]) -> Result<Self, ModelError> {
        Self::new(&physical(ModelKind::Mcm, values)?)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Physical;

    /// The closed-form dissipation rates are the power put in, `-F u`, less the rate of the
    /// stored energy, `∇stored · ṡ` (here by central differences along `ṡ`), at states on
    /// every branch of the hysteresis; and they are `>= 0`.
    #[test]
    fn dissipation_rates_are_the_power_less_the_storage_rate() {
        let law = Physical {
            k: 3e5,
            c: 60.0,
            n: 1.4,
            p: 1.6,
            alpha: 0.4,
            beta: 80.0,
            gamma: -30.0,
            a: 0.8,
        };
        fn check<L: ContactLaw<N>, const N: usize>(law: &L, s: State<N>, u: f64) {
            let (rate, f) = law.eval(&s, u);
            let h = 1e-7 / rate.norm().max(1e-300);
            let storage = (law.stored(&(s + rate * h)) - law.stored(&(s - rate * h))) / (2.0 * h);
            let expected = -f * u - storage;
            let got = law.dissipation(&s, u, &rate, f);
            let scale = (f * u).abs();
            assert!(got >= 0.0, "{got}");
            assert!(
                (got - expected).abs() <= 1e-6 * scale,
                "{got} vs {expected} ({scale})"
            );
        }
        let shccl = Bwshccl::new(&PhysicalParams::new(ModelKind::Shccm, law).unwrap()).unwrap();
        let mcl = Bwmcl::new(&PhysicalParams::new(ModelKind::Mcm, law).unwrap()).unwrap();
        for (x, z) in [(-1e-3, -8e-4), (-1e-3, 5e-4), (2e-4, -3e-4)] {
            for u in [-0.7, 0.4] {
                check(&shccl, State::<2>::new(x, z), u);
                check(&mcl, State::<3>::new(1e-4, x, z), u);
            }
        }
    }

    #[test]
    fn jacobians_of_the_laws_match_closed_forms() {
        // BWSHCCL with n = p = 1 away from its kinks (x, z < 0, u < 0, loading γ = -β):
        // F = -α k x - (1-α) k z - c |x| u, ż = A u.
        let law = Physical {
            k: 2e5,
            c: 40.0,
            n: 1.0,
            p: 1.0,
            alpha: 0.3,
            beta: 50.0,
            gamma: -50.0,
            a: 1.0,
        };
        let shccl = Bwshccl::new(&PhysicalParams::new(ModelKind::Shccm, law).unwrap()).unwrap();
        let (s, u) = (State::<2>::new(-1e-3, -8e-4), -0.7);
        let j = ContactLaw::jacobian(&shccl, &s, u);
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-6 * b.abs().max(1.0);
        // ∂F/∂x = -α k + c u (|x| = -x), ∂F/∂z = -(1-α) k, ∂F/∂u = -c |x|.
        assert!(
            close(j.force_state[0], -0.3 * 2e5 + 40.0 * u),
            "{:?}",
            j.force_state
        );
        assert!(close(j.force_state[1], -0.7 * 2e5));
        assert!(close(j.force_input, -40.0 * 1e-3), "{}", j.force_input);
        assert!(close(j.rate_input[0], 1.0) && close(j.rate_input[1], 1.0));
        assert_eq!(ContactLaw::kinks(&shccl, &s, u), [u, s[1]]);
        assert_eq!(ContactLaw::onset(&shccl), State::<2>::zeros());
        // BWMCL: F = -c ṙ, ẏ = u - ṙ; its rate kink is ẏ.
        let mcl = Bwmcl::new(&PhysicalParams::new(ModelKind::Mcm, law).unwrap()).unwrap();
        let s3 = State::<3>::new(0.0, -1e-3, -8e-4);
        let (rate, _) = ContactLaw::eval(&mcl, &s3, u);
        assert_eq!(ContactLaw::kinks(&mcl, &s3, u), [rate[1], s3[2]]);
        let j3 = ContactLaw::jacobian(&mcl, &s3, u);
        // ∂F/∂y = -α k (p = 1), ∂ẏ/∂u = 1.
        assert!(close(j3.force_state[1], -0.3 * 2e5) && close(j3.rate_input[1], 1.0));
    }

    #[test]
    fn hysteresis_skips_the_power_only_where_its_factor_vanishes() {
        let (beta, gamma, zn) = (7.3, -7.3, 0.37);
        let direct = |z: f64, w: f64| -> f64 {
            let sz = z.signum();
            w - beta * zn * sz * w.abs() - gamma * zn * w
        };
        for (z, w) in [
            (-0.4, -1.2),
            (0.4, 1.2),
            (-0.4, 1.2),
            (0.4, -1.2),
            (0.0, 0.3),
        ] {
            let mut called = false;
            let got = hysteresis(1.0, beta, gamma, z, w, || {
                called = true;
                zn
            });
            assert!(
                (got - direct(z, w)).abs() <= 1e-15 * direct(z, w).abs(),
                "{z} {w}"
            );
            // Loading (sgn z = sgn w, with sgn(+0) = 1) with γ = -β: the bracket is exactly 0.
            let loading = z.signum() == w.signum();
            assert_eq!(called, !loading, "z {z} w {w}");
        }
    }
}
