//! A CoR without time steps: the NDBWSHCCM with no input on the branch `Γ = -B`, reduced to
//! quadratures in phase space.
//!
//! Without an input the clock enters the NDBWSHCCM only through `d/dT`, and on each branch of
//! the hysteresis (fixed signs of `V` and `Z`) the displacement is a function of `Z` alone:
//! `dZ/dX = h(Z) = 1 - |Z|^n (B sgn(V Z) + Γ)`. With `W = V^2 / 2` and `dW/dX = F`, a CoR is
//! then two integrals over the bounded phase variables, not a run in time:
//!
//! * **Loading** (`V < 0`, `Z = X` since `h = 1` when `Γ = -B`) is the Hunt-Crossley problem
//!   `V dV / (1 - σV) = |X|^p dX`, solved in closed form: with
//!   `φ(y) = (-ln(1 - y) - y) / y^2`, `∫_0^V v dv / (1 - σv) = V^2 φ(σV)`, so the maximum
//!   compression `u_m = |X_m|` has `u_m^(p+1) = (p + 1) φ(-σ)`. Its duration `∫ dV / F` is a
//!   quadrature in `ξ`, `V = -1 + ξ^(p+1)`, which takes out the contact's branch point.
//! * **Unloading with `Z < 0`** (`h = 1 + 2B |Z|^n`), in `θ ∈ [0, π/2]` with `-Z = u_m cos^2 θ`:
//!   `dX/dθ = u_m sin 2θ / h`, `dW/dθ = F dX/dθ`, `dT/dθ = (dX/dθ) / V`. The map takes out both
//!   the square-root branch of `V` at the maximum compression and the branch point of `|Z|^n`
//!   at the root of `Z`; the blow-ups of `Z(T)` in complex time that bound every series in `T`
//!   sit at `Z = ∞` here.
//! * **Unloading with `Z >= 0`** (`h = 1`, so `Z = X - X_0`), in `t` with `X = X_0 + t^2`, up
//!   to the separation `F = 0`. Without damping the separation is where
//!   `κ^(1/p) |X| = (1 - κ)^(1/p) Z`; damping only brings it earlier, so that point closes the
//!   panel.
//!
//! Each part is a Chebyshev interpolant on `N` points of the first kind per panel (`N` from 8
//! to 96, chosen from the tolerance; a check compares with the next `N`). The part with `Z < 0`
//! has two panels, split at the real part of the nearest root of `h`, the singularity that
//! bounds one interpolant's convergence there (one panel needs twice the points for the same
//! error). `X` is a plain quadrature; `W` depends on itself only through the damping term
//! `-σ |X|^p V dX`, and is found panel by panel by fixed-point (Picard) iteration from the
//! undamped solution.
//!
//! On the paper's DSS (1) fit this is 6.7-8.6 times faster than plain DOP853 at equal error in
//! `e` from 2e-5 to 4e-14 (BENCHMARKS.md, "Session 30").
//!
//! ```
//! use bw_models::phase::{self, PhaseSettings};
//! use bw_models::{ModelKind, Nondim, NondimParams};
//! // Hunt-Crossley (B = Γ = 0): e solves e^2 φ(σe) = φ(-σ); σ = 0.5 gives 0.7484...
//! let p = NondimParams::new(ModelKind::Shccm, Nondim { b: 0.0, gamma: 0.0, kappa: 0.5, sigma: 0.5, n: 1.0, p: 1.5 })?;
//! let cor = phase::cor(&p, &PhaseSettings { tol: 1e-12, ..PhaseSettings::default() })?;
//! assert!((cor.e - 0.748434931597434).abs() < 1e-12 && cor.tolerance_met == Some(true));
//! println!("e = {} ± {:?}, T_s = {:?}, {} points a panel", cor.e, cor.e_error, cor.t_s, cor.nodes);
//! # Ok::<(), bw_models::ModelError>(())
//! ```

use crate::power::{Pow, Powers};
use crate::{ModelError, ModelKind, Nondim, NondimParams};
use std::f64::consts::FRAC_PI_2;
use std::sync::OnceLock;

/// The node counts tried, in order.
const RUNGS: [usize; 8] = [8, 12, 16, 24, 32, 48, 64, 96];
/// The largest node count: the size of every buffer.
const MAX_N: usize = 96;
/// Picard iterations allowed per part; each gains about `-log10(σ)` digits on the paper's fits.
const MAX_PICARD: usize = 80;

/// What [`cor`] computes, and how carefully.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PhaseSettings {
    /// The tolerance in `e` (absolute; `e` is at most 1).
    pub tol: f64,
    /// Whether to estimate the error: a second result on the next node count, reported with
    /// the change as its estimate, raising the count until the estimate meets `tol`. Without
    /// it one node count is chosen from `tol`, where it meets `tol` on the paper's DSS (1) fit
    /// at 0.5-5 m/s (like a Runge-Kutta run at `rtol`: no estimate of the error in `e`).
    pub check: bool,
    /// Whether to compute the separation time `T_s` too (the CoR alone needs no clock).
    pub duration: bool,
}

impl Default for PhaseSettings {
    /// `tol = 1e-10`, checked, with the duration.
    fn default() -> Self {
        PhaseSettings {
            tol: 1e-10,
            check: true,
            duration: true,
        }
    }
}

/// A CoR of the NDBWSHCCM computed in phase space (nondimensional: `V(0) = -1`, so `e` is
/// `V` at the separation, and `T_s` is in the model's time unit).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PhaseCor {
    /// Coefficient of restitution.
    pub e: f64,
    /// Separation time `T_s`, where [`PhaseSettings::duration`] asked for it.
    pub t_s: Option<f64>,
    /// Estimate of the error in `e` where [`PhaseSettings::check`] asked for it: the change
    /// from the previous node count (an estimate of that coarser result's error, so a generous
    /// one of this result's), plus what the fixed-point iteration for the damping left.
    pub e_error: Option<f64>,
    /// The same estimate for `t_s`.
    pub t_s_error: Option<f64>,
    /// Whether `e_error` met the tolerance (checked runs only); if not, `e` is the result at
    /// the largest node count.
    pub tolerance_met: Option<bool>,
    /// Chebyshev points per part of the reported result.
    pub nodes: usize,
}

/// The CoR of the NDBWSHCCM `params` with no input (the branch `Γ = -B`).
///
/// # Errors
/// [`ModelError::NotApplicable`] for the NDBWMCM, for `Γ != -B`, and where the fixed-point
/// iteration for the damping does not settle (large `σ`; the time-domain path
/// [`crate::impact`] serves every case). [`ModelError::InvalidSetting`] for `tol` not in
/// `(0, 1)`.
pub fn cor(params: &NondimParams, settings: &PhaseSettings) -> Result<PhaseCor, ModelError> {
    let tol = settings.tol;
    if !(tol > 0.0 && tol < 1.0) {
        return Err(ModelError::InvalidSetting {
            name: "tol",
            value: tol,
            allowed: "0 < tol < 1",
        });
    }
    if params.kind() != ModelKind::Shccm {
        return Err(not_applicable("the phase path covers the NDBWSHCCM only"));
    }
    let p = params.get();
    if p.gamma != -p.b {
        return Err(not_applicable("the phase path needs Gamma = -B"));
    }
    let k = Coefficients::new(p, tol, settings.duration);
    let first = RUNGS.iter().position(|&n| n >= nodes_for(tol)).unwrap_or(0);
    let (e, t_s, _) = k.solve(rung(RUNGS[first]))?;
    let mut out = PhaseCor {
        e,
        t_s,
        e_error: None,
        t_s_error: None,
        tolerance_met: None,
        nodes: RUNGS[first],
    };
    if !settings.check {
        return Ok(out);
    }
    for &n in &RUNGS[first + 1..] {
        let (e, t_s, residual) = k.solve(rung(n))?;
        let e_error = (e - out.e).abs() + residual;
        out = PhaseCor {
            e,
            t_s,
            e_error: Some(e_error),
            t_s_error: t_s.zip(out.t_s).map(|(a, b)| (a - b).abs()),
            tolerance_met: Some(e_error <= tol),
            nodes: n,
        };
        if e_error <= tol {
            break;
        }
    }
    Ok(out)
}

fn not_applicable(reason: &'static str) -> ModelError {
    ModelError::NotApplicable { reason }
}

/// The node count per panel where the paper's DSS (1) fit at 0.5-5 m/s is within `tol` in `e`
/// (largest errors over the speeds: 2e-5 at 8 nodes, 3e-7 at 12, 2e-8 at 16, 6e-11 at 24,
/// the reference's 2e-13 at 32), so that a check's next count usually meets `tol` at once.
fn nodes_for(tol: f64) -> usize {
    match tol {
        t if t >= 3e-5 => 8,
        t if t >= 5e-7 => 12,
        t if t >= 3e-8 => 16,
        t if t >= 1e-10 => 24,
        t if t >= 1e-13 => 32,
        _ => 48,
    }
}

/// `φ(y) = (-ln(1 - y) - y) / y^2 = Σ_{k>=2} y^(k-2) / k`, by its series near 0 where the
/// closed form cancels.
fn phi(y: f64) -> f64 {
    if y.abs() < 0.1 {
        (2..20).rev().fold(0.0, |acc, k| acc * y + 1.0 / k as f64)
    } else {
        (-(-y).ln_1p() - y) / (y * y)
    }
}

/// The model's parameters and the closed-form loading.
struct Coefficients {
    /// Whether `T` is wanted.
    duration: bool,
    b: f64,
    kappa: f64,
    sigma: f64,
    n: Pow,
    p: Pow,
    /// `|X_m|` at the maximum compression.
    u_m: f64,
    /// Where the Picard iteration stops: its change at most this.
    settle: f64,
}

/// What each part hands on.
struct Part {
    /// `X`, `W`, `T` and `F` at the part's end.
    x: f64,
    w: f64,
    t: f64,
    f: f64,
    /// `W` and `T` at the separation, where it came within the part.
    separated: Option<(f64, f64)>,
    /// The Picard iterations' last changes in `W` so far, summed.
    residual: f64,
}

impl Coefficients {
    fn new(nd: &Nondim, tol: f64, duration: bool) -> Self {
        let p = nd.p;
        let u_m = ((p + 1.0) * phi(-nd.sigma)).powf(1.0 / (p + 1.0));
        Coefficients {
            duration,
            b: nd.b,
            kappa: nd.kappa,
            sigma: nd.sigma,
            n: Pow::new(nd.n),
            p: Pow::new(p),
            u_m,
            settle: (0.1 * tol).max(1e-17),
        }
    }

    /// The force `F` at `X`, `Z` and `V`.
    fn force(&self, x: f64, z: f64, v: f64) -> f64 {
        let xp = self.p.of_abs(x.abs());
        -self.kappa * xp.copysign(x) - (1.0 - self.kappa) * self.p.signed(z) - self.sigma * xp * v
    }

    /// `e`, `T_s` and the Picard iterations' residual in `e` on `r`'s nodes.
    fn solve(&self, r: &Rung) -> Result<(f64, Option<f64>, f64), ModelError> {
        let t_c = if self.duration {
            self.loading_time(r)
        } else {
            0.0
        };
        let one = self.unloading_before_root(r, t_c)?;
        let (w_s, t_s, residual) = match one.separated {
            Some((w, t)) => (w, t, one.residual),
            None => self.unloading_after_root(r, &one)?,
        };
        let e = (2.0 * w_s.max(0.0)).sqrt();
        // `de = dW / e`.
        let residual = residual / e.max(f64::MIN_POSITIVE);
        Ok((e, self.duration.then_some(t_s), residual))
    }

    /// `T` at the maximum compression: `∫ dV / F` over `V = -1 + ξ^(p+1)`, `ξ ∈ [0, 1]`.
    fn loading_time(&self, r: &Rung) -> f64 {
        let p = self.p.exponent();
        let (s, q) = (self.sigma, p + 1.0);
        let c_p = (q / (1.0 + s)).powf(p / q);
        let pow_q = Pow::new(q);
        let mut f = [0.0; MAX_N];
        for (fk, &x) in f.iter_mut().zip(&r.x) {
            let delta = pow_q.of_abs(0.5 * (x + 1.0));
            let d = delta / (1.0 + s);
            let shrink = (1.0 - d * phi(s * d)).powf(p / q);
            *fk = q / (c_p * shrink * (1.0 + s - s * delta));
        }
        0.5 * r.total(&f[..r.n])
    }

    /// The part with `Z < 0`, in `θ` with `-Z = u_m cos^2 θ`, from the maximum compression, in
    /// two panels split at `θ_split`.
    fn unloading_before_root(&self, r: &Rung, t0: f64) -> Result<Part, ModelError> {
        let split = self.theta_split();
        let start = Part {
            x: -self.u_m,
            w: 0.0,
            t: t0,
            f: self.force(-self.u_m, -self.u_m, 0.0),
            separated: None,
            residual: 0.0,
        };
        let first = self.theta_panel(r, (0.0, split), &start)?;
        if first.separated.is_some() {
            return Ok(first);
        }
        self.theta_panel(r, (split, FRAC_PI_2), &first)
    }

    /// Where the first panel in `θ` ends: at the real part of the nearest root of
    /// `h = 1 + 2B u^n` (`u = (2B)^(-1/n) e^(±iπ/n)`), which bounds the convergence of one
    /// interpolant over the whole part; at `π/4` where `h` has no roots (`B = 0`).
    fn theta_split(&self) -> f64 {
        if self.b == 0.0 {
            return 0.5 * FRAC_PI_2;
        }
        let n = self.n.exponent();
        // cos θ = (|u| / u_m)^(1/2) e^(±iπ/(2n)); θ's real part by `acos` of the modulus, a
        // fair stand-in for the split.
        let modulus = ((2.0 * self.b).powf(-1.0 / n) / self.u_m).sqrt();
        let real = modulus * (std::f64::consts::PI / (2.0 * n)).cos();
        real.clamp(0.2, 0.98).acos().clamp(0.3, FRAC_PI_2 - 0.2)
    }

    /// One panel `θ ∈ [a, b]` of the part with `Z < 0`, from the state `from`.
    fn theta_panel(&self, r: &Rung, (a, b): (f64, f64), from: &Part) -> Result<Part, ModelError> {
        let (n, half) = (r.n, 0.5 * (b - a));
        let (mut dx, mut f0, mut g) = ([0.0; MAX_N], [0.0; MAX_N], [0.0; MAX_N]);
        let mut up = [0.0; MAX_N];
        for k in 0..n {
            let th = a + half * (r.x[k] + 1.0);
            let (s, c) = th.sin_cos();
            let u = self.u_m * c * c;
            let mut pw = Powers::of(u);
            dx[k] = self.u_m * 2.0 * s * c / (1.0 + 2.0 * self.b * pw.get(self.n));
            up[k] = pw.get(self.p);
        }
        let mut x = [0.0; MAX_N];
        r.cumulative(&dx[..n], half, &mut x[..n]);
        for k in 0..n {
            x[k] += from.x;
            let xp = self.p.of_abs(x[k].abs());
            f0[k] = (-self.kappa * xp.copysign(x[k]) + (1.0 - self.kappa) * up[k]) * dx[k];
            g[k] = self.sigma * xp * dx[k];
        }
        let (mut w, mut w_rhs) = ([0.0; MAX_N], [0.0; MAX_N]);
        let (w0, settle) = (from.w, self.settle);
        let change = picard(
            r,
            half,
            (w0, settle),
            (&f0[..n], &g[..n]),
            &mut w[..n],
            &mut w_rhs[..n],
        )?;
        let (mut dt, mut force) = ([0.0; MAX_N], [0.0; MAX_N]);
        for k in 0..n {
            let v = (2.0 * w[k]).max(0.0).sqrt();
            dt[k] = if self.duration { dx[k] / v } else { 0.0 };
            force[k] = (f0[k] - g[k] * v) / dx[k];
        }
        let x_end = from.x + r.total(&dx[..n]) * half;
        let w_end = from.w + r.total(&w_rhs[..n]) * half;
        let u_end = self.u_m * b.cos().powi(2);
        let f_end = self.force(x_end, -u_end, (2.0 * w_end).max(0.0).sqrt());
        let quadratures = Quadratures {
            r,
            half,
            w0: from.w,
            t0: from.t,
            w_rhs: &w_rhs[..n],
            dt: &dt[..n],
        };
        // Damping strong enough to part the bodies before `Z` returns to 0.
        let separated = (f_end <= 0.0).then(|| quadratures.at_root(&force[..n], from.f, f_end));
        Ok(Part {
            x: x_end,
            w: w_end,
            t: from.t + r.total(&dt[..n]) * half,
            f: f_end,
            separated,
            residual: from.residual + change,
        })
    }

    /// The part with `Z >= 0`, in `t` with `X = X_0 + t^2`, up to the separation.
    /// Returns `W`, `T` and the Picard residual at the separation.
    fn unloading_after_root(&self, r: &Rung, one: &Part) -> Result<(f64, f64, f64), ModelError> {
        let (n, x0) = (r.n, one.x);
        let (ka, kb) = (
            self.kappa.powf(1.0 / self.p.exponent()),
            (1.0 - self.kappa).powf(1.0 / self.p.exponent()),
        );
        let x_end = kb * x0 / (ka + kb);
        let xp_end = self.p.of_abs(x_end.abs());
        let t_end = (x_end - x0).max(0.0).sqrt();
        let half = 0.5 * t_end;
        let (mut fe, mut f0, mut g, mut xp) =
            ([0.0; MAX_N], [0.0; MAX_N], [0.0; MAX_N], [0.0; MAX_N]);
        for k in 0..n {
            let t = half * (r.x[k] + 1.0);
            let x = x0 + t * t;
            xp[k] = self.p.of_abs(x.abs());
            fe[k] = -self.kappa * xp[k].copysign(x) - (1.0 - self.kappa) * self.p.of_abs(t * t);
            f0[k] = 2.0 * t * fe[k];
            g[k] = 2.0 * t * self.sigma * xp[k];
        }
        let (mut w, mut w_rhs) = ([0.0; MAX_N], [0.0; MAX_N]);
        let (w0, settle) = (one.w, self.settle);
        let change = picard(
            r,
            half,
            (w0, settle),
            (&f0[..n], &g[..n]),
            &mut w[..n],
            &mut w_rhs[..n],
        )?;
        let (mut force, mut dt) = ([0.0; MAX_N], [0.0; MAX_N]);
        for k in 0..n {
            let v = (2.0 * w[k]).sqrt();
            force[k] = fe[k] - self.sigma * xp[k] * v;
            if self.duration {
                dt[k] = 2.0 * half * (r.x[k] + 1.0) / v;
            }
        }
        let quadratures = Quadratures {
            r,
            half,
            w0: one.w,
            t0: one.t,
            w_rhs: &w_rhs[..n],
            dt: &dt[..n],
        };
        // At the panel's end only the damping term is left, `F <= 0`.
        let v_end = (2.0 * (one.w + r.total(&w_rhs[..n]) * half))
            .max(0.0)
            .sqrt();
        let f_end = -self.sigma * xp_end * v_end;
        let (w_s, t_s) = quadratures.at_root(&force[..n], one.f, f_end);
        Ok((w_s, t_s, one.residual + change))
    }
}

/// A part's integrands of `W` and `T` on its nodes, to be read at the separation (the
/// integrand of `T` is zero where the duration is not wanted).
struct Quadratures<'a> {
    r: &'a Rung,
    half: f64,
    w0: f64,
    t0: f64,
    w_rhs: &'a [f64],
    dt: &'a [f64],
}

impl Quadratures<'_> {
    /// `W` and `T` at the root of the interpolant of `F` (`force` on the nodes) between the
    /// part's start (`f_start > 0`) and its end (`f_end <= 0`).
    fn at_root(&self, force: &[f64], f_start: f64, f_end: f64) -> (f64, f64) {
        let (r, n) = (self.r, self.r.n);
        if f_end == 0.0 {
            return (
                self.w0 + r.total(self.w_rhs) * self.half,
                self.t0 + r.total(self.dt) * self.half,
            );
        }
        let fc = r.coefficients(force);
        let s_r = root(&fc[..n], f_start, f_end);
        (
            self.w0 + self.half * r.integral_to(self.w_rhs, s_r),
            self.t0 + self.half * r.integral_to(self.dt, s_r),
        )
    }
}

/// `W = w0 + ∫ (f0 - g sqrt(2W))` on the rung's nodes by fixed-point iteration from `g = 0`,
/// into `w`, with its integrand into `rhs`; returns the last change (the iteration contracts
/// by about `σ |X|^p T`, a few hundredths on the paper's fits, so this bounds what is left).
fn picard(
    r: &Rung,
    half: f64,
    (w0, settle): (f64, f64),
    (f0, g): (&[f64], &[f64]),
    w: &mut [f64],
    rhs: &mut [f64],
) -> Result<f64, ModelError> {
    let mut next = [0.0; MAX_N];
    let next = &mut next[..r.n];
    r.cumulative(f0, half, w);
    w.iter_mut().for_each(|wk| *wk += w0);
    for _ in 0..MAX_PICARD {
        for (((rk, &fk), &gk), &wk) in rhs.iter_mut().zip(f0).zip(g).zip(w.iter()) {
            *rk = fk - gk * (2.0 * wk).max(0.0).sqrt();
        }
        r.cumulative(rhs, half, next);
        let (mut change, mut size) = (0.0f64, 0.0f64);
        for (wk, &nk) in w.iter_mut().zip(next.iter()) {
            let updated = w0 + nk;
            change = change.max((updated - *wk).abs());
            size = size.max(updated.abs());
            *wk = updated;
        }
        // Below a few roundings of `W` the iteration only moves the last bits.
        if change <= settle.max(8.0 * f64::EPSILON * size) {
            return Ok(change);
        }
    }
    Err(not_applicable(
        "the damping's fixed-point iteration did not settle (sigma too large for the phase path)",
    ))
}

/// Chebyshev points of the first kind on `[-1, 1]` and the matrices that act on values there.
struct Rung {
    n: usize,
    /// The points, increasing.
    x: Vec<f64>,
    /// Values to Chebyshev coefficients, column-major `n x n`.
    coef: Vec<f64>,
    /// Values to the integral from -1 at each point, column-major.
    int: Vec<f64>,
    /// Values to the integral over `[-1, 1]`.
    total: Vec<f64>,
}

fn rung(n: usize) -> &'static Rung {
    static RUNG_TABLES: [OnceLock<Rung>; RUNGS.len()] = [const { OnceLock::new() }; RUNGS.len()];
    let i = RUNGS.iter().position(|&m| m == n).expect("n is a rung");
    RUNG_TABLES[i].get_or_init(|| Rung::new(n))
}

impl Rung {
    fn new(n: usize) -> Self {
        let nf = n as f64;
        let angle = |k: usize| std::f64::consts::PI * (1.0 - (k as f64 + 0.5) / nf);
        let x: Vec<f64> = (0..n).map(|k| angle(k).cos()).collect();
        // Column-major: column `k` holds what the value at node `k` adds to each coefficient.
        let mut coef = vec![0.0; n * n];
        for j in 0..n {
            let scale = if j == 0 { 1.0 / nf } else { 2.0 / nf };
            for k in 0..n {
                coef[k * n + j] = scale * (j as f64 * angle(k)).cos();
            }
        }
        // The antiderivative of T_j that vanishes at -1, at `x = cos a`.
        let anti = |j: usize, a: f64| -> f64 {
            let t = |m: usize, a: f64| (m as f64 * a).cos();
            let raw = |a: f64| match j {
                0 => t(1, a),
                1 => 0.25 * t(2, a),
                _ => t(j + 1, a) / (2.0 * (j + 1) as f64) - t(j - 1, a) / (2.0 * (j - 1) as f64),
            };
            raw(a) - raw(std::f64::consts::PI)
        };
        let at_nodes: Vec<f64> = (0..n * n).map(|i| anti(i / n, angle(i % n))).collect();
        // Column-major: column `m` holds the weights of the value at node `m`.
        let mut int = vec![0.0; n * n];
        let mut total = vec![0.0; n];
        for m in 0..n {
            for j in 0..n {
                let c = coef[m * n + j];
                total[m] += anti(j, 0.0) * c;
                for k in 0..n {
                    int[m * n + k] += at_nodes[j * n + k] * c;
                }
            }
        }
        Rung {
            n,
            x,
            coef,
            int,
            total,
        }
    }

    /// `∫_{-1}^{x_k} f`, times `scale` (the half-width of the panel), into `out`.
    fn cumulative(&self, f: &[f64], scale: f64, out: &mut [f64]) {
        // Column by column: each pass is a vectorised `out += f_m column_m`.
        out.iter_mut().for_each(|o| *o = 0.0);
        for (column, &fm) in self.int.chunks_exact(self.n).zip(f) {
            for (o, &a) in out.iter_mut().zip(column) {
                *o += a * fm;
            }
        }
        out.iter_mut().for_each(|o| *o *= scale);
    }

    /// `∫_{-1}^{1} f`.
    fn total(&self, f: &[f64]) -> f64 {
        self.total.iter().zip(f).map(|(a, b)| a * b).sum()
    }

    /// `∫_{-1}^{s} f` through the interpolant's coefficients.
    fn integral_to(&self, f: &[f64], s: f64) -> f64 {
        let n = self.n;
        let c = self.coefficients(f);
        let mut ci = [0.0; MAX_N + 1];
        for j in 1..=n {
            let before = if j == 1 { 2.0 * c[0] } else { c[j - 1] };
            let after = if j + 1 < n { c[j + 1] } else { 0.0 };
            ci[j] = (before - after) / (2.0 * j as f64);
        }
        clenshaw(&ci[..=n], s) - clenshaw(&ci[..=n], -1.0)
    }

    fn coefficients(&self, f: &[f64]) -> [f64; MAX_N] {
        let mut c = [0.0; MAX_N];
        for (column, &fk) in self.coef.chunks_exact(self.n).zip(f) {
            for (cj, &a) in c[..self.n].iter_mut().zip(column) {
                *cj += a * fk;
            }
        }
        c
    }
}

/// The root in `[-1, 1]` of `Σ c_j T_j`, which is `f_lo > 0` at -1 and `f_hi <= 0` at 1: Newton
/// steps from the secant's guess, kept inside a shrinking bracket (bisection where a step
/// leaves it), to a change of `1e-15`.
fn root(c: &[f64], f_lo: f64, f_hi: f64) -> f64 {
    let (mut lo, mut hi) = (-1.0, 1.0);
    let mut s = -1.0 + 2.0 * f_lo / (f_lo - f_hi);
    for _ in 0..60 {
        let (f, df) = clenshaw_with_slope(c, s);
        if f > 0.0 {
            lo = s;
        } else {
            hi = s;
        }
        let newton = s - f / df;
        let next = if newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
        if (next - s).abs() <= 1e-15 || hi - lo <= 1e-15 {
            return next;
        }
        s = next;
    }
    s
}

/// `Σ c_j T_j(s)` and its derivative (`T_j' = j U_(j-1)`), by the three-term recurrences of
/// `T` and `U` (`U_(-1) = 0`, `U_0 = 1`).
fn clenshaw_with_slope(c: &[f64], s: f64) -> (f64, f64) {
    let (mut t0, mut t1) = (1.0, s);
    let (mut u0, mut u1) = (0.0, 1.0);
    let mut f = c[0] + c.get(1).map_or(0.0, |c1| c1 * s);
    let mut df = c.get(1).copied().unwrap_or(0.0);
    for (j, &cj) in c.iter().enumerate().skip(2) {
        let t2 = 2.0 * s * t1 - t0;
        let u2 = 2.0 * s * u1 - u0;
        f += cj * t2;
        df += cj * j as f64 * u2;
        (t0, t1, u0, u1) = (t1, t2, u1, u2);
    }
    (f, df)
}

/// `Σ c_j T_j(s)` by Clenshaw's recurrence.
fn clenshaw(c: &[f64], s: f64) -> f64 {
    let (mut b1, mut b2) = (0.0, 0.0);
    for &cj in c[1..].iter().rev() {
        let b0 = cj + 2.0 * s * b1 - b2;
        b2 = b1;
        b1 = b0;
    }
    c[0] + s * b1 - b2
}

#[cfg(test)]
mod tests;
