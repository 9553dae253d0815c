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
