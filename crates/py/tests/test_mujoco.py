"""MuJoCo as a client: examples/python/mujoco_drop.py drops a baseball on a floor in MuJoCo with
the bwc law as its contact force, and its bounces are bwc's sequence scene of the same law."""

import importlib.util
import pathlib

import pytest

import bwc

pytest.importorskip("mujoco", reason="MuJoCo (PyPI) is the host simulator")
ROOT = pathlib.Path(__file__).resolve().parents[3]
spec = importlib.util.spec_from_file_location("mujoco_drop", ROOT / "examples" / "python" / "mujoco_drop.py")
example = importlib.util.module_from_spec(spec)
spec.loader.exec_module(example)


@pytest.mark.parametrize("policy", ["reset", "carry"])
def test_mujoco_bounces_as_the_sequence_scene(policy):
    """MuJoCo (RK4) holds the applied force constant over its step of dt; the element is advanced
    over each step, tried first with the motion the last force predicts. The impact speeds come
    from MuJoCo's free fall (exact); the rebound speeds carry the coupling's error, which falls
    with MuJoCo's step: below 2e-4 at dt = 1e-5 s against contacts of 1.5 ms, and at least twice
    smaller than at dt = 2e-5 s."""
    h0 = 0.05
    scene = {"model": "shccm", "sequence": {"h0": h0, "bounces": 2, "policy": policy},
             "physical": {"m": example.MASS, **example.LAW}}
    reference = [(b.v_in, b.v_out) for b in bwc.simulate(scene).runs[0].bounces]
    worst = {}
    for dt in (2e-5, 1e-5):
        _, heights, bounces = example.drop(h0=h0, t_end=0.3, dt=dt, policy=policy)
        assert len(bounces) >= 2 and heights.min() > -1e-3
        errors = [abs(got / want - 1) for b, r in zip(bounces, reference) for got, want in zip(b, r)]
        assert abs(bounces[0][0] / reference[0][0] - 1) < 1e-9  # the fall: exact
        worst[dt] = max(errors)
    assert worst[1e-5] < 2e-4, worst
    assert worst[1e-5] < worst[2e-5] / 2, worst


def test_mujocos_default_contact_barely_bounces():
    """What the plot in the guide shows: MuJoCo's default soft contact (critically damped)
    returns the ball to under 1 % of its drop height, the bwc law to about 70 %."""
    h0 = 0.05
    t, h, _ = example.drop(h0=h0, t_end=0.3, dt=1e-5, contact="mujoco")
    after = h[t > 0.15]
    assert after.max() < 0.01 * h0
    t, h, _ = example.drop(h0=h0, t_end=0.3, dt=1e-5)
    assert 0.6 * h0 < h[t > 0.15].max() < 0.8 * h0
