"""Python-side benchmarks (BENCHMARKS.md, "Python and Dask"): the overhead of bwc.cor against
the same sweep in Rust on one thread each, and the Dask speed-up from 1 to 2 workers on a CoR
sweep of 10^6 impacts and on a batch of fits. Every speed is simulated (`[sweep] interpolate =
false`): these measure the cost of simulations, not of a sweep served by interpolants.

    python3 benches/py_bench.py target/release/sweep-time     # from the repository root
"""

import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

import bwc
import bwc.dask

EVERY_SPEED = {"interpolate": False}
DSS1 = {"B_b": 2.38, "Gamma_b": -2.38, "kappa": 0.677, "sigma_b": 0.0348, "n": 2.93, "p": 2.62}


def overhead(sweep_time):
    v0 = np.linspace(0.1, 6.0, 20000)
    scene = "model = \"shccm\"\nv0 = %s\n[sweep]\ninterpolate = false\n[base]\n%s\n" % (
        json.dumps(v0.tolist()),
        "\n".join("%s = %r" % kv for kv in DSS1.items()),
    )
    with tempfile.NamedTemporaryFile("w", suffix=".toml", delete=False) as f:
        f.write(scene)
    rust, python = [], []
    for _ in range(5):  # in turns
        out = subprocess.run([sweep_time, f.name, "1"], check=True, capture_output=True, text=True).stdout
        rust.append(float(out.split("median ")[1].split(" s")[0]))
        clock = time.perf_counter()
        bwc.cor("shccm", DSS1, v0, sweep=EVERY_SPEED, threads=1)
        python.append(time.perf_counter() - clock)
    os.unlink(f.name)
    r, p = statistics.median(rust), statistics.median(python)
    print(f"20,000 speeds, one thread: Rust {r:.3f} s ({r / 2e4 * 1e6:.2f} us/CoR), "
          f"bwc.cor {p:.3f} s, ratio {p / r:.3f}")


def dask_speedup():
    from dask.distributed import Client, LocalCluster

    rng = np.random.default_rng(1)
    params_list = [dict(DSS1, kappa=k) for k in rng.uniform(0.5, 0.8, 100)]
    v0 = np.linspace(0.1, 6.0, 10000)
    configs = ["fixtures/golf.toml", "fixtures/tennis.toml", "fixtures/pingpong.toml"] * 2
    seeds = [1, 1, 1, 2, 2, 2]
    for workers in (1, 2):
        with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
            with Client(cluster) as client:
                client.run(lambda: bwc.cor("shccm", DSS1, [1.0]))  # warm the workers
                clock = time.perf_counter()
                sweeps = bwc.dask.cor_sweep("shccm", params_list, v0, client, sweep=EVERY_SPEED)
                sweep_s = time.perf_counter() - clock
                clock = time.perf_counter()
                bwc.dask.identify_many(configs, client, seeds=seeds)
                fits_s = time.perf_counter() - clock
        impacts = sum(len(s["e"]) for s in sweeps)
        print(f"{workers} worker(s): {impacts} impacts in {sweep_s:.2f} s, 6 fits in {fits_s:.2f} s")


if __name__ == "__main__":
    overhead(sys.argv[1] if len(sys.argv) > 1 else "target/release/sweep-time")
    dask_speedup()
