"""bwc.Contact with the comparison laws by name (Hunt-Crossley, Kelvin-Voigt, Thornton): a
host bouncing a ball on each against an independent SciPy integration of the same law written
out here, and what is wrong with a law's name or parameters said."""

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import bwc
from hosts import rebound

M, V0, DT = 0.145, 2.0, 1e-6


def host_rebound(contact):
    """A ball of mass M meeting a fixed floor at V0, its contact the element, stepped by the
    host of hosts.py at DT: the rebound speed."""
    return rebound(contact, M, V0, DT)


def scipy_rebound(force, delta_dot0=V0):
    """The rebound speed of M delta'' = -force(delta, delta') from delta = 0 at V0, ended where
    the force falls to 0 while the ball leaves, by SciPy's DOP853."""

    def ended(t, y):
        return force(y[0], y[1]) if y[1] < 0 else 1.0

    ended.terminal, ended.direction = True, -1
    sol = solve_ivp(
        lambda t, y: [y[1], -force(y[0], y[1]) / M],
        (0, 1.0), [0.0, delta_dot0], method="DOP853", rtol=1e-12, atol=1e-16, events=ended,
    )
    return -sol.y_events[0][0][1]


def test_a_hunt_crossley_contact_rebounds_as_scipy_integrates_it():
    k, alpha = 1e7, 0.3
    want = scipy_rebound(lambda d, dd: k * max(d, 0.0) ** 1.5 * (1 + 1.5 * alpha * dd))
    got = host_rebound(bwc.Contact("hunt-crossley", {"k": k, "alpha": alpha}))
    assert abs(got - want) < 1e-6 * want, (got, want)
    assert want < 0.8 * V0


def test_a_kelvin_voigt_contact_rebounds_as_scipy_integrates_it():
    k, c = 1e5, 40.0
    want = scipy_rebound(lambda d, dd: k * d + c * dd)
    got = host_rebound(bwc.Contact("kelvin-voigt", {"k": k, "c": c}))
    assert abs(got - want) < 1e-6 * want, (got, want)


def test_a_thornton_contact_rebounds_as_scipy_integrates_it():
    """Thornton's loading (Hertz to delta_y, then its tangent) to the deepest point, then the
    Hertz unloading of the flattened sphere, k_p (delta - delta_f)^(3/2), integrated in two
    phases; the element's state names the deepest point."""
    k, delta_y = 1e7, 2e-5

    def loading(d):
        if d <= delta_y:
            return k * max(d, 0.0) ** 1.5
        return k * delta_y ** 1.5 + 1.5 * k * delta_y ** 0.5 * (d - delta_y)

    turn = lambda t, y: y[1]
    turn.terminal = True
    first = solve_ivp(lambda t, y: [y[1], -loading(y[0]) / M], (0, 1.0), [0.0, V0],
                      method="DOP853", rtol=1e-12, atol=1e-16, events=turn)
    d_m = first.y_events[0][0][0]
    f_m = loading(d_m)
    d_f = d_m - f_m / (k * d_m ** 0.5)
    k_p = k * (k * d_m ** 1.5 / f_m) ** 0.5
    # Energy along the elastic unloading: M v^2 / 2 = (2/5) k_p (d_m - d_f)^(5/2).
    want = (2 * 0.4 * k_p * (d_m - d_f) ** 2.5 / M) ** 0.5
    contact = bwc.Contact("thornton", {"k": k, "delta_y": delta_y})
    got = host_rebound(contact)
    assert abs(got - want) < 1e-6 * want, (got, want)
    assert d_m > 2 * delta_y and want < 0.9 * V0
    assert contact.model == "thornton" and contact.state.shape == (2,)
    assert abs(-contact.state[1] - d_m) < 1e-6 * d_m


def test_many_contacts_of_a_law_by_name():
    many = bwc.Contacts("kelvin-voigt", {"k": 1e5, "c": 40.0}, 3)
    many.advance(1e-6, np.full(3, -1.0), np.full(3, -1.0))
    assert many.state.shape == (3, 1) and many.model == "kelvin-voigt"


@pytest.mark.parametrize(
    "model, params, message",
    [
        ("hertz", {}, r'^model: "hertz" is not a model: "shccm", "mcm", "hunt-crossley", "kelvin-voigt", "thornton" or "jackson-green"$'),
        ("thornton", {"k": 1e7}, r"^params: law \"thornton\": parameter `delta_y` is missing; the law takes: k, delta_y$"),
        ("thornton", {"k": 1e7, "delta_y": 1e-5, "R": 0.01}, r"`R` is not one of its parameters, which are: k, delta_y"),
        ("kelvin-voigt", {"k": 1e5, "c": -1.0}, r"`c` = -1 is not admissible: c >= 0 \(N s/m\)"),
        ("hunt-crossley", {"k": "stiff", "alpha": 0.1}, r'^params\["k"\]: not a number$'),
        ("hunt-crossley", [1e7, 0.1], r"^params = \[10000000\.0, 0\.1\] is not admissible: a dict of the law's parameters \(k, alpha\)$"),
    ],
)
def test_bad_laws_by_name_are_named(model, params, message):
    with pytest.raises(bwc.BwcError, match=message):
        bwc.Contact(model, params)
