#!/usr/bin/env python3
"""The paper's numerical setup (Appendix D) for one CoR evaluation, for side-by-side timing.

SciPy solve_ivp with DOP853, rtol 1e-10, atol 1e-12, with and without max_step 1e-2, on the
NDBWSHCCM at Table 3's DSS (1) base parameters, u = 0. Separation t_s = inf{t : F <= 0 <= v} is
the first downward zero of the continuous event function max(F, -v) (positive at impact, where
F = 0 and v = -1). Prints one JSON object per line: v0, max_step, e, T_s, nfev, median time (s).

Not part of the build or the tests: `python3 benches/scipy_cor.py` (installs SciPy with pip when
it is missing). Used by `cargo run --release -p bwc-benches --bin work-precision-cor`.
"""
import json
import subprocess
import sys
import time

try:
    import numpy as np
    from scipy.integrate import solve_ivp
except ImportError:
    subprocess.run([sys.executable, "-m", "pip", "install", "--quiet", "scipy"], check=True)
    import numpy as np
    from scipy.integrate import solve_ivp

# Table 3, DSS (1), NDBWSHCCM.
B_B, GAMMA_B, KAPPA, SIGMA_B, N, P = 2.38, -2.38, 0.677, 0.0348, 2.93, 2.62


def nondimensional(v0):
    s = v0 ** (2 * N / (P + 1))
    return B_B * s, GAMMA_B * s, KAPPA, SIGMA_B * v0


def cor(v0, max_step):
    b, g, k, sigma = nondimensional(v0)
    kc = 1.0 - k

    def force(x, z, v):
        return -k * abs(x) ** (P - 1) * x - kc * abs(z) ** (P - 1) * z - sigma * abs(x) ** P * v

    def rhs(t, y):
        x, z, v = y
        zn = abs(z) ** N
        return [v, v - b * abs(z) ** (N - 1) * z * abs(v) - g * zn * v, force(x, z, v)]

    def separation(t, y):
        return max(force(*y), -y[2])

    separation.terminal = True
    separation.direction = -1
    kw = {"max_step": max_step} if max_step else {}
    sol = solve_ivp(rhs, (0.0, 1e3), [0.0, 0.0, -1.0], method="DOP853", rtol=1e-10, atol=1e-12, events=separation, **kw)
    return sol.y_events[0][0][2], sol.t_events[0][0], sol.nfev


def median_time(f, reps):
    samples = []
    for _ in range(reps):
        t0 = time.perf_counter()
        f()
        samples.append(time.perf_counter() - t0)
    return float(np.median(samples))


if __name__ == "__main__":
    for v0 in (0.5, 2.0, 5.0):
        for max_step in (1e-2, None):
            e, ts, nfev = cor(v0, max_step)
            secs = median_time(lambda: cor(v0, max_step), 5)
            print(json.dumps({"v0": v0, "max_step": max_step, "e": e, "T_s": ts, "nfev": int(nfev), "time_s": secs}))
