"""How far Taylor-Pade steps could reach over an unloading, against Taylor steps from the same
coefficients (BENCHMARKS.md, "One CoR: the series path", tried and dropped): DSS (1)'s NDBWSHCCM at v0 = 2 m/s, from the maximum
compression to the root of Z, where the series path's steps are shortest.

A ceiling, not a solver: every step starts on the truth (SciPy's DOP853 at rtol 2.3e-14, dense
output) and is as long as the approximant stays within the tolerance of the truth (relative to
the state, on a grid of 400 step lengths). Both approximants use the 17 Taylor coefficients of
an order-16 step: the Taylor polynomial itself, or its [8/8] Pade approximant per component.

On the unloading (Y = -X, D = -Z, both > 0, V > 0; the branch Gamma = -B):
Y' = -V, D' = -V (1 + 2B D^n), V' = kappa Y^p + (1 - kappa) D^p - sigma Y^p V.

    python3 benches/pade_ceiling.py        # about 2 min
"""

import numpy as np
from scipy.integrate import solve_ivp

# Table 3's DSS (1), base parameters, and Table 1's map to the nondimensional ones at v0.
B_B, GAMMA_B, KAPPA, SIGMA_B, N, P = 2.38, -2.38, 0.677, 0.0348, 2.93, 2.62
V0 = 2.0
B = B_B * V0 ** (2 * N / (P + 1))
GAMMA = GAMMA_B * V0 ** (2 * N / (P + 1))
SIGMA = SIGMA_B * V0
ORDER = 16


def model(_t, y):
    """The NDBWSHCCM (x, z, v), compression negative, from (0, 0, -1)."""
    x, z, v = y
    zdot = v - B * abs(z) ** (N - 1) * z * abs(v) - GAMMA * abs(z) ** N * v
    force = -KAPPA * abs(x) ** (P - 1) * x - (1 - KAPPA) * abs(z) ** (P - 1) * z - SIGMA * abs(x) ** P * v
    return [v, zdot, force]


def unloading(_t, u):
    y, d, v = u
    ad = abs(d)
    return [-v, -v * (1 + 2 * B * ad**N), KAPPA * abs(y) ** P + (1 - KAPPA) * np.sign(d) * ad**P - SIGMA * abs(y) ** P * v]


def at_rest(_t, y):
    return y[2]


def root_of_z(_t, u):
    return u[1]


at_rest.terminal, at_rest.direction = True, 1
root_of_z.terminal, root_of_z.direction = True, -1
TOL = dict(method="DOP853", rtol=2.3e-14, atol=1e-16)
loading = solve_ivp(model, (0, 20), [0.0, 0.0, -1.0], events=at_rest, **TOL)
T_M, (X_M, Z_M, _) = loading.t_events[0][0], loading.y_events[0][0]
TRUTH = solve_ivp(unloading, (T_M, T_M + 5), [-X_M, -Z_M, 0.0], dense_output=True, events=root_of_z, **TOL)
T_ROOT = TRUTH.t_events[0][0]


def power(u, a):
    """The Taylor coefficients of u^a for u[0] > 0 (as many as u has)."""
    w = np.zeros(len(u))
    w[0] = u[0] ** a
    for k in range(1, len(u)):
        w[k] = sum((a * j - (k - j)) * u[j] * w[k - j] for j in range(1, k + 1)) / (k * u[0])
    return w


def taylor(state, terms):
    """The unloading's Taylor coefficients at `state`, by the recurrences of its equations."""
    y, d, v = (np.zeros(terms) for _ in range(3))
    y[0], d[0], v[0] = state
    for k in range(terms - 1):
        yp, dp, dn = power(y[: k + 1], P), power(d[: k + 1], P), power(d[: k + 1], N)
        y[k + 1] = -v[k] / (k + 1)
        d[k + 1] = -(v[k] + 2 * B * np.dot(v[: k + 1], dn[::-1])) / (k + 1)
        v[k + 1] = (KAPPA * yp[k] + (1 - KAPPA) * dp[k] - SIGMA * np.dot(yp, v[: k + 1][::-1])) / (k + 1)
    return [y, d, v]


def pade(c, m):
    """The [m/m] Pade approximant of the series c[0..2m]: numerator and denominator (b0 = 1)."""
    a_mat = np.array([[c[m + i - j] if m + i - j >= 0 else 0.0 for j in range(1, m + 1)] for i in range(1, m + 1)])
    b = np.concatenate([[1.0], np.linalg.lstsq(a_mat, -c[m + 1 : 2 * m + 1], rcond=None)[0]])
    a = np.array([np.dot(b[: i + 1], c[i::-1][: i + 1]) for i in range(m + 1)])
    return a, b


def step(kind, t, tol):
    """The longest step from the truth at t whose approximant stays within tol of the truth."""
    state = TRUTH.sol(t)
    coefficients = taylor(state, ORDER + 1)
    if kind == "taylor":
        approx = lambda h: np.array([np.polyval(c[::-1], h) for c in coefficients])
    else:
        parts = [pade(c, ORDER // 2) for c in coefficients]
        approx = lambda h: np.array([np.polyval(a[::-1], h) / np.polyval(b[::-1], h) for a, b in parts])
    longest = 0.0
    for h in np.linspace(0, min(1.5, T_ROOT - t), 401)[1:]:
        want = TRUTH.sol(t + h)
        if np.any(np.abs(approx(h) - want) > tol * np.maximum(np.abs(state) + 1e-3, np.abs(want))):
            break
        longest = h
    return longest


def main():
    print(f"maximum compression at T = {T_M:.4f}, root of Z at T = {T_ROOT:.4f}")
    print("tolerance\tapproximant\tsteps\tfirst steps")
    for tol in (1e-6, 1e-8, 1e-10, 1e-11):
        for kind in ("taylor", "pade"):
            t, steps = T_M, []
            while t < T_ROOT - 1e-12:
                h = step(kind, t, tol)
                if h == 0.0:
                    raise SystemExit(f"{kind}: no step at T = {t}")
                steps.append(h)
                t += h
            print(f"{tol:g}\t{kind}\t{len(steps)}\t{', '.join(f'{h:.3f}' for h in steps[:4])}")


if __name__ == "__main__":
    main()
