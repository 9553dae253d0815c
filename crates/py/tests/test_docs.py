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
def test_example_runs_as_written(block):
    # Under `if __name__ == "__main__"`, as a script that starts worker processes must be.
    script = "if __name__ == '__main__':\n" + "\n".join("    " + line for line in block.splitlines())
    run = subprocess.run(
        [sys.executable, "-c", script], cwd=ROOT, capture_output=True, text=True, timeout=600
    )
    assert run.returncode == 0, run.stderr[-3000:]
