"""bwc_contact.fmu (FMI 2.0 Co-Simulation) imported by FMPy, a tool no one here wrote: its model
description validates, and a ball dropped on a floor whose contact is the FMU bounces as bwc's
own sequence scene of the same law."""

import pathlib
import subprocess

import numpy as np
import pytest

import bwc
from laws import CROSS_BWSHCCM, CROSS_MASS

fmpy = pytest.importorskip("fmpy", reason="FMPy (PyPI) imports the FMU")
from fmpy import extract, read_model_description  # noqa: E402
from fmpy.fmi2 import FMU2Slave  # noqa: E402
from fmpy.validation import validate_fmu  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[3]
LAW = CROSS_BWSHCCM
M, G = CROSS_MASS, 9.81


@pytest.fixture(scope="module")
def fmu(tmp_path_factory):
    """The FMU as scripts/build-fmu builds it."""
    path = tmp_path_factory.mktemp("fmu") / "bwc_contact.fmu"
    subprocess.run([str(ROOT / "scripts" / "build-fmu"), str(path)], check=True, capture_output=True)
    return path


def test_the_model_description_validates(fmu):
    assert validate_fmu(str(fmu)) == []
    md = read_model_description(str(fmu))
    assert md.fmiVersion == "2.0" and md.coSimulation.canGetAndSetFMUstate


class Master:
    """FMPy driving the FMU: instantiate, set the law's parameters, initialize."""

    def __init__(self, fmu, policy):
        md = read_model_description(str(fmu))
        self.vr = {v.name: v.valueReference for v in md.modelVariables}
        self.slave = FMU2Slave(guid=md.guid, unzipDirectory=extract(str(fmu)),
                               modelIdentifier=md.coSimulation.modelIdentifier, instanceName="ball")
        self.slave.instantiate()
        self.slave.setupExperiment(startTime=0.0)
        self.slave.setInteger([self.vr["model"], self.vr["policy"]], [0, 1 if policy == "carry" else 0])
        self.slave.setReal([self.vr[k] for k in LAW], list(LAW.values()))
        self.slave.enterInitializationMode()
        self.slave.exitInitializationMode()
        self.t = 0.0

    def step(self, dt, y, v, accel):
        """One step from the ball's height y and velocity v with the relative acceleration
        accel over it: the impulse and the force at its end."""
        s, vr = self.slave, self.vr
        s.setReal([vr["delta"], vr["delta_dot"]], [-y, -v])
        s.setRealInputDerivatives([vr["delta_dot"]], [1], [-accel])
        s.doStep(self.t, dt)
        return s.getReal([vr["impulse"], vr["force"]])


def fmu_flights(fmu, policy, h0, bounces, dt):
    """The ball of tests/test_contact.py's host, its contact the FMU: a predictor-corrector whose
    prediction is tried and rolled back with fmi2GetFMUstate / fmi2SetFMUstate (in flight the
    prediction is exact and taken at once). After each contact: the flight's energy per unit
    mass v^2/2 + g y (J/kg, exact in flight) and the work absorbed by the contact so far (J)."""
    master = Master(fmu, policy)
    s, vr = master.slave, master.vr
    y, v, force, out = h0, 0.0, 0.0, []
    while len(out) < bounces:
        accel = force / M - G
        if force == 0.0 and y + dt * (v + 0.5 * dt * accel) > 1e-6:
            impulse, force1 = master.step(dt, y, v, accel)
        else:
            state = s.getFMUstate()
            impulse, _ = master.step(dt, y, v, accel)
            s.setFMUstate(state)
            s.freeFMUstate(state)
            v1 = v + impulse / M - G * dt
            impulse, force1 = master.step(dt, y, v, (v1 - v) / dt)
        v1 = v + impulse / M - G * dt
        y, v, force = y + 0.5 * dt * (v + v1), v1, force1
        master.t += dt
        if s.getInteger([vr["contacts"]])[0] > len(out):
            out.append((0.5 * v * v + G * y, s.getReal([vr["absorbed"]])[0]))
    s.terminate()
    s.freeInstance()
    return np.array(out)


@pytest.mark.parametrize("policy", ["reset", "carry"])
def test_a_ball_on_the_fmu_bounces_as_the_sequence_scene(fmu, policy):
    """The flight after each contact has the scene's energy, v_out^2/2 + g y_s (y_s: the height of
    the separation, from the scene's x_s), and the FMU's absorbed work is the energy the ball lost:
    to 1e-6, the master's O(dt^2) at dt = 1 us against contacts of 2 ms."""
    h0 = 0.01
    scene = {"model": "shccm", "sequence": {"h0": h0, "bounces": 2, "policy": policy},
             "physical": {"m": M, **LAW}}
    bounces = bwc.simulate(scene).runs[0].bounces
    x_s = np.array([b.x_s for b in bounces])
    # Reset: each contact starts from the law at rest where the last one separated; carry: the
    # law's displacement goes on from the first onset.
    y_s = np.cumsum(x_s) if policy == "reset" else x_s
    energy = np.array([0.5 * b.v_out ** 2 for b in bounces]) + G * y_s
    flights = fmu_flights(fmu, policy, h0, 2, 1e-6)
    np.testing.assert_allclose(flights[:, 0], energy, rtol=1e-6)
    np.testing.assert_allclose(flights[:, 1], M * (G * h0 - energy), rtol=1e-6)


def logged_slave(fmu):
    """An instance of the FMU whose logger's messages are collected: (slave, value references,
    messages)."""
    from fmpy import calloc, free
    from fmpy.fmi2 import (fmi2CallbackAllocateMemoryTYPE, fmi2CallbackFreeMemoryTYPE, fmi2CallbackFunctions,
                           fmi2CallbackLoggerTYPE)

    messages = []
    callbacks = fmi2CallbackFunctions()
    callbacks.logger = fmi2CallbackLoggerTYPE(lambda env, name, status, cat, msg: messages.append(msg.decode()))
    callbacks.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
    callbacks.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
    md = read_model_description(str(fmu))
    vr = {v.name: v.valueReference for v in md.modelVariables}
    slave = FMU2Slave(guid=md.guid, unzipDirectory=extract(str(fmu)),
                      modelIdentifier=md.coSimulation.modelIdentifier, instanceName="bad")
    slave.instantiate(callbacks=callbacks)
    # The callbacks must outlive the instance: kept with it.
    slave.bwc_callbacks = callbacks
    return slave, vr, messages


def test_bad_input_is_refused_and_named_through_the_logger(fmu):
    slave, vr, messages = logged_slave(fmu)
    slave.setReal([vr["k"]], [-1.0])
    slave.enterInitializationMode()
    with pytest.raises(Exception):
        slave.exitInitializationMode()
    assert "fmi2ExitInitializationMode: parameter `k` = -1 is not admissible: k > 0" in messages[-1]
    slave.reset()
    slave.setupExperiment(startTime=0.0)
    slave.enterInitializationMode()
    slave.exitInitializationMode()
    with pytest.raises(Exception):
        slave.setReal([vr["delta"]], [float("nan")])
    assert "input `delta` = NaN is not admissible" in messages[-1]
    with pytest.raises(Exception):
        slave.setReal([vr["k"]], [2.0])
    assert "parameter `k` is fixed once initialized" in messages[-1]
    with pytest.raises(Exception):
        slave.doStep(0.0, -1e-6)
    assert "communicationStepSize = -1e-6 is not admissible" in messages[-1]
    slave.setReal([vr["delta"], vr["delta_dot"]], [1e-5, 1.0])
    slave.doStep(0.0, 1e-6)
    assert slave.getReal([vr["force"]])[0] > 0
    # Steps the law cannot be integrated over say which setting helps (they named nothing: the
    # solver's "step size too small", "initial value not finite").
    with pytest.raises(Exception):
        slave.doStep(1e-6, 1e308)
    assert "take a shorter communicationStepSize" in messages[-1]
    with pytest.raises(Exception):
        slave.doStep(1e-6, 4e-306)
    assert messages[-1].startswith("fmi2DoStep: communicationStepSize = 4e-306 is not admissible: a step long enough")
    slave.terminate()
    slave.freeInstance()


def test_a_thornton_contact_in_the_fmu_rebounds_at_thorntons_closed_form(fmu):
    """model = 4 selects Thornton's elastic-plastic sphere, its parameters thornton.k and
    thornton.delta_y. A ball of mass M meeting the floor at v0 without gravity rebounds at
    Thornton's (1997) e = (6 sqrt(3) / 5)^(1/2) (1 - r^2/6)^(1/2) (r / (r + 2 sqrt(6/5 - r^2/5)))^(1/4),
    r = v_y / v0, with the yield speed from (5/4) M v_y^2 = k delta_y^(5/2): to 1e-6 at dt = 1 us."""
    k, v0, r, dt = 1e7, 2.0, 0.3, 1e-6
    delta_y = (1.25 * M * (r * v0) ** 2 / k) ** 0.4
    md = read_model_description(str(fmu))
    vr = {v.name: v.valueReference for v in md.modelVariables}
    s = FMU2Slave(guid=md.guid, unzipDirectory=extract(str(fmu)),
                  modelIdentifier=md.coSimulation.modelIdentifier, instanceName="thornton")
    s.instantiate()
    s.setupExperiment(startTime=0.0)
    s.setInteger([vr["model"]], [4])
    s.setReal([vr["thornton.k"], vr["thornton.delta_y"]], [k, delta_y])
    s.enterInitializationMode()
    s.exitInitializationMode()

    def step(t, y, v, accel):
        s.setReal([vr["delta"], vr["delta_dot"]], [-y, -v])
        s.setRealInputDerivatives([vr["delta_dot"]], [1], [-accel])
        s.doStep(t, dt)
        return s.getReal([vr["impulse"], vr["force"]])

    t, y, v, force = 0.0, 0.0, -v0, 0.0
    while s.getInteger([vr["contacts"]])[0] == 0:
        state = s.getFMUstate()
        impulse, _ = step(t, y, v, force / M)
        s.setFMUstate(state)
        s.freeFMUstate(state)
        impulse, force = step(t, y, v, impulse / M / dt)
        v1 = v + impulse / M
        y, v, t = y + 0.5 * dt * (v + v1), v1, t + dt
    s.terminate()
    s.freeInstance()
    want = (6 * 3 ** 0.5 / 5) ** 0.5 * (1 - r * r / 6) ** 0.5 * (r / (r + 2 * (1.2 - 0.2 * r * r) ** 0.5)) ** 0.25
    assert abs(v / v0 - want) < 1e-6, (v / v0, want)


def test_the_other_laws_parameters_are_checked_under_their_fmu_names(fmu):
    slave, vr, messages = logged_slave(fmu)
    with pytest.raises(Exception):
        slave.setInteger([vr["model"]], [9])
    assert "parameter `model` = 9 is not admissible: 0: BWSHCCM" in messages[-1]
    slave.setInteger([vr["model"]], [4])
    slave.setReal([vr["thornton.delta_y"]], [-1.0])
    slave.enterInitializationMode()
    with pytest.raises(Exception):
        slave.exitInitializationMode()
    assert "parameter `thornton.delta_y` = -1 is not admissible: delta_y > 0 (m)" in messages[-1]
    slave.freeInstance()
