"""Peak memory and wall time of large sweeps written to an output folder (BENCHMARKS.md, "Studies
that scale"): Table 3's DSS (1) NDBWSHCCM with T_b = 1e-5 s, COUNT log-spaced speeds from 0.1 to
6 m/s, `bwc-simulate run SCENE --out DIR`, the peak resident set of the whole process from GNU
time's %M; served by interpolants (the default) and, with `simulated`, every speed simulated
(`[sweep] interpolate = false`). Each folder is removed after it is measured (10^7 speeds write
8.8 GB).

    cargo build --release -p bwc-cli
    python3 benches/study_memory.py target/release/bwc-simulate 10000 100000 1000000 10000000
    python3 benches/study_memory.py target/release/bwc-simulate simulated 10000 100000 1000000
"""

import os
import shutil
import subprocess
import sys
import tempfile

SCENE = """v0 = {{ from = 0.1, to = 6.0, count = {count}, spacing = "log" }}
[[base]]
name = "DSS (1) NDBWSHCCM"
model = "shccm"
B_b = 2.38
Gamma_b = -2.38
kappa = 0.677
sigma_b = 0.0348
n = 2.93
p = 2.62
T_b = 1e-5
[sweep]
interpolate = {interpolate}
"""


def measure(exe, count, interpolate, work):
    scene = os.path.join(work, f"sweep-{count}.toml")
    with open(scene, "w") as f:
        f.write(SCENE.format(count=count, interpolate="true" if interpolate else "false"))
    out = os.path.join(work, f"out-{count}")
    stats = os.path.join(work, "time.txt")
    subprocess.run(
        ["/usr/bin/time", "-o", stats, "-f", "%M %e", exe, "run", scene, "--out", out],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        check=True,
    )
    peak_kb, wall = open(stats).read().split()[-2:]
    size = sum(os.path.getsize(os.path.join(out, n)) for n in os.listdir(out))
    shutil.rmtree(out)
    return int(peak_kb) / 1024, float(wall), size / 1e6


def main():
    exe, rest = sys.argv[1], sys.argv[2:]
    interpolate = not (rest and rest[0] == "simulated")
    counts = [int(c) for c in (rest[1:] if not interpolate else rest)] or [10_000, 100_000]
    print("| speeds | peak memory (MB) | wall (s) | written (MB) | bytes per speed held |")
    print("| ---: | ---: | ---: | ---: | ---: |")
    base = None
    with tempfile.TemporaryDirectory() as work:
        for count in counts:
            peak, wall, size = measure(exe, count, interpolate, work)
            base = peak if base is None else base
            per = (peak - base) * 2**20 / count if count != counts[0] else float("nan")
            print(f"| {count:,} | {peak:.1f} | {wall:.2f} | {size:,.0f} | {per:.1f} |")


if __name__ == "__main__":
    main()
