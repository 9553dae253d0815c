"""The Python package against the command-line tools' JSON and against independent SciPy
implementations of the nondimensional models (closed forms where they exist)."""

import json
import math
import os
import pathlib
import subprocess
import warnings

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq
from scipy.special import beta as beta_fn

import bwc
from laws import CROSS_BWSHCCM, CROSS_MASS

ROOT = pathlib.Path(__file__).resolve().parents[3]
FIXTURES = ROOT / "fixtures"
BIN = pathlib.Path(os.environ.get("BWC_BIN_DIR", ROOT / "target" / "release"))


def cli(tool, *args):
    """The one JSON object a command-line tool prints (without its command line)."""
    exe = BIN / tool
    assert exe.exists(), f"{exe} missing: build the workspace first (cargo test --release) or set BWC_BIN_DIR"
    out = subprocess.run([str(exe), *args], check=True, capture_output=True, text=True)
    value = json.loads(out.stdout)
    value.pop("command")
    return value


def hunt_crossley_e(sigma):
    """e is the root in (0, min(1, 1/sigma)) of sigma - ln(1 + sigma) = -sigma e - ln(1 - sigma e)."""
    g = lambda e: sigma - math.log1p(sigma) + sigma * e + math.log1p(-sigma * e)
    return brentq(g, 1e-12, min(1.0, 1.0 / sigma) * (1 - 1e-12), xtol=1e-15)


def ndbwshccm_e(B, Gamma, kappa, sigma, n, p):
    """An independent NDBWSHCCM: X' = V, Z' = V - B|Z|^(n-1) Z |V| - Gamma |Z|^n V,
    V' = F = -kappa |X|^(p-1) X - (1-kappa) |Z|^(p-1) Z - sigma |X|^p V, from (0, 0, -1) to the
    first instant after contact with F <= 0 <= V (SciPy's DOP853 with events)."""

    def force(y):
        x, z, v = y
        return -kappa * abs(x) ** (p - 1) * x - (1 - kappa) * abs(z) ** (p - 1) * z - sigma * abs(x) ** p * v

    def rhs(_t, y):
        x, z, v = y
        zdot = v - B * abs(z) ** (n - 1) * z * abs(v) - Gamma * abs(z) ** n * v
        return [v, zdot, force(y)]

    # After the maximum compression (v = 0) the force decreases to zero while v >= 0.
    def released(_t, y):
        return force(y) if y[2] > 0 else 1.0

    released.terminal = True
    released.direction = -1
    sol = solve_ivp(rhs, (0, 50), [0.0, 0.0, -1.0], method="DOP853", rtol=1e-12, atol=1e-14, events=released)
    return sol.y_events[0][0][2]


def test_the_docstring_examples_run(monkeypatch):
    """The Examples of every docstring (numpydoc) are what they say, from the repository's root."""
    import doctest

    monkeypatch.chdir(ROOT)
    result = doctest.testmod(bwc, verbose=False)
    assert result.attempted >= 15 and result.failed == 0, result
    for name in ("cor", "simulate", "identify", "coverage"):
        doc = getattr(bwc, name).__doc__
        for section in ("Parameters\n", "Returns\n", "Raises\n", "Examples\n"):
            assert section in doc, (name, section)


@pytest.mark.filterwarnings("error::bwc.BwcWarning")  # checked separations: nothing to warn of
def test_cor_meets_the_closed_forms():
    for sigma in (0.05, 0.5, 0.9):
        out = bwc.cor("shccm", {"B": 0, "Gamma": 0, "kappa": 0.3, "sigma": sigma, "n": 1.5, "p": 1.5})
        assert out["separated"][0] and out["outcome"].tolist() == ["separated"]
        assert abs(out["e"][0] - hunt_crossley_e(sigma)) < 1e-10
    # Elastic limit: e = 1, T_s = 2/(p+1) s_max B(1/(p+1), 1/2), s_max = ((p+1)/2)^(1/(p+1)).
    for p in (1.0, 1.5, 2.5):
        out = bwc.cor("mcm", {"B": 0, "Gamma": 0, "kappa": 0.6, "sigma": 1e-17, "n": 2, "p": p})
        s_max = ((p + 1) / 2) ** (1 / (p + 1))
        t_s = 2 / (p + 1) * s_max * beta_fn(1 / (p + 1), 0.5)
        assert abs(out["e"][0] - 1) < 1e-10 and abs(out["t_s"][0] - t_s) < 1e-9 * t_s


def test_each_cor_carries_its_error_estimate():
    """By default a CoR is checked to solver["e_tol"] = 1e-10 and says by how much it may be off;
    a loose rtol is tightened until the check holds; e_tol = 0 is one run at rtol."""
    hc = {"B": 0, "Gamma": 0, "kappa": 0.3, "sigma": 0.5, "n": 1.5, "p": 1.5}
    want = hunt_crossley_e(0.5)
    checked = bwc.cor("shccm", hc)
    assert 0 <= checked["e_error"][0] <= 1e-11 and abs(checked["e"][0] - want) < 1e-11
    assert checked["check"][0] == "met"
    loose = {"rtol": 1e-5, "series": False}
    tightened = bwc.cor("shccm", hc, solver=loose)
    assert tightened["e_error"][0] <= 1e-11 and abs(tightened["e"][0] - want) < 1e-10
    single = bwc.cor("shccm", hc, solver={**loose, "e_tol": 0})
    assert np.isnan(single["e_error"][0]) and abs(single["e"][0] - want) > 1e-9
    assert single["check"][0] == "off"
    assert single["rhs_evals"][0] < tightened["rhs_evals"][0]
    assert np.isnan(checked["tighter_failed_rtol"][0]) and not checked["tighter_out_of_steps"][0]
    # A tighter run that needs more steps than allowed: the check stops at the run before it.
    run = bwc.simulate({"model": "shccm", "nondimensional": hc,
                        "solver": {**loose, "e_tol": 0}})["runs"][0]
    limit = run["accepted"] + run["rejected"]
    with pytest.warns(bwc.BwcWarning, match=r"1 of 1 CoRs did not meet \[solver\]\.e_tol = 1e-18"):
        short = bwc.cor("shccm", hc, solver={**loose, "e_tol": 1e-18, "max_steps": limit})
    assert short["check"][0] == "unmet" and short["tighter_out_of_steps"][0]
    assert short["tighter_failed_rtol"][0] == 1e-7
    # A target double precision cannot check is met in double-double arithmetic (the default).
    assert not checked["double_double"][0]
    precise = bwc.cor("shccm", hc, solver={"series": False, "e_tol": 1e-15})
    assert precise["double_double"][0] and precise["check"][0] == "met"
    assert abs(precise["e"][0] - want) < 2e-15  # the reference's own xtol is 1e-15
    with pytest.warns(bwc.BwcWarning, match="did not meet"):
        double = bwc.cor("shccm", hc, solver={"series": False, "e_tol": 1e-15, "double_double": False})
    assert not double["double_double"][0] and double["check"][0] == "unmet"
    assert precise["double_double_declined"][0] == double["double_double_declined"][0] == "none"
    # The phase path where asked for: the same CoR without time steps, checked to e_tol.
    phase = bwc.cor("shccm", hc, solver={"phase": True})
    assert phase["phase"][0] and not checked["phase"][0] and phase["rhs_evals"][0] == 0
    assert phase["check"][0] == "met" and abs(phase["e"][0] - want) < 1e-10


def test_a_stiff_unmet_cor_says_why_double_double_was_not_tried():
    # Case 5523 of the stress sweep's seed 3 (STABILITY.md, "Double-double"); the reference
    # 0.127578645362 is Verner's 9(8), Verner's 7(6) and DOP853 at rtol 3e-15.
    base = {"B_b": 35.85524463149488, "Gamma_b": -35.85524463149488,
            "kappa": 0.2754451940192927, "sigma_b": 0.012827185718774515, "n": 10,
            "p": 5.367702693104487}
    with pytest.warns(bwc.BwcWarning, match=r"1 of 2 CoRs did not meet .*: v0 = 506\.9132 m/s\)") as caught:
        out = bwc.cor("mcm", base, [506.91324093318553, 1.0])
    # One warning of the unmet check (and the hint that 507 m/s may be mm/s).
    assert len([w for w in caught if "did not meet" in str(w.message)]) == 1
    assert list(out["check"]) == ["unmet", "met"]
    assert list(out["double_double_declined"]) == ["stiff", "none"]
    assert abs(out["e"][0] - 0.127578645362) < out["e_error"][0]


def test_a_run_that_meets_its_horizon_warns_and_names_the_setting():
    hc = {"B": 0, "Gamma": 0, "kappa": 0.3, "sigma": 0.5, "n": 1.5, "p": 1.5}
    with pytest.warns(bwc.BwcWarning, match=r"1 of 1 runs did not separate by \[solver\]\.t_max = 0\.5 "
                      r"\(outcome \"horizon\", e = 0: run\): the horizon came first; raise \[solver\]\.t_max"):
        out = bwc.cor("shccm", hc, solver={"t_max": 0.5})
    assert out["outcome"].tolist() == ["horizon"] and out["e"][0] == 0
    # The setting it names works: the contact lasts about 3.4 (nondimensional).
    with warnings.catch_warnings():
        warnings.simplefilter("error", bwc.BwcWarning)
        assert bwc.cor("shccm", hc, solver={"t_max": 5.0})["outcome"].tolist() == ["separated"]


def test_a_long_sweep_is_interpolated_to_the_closed_form():
    speeds = np.geomspace(0.1, 6.0, 500)
    hc = {"B_b": 0, "Gamma_b": 0, "kappa": 0.5, "sigma_b": 0.3, "n": 1, "p": 1.5}
    out = bwc.cor("shccm", hc, speeds)
    want = np.array([hunt_crossley_e(0.3 * v) for v in speeds])
    assert out["interpolated"].sum() >= 490
    assert (out["rhs_evals"][out["interpolated"]] == 0).all()
    assert (out["check"][out["interpolated"]] == "none").all()
    assert np.abs(out["e"] - want).max() < 1e-11
    every = bwc.cor("shccm", hc, speeds, sweep={"interpolate": False})
    assert not every["interpolated"].any() and (every["rhs_evals"] > 0).all()
    assert (every["check"] == "met").all()
    assert np.abs(out["e"] - every["e"]).max() < 1e-11
    assert np.abs(out["t_s"] / every["t_s"] - 1).max() < 2e-11


def test_a_sweep_too_noisy_to_interpolate_warns_and_names_the_setting():
    # Plain DOP853 without the stops at kinks: e is about 4e-7 off at rtol 1e-8, and as noisy
    # in v0, so no interpolant holds to the default tolerance (the rtol, e_tol being off).
    dss1 = {"B_b": 2.38, "Gamma_b": -2.38, "kappa": 0.677, "sigma_b": 0.0348, "n": 2.93, "p": 2.62}
    plain = {"series": False, "stop_at_kinks": False, "method": "dop853", "e_tol": 0, "rtol": 1e-8,
             "atol": 1e-10}
    speeds = np.linspace(0.5, 5.0, 300)
    with pytest.warns(bwc.BwcWarning, match=r"no interpolant held to \[sweep\]\.tolerance 1e-8, "
                      r"so all 300 speeds were simulated") as caught:
        out = bwc.cor("shccm", dss1, speeds, solver=plain)
    assert not out["interpolated"].any()
    assert (out["sweep_gave_up"] == "noise").all()
    # Attributed to the caller's line, not to the package's wrapper.
    assert [pathlib.Path(w.filename).name for w in caught] == ["test_bwc.py"]
    # The setting the warning names lets the sweep interpolate, and then nothing is said.
    with warnings.catch_warnings():
        warnings.simplefilter("error", bwc.BwcWarning)
        loose = bwc.cor("shccm", dss1, speeds, solver=plain, sweep={"tolerance": 1e-5})
    assert loose["interpolated"].sum() > 250


def test_a_kink_in_e_needs_more_speeds_and_the_warning_says_so():
    # Table 4's baseball law (the README's example): e(v0) has a kink near 2.97 m/s. 200 speeds
    # over 0.5-10 m/s cannot pay for pieces around it; 2,000 can, and then nothing is said.
    law = {"m": CROSS_MASS, **CROSS_BWSHCCM}
    with pytest.warns(bwc.BwcWarning, match="changes too sharply .* more speeds let the sweep isolate"):
        few = bwc.cor("shccm", law, np.linspace(0.5, 10.0, 200))
    assert not few["interpolated"].any()
    assert (few["sweep_gave_up"] == "too-few-speeds").sum() >= 20
    assert np.isin(few["sweep_gave_up"], ["too-few-speeds", "budget"]).all()
    speeds = np.linspace(0.5, 10.0, 2000)
    with warnings.catch_warnings():
        warnings.simplefilter("error", bwc.BwcWarning)
        many = bwc.cor("shccm", law, speeds)
    assert many["interpolated"].sum() > 1500
    assert (many["sweep_gave_up"][many["interpolated"]] == "none").all()
    # The interpolated rows agree with simulations at the same speeds (every tenth speed).
    every = bwc.cor("shccm", law, speeds[::10], sweep={"interpolate": False})
    assert np.abs(many["e"][::10] - every["e"]).max() < 1e-11


def test_cor_matches_an_independent_scipy_model():
    rng = np.random.default_rng(7)
    for _ in range(6):
        B = rng.uniform(0, 3)
        q = dict(B=B, Gamma=rng.uniform(-1, 1) * B, kappa=rng.uniform(0.1, 0.9), sigma=rng.uniform(0, 0.5),
                 n=rng.uniform(1, 3), p=rng.uniform(1, 3))
        out = bwc.cor("shccm", q)
        assert abs(out["e"][0] - ndbwshccm_e(**q)) < 1e-8, q


CROSS = {"m": CROSS_MASS, **CROSS_BWSHCCM}


def test_cor_equals_the_simulate_tool():
    speeds = np.linspace(1.0, 5.0, 9)
    out = bwc.cor("shccm", CROSS, speeds)
    scene = {"model": "shccm", "v0": speeds.tolist(), "physical": CROSS}
    runs = bwc.simulate(scene)["runs"]
    assert [r["e"] for r in runs] == out["e"].tolist()
    assert [r["rhs_evals"] for r in runs] == out["rhs_evals"].tolist()
    # And the command-line tool on the fixture, key for key.
    for name in ("kharaz_curves.toml", "two_balls_mcm.toml"):
        mine = bwc.simulate(FIXTURES / name)
        mine.pop("command")
        for run in mine["runs"]:
            run.pop("trajectory", None)  # numpy arrays the JSON does not carry
        theirs = cli("bwc-simulate", "run", str(FIXTURES / name), "--json")
        assert mine["runs"] == theirs["runs"] and mine["units"] == theirs["units"]


def test_trajectories_come_as_numpy_arrays_equal_to_the_tools_csv(tmp_path):
    scene = FIXTURES / "two_balls_shccm.toml"
    run = bwc.simulate(scene)["runs"][0]
    traj = run["trajectory"]
    subprocess.run([str(BIN / "bwc-simulate"), "run", str(scene), "--out", str(tmp_path)], check=True,
                   capture_output=True)
    csv = np.genfromtxt(tmp_path / "trajectory.csv", delimiter=",", names=True)
    for name in ("t", "x", "v", "u", "F", "z"):
        assert np.array_equal(traj[name], csv[name]), name
    assert traj["t"][-1] == run["t_s"]


def test_identify_equals_the_identify_tool():
    config = FIXTURES / "golf.toml"
    mine = bwc.identify(config, seed=3)
    theirs = cli("bwc-identify", "run", str(config), "--json", "--seed", "3")
    mine.pop("command")
    for a, b in zip(mine["fits"], theirs["fits"]):
        a.pop("wall_s"), b.pop("wall_s")
        assert a == b


def test_bad_input_raises_bwc_error_with_the_tools_message():
    with pytest.raises(bwc.BwcError, match=r'^params\["kappa"\]: 1\.5 is not admissible: 0 < kappa < 1'):
        bwc.cor("shccm", {"B": 0, "Gamma": 0, "kappa": 1.5, "sigma": 0.5, "n": 1, "p": 1.5})
    with pytest.raises(ValueError, match="cannot tell the description"):
        bwc.cor("shccm", {"x": 1})
    with pytest.raises(bwc.BwcError, match="v0"):
        bwc.cor("shccm", CROSS, [-1.0])
    with pytest.raises(bwc.BwcError, match="more than 20 steps"):
        bwc.cor("shccm", CROSS, [2.0], solver={"max_steps": 20, "switch_when_stiff": False})
    with pytest.raises(bwc.BwcError, match="not a model"):
        bwc.simulate({"model": "nope", "nondimensional": {"B": 0}})


PAPER_DSS = {"B_b": 2.38, "Gamma_b": -2.38, "kappa": 0.677, "sigma_b": 0.0348, "n": 2.93, "p": 2.62}


def test_results_are_objects_with_attributes_and_dicts_still():
    out = bwc.cor("shccm", PAPER_DSS, [1.0, 3.0])
    assert isinstance(out, bwc.Cor) and isinstance(out, dict)
    assert out.e is out["e"] and out.check.tolist() == ["met", "met"]
    assert repr(out).startswith("Cor(2 speeds: e=[0.8461, 0.7655]")
    with pytest.raises(AttributeError, match="Cor has no 'E'; its keys: e, t_s"):
        out.E
    run = bwc.simulate(FIXTURES / "two_balls_shccm.toml").runs[0]
    assert isinstance(run, bwc.Run) and run.e == run["e"] and repr(run).startswith("Run(v0=2, e=")
    # Still JSON: a result without trajectories dumps as the tool's object.
    json.dumps(bwc.simulate({"model": "shccm", "v0": [1.0], "base": PAPER_DSS}))


def test_a_scalar_speed_gives_scalars():
    one = bwc.cor("shccm", PAPER_DSS, 3.0)
    many = bwc.cor("shccm", PAPER_DSS, [3.0])
    for key, value in one.items():
        assert np.ndim(value) == 0 and not isinstance(value, np.ndarray), key
        assert value == many[key][0] or (value != value and many[key][0] != many[key][0]), key
    assert isinstance(one.e, float) and isinstance(one.check, str) and isinstance(one.separated, bool)


def test_a_fits_parameters_go_straight_back_into_cor_and_simulate():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", bwc.BwcWarning)
        fit = bwc.identify(FIXTURES / "kharaz.toml").fits[0]
    assert isinstance(fit, bwc.Fit) and isinstance(fit.params, bwc.Params)
    assert fit.params.U_b is None and fit.params.T_b is None
    e = bwc.cor(fit.model, fit.params, [0.5, 3.0]).e
    runs = bwc.simulate({"model": fit.model, "v0": [0.5, 3.0], "base": fit.params}).runs
    assert [r.e for r in runs] == e.tolist()
    assert repr(fit.params).startswith("Params(B_b=1.178, Gamma_b=-1.166, kappa=0.5819")
    assert "U_b" not in repr(fit.params)


def test_the_version_is_the_packages():
    text = (ROOT / "crates" / "py" / "Cargo.toml").read_text()
    version = next(l.split('"')[1] for l in text.splitlines() if l.startswith("version"))
    assert bwc.__version__ == version


def test_errors_from_dicts_name_the_dict_key():
    with pytest.raises(bwc.BwcError, match=r'^solver\["rtol"\]: '):
        bwc.cor("shccm", PAPER_DSS, [1.0], solver={"rtol": -1.0})
    with pytest.raises(bwc.BwcError, match=r'^v0: -1 is not admissible'):
        bwc.cor("shccm", PAPER_DSS, [-1.0])
    with pytest.raises(bwc.BwcError, match=r'^params\["kappa"\]: .*number'):
        bwc.cor("shccm", dict(PAPER_DSS, kappa="x"), [1.0])
    with pytest.raises(bwc.BwcError, match=r'^scene\["base"\]\["kappa"\]: 1\.5 is not admissible'):
        bwc.simulate({"model": "shccm", "v0": [1.0], "base": dict(PAPER_DSS, kappa=1.5)})
    bounds = {"B_b": [0, 2], "g": [-1, 1], "kappa": [0.1, 0.9], "sigma_b": [0, 0.1], "n": [1, 6], "p": [1, 2]}
    data = str(FIXTURES / "data" / "kharaz_dss.csv")
    config = {"fit": [
        {"name": "a", "model": "shccm", "data": data, "bounds": bounds},
        {"name": "b", "model": "shcm", "data": data, "bounds": dict(bounds, n=[6, 1])},
    ]}
    with pytest.raises(bwc.BwcError) as caught:
        bwc.identify(config)
    lines = str(caught.value).splitlines()
    assert lines == [
        'config["fit"][1]["model"]: "shcm" is not a model: use "shccm" or "mcm" (the Bouc-Wen '
        'models), or a contact-law family: "hunt-crossley", "kelvin-voigt", "hertz-ln", "hertz-flores", '
        '"thornton"',
        'config["fit"][1]["bounds"]["n"]: [6, 1] is not admissible: lower bound <= upper bound',
    ], lines


def test_every_fit_warning_reaches_python_once_per_kind():
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = bwc.identify(FIXTURES / "golf_drops.toml")
    messages = [str(w.message) for w in caught if issubclass(w.category, bwc.BwcWarning)]
    for fit in result.fits:
        # Every warning of the fit is in one BwcWarning of its kind.
        for text in fit.warnings:
            assert sum(text in m for m in messages) == 1, text
        mine = [m for m in messages if m.startswith('"%s"' % fit.name)]
        assert len(mine) == len({m.split(":")[1] for m in mine}) or len(mine) <= 3
        assert any("on its" in m and "bound" in m for m in mine), mine
        # A drop-test fit says why it has no intervals.
        assert any("no intervals" in m for m in mine), mine
        assert fit.intervals.method is None and "drop-test fit" in fit.intervals.error


def test_unit_slips_warn_from_python():
    law = dict(CROSS)
    with pytest.warns(bwc.BwcWarning, match=r"if mm/s were meant, divide by 1000 \(3\.03 m/s\)"):
        bwc.cor("shccm", law, [2150.0, 3030.0])
    with pytest.warns(bwc.BwcWarning, match=r"if grams were meant"):
        bwc.cor("shccm", dict(law, m=145.0), [2.0])


def test_errors_and_warnings_are_the_packages_and_pickle():
    """BwcError and BwcWarning live in module ``bwc``, where they are imported from: they print
    as ``bwc.BwcError`` and cross processes (Dask workers, pytest-xdist) by pickle."""
    import pickle

    assert bwc.BwcError.__module__ == "bwc" and bwc.BwcWarning.__module__ == "bwc"
    for cls in (bwc.BwcError, bwc.BwcWarning):
        back = pickle.loads(pickle.dumps(cls("what went wrong")))
        assert type(back) is cls and back.args == ("what went wrong",)
    with pytest.raises(bwc.BwcError) as caught:
        bwc.cor({"model": "shccm"}, 1.0)
    assert pickle.loads(pickle.dumps(caught.value)).args == caught.value.args
