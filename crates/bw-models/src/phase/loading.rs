//! The loading, from contact to the maximum compression: in closed form for the NDBWSHCCM on
//! `Γ = -B` (Hunt-Crossley), searched otherwise.

use super::chebyshev::{picard, Rung, Start, MAX_N, RUNGS};
use super::{not_applicable, phi, Coefficients, Hysteretic, Loading};
use crate::power::{Pow, Powers};
use crate::{ModelError, ModelKind};
use std::f64::consts::FRAC_PI_4;
use std::sync::OnceLock;

/// Newton steps allowed for the search of the maximum compression (two or three on the
/// paper's fits, more where `σ` or `B + Γ` is large).
const MAX_NEWTON: usize = 12;
/// The largest `(B + Γ) |Z|^n` at the maximum compression the phase path takes: nearer the
/// saturation `dq/dZ = 1 / h` grows without bound and the loading in `Z` converges slowly.
const SATURATED: f64 = 0.5;
/// The same for the search's first guess, a little above [`SATURATED`] (the guess can be low).
const EARLY_SATURATED: f64 = 0.6;
/// Why a loading near saturation is declined.
const SATURATION: &str = "the loading nears the hysteresis' saturation, where Z is a poor variable (B + Gamma too large for the phase path)";

impl Coefficients {
    /// The NDBWSHCCM's loading in closed form, and its duration `∫ dV / F` over
    /// `V = -1 + ξ^(p+1)`, `ξ ∈ [0, 1]` (where `|X|^(p+1) = (p + 1) d (1 - d φ(σd))`,
    /// `d = (1 + V) / (1 + σ)`).
    pub(super) fn hunt_crossley(&self, r: &Rung) -> Loading {
        let p = self.p.exponent();
        let (s, q) = (self.sigma, p + 1.0);
        let u_m = (q * phi(-s)).powf(1.0 / q);
        let mut t = 0.0;
        if self.duration {
            let c_p = (q / (1.0 + s)).powf(p / q);
            let pow_q = Pow::new(q);
            let mut f = [0.0; MAX_N];
            for (fk, &x) in f.iter_mut().zip(&r.x) {
                let delta = pow_q.of_abs(0.5 * (x + 1.0));
                let d = delta / (1.0 + s);
                let shrink = (1.0 - d * phi(s * d)).powf(p / q);
                *fk = q / (c_p * shrink * (1.0 + s - s * delta));
            }
            t = 0.5 * r.total(&f[..r.n]);
        }
        Loading {
            u_m,
            q_m: -u_m,
            t,
            residual: 0.0,
        }
    }

    /// The loading on `u = -Z = u_m sin^4 φ`: `dq/du = -1 / h`, `dW/dq = F_el + c sqrt(2W)`
    /// from `W = 1/2`, with `u_m` moved by the steps of [`Slope::distance`] from
    /// [`Coefficients::first_guess`] until `W(u_m) = 0`.
    pub(super) fn searched_loading(&self, r: &Rung) -> Result<Loading, ModelError> {
        let n = r.n;
        let mut factors = LoadingFactors::default();
        let unit = unit_nodes(r);
        for k in 0..n {
            let mut pw = Powers::with_log2(unit.unit[k], unit.log2[k]);
            factors.unit_p[k] = pw.get(self.p);
            factors.unit_n[k] = if self.beta == 0.0 {
                0.0
            } else {
                pw.get(self.n)
            };
        }
        let saturation = match self.beta {
            0.0 => f64::INFINITY,
            beta => beta.powf(-1.0 / self.n.exponent()),
        };
        let mut u_m = self.first_guess().min(0.9 * saturation);
        // The guess is within a few per cent of `u_m` off saturation: decline a loading that
        // will end near it before the search spends its steps.
        if self.beta * self.n.of_abs(u_m) > EARLY_SATURATED {
            return Err(not_applicable(SATURATION));
        }
        // `W` starts at 1/2: a few of its roundings are as close to 0 as it gets. `T` needs
        // more: its integrand `1 / sqrt(2W)` turns a miss `δ` at the end into about `sqrt(δ)`;
        // the Newton steps converge quadratically, so that costs one step more.
        let miss = match self.duration {
            true => self.settle * self.settle,
            false => self.settle,
        }
        .max(4.0 * f64::EPSILON);
        let mut nodes = LoadingNodes::default();
        let mut last_step = f64::NAN;
        for _ in 0..MAX_NEWTON {
            let (w_end, slope, change) = nodes.solve(self, r, (u_m, miss), &factors)?;
            let mut end = Loading {
                u_m,
                q_m: nodes.q_end,
                t: 0.0,
                residual: change + w_end.abs(),
            };
            let step = slope.distance(w_end);
            // A step leaves about `K s^(5/2)` of its `s`; `K` from the last step's landing.
            // For `e` alone the last step needs no solve where that is well below `miss`: it
            // moves the end along `dq/du = -1/h` (its `s^2` term is below `miss` too).
            let left = slope.a * step.abs().powf(3.5) / last_step.abs().powf(2.5);
            let landed = !self.duration && step * step <= miss && left + change <= miss;
            if landed {
                let h_end = 1.0 - self.beta * self.n.of_abs(u_m);
                end.u_m += step;
                end.q_m -= step / h_end;
                end.residual = change + left;
            }
            if w_end.abs() <= miss || landed {
                if self.beta * self.n.of_abs(end.u_m) > SATURATED {
                    return Err(not_applicable(SATURATION));
                }
                if self.duration {
                    end.t = nodes.time(r);
                }
                return Ok(end);
            }
            u_m = (u_m + step).min(0.5 * (u_m + saturation));
            last_step = step;
        }
        Err(not_applicable(
            "the search for the maximum compression did not settle (sigma too large for the phase path)",
        ))
    }

    /// The search's first guess of `u_m`: `|q_m|` where `B + Γ = 0` (for the NDBWSHCCM
    /// Hunt-Crossley's, `|q_m|^(p+1) = (p + 1) φ(-σ)`; for the NDBWMCM
    /// [`Coefficients::mcm_compression`]), moved to first order in `β = B + Γ`. There
    /// `u = |q| - β |q|^(n+1) / (n + 1)`, so `F_el` is lower by `(1 - κ) p β |q|^(p+n) / (n + 1)`
    /// and the work to `x_0` by `δE = (1 - κ) p β x_0^(p+n+1) / ((n + 1)(p + n + 1))`: `|q_m|` is
    /// further by `δE / x_0^p`. On DSA (1)'s NDBWSHCCM this is 1.4e-4 off (5e-3 without the
    /// force's part).
    pub(super) fn first_guess(&self) -> f64 {
        let p = self.p.exponent();
        let x_0 = match self.kind {
            ModelKind::Shccm => ((p + 1.0) * phi(-self.sigma)).powf(1.0 / (p + 1.0)),
            ModelKind::Mcm => self.mcm_compression(),
        };
        let n1 = self.n.exponent() + 1.0;
        let shift = |x: f64| self.beta * self.n.of_abs(x) * x / n1;
        let x_m = x_0 + (1.0 - self.kappa) * p * shift(x_0) / (p + n1);
        (x_m - shift(x_m)).max(0.5 * x_0)
    }

    /// The NDBWMCM's maximum compression on `B + Γ = 0` to first order in `σ`: undamped,
    /// `x_0^(p+1) = (p + 1) / 2`; the damping `c = σ p |Y|^(p-1)` over the undamped loading,
    /// `sqrt(2W) = sqrt(1 - (Y / x_0)^(p+1))`, dissipates `D = σ p x_0^p B(p / (p + 1), 3/2) /
    /// (p + 1)` (`B` Euler's Beta function, with `w = (Y / x_0)^(p+1)`), which moves `x_0` in
    /// by `D / x_0^p`. On DSA (1)'s NDBWMCM this is 2e-4 off (1.2e-2 undamped).
    pub(super) fn mcm_compression(&self) -> f64 {
        let p = self.p.exponent();
        let undamped = (0.5 * (p + 1.0)).powf(1.0 / (p + 1.0));
        let a = p / (p + 1.0);
        // `ln Γ(3/2) = ln(sqrt(π) / 2)`.
        let ln_gamma_3_2 = (0.5 * std::f64::consts::PI.sqrt()).ln();
        let beta = (libm::lgamma(a) + ln_gamma_3_2 - libm::lgamma(a + 1.5)).exp();
        // Past first order (large `σ`) the guess only needs to be positive.
        (undamped - self.sigma * a * beta).max(0.5 * undamped)
    }
}

/// How `W` runs out near the maximum compression `u*`, from a trial end `u_m = u* - s`: with
/// `dW/ds = A + C sqrt(2W)` (`A = F_el / h`, `C` the damping's coefficient over `h`),
/// `W(u_m) = a s + (2/3) c sqrt(2a) s^(3/2) + (c^2/3 + a'/2) s^2 + O(s^(5/2))`, with `a`, `c`
/// and `a' = dA/du` at the trial end.
pub(super) struct Slope {
    pub(super) a: f64,
    pub(super) c: f64,
    pub(super) da: f64,
}

impl Slope {
    /// The step to `u*` from a trial end where `W = w`. Short of `u*` (`w > 0`) the terms to
    /// `s^2` are kept, so a step leaves an error of order `s^(5/2)`; past it (`w < 0`) the
    /// iteration has no damping (`sqrt(2 max(W, 0))`), and `W = -(a s - a' s^2 / 2)`.
    pub(super) fn distance(&self, w: f64) -> f64 {
        let mut s = w.abs() / self.a;
        if w <= 0.0 {
            for _ in 0..3 {
                s = -w / (self.a - 0.5 * self.da * s).max(0.5 * self.a);
            }
            return -s;
        }
        let b = 2.0 / 3.0 * self.c * (2.0 * self.a).sqrt();
        let d = self.c * self.c / 3.0 + 0.5 * self.da;
        for _ in 0..4 {
            s = w / (self.a + b * s.sqrt() + d * s);
        }
        s
    }
}

/// `sin^4 φ`, its `log2` and `d(sin^4 φ)/dφ` at a rung's nodes on `φ ∈ [0, π/2]`: the same
/// for every loading, so computed once per rung.
struct UnitNodes {
    unit: Vec<f64>,
    log2: Vec<f64>,
    slope: Vec<f64>,
}

fn unit_nodes(r: &Rung) -> &'static UnitNodes {
    static TABLES: [OnceLock<UnitNodes>; RUNGS.len()] = [const { OnceLock::new() }; RUNGS.len()];
    let i = RUNGS.iter().position(|&m| m == r.n).expect("n is a rung");
    TABLES[i].get_or_init(|| {
        let (mut unit, mut log2, mut slope) = (vec![], vec![], vec![]);
        for &x in &r.x {
            let (s, c) = (FRAC_PI_4 * (x + 1.0)).sin_cos();
            unit.push(s * s * s * s);
            log2.push(4.0 * s.log2());
            slope.push(4.0 * s * s * s * c);
        }
        UnitNodes { unit, log2, slope }
    })
}

/// What the loading's nodes on `u = u_m sin^4 φ` need whatever `u_m`: the `p`-th and `n`-th
/// powers of `sin^4 φ` (the latter where `B + Γ != 0`).
struct LoadingFactors {
    unit_p: [f64; MAX_N],
    unit_n: [f64; MAX_N],
}

impl Default for LoadingFactors {
    fn default() -> Self {
        LoadingFactors {
            unit_p: [0.0; MAX_N],
            unit_n: [0.0; MAX_N],
        }
    }
}

/// The loading's nodes at one trial `u_m`: `dq/dφ`, `W` and its integrand.
struct LoadingNodes {
    dq: [f64; MAX_N],
    w: [f64; MAX_N],
    rhs: [f64; MAX_N],
    q_end: f64,
    /// `W(u_m)` of the earlier step whose solution `w` holds.
    last_w_end: Option<f64>,
}

impl Default for LoadingNodes {
    fn default() -> Self {
        LoadingNodes {
            dq: [0.0; MAX_N],
            w: [0.0; MAX_N],
            rhs: [0.0; MAX_N],
            q_end: 0.0,
            last_w_end: None,
        }
    }
}

impl LoadingNodes {
    /// `W(u_m)`, its slopes in `u` there and the Picard residual, with the Picard iterations
    /// settled to `settle` (the search's miss: the steps cannot land closer than the noise in
    /// `W(u_m)`).
    fn solve(
        &mut self,
        k: &Coefficients,
        r: &Rung,
        (u_m, settle): (f64, f64),
        f: &LoadingFactors,
    ) -> Result<(f64, Slope, f64), ModelError> {
        let (n, unit) = (r.n, unit_nodes(r));
        let (ump, umn) = (k.p.of_abs(u_m), k.n.of_abs(u_m));
        let mut z = [Hysteretic::default(); MAX_N];
        for (i, zi) in z[..n].iter_mut().enumerate() {
            let h = 1.0 - k.beta * umn * f.unit_n[i];
            if h <= 0.0 {
                return Err(not_applicable(
                    "the loading reaches the hysteresis' saturation (B + Gamma too large for the phase path)",
                ));
            }
            self.dq[i] = -u_m * unit.slope[i] / h;
            let (z_abs, zp) = (u_m * unit.unit[i], ump * f.unit_p[i]);
            *zi = Hysteretic {
                z_abs,
                zp,
                sign: -1.0,
                h,
            };
        }
        let mut q = [0.0; MAX_N];
        r.cumulative(&self.dq[..n], FRAC_PI_4, &mut q[..n]);
        let (mut f0, mut g) = ([0.0; MAX_N], [0.0; MAX_N]);
        for i in 0..n {
            let (fe, c) = if k.beta == 0.0 {
                // `q = Z` exactly (`h = 1`): its powers are `Z`'s.
                k.terms_of(-z[i].z_abs, z[i].zp, z[i])
            } else {
                k.terms(q[i], z[i])
            };
            (f0[i], g[i]) = (fe * self.dq[i], -c * self.dq[i]);
        }
        let (f0, g, w0) = (&f0[..n], &g[..n], (0.5, k.picard_settle(settle)));
        let (w, rhs) = (&mut self.w[..n], &mut self.rhs[..n]);
        // A later step's `W` starts from the last step's, at the same `φ`, where the move of
        // `u_m` changed it less (by about the last `W(u_m)`) than the damping changes the
        // undamped solution (by at most `∫ |g|`, as `sqrt(2W) <= 1`).
        let damping = FRAC_PI_4 * g.iter().map(|gk| gk.abs()).sum::<f64>() * 2.0 / n as f64;
        let start = match self.last_w_end {
            Some(last) if last.abs() < damping => Start::Given,
            _ => Start::Undamped,
        };
        let change = picard(r, FRAC_PI_4, w0, (f0, g), (w, start), rhs)?;
        self.q_end = FRAC_PI_4 * r.total(&self.dq[..n]);
        let h_end = 1.0 - k.beta * umn;
        let end = Hysteretic {
            z_abs: u_m,
            zp: ump,
            sign: -1.0,
            h: h_end,
        };
        let (f_el, c) = k.terms(self.q_end, end);
        // `dF_el/du` (`d|q|/du = 1/h`) and `dh/du`.
        let q_abs = self.q_end.abs();
        let q_p = k.p.of_abs(q_abs);
        let p = k.p.exponent();
        let df = p * (k.kappa * q_p / q_abs / h_end + (1.0 - k.kappa) * ump / u_m);
        let dh = -k.beta * k.n.exponent() * umn / u_m;
        let w_end = 0.5 + FRAC_PI_4 * r.total(&self.rhs[..n]);
        self.last_w_end = Some(w_end);
        let slope = Slope {
            a: f_el / h_end,
            c: c / h_end,
            da: df / h_end - f_el * dh / (h_end * h_end),
        };
        Ok((w_end, slope, change))
    }

    /// `T` at the maximum compression: `∫ |dq| / sqrt(2W)`.
    fn time(&self, r: &Rung) -> f64 {
        let mut dt = [0.0; MAX_N];
        for (i, dti) in dt[..r.n].iter_mut().enumerate() {
            *dti = -self.dq[i] / (2.0 * self.w[i]).max(0.0).sqrt();
        }
        FRAC_PI_4 * r.total(&dt[..r.n])
    }
}
