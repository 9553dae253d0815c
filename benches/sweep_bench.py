"""Sweeps served by verified interpolants against simulating every speed (BENCHMARKS.md,
"Sweeps from verified interpolants"): 20,000 speeds from 0.1 to 6 m/s of Table 3's DSS (1)
and DSA (1), both models, default settings, one thread, the whole `bwc-simulate run --json`
process, the two settings timed in turns; medians, and the largest differences in `e` and
(relative) in `t_s` between the two outputs.

With `precision` it measures a sweep's work against its error instead: COUNT (2,000) speeds
from 0.5 to 5 m/s of each case, at rtol 1e-5 ... 1e-12 by the defaults (series path, served by
interpolants to rtol) against plain DOP853 simulating every speed (`series = false`,
`stop_at_kinks = false`, atol = rtol / 100), all single runs (`e_tol = 0`), whole process, in turns; errors in `e` against
the series path at rtol 1e-13 simulating every speed.

    cargo build --release -p bwc-cli
    python3 benches/sweep_bench.py target/release/bwc-simulate [ROUNDS]   # from the repository root
    python3 benches/sweep_bench.py target/release/bwc-simulate precision [ROUNDS] [COUNT]
    python3 benches/sweep_bench.py target/release/bwc-simulate against OTHER_EXE [ROUNDS]
    python3 benches/sweep_bench.py target/release/bwc-simulate phase [ROUNDS]

`against` times the interpolated 20,000-speed sweeps of two builds in turns and says whether
their outputs are identical; `phase` times them with the defaults and with
`[solver] phase = true`.
"""

import json
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

CASES = {
    "NDBWSHCCM DSS (1)": ("shccm", dict(B_b=2.38, Gamma_b=-2.38, kappa=0.677, sigma_b=0.0348, n=2.93, p=2.62)),
    "NDBWMCM DSS (1)": ("mcm", dict(B_b=0.966, Gamma_b=-0.966, kappa=0.531, sigma_b=2.22e-16, n=1.57, p=1.75)),
    "NDBWSHCCM DSA (1)": ("shccm", dict(B_b=1.04, Gamma_b=-1.02, kappa=0.362, sigma_b=0.017, n=1.01, p=1.67)),
    "NDBWMCM DSA (1)": ("mcm", dict(B_b=0.521, Gamma_b=-0.521, kappa=0.168, sigma_b=0.0144, n=1.0, p=2.04)),
}


def scene(model, base, interpolate, v0=None, solver=""):
    v0 = np.linspace(0.1, 6.0, 20000).tolist() if v0 is None else v0
    lines = ['model = "%s"' % model, "v0 = %s" % json.dumps(v0), "[sweep]",
             "interpolate = %s" % str(interpolate).lower(), solver, "[base]"]
    lines += ["%s = %r" % kv for kv in base.items()]
    return "\n".join(lines) + "\n"


def timed(exe, path):
    clock = time.perf_counter()
    out = subprocess.run([exe, "run", path, "--json", "--threads", "1"], check=True,
                         capture_output=True, text=True).stdout
    return time.perf_counter() - clock, json.loads(out)["runs"]


def main(exe, rounds):
    print("| case | every speed simulated | interpolants | ratio | simulated / interpolated "
          "| max diff e | max rel diff t_s |")
    print("| --- | ---: | ---: | ---: | ---: | ---: | ---: |")
    for name, (model, base) in CASES.items():
        paths = []
        for interpolate in (False, True):
            with tempfile.NamedTemporaryFile("w", suffix=".toml", delete=False) as f:
                f.write(scene(model, base, interpolate))
                paths.append(f.name)
        times = ([], [])
        for _ in range(rounds):  # in turns
            for i, path in enumerate(paths):
                t, runs = timed(exe, path)
                times[i].append(t)
                if i == 0:
                    every = runs
                else:
                    fast = runs
        for p in paths:
            os.unlink(p)
        de = max(abs(a["e"] - b["e"]) for a, b in zip(every, fast))
        dt = max(abs(a["t_s"] - b["t_s"]) / b["t_s"] for a, b in zip(every, fast))
        inter = sum(r["source"] == "interpolated" for r in fast)
        slow, quick = statistics.median(times[0]), statistics.median(times[1])
        print(f"| {name} | {slow:.3f} s ({slow / 2e4 * 1e6:.1f} us/CoR) | {quick:.3f} s "
              f"({quick / 2e4 * 1e6:.2f} us/CoR) | {slow / quick:.1f} | {len(fast) - inter} / {inter} "
              f"| {de:.1e} | {dt:.1e} |")


def written(text):
    with tempfile.NamedTemporaryFile("w", suffix=".toml", delete=False) as f:
        f.write(text)
        return f.name


def precision(exe, rounds, count):
    for name, (model, base) in CASES.items():
        print(f"\n{name}, {count} speeds from 0.5 to 5 m/s\n")
        precision_case(exe, rounds, model, base, np.linspace(0.5, 5.0, count).tolist())


def precision_case(exe, rounds, model, base, v0):
    ref_path = written(scene(model, base, False, v0, "[solver]\nrtol = 1e-13\natol = 1e-15\ne_tol = 0"))
    ref = np.array([r["e"] for r in timed(exe, ref_path)[1]])
    os.unlink(ref_path)
    rows = []
    for k in range(5, 13):
        rtol = 10.0 ** -k
        plain = written(scene(model, base, False, v0, "[solver]\nrtol = %r\natol = %r\ne_tol = 0\nseries = false\n"
                              "stop_at_kinks = false\nmethod = \"dop853\"" % (rtol, rtol / 100)))
        default = written(scene(model, base, True, v0, "[solver]\nrtol = %r\natol = %r\ne_tol = 0" % (rtol, rtol / 100)))
        times, errors = ([], []), [0.0, 0.0]
        for _ in range(rounds):  # in turns
            for i, path in enumerate((plain, default)):
                t, runs = timed(exe, path)
                times[i].append(t)
                errors[i] = float(np.abs(np.array([r["e"] for r in runs]) - ref).max())
        os.unlink(plain)
        os.unlink(default)
        rows.append((rtol, statistics.median(times[0]), errors[0], statistics.median(times[1]), errors[1]))
    # Plain DOP853's time at each default row's error: log-log between the plain rows that
    # bracket it.
    plain_pts = sorted((math.log(e), math.log(t)) for _, t, e, _, _ in rows)
    print("| rtol | plain DOP853: error in e, time | defaults: error in e, time | plain's time at that error / defaults' |")
    print("| ---: | ---: | ---: | ---: |")
    for rtol, tp, ep, td, ed in rows:
        x = math.log(ed)
        # Below plain's smallest error: at least its time there over the defaults'.
        ratio = "> %.1f" % (math.exp(plain_pts[0][1]) / td) if x < plain_pts[0][0] else "-"
        for (x0, y0), (x1, y1) in zip(plain_pts, plain_pts[1:]):
            if x0 <= x <= x1:
                ratio = "%.1f" % (math.exp(y0 + (y1 - y0) * (x - x0) / (x1 - x0)) / td)
        print(f"| {rtol:.0e} | {ep:.1e}, {tp:.3f} s | {ed:.1e}, {td:.3f} s | {ratio} |")


def paired(exes_and_solvers, rounds):
    """The interpolated 20,000-speed sweeps, each (executable, [solver] text) in turns: medians
    per CoR, the largest difference in `e` from the first, and whether the outputs match."""
    for name, (model, base) in CASES.items():
        paths = [written(scene(model, base, True, None, solver)) for _, solver in exes_and_solvers]
        times = [[] for _ in exes_and_solvers]
        outs = [None] * len(exes_and_solvers)
        for _ in range(rounds):  # in turns
            for i, ((exe, _), path) in enumerate(zip(exes_and_solvers, paths)):
                t, outs[i] = timed(exe, path)
                times[i].append(t)
        for p in paths:
            os.unlink(p)
        cells = []
        for i, runs in enumerate(outs):
            de = max(abs(a["e"] - b["e"]) for a, b in zip(outs[0], runs))
            same = all(a["e"] == b["e"] and a["t_s"] == b["t_s"] for a, b in zip(outs[0], runs))
            per = statistics.median(times[i]) / 2e4 * 1e6
            cells.append(f"{per:.2f} us/CoR (max diff e {de:.1e}, identical {same})")
        print(f"| {name} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    exe = sys.argv[1] if len(sys.argv) > 1 else "target/release/bwc-simulate"
    if len(sys.argv) > 3 and sys.argv[2] == "against":
        paired([(exe, ""), (sys.argv[3], "")], int(sys.argv[4]) if len(sys.argv) > 4 else 5)
    elif len(sys.argv) > 2 and sys.argv[2] == "phase":
        paired([(exe, ""), (exe, "[solver]\nphase = true")], int(sys.argv[3]) if len(sys.argv) > 3 else 3)
    elif len(sys.argv) > 2 and sys.argv[2] == "precision":
        precision(exe, int(sys.argv[3]) if len(sys.argv) > 3 else 3,
                  int(sys.argv[4]) if len(sys.argv) > 4 else 2000)
    else:
        main(exe, int(sys.argv[2]) if len(sys.argv) > 2 else 7)
