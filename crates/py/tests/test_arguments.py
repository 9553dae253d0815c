"""Bad arguments from Python get the command line's treatment: a BwcError naming the argument or
the dict key and what is admissible, never an internal message, a silent run or a raw
OverflowError; and results print what they hold."""

import pathlib

import numpy as np
import pytest

import bwc
from laws import CROSS_BWSHCCM

ROOT = pathlib.Path(__file__).resolve().parents[3]
FIXTURES = ROOT / "fixtures"
HUNT_CROSSLEY = {"B": 0, "Gamma": 0, "kappa": 0.5, "sigma": 0.5, "n": 1, "p": 1.5}
PAPER_DSS = {"B_b": 2.38, "Gamma_b": -2.38, "kappa": 0.677, "sigma_b": 0.0348, "n": 2.93, "p": 2.62}
LAW = CROSS_BWSHCCM


@pytest.mark.parametrize("value", [float("nan"), float("inf"), -float("inf")])
def test_a_number_that_is_not_finite_is_named_by_its_key(value):
    with pytest.raises(bwc.BwcError, match=r'^params\[\'sigma\'\] = .* is not admissible: a finite number'):
        bwc.cor("shccm", {**HUNT_CROSSLEY, "sigma": value})
    with pytest.raises(bwc.BwcError, match=r"^v0\[1\] = .* is not admissible: a finite impact speed > 0"):
        bwc.cor("shccm", PAPER_DSS, [1.0, value])
    with pytest.raises(bwc.BwcError, match=r"^solver\['rtol'\] = "):
        bwc.cor("shccm", PAPER_DSS, 1.0, solver={"rtol": value})
    scene = {"model": "shccm", "v0": [1.0], "base": {**PAPER_DSS, "kappa": value}}
    with pytest.raises(bwc.BwcError, match=r"^scene\['base'\]\['kappa'\] = "):
        bwc.simulate(scene)
    with pytest.raises(bwc.BwcError, match=r"^scene\['v0'\]\[0\] = "):
        bwc.simulate({**scene, "v0": [value], "base": PAPER_DSS})


def test_speeds_of_the_wrong_shape_are_named():
    with pytest.raises(bwc.BwcError, match=r"^v0: an array of shape \(2, 2\): give a scalar or a 1-D array"):
        bwc.cor("shccm", PAPER_DSS, np.ones((2, 2)))


@pytest.mark.parametrize("threads", [0, -1, 1025, 1.5, "2"])
def test_threads_outside_one_to_1024_are_refused(threads):
    with pytest.raises(bwc.BwcError, match=r"^threads = .* is not admissible: an integer in \[1, 1024\]"):
        bwc.cor("shccm", HUNT_CROSSLEY, threads=threads)
    with pytest.raises(bwc.BwcError, match=r"^threads = "):
        bwc.simulate({"model": "shccm", "v0": [1.0], "base": PAPER_DSS}, threads=threads)


def test_seeds_and_counts_outside_their_ranges_are_refused():
    config = FIXTURES / "kharaz.toml"
    with pytest.raises(bwc.BwcError, match=r"^seed = -1 is not admissible: an integer in \[0, 18446744073709551615\]"):
        bwc.identify(config, seed=-1)
    with pytest.raises(bwc.BwcError, match=r"^seed = 18446744073709551616 is not admissible"):
        bwc.identify(config, seed=2**64)
    with pytest.raises(bwc.BwcError, match=r"^replicates = 0 is not admissible: an integer in \[1, 100000\]"):
        bwc.coverage(config, replicates=0, fit="DSA NDBWSHCCM")
    with pytest.raises(bwc.BwcError, match=r"^first_seed = -3 is not admissible"):
        bwc.coverage(config, replicates=1, first_seed=-3, fit="DSA NDBWSHCCM")
    with pytest.raises(bwc.BwcError, match=r"^noise = -0.01 is not admissible"):
        bwc.coverage(config, replicates=1, noise=-0.01, fit="DSA NDBWSHCCM")
    with pytest.raises(bwc.BwcError, match=r"^particles = 8 is not admissible: an integer in \[16, 1000000\]"):
        bwc.posterior(config, fit="DSS NDBWSHCCM", particles=8)
    with pytest.raises(bwc.BwcError, match=r"^runs = 1 is not admissible: an integer in \[2, 10000\]"):
        bwc.posterior(config, fit="DSS NDBWSHCCM", runs=1)


def test_arrays_of_the_wrong_shape_given_to_contacts_are_named():
    many = bwc.Contacts("shccm", LAW, 4)
    with pytest.raises(bwc.BwcError, match=r"^u_start: an array of shape \(2, 2\): give a 1-D array"):
        many.advance(1e-5, np.full((2, 2), -2.0), np.full(4, -2.0))
    with pytest.raises(bwc.BwcError, match=r"^u_end: 3 values for 4 contacts"):
        many.advance(1e-5, np.full(4, -2.0), np.full(3, -2.0))
    assert not many.in_contact.any()


def test_the_package_namespace_holds_only_its_own_names():
    public = {n for n in dir(bwc) if not n.startswith("_")}
    assert public <= set(bwc.__all__) | {"dask"}, public - set(bwc.__all__)


def test_results_print_what_they_hold():
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", bwc.BwcWarning)
        fit = bwc.identify(FIXTURES / "kharaz.toml").fits[0]
    text = repr(fit.intervals)
    assert "params=Params(B_b=[" in text and "sigma_e=" in text and "dof=" in text, text
    text = repr(fit.predictions)
    assert text.startswith("Result(e=Result(above=Result(halfwidth=") and "summary='e is determined" in text, text
    chain = bwc.simulate(FIXTURES / "newtons_cradle.toml")
    assert repr(chain).startswith("Simulation(chain: horizon at t = 0.001 s, 5 bodies, 4 contacts"), repr(chain)
    contact = bwc.Contact("shccm", LAW)
    assert "force=0.0, dissipated=0.0" in repr(contact), repr(contact)
    # Rising through the onset depth at the step's start: the contact began there, at 0 s.
    step = contact.advance_penetration(1e-5, 0.0, 2.0, 2e-5, 2.0)
    assert step.began_at == 0.0, step
    assert "began_at=0.0" in repr(step), repr(step)
    assert "e0" not in repr(step) and "5e-324" not in repr(step), repr(step)


@pytest.mark.parametrize("call, message", [
    (lambda: bwc.cor(float("nan"), HUNT_CROSSLEY), r'^model = nan is not admissible: "shccm" \(BWSHCCM\) or "mcm"'),
    (lambda: bwc.cor({"kind": "sine"}, HUNT_CROSSLEY), r"^model = \{'kind': 'sine'\} is not admissible"),
    (lambda: bwc.cor("shccm", [0.5, None]), r"^params = \[0.5, None\] is not admissible: a dict of parameters"),
    (lambda: bwc.cor("shccm", None), r"^params = None is not admissible"),
    (lambda: bwc.cor("shccm", PAPER_DSS, "fast"), r"^v0 = 'fast' is not admissible: a speed or a 1-D array"),
    (lambda: bwc.cor("shccm", PAPER_DSS, 1.0, solver=1.5), r"^solver = 1.5 is not admissible: a dict as a scene's \[solver\] table"),
    (lambda: bwc.cor("shccm", PAPER_DSS, 1.0, input=[1.0]), r"^input = \[1.0\] is not admissible"),
])
def test_arguments_of_the_wrong_type_are_named(call, message):
    # These raised TypeError ("'<' not supported", "'float' object is not iterable") or reached
    # the JSON parser ("not a JSON-like dict: invalid number at line 1 column 12").
    with pytest.raises(bwc.BwcError, match=message):
        call()


def test_a_dict_or_list_where_a_value_belongs_names_its_key():
    """A dict given where a number or a string belongs names its key in the dict's terms (it
    was the parser's "invalid type: map, expected f64", naming nothing)."""
    hc = {"B": 0, "Gamma": 0, "kappa": 0.3, "sigma": 0.5, "n": 1.5, "p": 1.5}
    base = {"B_b": 1, "Gamma_b": 0, "kappa": 0.5, "sigma_b": 0.1, "n": 1, "p": 1.5}
    cases = [
        (lambda: bwc.cor("shccm", hc, solver={"rtol": {"a": 1}}),
         r'^solver\["rtol"\]: a dict given where a value belongs$'),
        (lambda: bwc.cor("shccm", hc, input={"kind": "constant", "value": {"x": 1}}),
         r'^input\["value"\]: a dict given where a number belongs$'),
        (lambda: bwc.simulate({"model": {"kind": "sine"}, "v0": [1.0], "base": base}),
         r'^scene\["model"\]: a dict given where a string in quotes belongs$'),
        (lambda: bwc.simulate({"model": "shccm", "v0": [1.0], "base": {**base, "B_b": {"x": 1}}}),
         r'^scene\["base"\]\["B_b"\]: a dict given where a number belongs$'),
    ]
    for call, message in cases:
        with pytest.raises(bwc.BwcError, match=message):
            call()
