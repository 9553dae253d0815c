"""bwc.Contact and bwc.Contacts: the contact element from Python, against the sequence scene of
the same law, against an independent SciPy integration of the law, one against many, and bad
input."""

import os
import subprocess
import sys

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import bwc
from laws import CROSS_BWMCM, CROSS_BWSHCCM, CROSS_MASS

# Table 4's BWSHCCM (the Cross baseball), as in fixtures/cross_shccm.toml.
LAW = CROSS_BWSHCCM
M, G = CROSS_MASS, 9.81


def host_bounces(contact, h0, bounces, dt):
    """A ball dropped from h0 on a floor, its contact the element, tracked by penetration: a
    predictor-corrector of step dt (the prediction tried on a copy). (v_in, v_out) per contact,
    from the free flight on either side (exact there)."""
    y, v, force, v_in, out = h0, 0.0, 0.0, None, []
    while len(out) < bounces:
        predicted = v + (force / M - G) * dt
        trial = contact.copy().advance_penetration(dt, -y, -v, -(y + 0.5 * dt * (v + predicted)), -predicted)
        v1 = v + trial.impulse / M - G * dt
        y1 = y + 0.5 * dt * (v + v1)
        step = contact.advance_penetration(dt, -y, -v, -y1, -v1)
        if step.began_at is not None:
            v_in = G * step.began_at - v
        if step.separated_at is not None:
            out.append((v_in, v1 + G * (dt - step.separated_at)))
        y, v, force = y1, v1, step.force
    return np.array(out)


@pytest.mark.parametrize("policy", ["reset", "carry"])
def test_a_python_host_bounces_as_the_sequence_scene(policy):
    """The host's error is O(dt^2) of the contact (about 2 ms): 1e-7 relative at dt = 1 us."""
    scene = {"model": "shccm", "sequence": {"h0": 0.02, "bounces": 2, "policy": policy},
             "physical": {"m": M, **LAW}}
    reference = np.array([(b.v_in, b.v_out) for b in bwc.simulate(scene).runs[0].bounces])
    host = host_bounces(bwc.Contact("shccm", LAW, policy=policy), 0.02, 2, 1e-6)
    np.testing.assert_allclose(host, reference, rtol=1e-6)


def scipy_law(t_end, u, rtol=1e-12):
    """The BWSHCCL integrated by SciPy: x' = u, z' = A u - beta |z|^(n-1) z |u| - gamma |z|^n u,
    F = -alpha k |x|^(p-1) x - (1-alpha) k |z|^(p-1) z - c |x|^p u, from rest; (x, z, F) at
    t_end."""
    k, c, n, p, alpha, beta, gamma, a = (LAW[key] for key in ("k", "c", "n", "p", "alpha", "beta", "gamma", "A"))

    def rhs(t, s):
        x, z = s
        w = u(t)
        return [w, a * w - beta * abs(z) ** (n - 1) * z * abs(w) - gamma * abs(z) ** n * w]

    sol = solve_ivp(rhs, (0, t_end), [0.0, 0.0], method="DOP853", rtol=rtol, atol=1e-18)
    x, z = sol.y[:, -1]
    w = u(t_end)
    return x, z, -alpha * LAW["k"] * abs(x) ** (p - 1) * x - (1 - alpha) * k * abs(z) ** (p - 1) * z - c * abs(x) ** p * w


def test_the_element_integrates_the_law_as_scipy_does():
    """A compression at a velocity rising linearly from -2 m/s, in host steps of 20 us: the
    element's state and force at each step's end are SciPy's to 1e-8 (both integrate to about
    1e-10 and beyond)."""
    u = lambda t: -2.0 + 2.0e3 * t
    contact = bwc.Contact("shccm", LAW)
    dt = 2e-5
    for i in range(20):
        step = contact.advance(dt, u(i * dt), u((i + 1) * dt))
        x, z, force = scipy_law((i + 1) * dt, u)
        np.testing.assert_allclose(contact.state, [x, z], rtol=1e-8)
        assert step.force == pytest.approx(force, rel=1e-8)


def test_many_contacts_are_each_one_contact_on_any_thread_count():
    speeds = -np.linspace(0.5, 3.0, 64)
    many = bwc.Contacts("shccm", LAW, 64, policy="carry")
    for _ in range(30):
        out = many.advance(2e-5, speeds, speeds + 0.1)
        speeds = speeds + 0.1
    one = bwc.Contact("shccm", LAW, policy="carry")
    u = -3.0
    for _ in range(30):
        step = one.advance(2e-5, u, u + 0.1)
        u += 0.1
    assert out["force"][-1] == step.force  # the same arithmetic, bit for bit
    np.testing.assert_array_equal(many.state[-1], one.state)
    assert many.dissipated[-1] == one.dissipated and many.contacts[-1] == one.contacts
    # One thread gives the same bits as this process's pool.
    script = (
        "import numpy as np, bwc, sys; s = -np.linspace(0.5, 3.0, 64); m = bwc.Contacts('shccm', %r, 64, policy='carry')\n"
        "for _ in range(30):\n    o = m.advance(2e-5, s, s + 0.1); s = s + 0.1\n"
        "sys.stdout.write(o['force'].tobytes().hex())" % LAW
    )
    env = dict(os.environ, RAYON_NUM_THREADS="1")
    single = subprocess.run([sys.executable, "-c", script], env=env, capture_output=True, text=True, check=True)
    assert single.stdout == out["force"].tobytes().hex()


def test_penetration_steps_find_onsets_in_many_contacts():
    """Contacts whose overlap begins at different instants in one step: each onset is where the
    linear penetration crosses 0."""
    many = bwc.Contacts("mcm", CROSS_BWMCM, 4)
    d0 = np.array([-4e-6, -1e-6, -3e-6, -5e-6])  # m, approaching at 1 m/s
    out = many.advance_penetration(1e-5, d0, np.ones(4), d0 + 1e-5, np.ones(4))
    np.testing.assert_allclose(out["began_at"], -d0 / 1.0, rtol=1e-12)
    assert np.all(out["force"] > 0) and np.all(many.in_contact)


def test_bad_input_is_named_and_changes_nothing():
    with pytest.raises(bwc.BwcError, match='model: "hertz" is not a model'):
        bwc.Contact("hertz", LAW)
    with pytest.raises(bwc.BwcError, match=r'params\["A"\] is missing'):
        bwc.Contact("shccm", {key: v for key, v in LAW.items() if key != "A"})
    with pytest.raises(bwc.BwcError, match=r'params\["kk"\]: not a parameter'):
        bwc.Contact("shccm", {**LAW, "kk": 1.0})
    with pytest.raises(bwc.BwcError, match=r"`alpha` = 1\.5 is not admissible"):
        bwc.Contact("shccm", {**LAW, "alpha": 1.5})
    with pytest.raises(bwc.BwcError, match='policy: "keep"'):
        bwc.Contact("shccm", LAW, policy="keep")
    with pytest.raises(bwc.BwcError, match="`rtol` = 1 is not admissible"):
        bwc.Contact("shccm", LAW, rtol=1.0)
    contact = bwc.Contact("shccm", LAW)
    contact.advance(1e-5, -1.0, -1.0)
    before = (contact.state.copy(), contact.absorbed, contact.force)
    with pytest.raises(bwc.BwcError, match="`dt` = 0 is not admissible"):
        contact.advance(0.0, -1.0, -1.0)
    with pytest.raises(bwc.BwcError, match="`depth_end` = NaN is not admissible"):
        contact.advance_penetration(1e-5, 0.0, 1.0, float("nan"), 1.0)
    np.testing.assert_array_equal(contact.state, before[0])
    assert (contact.absorbed, contact.force) == before[1:]

    many = bwc.Contacts("shccm", LAW, 3)
    u = np.array([-1.0, np.nan, -1.0])
    with pytest.raises(bwc.BwcError, match=r"contact 1 .*`u_start` = NaN.*no contact was advanced"):
        many.advance(1e-5, u, u)
    assert not np.any(many.in_contact)
    with pytest.raises(bwc.BwcError, match="u_end: 2 values for 3 contacts"):
        many.advance(1e-5, [-1.0] * 3, [-1.0] * 2)
    with pytest.raises(bwc.BwcError, match=r"index\[1\] = 3: not a contact: 0 <= index < 3"):
        many.advance(1e-5, [-1.0] * 2, [-1.0] * 2, index=[0, 3])
    with pytest.raises(bwc.BwcError, match=r"index\[1\] = 0: named twice"):
        many.advance(1e-5, [-1.0] * 2, [-1.0] * 2, index=[0, 0])
    with pytest.raises(bwc.BwcError, match="count = 0"):
        bwc.Contacts("shccm", LAW, 0)
    # A count whose elements no memory holds is refused before anything is allocated (it was a
    # panic: "capacity overflow").
    with pytest.raises(bwc.BwcError, match=r"count = 9223372036854775808 is not admissible: an integer, 1 <= count <= 100000000"):
        bwc.Contacts("shccm", LAW, 2**63)
    # A negative count was Python's OverflowError ("can't convert negative int to unsigned").
    for count, shown in [(-3, "-3"), (2.5, "2.5"), ("3", "'3'"), (True, "True")]:
        with pytest.raises(bwc.BwcError, match=r"^count = %s is not admissible" % shown):
            bwc.Contacts("shccm", LAW, count)


def test_arguments_of_the_wrong_type_are_named_in_pythons_terms():
    """A model, params, policy, key or array of the wrong type is a BwcError naming the
    argument and what it may be (they were the binding's "cannot be converted to 'PyString'"
    and numpy's ValueError)."""
    cases = [
        (lambda: bwc.Contact(3.5, LAW), r'^model = 3\.5 is not a model: the string "shccm", "mcm", "hunt-crossley", "kelvin-voigt", "thornton" or "jackson-green"$'),
        (lambda: bwc.Contact("shccm", [1, 2]), r"^params = \[1, 2\] is not admissible: a dict"),
        (lambda: bwc.Contact("shccm", {**LAW, 7: 1.0}), r"^params: the key 7 is not a parameter"),
        (lambda: bwc.Contact("shccm", LAW, policy=None), None),
        (lambda: bwc.Contact("shccm", LAW, policy=["reset"]), r"^policy = \['reset'\] is not a policy"),
        (lambda: bwc.Contacts(None, LAW, 2), r"^model = None is not a model"),
        (lambda: bwc.Contacts("shccm", "k=1", 2), r"^params = 'k=1' is not admissible"),
    ]
    for call, message in cases:
        if message is None:
            assert call().policy == "reset"
            continue
        with pytest.raises(bwc.BwcError, match=message):
            call()
    many = bwc.Contacts("shccm", LAW, 2)
    with pytest.raises(bwc.BwcError, match=r"^u_start: could not convert string to float: 'a': give numbers"):
        many.advance(1e-5, [-1.0, "a"], [-1.0, -1.0])
    with pytest.raises(bwc.BwcError, match=r"^index: .*'x'.*: give integers, the contacts to advance"):
        many.advance(1e-5, [-1.0], [-1.0], index=["x"])
    with pytest.raises(bwc.BwcError, match=r"^depth_end: .*: give numbers"):
        many.advance_penetration(1e-5, [0.0, 0.0], [1.0, 1.0], [{}, 1e-5], [1.0, 1.0])
    assert not np.any(many.in_contact)


def test_base_parameters_give_the_law_and_its_mass():
    """A law from base parameters (A = 1) at the mass T_b / U_b rebounds as the nondimensional
    model at those base parameters."""
    base = {"B_b": 0.6, "Gamma_b": -0.4, "kappa": 0.3, "sigma_b": 0.2, "n": 1.2, "p": 1.5,
            "U_b": 0.01, "T_b": 1e-3}
    contact = bwc.Contact("shccm", base)
    assert contact.mass == pytest.approx(0.1, rel=1e-15)
    v0, dt, v = 2.0, 1e-7, -2.0
    e_nd = bwc.cor("shccm", {**base}, v0).e
    # Two bodies of reduced mass m, no external force: v' = F/m, a predictor-corrector.
    force = 0.0
    while True:
        predicted = v + force / contact.mass * dt
        trial = contact.copy().advance(dt, v, predicted)
        v1 = v + trial.impulse / contact.mass
        step = contact.advance(dt, v, v1)
        if step.separated_at is not None:
            break
        v, force = v1, step.force
    v_out = v + (v1 - v) * step.separated_at / dt
    assert v_out / v0 == pytest.approx(e_nd, rel=1e-5)


def test_steps_the_law_cannot_be_integrated_over_say_what_helps():
    """A step too long for the solver, or too short for its ends' velocities, names the setting
    that helps (they were the solver's words alone, or 310 zeros)."""
    contact = bwc.Contact("shccm", LAW)
    with pytest.raises(bwc.BwcError, match=r"^advance: simulation failed: .*; take a shorter step dt"):
        contact.advance(1e308, -1.0, -1.0)
    with pytest.raises(bwc.BwcError, match=r"^advance: setting `dt` = 1e-310 is not admissible: a step long enough"):
        contact.advance(1e-310, -1.0, 1.0)
    assert not contact.in_contact and contact.contacts == 0


def test_the_test_laws_are_the_fixtures_table_4():
    """The laws the tests share are the scenes of `fixtures/cross_*.toml` (Table 4)."""
    import tomllib
    fixtures = os.path.join(os.path.dirname(__file__), "..", "..", "..", "fixtures")
    for name, law in [("cross_shccm.toml", CROSS_BWSHCCM), ("cross_mcm.toml", CROSS_BWMCM)]:
        with open(os.path.join(fixtures, name), "rb") as f:
            physical = tomllib.load(f)["physical"]
        assert physical == {"m": CROSS_MASS, **law}, name
