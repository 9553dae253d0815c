"""bwc.posterior against an independent evidence computed with SciPy's quadrature, its samples
as numpy arrays, identical on any thread or worker count, and its errors."""

import math
import warnings
import pathlib

import numpy as np
import pytest

import bwc

FIXTURES = pathlib.Path(__file__).resolve().parents[3] / "fixtures"
TRUTH = {"B_b": 1.0, "Gamma_b": -1.0, "kappa": 0.6, "sigma_b": 0.03, "n": 1.5, "p": 1.5}
SPEEDS = [0.3, 0.8, 1.5, 2.5, 4.0]
NOISE = 0.01


def _data(tmp_path, noise=NOISE, speeds=SPEEDS, column="e_std"):
    """Synthetic CoRs of the truth with seeded Gaussian noise, the noise column beside them."""
    rng = np.random.default_rng(5)
    e = np.asarray(bwc.cor("shccm", TRUTH, speeds).e) + rng.normal(0, NOISE, len(speeds))
    path = tmp_path / "data.csv"
    lines = ["v_0,e,%s" % column] + ["%r,%r,%r" % (v, float(x), noise) for v, x in zip(speeds, e)]
    path.write_text("\n".join(lines) + "\n")
    return path, e


def _config(path, **extra):
    """kappa free in [0.3, 0.9], the rest fixed at the truth."""
    fixed = {k: v for k, v in TRUTH.items() if k not in ("kappa", "Gamma_b")}
    fixed["g"] = -1.0
    fit = {"name": "kappa", "model": "shccm", "data": str(path), "bounds": {"kappa": [0.3, 0.9]},
           "fixed": fixed, "posterior": {"particles": 300, "runs": 4}}
    fit.update(extra)
    return {"fit": [fit]}


def test_the_evidence_and_the_posterior_of_one_quantity_match_scipy_quadrature(tmp_path):
    integrate = pytest.importorskip("scipy.integrate")
    path, e = _data(tmp_path)

    def likelihood(kappa):
        model = np.asarray(bwc.cor("shccm", {**TRUTH, "kappa": kappa}, SPEEDS).e)
        r = (model - e) / NOISE
        return math.exp(-0.5 * float(r @ r) - len(e) * math.log(NOISE * math.sqrt(2 * math.pi)))

    # The prior is uniform on [0.3, 0.9]: Z = ∫ L dκ / 0.6.
    z, _ = integrate.quad(likelihood, 0.3, 0.9, points=[0.6], limit=200, epsabs=0)
    mean, _ = integrate.quad(lambda k: k * likelihood(k), 0.3, 0.9, points=[0.6], limit=200, epsabs=0)
    exact, exact_mean = math.log(z / 0.6), mean / z

    # Eight runs: the error is their spread, and four runs estimate a spread poorly.
    p = bwc.posterior(_config(path, posterior={"particles": 300, "runs": 8}), seed=3).posteriors[0]
    assert abs(p.log_evidence - exact) < 3 * p.log_evidence_error < 0.1, (p.log_evidence, exact)
    s = p.samples
    got_mean = float(np.sum(s.weight * s.kappa))
    sd = math.sqrt(float(np.sum(s.weight * (s.kappa - got_mean) ** 2)))
    assert abs(got_mean - exact_mean) < 0.1 * sd, (got_mean, exact_mean, sd)
    assert p.marginals.kappa.lo < exact_mean < p.marginals.kappa.hi
    assert abs(float(s.weight.sum()) - 1) < 1e-12 and len(s.weight) == 2400
    assert set(s) >= {"B_b", "Gamma_b", "kappa", "sigma_b", "n", "p", "weight", "run", "log_likelihood"}
    assert "e_std" in p.noise


def test_a_sampled_noise_scale_is_a_sampled_quantity(tmp_path):
    path, _ = _data(tmp_path)
    config = _config(path, posterior={"particles": 100, "runs": 2, "noise": "sampled", "sigma_e": [1e-4, 0.3]})
    p = bwc.posterior(config).posteriors[0]
    assert sorted(p.marginals) == ["kappa", "sigma_e"]
    # Five residuals of scale 0.01: the noise's posterior holds it, far from its bounds.
    assert p.marginals.sigma_e.lo < NOISE < p.marginals.sigma_e.hi < 0.1
    assert len(p.samples.sigma_e) == 200


def test_results_do_not_depend_on_the_thread_count(tmp_path):
    path, _ = _data(tmp_path)
    config = _config(path, posterior={"particles": 64, "runs": 2})
    one, two = (bwc.posterior(config, seed=9, threads=t).posteriors[0] for t in (1, 2))
    assert np.array_equal(one.samples.kappa, two.samples.kappa)
    assert np.array_equal(one.samples.weight, two.samples.weight)
    assert one.log_evidence == two.log_evidence


def test_bad_input_is_named(tmp_path):
    path, _ = _data(tmp_path)
    with pytest.raises(bwc.BwcError, match=r"prior.*kappa.*outside the bounds"):
        bwc.posterior(_config(path, prior={"kappa": {"normal": [1.5, 0.1]}}))
    one, _ = _data(tmp_path, speeds=[1.0])
    with pytest.raises(bwc.BwcError, match="at least 2"):
        bwc.posterior(_config(one))
    zero, _ = _data(tmp_path, noise=0.0)
    with pytest.raises(bwc.BwcError, match=r"data.csv:2: column `e_std`: 0 is not a noise scale"):
        bwc.posterior(_config(zero))
    with pytest.raises(bwc.BwcError, match="runs = 1"):
        bwc.posterior(_config(path), runs=1)
    with pytest.raises(bwc.BwcError, match="names no"):
        bwc.posterior(_config(path), fit="nope")


def test_a_gaussian_prior_narrows_the_posterior(tmp_path):
    path, _ = _data(tmp_path)
    flat = bwc.posterior(_config(path, posterior={"particles": 100, "runs": 2})).posteriors[0]
    narrow = bwc.posterior(_config(path, posterior={"particles": 100, "runs": 2},
                                   prior={"kappa": {"normal": [0.6, 0.005]}})).posteriors[0]
    width = lambda p: p.marginals.kappa.hi - p.marginals.kappa.lo
    assert width(narrow) < 0.8 * width(flat)
    assert narrow.priors == [{"quantity": "kappa", "normal": [0.6, 0.005]}]


def test_runs_spread_over_dask_workers_equal_the_local_posterior(tmp_path):
    distributed = pytest.importorskip("dask.distributed")
    import bwc.dask

    path, _ = _data(tmp_path)
    config = _config(path, posterior={"particles": 64, "runs": 3})
    local = bwc.posterior(config, seed=4)
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None)
    with distributed.Client(cluster) as client:
        remote = bwc.dask.posterior(config, client, seed=4)
    cluster.close()
    a, b = local.posteriors[0], remote.posteriors[0]
    assert np.array_equal(a.samples.kappa, b.samples.kappa)
    assert np.array_equal(a.samples.weight, b.samples.weight)
    assert a.log_evidence == b.log_evidence and a.band == b.band


def test_runs_that_weigh_regions_differently_are_a_warning(tmp_path):
    """The tennis drops' NDBWSHCCM posterior (B_b in three regions) warns that its runs disagree
    (at 200 particles a run as at the default 500, medians of B_b 1.19 to 1.49); the one-region
    posterior of kappa does not."""
    with pytest.warns(bwc.BwcWarning, match="runs disagree on B_b"):
        bwc.posterior(str(FIXTURES / "tennis.toml"), fit="Tennis NDBWSHCCM", particles=200)
    path, _ = _data(tmp_path)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        bwc.posterior(_config(path))
    assert not [w for w in caught if "runs disagree" in str(w.message)]
