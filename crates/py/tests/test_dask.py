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
