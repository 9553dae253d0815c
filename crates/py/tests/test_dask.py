"""The Dask path on a local cluster of two worker processes: the same results as local runs."""

import pathlib

import numpy as np
import pytest

import bwc

distributed = pytest.importorskip("dask.distributed")
FIXTURES = pathlib.Path(__file__).resolve().parents[3] / "fixtures"


@pytest.fixture(scope="module")
def client():
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None)
    with distributed.Client(cluster) as c:
        yield c
    cluster.close()


def test_cor_sweeps_on_workers_equal_local_runs(client):
    import bwc.dask

    rng = np.random.default_rng(3)
    params_list = [
        {"B_b": b, "Gamma_b": -b, "kappa": k, "sigma_b": 0.03, "n": 2.0, "p": 2.0}
        for b, k in zip(rng.uniform(0.5, 3, 6), rng.uniform(0.3, 0.8, 6))
    ]
    v0 = np.linspace(0.2, 5.0, 50)
    remote = bwc.dask.cor_sweep("shccm", params_list, v0, client)
    for p, r in zip(params_list, remote):
        local = bwc.cor("shccm", p, v0)
        assert np.array_equal(local["e"], r["e"]) and np.array_equal(local["rhs_evals"], r["rhs_evals"])


def test_the_workers_warnings_reach_the_client(client):
    import bwc.dask

    hc = {"B": 0, "Gamma": 0, "kappa": 0.3, "sigma": 0.5, "n": 1.5, "p": 1.5}
    with pytest.warns(bwc.BwcWarning, match=r"^params_list\[[01]\]: 1 of 1 runs did not separate") as caught:
        remote = bwc.dask.cor_sweep("shccm", [hc, {**hc, "sigma": 0.9}], None, client, solver={"t_max": 1.0})
    assert [str(w.message)[:16] for w in caught] == ["params_list[0]: ", "params_list[1]: "]
    assert [r["outcome"].tolist() for r in remote] == [["horizon"], ["horizon"]]


def test_fits_on_workers_equal_local_fits(client):
    import bwc.dask

    config = str(FIXTURES / "golf.toml")
    remote = bwc.dask.identify_many([config, config], client, seeds=[1, 2])
    for seed, r in zip([1, 2], remote):
        local = bwc.identify(config, seed=seed)
        for a, b in zip(local["fits"], r["fits"]):
            a.pop("wall_s"), b.pop("wall_s")
            assert a == b
    with pytest.raises(bwc.BwcError, match="seeds"):
        bwc.dask.identify_many([config], client, seeds=[1, 2])


def test_a_coverage_study_split_over_workers_equals_the_local_study(client):
    import bwc.dask

    config = str(FIXTURES / "golf.toml")
    local = bwc.coverage(config, replicates=4, first_seed=1, fit="Golf NDBWSHCCM")
    remote = bwc.dask.coverage(config, client, replicates=4, first_seed=1, chunk=2, fit="Golf NDBWSHCCM")
    local.pop("command"), remote.pop("command")
    assert local == remote
    assert [r["seed"] for r in remote["coverage"][0]["replicates"]] == [1, 2, 3, 4]


def cut(path, keep):
    """The checkpoint at ``path`` as a killed client leaves it: its head, ``keep`` finished
    entries and half of the next line."""
    lines = pathlib.Path(path).read_text().splitlines(keepends=True)
    pathlib.Path(path).write_text("".join(lines[:1 + keep]) + lines[1 + keep][:30])


def test_studies_on_workers_resume_from_their_checkpoints(client, tmp_path, quick):
    import bwc.dask

    config = quick("golf.toml")
    fit = "Golf NDBWSHCCM"
    local = bwc.coverage(config, replicates=6, fit=fit)
    checkpoint = tmp_path / "coverage.jsonl"
    bwc.dask.coverage(config, client, replicates=6, chunk=2, fit=fit, checkpoint=checkpoint)
    cut(checkpoint, 1)
    resumed = bwc.dask.coverage(config, client, replicates=6, chunk=2, fit=fit, checkpoint=checkpoint)
    assert resumed["coverage"] == local["coverage"]
    assert len(checkpoint.read_text().splitlines()) == 1 + 3

    sizes = {"fit": fit, "particles": 32, "runs": 3}
    local = bwc.posterior(config, **sizes)
    checkpoint = tmp_path / "posterior.jsonl"
    bwc.dask.posterior(config, client, **sizes, checkpoint=checkpoint)
    cut(checkpoint, 2)
    resumed = bwc.dask.posterior(config, client, **sizes, checkpoint=checkpoint)
    a, b = local.posteriors[0], resumed.posteriors[0]
    assert a.log_evidence == b.log_evidence and a.marginals == b.marginals
    assert np.array_equal(a.samples.weight, b.samples.weight)

    checkpoint = tmp_path / "fits.jsonl"
    bwc.dask.identify_many([config, config], client, seeds=[1, 2], checkpoint=checkpoint)
    cut(checkpoint, 1)
    resumed = bwc.dask.identify_many([config, config], client, seeds=[1, 2], checkpoint=checkpoint)
    for seed, r in zip([1, 2], resumed):
        for a, b in zip(bwc.identify(config, seed=seed)["fits"], r["fits"]):
            a.pop("wall_s"), b.pop("wall_s")
            assert a == b


def test_chains_begun_locally_resume_on_workers(client, tmp_path):
    import bwc.dask

    scene = str(FIXTURES / "granular_chain.toml")
    scenes = [scene] * 3
    checkpoint = tmp_path / "chains.jsonl"
    local = bwc.simulate_many(scenes, checkpoint=checkpoint)
    cut(checkpoint, 1)
    remote = bwc.dask.simulate_many(scenes, client, checkpoint=checkpoint)
    for a, b in zip(local, remote):
        a, b = dict(a), dict(b)
        a.pop("command"), b.pop("command")
        sa, sb = a.pop("samples", {}), b.pop("samples", {})
        assert a == b
        assert sorted(sa) == sorted(sb) and all(np.array_equal(sa[k], sb[k]) for k in sa)


KILLED = """
import sys
import bwc, bwc.dask
from dask.distributed import Client, LocalCluster

if __name__ == "__main__":
    with Client(LocalCluster(n_workers=1, threads_per_worker=1, processes=False,
                             dashboard_address=None)) as client:
        bwc.dask.coverage(sys.argv[1], client, replicates=16, chunk=1, fit=sys.argv[2],
                          checkpoint=sys.argv[3])
"""


def test_a_coverage_study_whose_client_is_killed_resumes_on_workers(client, tmp_path, quick):
    import os
    import signal
    import subprocess
    import sys
    import time

    import bwc.dask

    config = quick("golf.toml")
    fit = "Golf NDBWSHCCM"
    checkpoint = tmp_path / "coverage.jsonl"
    script = tmp_path / "study.py"
    script.write_text(KILLED)
    child = subprocess.Popen([sys.executable, str(script), config, fit, str(checkpoint)],
                             stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    began = time.monotonic()
    while time.monotonic() - began < 120 and child.poll() is None:
        if checkpoint.exists() and len(checkpoint.read_text().splitlines()) >= 1 + 3:
            break
        time.sleep(0.02)
    os.kill(child.pid, signal.SIGKILL)
    child.wait()
    done = len(checkpoint.read_text().splitlines()) - 1
    assert 3 <= done < 16, done
    resumed = bwc.dask.coverage(config, client, replicates=16, chunk=1, fit=fit, checkpoint=checkpoint)
    local = bwc.coverage(config, replicates=16, fit=fit)
    assert resumed["coverage"] == local["coverage"]
    assert len(checkpoint.read_text().splitlines()) - 1 == 16
