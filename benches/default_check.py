"""The work-precision cases at the default settings (BENCHMARKS.md, "The cost of a
checked CoR"): Table 3's DSS (1) and DSA (1), both models, v0 = 0.5, 2, 5 m/s, each CoR checked to
`e_tol` = 1e-10 by default, against Vern9 at rtol 1e-14 (checked by DOP853 at rtol 1e-14), all
through the whole `bwc-simulate run --json` process.

    cargo build --release -p bwc-cli
    python3 benches/default_check.py target/release/bwc-simulate
"""

import json
import os
import subprocess
import sys
import tempfile

CASES = {
    "NDBWSHCCM DSS (1)": ("shccm", dict(B_b=2.38, Gamma_b=-2.38, kappa=0.677, sigma_b=0.0348, n=2.93, p=2.62)),
    "NDBWMCM DSS (1)": ("mcm", dict(B_b=0.966, Gamma_b=-0.966, kappa=0.531, sigma_b=2.22e-16, n=1.57, p=1.75)),
    "NDBWSHCCM DSA (1)": ("shccm", dict(B_b=1.04, Gamma_b=-1.02, kappa=0.362, sigma_b=0.017, n=1.01, p=1.67)),
    "NDBWMCM DSA (1)": ("mcm", dict(B_b=0.521, Gamma_b=-0.521, kappa=0.168, sigma_b=0.0144, n=1.0, p=2.04)),
}


def run(exe, model, base, solver):
    """The runs of one case at the three speeds with the `[solver]` table `solver`."""
    text = (f'model = "{model}"\nv0 = [0.5, 2.0, 5.0]\n[base]\n'
            + "".join(f"{k} = {v!r}\n" for k, v in base.items()) + solver)
    with tempfile.NamedTemporaryFile("w", suffix=".toml", delete=False) as f:
        f.write(text)
    try:
        out = subprocess.run([exe, "run", f.name, "--json"], capture_output=True, text=True, check=True)
    finally:
        os.unlink(f.name)
    return json.loads(out.stdout)["runs"]


def main(exe):
    tight = "[solver]\nrtol = 1e-14\natol = 1e-16\ne_tol = 0\nseries = false\n"
    print("| case | largest error in e | references agree to | largest e_error | rtol of the runs |")
    print("| --- | ---: | ---: | ---: | --- |")
    for name, (model, base) in CASES.items():
        runs = run(exe, model, base, "")
        dop853 = run(exe, model, base, tight)
        vern9 = run(exe, model, base, tight + 'method = "vern9"\n')
        error = max(abs(a["e"] - b["e"]) for a, b in zip(runs, vern9))
        agree = max(abs(a["e"] - b["e"]) for a, b in zip(dop853, vern9))
        estimate = max(r["e_error"] for r in runs)
        rtols = sorted({r["rtol"] for r in runs})
        print(f"| {name} | {error:.1e} | {agree:.1e} | {estimate:.1e} | {rtols} |")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "target/release/bwc-simulate")
