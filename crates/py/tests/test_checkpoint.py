"""Studies resumed from their checkpoints end with the results of uninterrupted runs: a coverage
study, a posterior and many chains, each cut part way (a partial last line included, as a kill
while writing leaves it) and run again with the same file."""

import json
import pathlib

import numpy as np
import pytest

import bwc

FIT = "DSA NDBWSHCCM"


def cut(path, keep):
    """The checkpoint at ``path`` as a kill leaves it: its head, ``keep`` finished entries and
    half of the next line; the number of entries it had."""
    lines = pathlib.Path(path).read_text().splitlines(keepends=True)
    pathlib.Path(path).write_text("".join(lines[:1 + keep]) + lines[1 + keep][:30])
    return len(lines) - 1


def entries(path):
    return len(pathlib.Path(path).read_text().splitlines()) - 1


def test_a_coverage_study_resumes_to_the_uninterrupted_study(tmp_path, quick):
    kharaz = quick("kharaz.toml")
    whole = bwc.coverage(kharaz, replicates=5, fit=FIT)
    checkpoint = tmp_path / "coverage.jsonl"
    first = bwc.coverage(kharaz, replicates=5, fit=FIT, checkpoint=checkpoint)
    assert first.coverage == whole.coverage
    assert cut(checkpoint, 2) == 5
    resumed = bwc.coverage(kharaz, replicates=5, fit=FIT, checkpoint=str(checkpoint))
    assert resumed.coverage == whole.coverage
    assert entries(checkpoint) == 5
    # The head names the command: a posterior cannot take this file.
    head = json.loads(checkpoint.read_text().splitlines()[0])
    assert head["command"] == "coverage" and head["version"] == bwc.__version__
    with pytest.raises(bwc.BwcError, match=r"a checkpoint of `coverage`, not of `posterior`"):
        bwc.posterior(kharaz, fit=FIT, checkpoint=checkpoint)
    with pytest.raises(bwc.BwcError, match=r"checkpoint = 3 is not admissible: a file path"):
        bwc.coverage(kharaz, replicates=1, fit=FIT, checkpoint=3)


def posterior_equal(a, b):
    a, b = a.posteriors[0], b.posteriors[0]
    assert a.log_evidence == b.log_evidence and a.evaluations == b.evaluations
    assert a.marginals == b.marginals and a.band == b.band
    for k in a.samples:
        assert np.array_equal(a.samples[k], b.samples[k]), k


def test_a_posterior_resumes_to_the_uninterrupted_posterior(tmp_path, quick, recwarn):
    kharaz = quick("kharaz.toml")
    sizes = {"fit": FIT, "particles": 32, "runs": 3}
    whole = bwc.posterior(kharaz, **sizes)
    checkpoint = tmp_path / "posterior.jsonl"
    bwc.posterior(kharaz, **sizes, checkpoint=checkpoint)
    # The reference search and three runs.
    assert cut(checkpoint, 2) == 4
    posterior_equal(bwc.posterior(kharaz, **sizes, checkpoint=checkpoint), whole)


def chain_scenes(count):
    scene = {"model": "shccm",
             "physical": {"k": 1e7, "c": 0.0, "n": 1.0, "p": 1.5, "alpha": 0.5, "beta": 0.0,
                          "gamma": 0.0, "A": 1.0},
             "chain": {"mass": [0.1, 0.2], "position": [0.0, 0.03], "length": 0.02,
                       "velocity": [1.0, 0.0], "horizon": 0.1},
             "output": {"dt": 1e-3}}
    return [{**scene, "chain": {**scene["chain"], "mass": [0.1, 0.1 + 0.05 * i]}}
            for i in range(count)]


def chains_equal(a, b):
    assert len(a) == len(b)
    for x, y in zip(a, b):
        x, y = dict(x), dict(y)
        sx, sy = x.pop("samples"), y.pop("samples")
        assert x == y
        assert sorted(sx) == sorted(sy)
        for k in sx:
            assert sx[k].dtype == sy[k].dtype and np.array_equal(sx[k], sy[k], equal_nan=True), k


def test_many_chains_resume_to_the_uninterrupted_study(tmp_path):
    scenes = chain_scenes(9)
    whole = bwc.simulate_many(scenes)
    checkpoint = tmp_path / "chains.jsonl"
    # One thread: batches of four, each recorded when it ends.
    chains_equal(bwc.simulate_many(scenes, threads=1, checkpoint=checkpoint), whole)
    assert cut(checkpoint, 5) == 9
    chains_equal(bwc.simulate_many(scenes, checkpoint=checkpoint), whole)
    assert entries(checkpoint) == 9
    # A changed scene is computed again, the others taken.
    changed = scenes[:8] + [{**scenes[8], "chain": {**scenes[8]["chain"], "horizon": 0.05}}]
    chains_equal(bwc.simulate_many(changed, checkpoint=checkpoint), bwc.simulate_many(changed))
    assert entries(checkpoint) == 10


def test_many_fits_resume_to_the_uninterrupted_fits(tmp_path, quick, recwarn):
    kharaz = quick("kharaz.toml")
    whole = bwc.identify(kharaz, seed=2)
    checkpoint = tmp_path / "run.jsonl"
    bwc.identify(kharaz, seed=2, checkpoint=checkpoint)
    assert cut(checkpoint, 1) == 4
    resumed = bwc.identify(kharaz, seed=2, checkpoint=checkpoint)
    for a, b in zip(whole.fits, resumed.fits):
        a.pop("wall_s"), b.pop("wall_s")
        assert a == b
    assert entries(checkpoint) == 4
