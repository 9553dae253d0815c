//! The recurrences of an expansion: the Taylor coefficients of a power `b^e` of a series and of
//! the Cauchy products, order by order, from the coefficients before them (the scratch of
//! [`super::jet::Jet`]).

use super::polynomial::{Series, ORDER};
use crate::models::NdCoefficients;
use crate::power::Pow;

/// `1/k` for `k = 0 ..= ORDER + 1` (`INVERSE[0]` unused): the recurrences multiply by it, off the
/// critical path, rather than divide on it.
pub(super) const INVERSE: [f64; ORDER + 2] = {
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
pub(super) fn clocked(w: &Series, clock: &Series, j: usize) -> f64 {
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
pub(super) struct JetPowers<'a> {
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
    pub(super) fn new(
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
    pub(super) fn start(&mut self, d0: f64, z0: f64) -> (f64, f64) {
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
    pub(super) fn order<const OWN_Z: bool, const HYSTERETIC: bool>(
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
    pub(super) fn order_in_branch(&mut self, j: usize, d_j: f64, z_j: f64, w: &Series) -> [f64; 4] {
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
    pub(super) fn hysteresis_leading(&self) -> f64 {
        self.powers[2].r[ORDER]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
