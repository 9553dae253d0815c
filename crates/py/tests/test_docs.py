"""The Python examples of the README and the user guide run as written, from the repository's
root, each in a fresh interpreter (so that a Dask example's processes start as they would for a
user)."""

import pathlib
import re
import subprocess
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[3]
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs" / "src").rglob("*.md"))]
BLOCKS = [
    pytest.param(block, id=f"{page.relative_to(ROOT)}:{i}")
    for page in PAGES
    for i, block in enumerate(re.findall(r"```python\n(.*?)```", page.read_text(), re.S))
]


def test_the_pages_have_python_examples():
    assert len(BLOCKS) >= 4


@pytest.mark.parametrize("block", BLOCKS)
def test_example_runs_as_written(block, tmp_path):
    # As a script file pasted from the page: one that starts worker processes (Dask spawns
    # them, importing the script again) works only under its own `if __name__ == "__main__":`.
    script = tmp_path / "example.py"
    script.write_text(block)
    run = subprocess.run(
        [sys.executable, str(script)], cwd=ROOT, capture_output=True, text=True, timeout=600
    )
    assert run.returncode == 0, run.stderr[-3000:]


def test_the_guides_shown_outputs_are_what_its_commands_print():
    # The fast ones; `scripts/guide-outputs --slow` checks the rest (and `--write` renews them).
    run = subprocess.run(
        [sys.executable, str(ROOT / "scripts" / "guide-outputs")], cwd=ROOT, capture_output=True,
        text=True, timeout=600,
    )
    assert run.returncode == 0, run.stdout[-3000:] + run.stderr[-3000:]
    assert "0 differences" in run.stdout and not run.stdout.startswith("0 shown"), run.stdout


def test_the_reference_lists_every_column_of_cor():
    """The reference's row of ``bwc.cor`` names exactly the columns it returns, and each
    column it calls a run's key is a key of a run of ``bwc.simulate``."""
    import bwc
    row = next(line for line in (ROOT / "docs/src/reference/python.md").read_text().splitlines()
               if line.startswith("| `bwc.cor("))
    described = row.split("|")[2]
    named = set(re.findall(r"`([A-Za-z_]+)`", described)) - {"bwc"}
    law = {"B": 0.0, "Gamma": 0.0, "kappa": 0.5, "sigma": 0.5, "n": 1.0, "p": 1.5}
    out = bwc.cor("shccm", law)
    run = bwc.simulate({"model": "shccm", "nondimensional": law})["runs"][0]
    derived = {"double_double", "interpolated", "tighter_failed_rtol", "tighter_out_of_steps"}
    run_keys = named - derived - {"Cor", "arithmetic", "source", "tighter_failed"}
    assert set(out) == run_keys | derived, (set(out) ^ (run_keys | derived))
    assert run_keys <= set(run), run_keys - set(run)
