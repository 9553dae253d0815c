"""Shared helpers of the package's tests."""

import pathlib

import pytest

FIXTURES = pathlib.Path(__file__).resolve().parents[3] / "fixtures"


@pytest.fixture
def quick(tmp_path):
    """A function writing ``fixtures/<name>`` into ``tmp_path`` with two starts per fit, and
    returning its path: for tests of how a study is cut, resumed or spread over workers, which
    do not depend on the search's budget (a quarter of the default's time)."""

    def write(name):
        text = (FIXTURES / name).read_text()
        text = text.replace('data = "data/', f'data = "{FIXTURES / "data"}/')
        text = text.replace(
            "[fit.bounds]", "[fit.optimizer]\nstarts = 2\nmax_starts = 2\n\n[fit.bounds]"
        )
        path = tmp_path / f"quick-{name}"
        path.write_text(text)
        return str(path)

    return write
