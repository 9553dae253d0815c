"""bwc's chains against the independent SciPy implementation of the tests
(`crates/py/tests/test_chain.py`: solve_ivp, DOP853, an event per onset and separation), on
a granular chain like `benches/src/bin/chain-scale.rs`'s (N steel beads with the elastic Hertz
law, the first at 0.5 m/s, until the wave has crossed), the beads 0.1 micrometre apart (the
reference takes up contacts at gap closings only). Per size: bwc's time at its
default tolerances (rtol 1e-10) and SciPy's at rtol 1e-10 and 1e-12, medians of 3 runs, and
each one's largest final-velocity difference to SciPy at 1e-12.

    python benches/chain_scipy.py 10 30 100      # needs the bwc package, numpy and scipy
"""

import pathlib
import statistics
import sys
import time

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "crates" / "py" / "tests"))
import bwc  # noqa: E402
from test_chain import Reference  # noqa: E402

R, M = 0.005, 4.1092e-3
LAW = {"k": 7.326e9, "c": 0.0, "n": 1.0, "p": 1.5, "alpha": 0.5, "beta": 0.0, "gamma": 0.0, "A": 1.0}


def median_time(f, rounds=3):
    times, out = [], None
    for _ in range(rounds):
        start = time.perf_counter()
        out = f()
        times.append(time.perf_counter() - start)
    return statistics.median(times), out


def main(sizes):
    print("| beads | bwc (s) | SciPy rtol 1e-10 (s) | SciPy rtol 1e-12 (s) | bwc - SciPy 1e-12 (m/s) | SciPy 1e-10 - SciPy 1e-12 (m/s) |")
    print("| ---: | ---: | ---: | ---: | ---: | ---: |")
    for n in sizes:
        horizon = 1.2 * n * 2 * R / 580.0
        v = [0.5] + [0.0] * (n - 1)
        x = [(2 * R + 1e-7) * i for i in range(n)]
        scene = {"model": "shccm", "physical": LAW,
                 "chain": {"mass": M, "position": x, "velocity": v, "length": 2 * R,
                           "horizon": horizon, "until": "horizon"}}
        s = dict(m=np.full(n, M), x=np.array(x), v=np.array(v), length=np.full(n, 2 * R), g=0.0,
                 left=None, right=None, law=LAW, horizon=horizon)
        t_bwc, out = median_time(lambda: bwc.simulate(scene, threads=1))
        ours = np.array([b.velocity_m_s for b in out.chain.bodies])
        t_10, loose = median_time(lambda: Reference(s, rtol=1e-10).run())
        t_12, tight = median_time(lambda: Reference(s, rtol=1e-12).run())
        print(f"| {n} | {t_bwc:.3g} | {t_10:.3g} | {t_12:.3g} | {np.abs(ours - tight).max():.1e} | "
              f"{np.abs(loose - tight).max():.1e} |", flush=True)


if __name__ == "__main__":
    main([int(a) for a in sys.argv[1:]] or [10, 30, 100])
