"""Where SciPy's bounded least squares ends from uniform starts on a single-baseball fit.

The reference behind BENCHMARKS.md, "Identification: the global optimum on measured data":
the fit "Baseball 3 on wood NDBWMCM" of fixtures/measured_cor.toml (bounds and log scale of
sigma_b as there), residuals from bwc.cor, scipy.optimize.least_squares from N uniform points
of the unit cube with the given method ("trf": interior, Coleman-Li scaling; "dogbox": an
active set) and x_scale ("jac" or a number). Prints how many end within 2 % of the best known
J1 = 4.43016e-6 and the mean evaluations per start (a Jacobian counted as 6).

    python benches/trf_basins.py SEED N METHOD X_SCALE     # e.g. 1 30 trf jac
"""
import csv
import sys

import numpy as np
from scipy.optimize import least_squares

import bwc

BEST = 4.43016e-6
DATA = "fixtures/data/real/baseball_ball3_v0_e.csv"


def decode(s):
    b = 10 * s[0]
    return dict(B_b=b, Gamma_b=(-1 + 2 * s[1]) * b, kappa=0.02 + 0.96 * s[2],
                sigma_b=10 ** (-5 + 5 * s[3]), n=1 + 3 * s[4], p=1 + 3 * s[5],
                U_b=1.0, T_b=None)


def main():
    seed, n, method, x_scale = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3], sys.argv[4]
    with open(DATA) as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    v0 = np.array([float(r["v_0"]) for r in rows])
    e = np.array([float(r["e"]) for r in rows])

    def residuals(s):
        return (np.asarray(bwc.cor("mcm", decode(s), v0, threads=1)["e"]) - e) / np.sqrt(len(e))

    rng = np.random.default_rng(seed)
    costs, evaluations = [], []
    for _ in range(n):
        r = least_squares(residuals, rng.random(6), bounds=(0, 1), method=method,
                          x_scale=x_scale if x_scale == "jac" else float(x_scale),
                          diff_step=1e-5)
        costs.append(np.sum(r.fun ** 2))
        evaluations.append(r.nfev + 6 * (r.njev or 0))
    costs = np.array(costs)
    print(f"{method} x_scale={x_scale}: {np.sum(costs <= 1.02 * BEST)}/{n} within 2 % of "
          f"{BEST:.5e}; {np.mean(evaluations):.0f} evaluations per start")
    print(np.sort(costs / BEST).round(3))


if __name__ == "__main__":
    main()
