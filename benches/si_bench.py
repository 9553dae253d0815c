"""SI CoR evaluations, two binaries side by side (BENCHMARKS.md, "SI models take the series path
through their nondimensional form"): Table 4's laws at 1,000 speeds from 0.5 to 10 m/s, every
speed simulated, whole process, one thread, in turns; errors against the Runge-Kutta path at
rtol 1e-13.

    python3 benches/si_bench.py OLD/bwc-simulate NEW/bwc-simulate [ROUNDS]
"""

import os
import statistics
import sys

from sweep_bench import timed as run  # one whole-process run: (seconds, runs)
from sweep_bench import written  # a scene's text in a temporary file

LAWS = {
    "BWSHCCM": ("shccm", "m = 0.145\nk = 117080063.0\nc = 5854003.0\nn = 1.1\np = 1.7\nalpha = 0.1\n"
                         "beta = 981.05\ngamma = -961.4\nA = 0.925\n"),
    "BWMCM": ("mcm", "m = 0.145\nk = 253000000.0\nc = 2811.0\nn = 1.2\np = 1.8\nalpha = 0.15\n"
                     "beta = 1200.0\ngamma = -1200.0\nA = 1.01\n"),
}


def scene(model, law, solver=""):
    text = (f'model = "{model}"\nv0 = {{ from = 0.5, to = 10.0, count = 1000 }}\n'
            f"[sweep]\ninterpolate = false\n{solver}[physical]\n{law}")
    return written(text)


def errors(runs, ref):
    e = max(abs(a["e"] - b["e"]) for a, b in zip(runs, ref))
    t = max(abs(a["t_s"] - b["t_s"]) / b["t_s"] for a, b in zip(runs, ref))
    return f"{e:.1e}, {t:.1e}"


def main(old, new, rounds):
    print("| law | before: time, error in e, in t_s (rel.) | after: time, error in e, in t_s | ratio |")
    print("| --- | ---: | ---: | ---: |")
    for name, (model, law) in LAWS.items():
        ref_path = scene(model, law, "[solver]\nrtol = 1e-13\natol = 1e-15\ne_tol = 0\nseries = false\n")
        ref = run(new, ref_path)[1]
        path = scene(model, law)
        times, runs = {old: [], new: []}, {}
        for _ in range(rounds):  # in turns
            for exe in (old, new):
                t, runs[exe] = run(exe, path)
                times[exe].append(t)
        os.unlink(ref_path)
        os.unlink(path)
        a, b = statistics.median(times[old]), statistics.median(times[new])
        print(f"| {name} | {a:.3f} s, {errors(runs[old], ref)} | {b:.3f} s, {errors(runs[new], ref)} | {a / b:.2f} |")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2], int(sys.argv[3]) if len(sys.argv) > 3 else 7)
