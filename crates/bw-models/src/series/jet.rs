//! The jets of the series path: Taylor coefficients of the solution of each nondimensional model
//! about the start of a step, in time or in logarithmic time ([`Clock`]), by the recurrences of
//! the powers and Cauchy products.

use super::{crossing, ORDER};
use crate::impact::Settings;
use crate::input::Input;
use crate::models::{CollisionModel, NdCoefficients, Ndbwmcm, Ndbwshccm};
use crate::power::Pow;
use crate::State;

/// Taylor coefficients `c_0 ..= c_ORDER` of one function about the start of a step.
pub(crate) type Series = [f64; ORDER + 1];

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

/// `1/k` for `k = 0 ..= ORDER + 1` (`INVERSE[0]` unused): the recurrences multiply by it, off the
/// critical path, rather than divide on it.
const INVERSE: [f64; ORDER + 2] = {
    let mut t = [0.0; ORDER + 2];
    let mut k = 1;
    while k < ORDER + 2 {
        t[k] = 1.0 / k as f64;
        k += 1;
    }
    t
};

/// `Σ_j p_j q_j` over the common length, in four lanes.
#[inline(always)]
fn dot(p: &[f64], q: &[f64]) -> f64 {
    let n = p.len().min(q.len());
    let (p, q) = (p[..n].chunks_exact(4), q[..n].chunks_exact(4));
    let tail: f64 = p
        .remainder()
        .iter()
        .zip(q.remainder())
        .map(|(a, b)| a * b)
        .sum();
    let mut acc = [0.0; 4];
    for (a, b) in p.zip(q) {
        for l in 0..4 {
            acc[l] += a[l] * b[l];
        }
    }
    (acc[0] + acc[1]) + (acc[2] + acc[3]) + tail
}

/// `(Σ_j a_j q_j, Σ_j b_j q_j)` over the common length of `a`, `b` (equal) and `q`, in four
/// lanes: two convolutions with one pass over `q`.
#[inline(always)]
pub(super) fn dot2(a: &[f64], b: &[f64], q: &[f64]) -> (f64, f64) {
    let n = a.len().min(q.len());
    let (a, b, q) = (
        a[..n].chunks_exact(4),
        b[..n].chunks_exact(4),
        q[..n].chunks_exact(4),
    );
    let (mut tx, mut ty) = (0.0, 0.0);
    for ((x, y), z) in a.remainder().iter().zip(b.remainder()).zip(q.remainder()) {
        tx += x * z;
        ty += y * z;
    }
    let (mut x, mut y) = ([0.0; 4], [0.0; 4]);
    for ((ca, cb), cq) in a.zip(b).zip(q) {
        for l in 0..4 {
            x[l] += ca[l] * cq[l];
            y[l] += cb[l] * cq[l];
        }
    }
    (
        (x[0] + x[1]) + (x[2] + x[3]) + tx,
        (y[0] + y[1]) + (y[2] + y[3]) + ty,
    )
}

/// Coefficient `j` of `Δ e^σ w` from the reversed clock of [`Jet::set_log_clock`].
#[inline(always)]
fn clocked(w: &Series, clock: &Series, j: usize) -> f64 {
    // The last term reads the coefficient computed last: it comes last, so that the sum of the
    // others need not wait for it.
    dot(&w[..j], &clock[ORDER - j..ORDER]) + w[j] * clock[ORDER]
}

/// The base `b` of a power: its coefficients, the coefficients times their index, and `1/b_0`.
pub(super) struct Base {
    pub(super) c: Series,
    kc: Series,
    inverse: f64,
}

impl Base {
    pub(super) const ZERO: Self = Self {
        c: [0.0; ORDER + 1],
        kc: [0.0; ORDER + 1],
        inverse: 0.0,
    };

    #[inline(always)]
    pub(super) fn set(&mut self, k: usize, v: f64) {
        self.c[k] = v;
        self.kc[k] = k as f64 * v;
        if k == 0 {
            self.inverse = 1.0 / v;
        }
    }
}

/// A power `y = b^e` of a base, stored in reverse (`r[ORDER - k] = y_k`) so that the
/// convolutions of the recurrence, `Σ_m w_m y_{k-m}`, are forward dot products.
pub(super) struct Power {
    r: Series,
}

impl Power {
    pub(super) const ZERO: Self = Self {
        r: [0.0; ORDER + 1],
    };

    #[inline(always)]
    pub(super) fn set(&mut self, k: usize, v: f64) {
        self.r[ORDER - k] = v;
    }

    /// Coefficient `k >= 1` of `y = b^e` from `b_0 ..= b_k` and `y_0 .. y_{k-1}` (`b_0 > 0`):
    /// `k b_0 y_k = e Σ_{m=1..k} m b_m y_{k-m} - Σ_{m=1..k} b_m (k-m) y_{k-m}
    /// = (e + 1) A - k B` with `A = Σ m b_m y_{k-m}`, `B = Σ b_m y_{k-m}` (one pass).
    #[inline(always)]
    pub(super) fn term(&self, b: &Base, e: f64, k: usize) -> f64 {
        let w = ORDER + 1 - k;
        let (a, s) = dot2(&b.kc[1..=k], &b.c[1..=k], &self.r[w..]);
        ((e + 1.0) * a - k as f64 * s) * (INVERSE[k] * b.inverse)
    }

    /// Coefficient `k` of the product of this power and the series `w`.
    #[inline(always)]
    pub(super) fn times(&self, w: &Series, k: usize) -> f64 {
        dot(&w[..=k], &self.r[ORDER - k..])
    }
}

/// Order by order, the powers of an expansion: `|D|^p` of the displacement `D` (`X` or `Y`),
/// `|Z|^p` (that of `D` while `Z = D`) and `|Z|^n` (only where the hysteresis needs it).
struct JetPowers<'a> {
    p: Pow,
    n: Pow,
    /// `Z = D` and stays so (loading with `Γ = -B` from contact).
    shared: bool,
    /// The hysteresis bracket is nonzero in this branch: `|Z|^n` is needed.
    hysteretic: bool,
    bases: &'a mut [Base; 2],
    powers: &'a mut [Power; 3],
}

impl<'a> JetPowers<'a> {
    /// The powers of the model with coefficients `k` in the branch with hysteresis bracket
    /// factor `c`, in the scratch `bases` and `powers`.
    fn new(
        k: &NdCoefficients,
        shared: bool,
        c: f64,
        bases: &'a mut [Base; 2],
        powers: &'a mut [Power; 3],
    ) -> Self {
        Self {
            p: k.p,
            n: k.n,
            shared,
            hysteretic: c != 0.0,
            bases,
            powers,
        }
    }

    /// Coefficient 0 of `|D|^p` and `|Z|^p` (and of `|Z|^n` where the hysteresis needs it) from
    /// `|D|` and `|Z|` at the step's start.
    #[inline(always)]
    fn start(&mut self, d0: f64, z0: f64) -> (f64, f64) {
        let [d, z] = &mut *self.bases;
        let [dp, zp, zn] = &mut *self.powers;
        d.set(0, d0);
        let dp0 = self.p.of_abs(d0);
        dp.set(0, dp0);
        let zp0 = if self.shared {
            dp0
        } else {
            z.set(0, z0);
            if self.hysteretic {
                // |Z|^n and |Z|^p of one base share its logarithm.
                let mut powers = crate::power::Powers::of(z0);
                zn.set(0, powers.get(self.n));
                powers.get(self.p)
            } else {
                self.p.of_abs(z0)
            }
        };
        zp.set(0, zp0);
        (dp0, zp0)
    }

    /// Order `j >= 1`: coefficient `j` of `|D|^p` and `|Z|^p` from coefficient `j` of `|D|` and
    /// `|Z|`, and of the products `|D|^p w` and `|Z|^n w`, as `[|D|^p, |Z|^p, |D|^p w, |Z|^n w]`,
    /// with all the sums of the recurrences and the products in one pass over `m = 1 ..= j`
    /// (`Σ_m y_(j-m) w_m`; the term `y_j w_0` is added after). `OWN_Z`: `Z != D` (else
    /// `|Z|^p = |D|^p`); `HYSTERETIC`: `|Z|^n` is needed (only with `OWN_Z`; else its
    /// product is 0).
    #[inline(always)]
    fn order<const OWN_Z: bool, const HYSTERETIC: bool>(
        &mut self,
        j: usize,
        d_j: f64,
        z_j: f64,
        w: &Series,
    ) -> [f64; 4] {
        let [d, z] = &mut *self.bases;
        let [dp, zp, zn] = &mut *self.powers;
        d.set(j, d_j);
        if OWN_Z {
            z.set(j, z_j);
        }
        let at = ORDER + 1 - j;
        let (kd, cd, kz, cz) = (&d.kc[1..=j], &d.c[1..=j], &z.kc[1..=j], &z.c[1..=j]);
        let (yd, yn, yp) = (&dp.r[at..=ORDER], &zn.r[at..=ORDER], &zp.r[at..=ORDER]);
        let wm = &w[1..=j];
        let mut acc = [0.0; 8];
        macro_rules! add {
            ($m:expr) => {{
                let m = $m;
                acc[0] += kd[m] * yd[m];
                acc[1] += cd[m] * yd[m];
                if HYSTERETIC {
                    acc[2] += kz[m] * yn[m];
                    acc[3] += cz[m] * yn[m];
                }
                if OWN_Z {
                    acc[4] += kz[m] * yp[m];
                    acc[5] += cz[m] * yp[m];
                }
                acc[6] += yd[m] * wm[m];
                if HYSTERETIC {
                    acc[7] += yn[m] * wm[m];
                }
            }};
        }
        // The terms m = 0 (with y_(j-1)) and m = j - 1 (with b_j, w_j) read the coefficients
        // computed last: they come last, so that the sums need not wait for them until the end.
        for m in 1..j.saturating_sub(1) {
            add!(m);
        }
        if j > 1 {
            add!(j - 1);
        }
        add!(0);
        let (jf, p) = (j as f64, self.p.exponent());
        let (scale_d, scale_z) = (INVERSE[j] * d.inverse, INVERSE[j] * z.inverse);
        let dpj = ((p + 1.0) * acc[0] - jf * acc[1]) * scale_d;
        dp.set(j, dpj);
        let zpj = if OWN_Z {
            ((p + 1.0) * acc[4] - jf * acc[5]) * scale_z
        } else {
            dpj
        };
        zp.set(j, zpj);
        let znw = if HYSTERETIC {
            let znj = ((self.n.exponent() + 1.0) * acc[2] - jf * acc[3]) * scale_z;
            zn.set(j, znj);
            acc[7] + znj * w[0]
        } else {
            0.0
        };
        [dpj, zpj, acc[6] + dpj * w[0], znw]
    }

    /// [`JetPowers::order`] in this expansion's branch (`z_j` unused while `Z = D`).
    #[inline(always)]
    fn order_in_branch(&mut self, j: usize, d_j: f64, z_j: f64, w: &Series) -> [f64; 4] {
        if self.shared {
            self.order::<false, false>(j, d_j, 0.0, w)
        } else if self.hysteretic {
            self.order::<true, true>(j, d_j, z_j, w)
        } else {
            self.order::<true, false>(j, d_j, z_j, w)
        }
    }

    /// Coefficient 0 of `|Z|^n`.
    #[inline(always)]
    fn hysteresis_leading(&self) -> f64 {
        self.powers[2].r[ORDER]
    }
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
        let tol = super::START_TOLERANCE * super::step_tolerance(&self.initial_state(), settings);
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

    /// Coefficients of `(1 + s)^e` by the binomial series.
    fn binomial(e: f64) -> Series {
        let mut c = [0.0; ORDER + 1];
        c[0] = 1.0;
        for k in 1..=ORDER {
            c[k] = c[k - 1] * (e - (k - 1) as f64) / k as f64;
        }
        c
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

    #[test]
    fn power_recurrence_gives_the_binomial_series() {
        let mut b = Base::ZERO;
        b.set(0, 1.0);
        b.set(1, 1.0);
        for e in [1.0, 1.75, 2.62, 2.93, 0.5] {
            let want = binomial(e);
            let mut y = Power::ZERO;
            y.set(0, 1.0);
            for (k, wk) in want.iter().enumerate().skip(1) {
                let yk = y.term(&b, e, k);
                y.set(k, yk);
                assert!((yk - wk).abs() <= 1e-14 * wk.abs().max(1e-3), "e {e} k {k}");
            }
            // (1 + s)^e (1 - s): coefficient k is want_k - want_{k-1}.
            let mut w = [0.0; ORDER + 1];
            (w[0], w[1]) = (1.0, -1.0);
            for (k, pair) in want.windows(2).enumerate() {
                let k = k + 1;
                let got = y.times(&w, k);
                let exact = pair[1] - pair[0];
                assert!(
                    (got - exact).abs() <= 1e-14 * exact.abs().max(1e-3),
                    "e {e} k {k}"
                );
            }
        }
        // The fused pass of the hysteretic branch: |D|^p, |Z|^n, |Z|^p of D = Z = 1 + s are
        // binomial series, and the products with w = (1, -1) are their differences.
        let (p, n) = (2.62, 2.93);
        let (bp, bn) = (binomial(p), binomial(n));
        let (mut bases, mut powers) = (
            [Base::ZERO, Base::ZERO],
            [Power::ZERO, Power::ZERO, Power::ZERO],
        );
        let mut pw = JetPowers {
            p: Pow::new(p),
            n: Pow::new(n),
            shared: false,
            hysteretic: true,
            bases: &mut bases,
            powers: &mut powers,
        };
        let mut w = [0.0; ORDER + 1];
        (w[0], w[1]) = (1.0, -1.0);
        assert_eq!(pw.start(1.0, 1.0), (1.0, 1.0));
        for k in 1..=ORDER {
            let d_k = if k == 1 { 1.0 } else { 0.0 };
            let [dp, zp, dpw, znw] = pw.order::<true, true>(k, d_k, d_k, &w);
            let close = |got: f64, want: f64| (got - want).abs() <= 1e-14 * want.abs().max(1e-3);
            assert!(close(dp, bp[k]) && close(zp, bp[k]), "k {k}");
            assert!(close(dpw, bp[k] - bp[k - 1]), "k {k}");
            assert!(close(znw, bn[k] - bn[k - 1]), "k {k}");
        }
    }
}
