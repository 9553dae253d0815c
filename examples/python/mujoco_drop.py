"""A baseball dropped on a floor in MuJoCo, its normal contact force a bwc law.

MuJoCo's own contact is off for the ball (``contype = conaffinity = 0``); each MuJoCo step the
ball's penetration into the floor and its rate go to a :class:`bwc.Contact`, whose impulse over
the step is applied to the ball as an external force (``xfrc_applied``). The element's step is
first tried on a copy with the motion the last force predicts, then taken with the motion
MuJoCo made.

Run from the repository's root (``pip install mujoco matplotlib`` and the bwc package)::

    python examples/python/mujoco_drop.py figure.svg

It prints each contact's impact and rebound speeds beside bwc's ``[sequence]`` scene of the same
law, and draws the ball's height against time beside MuJoCo's default soft contact.
"""

import sys

import mujoco
import numpy as np

import bwc

# The BWSHCCM of the paper's Table 4 (Cross's baseball), and the ball.
LAW = {"k": 117080063.0, "c": 5854003.0, "n": 1.1, "p": 1.7, "alpha": 0.1, "beta": 981.05,
       "gamma": -961.4, "A": 0.925}
MASS, RADIUS, G = 0.145, 0.0366, 9.81


def model(h0, dt, mujoco_contact, integrator="RK4"):
    """The scene: a floor and a free ball whose lowest point is h0 (m) above it."""
    collide = 1 if mujoco_contact else 0
    xml = f"""
    <mujoco>
      <option timestep="{dt}" gravity="0 0 {-G}" integrator="{integrator}"/>
      <worldbody>
        <geom name="floor" type="plane" size="1 1 0.1"/>
        <body name="ball" pos="0 0 {h0 + RADIUS}">
          <freejoint/>
          <geom type="sphere" size="{RADIUS}" mass="{MASS}" contype="{collide}" conaffinity="{collide}"/>
        </body>
      </worldbody>
    </mujoco>"""
    return mujoco.MjModel.from_xml_string(xml)


def drop(h0=0.05, t_end=0.3, dt=1e-5, contact=None, policy="reset"):
    """Drops the ball; with ``contact=None`` its contact is the bwc law, with
    ``contact="mujoco"`` MuJoCo's default soft contact.

    Returns the times (s), the heights of the ball's lowest point (m), and per bwc contact its
    impact and rebound speeds (m/s), from the free flight on either side of the onset and the
    separation inside their steps.
    """
    m = model(h0, dt, contact == "mujoco")
    d = mujoco.MjData(m)
    ball = m.body("ball").id
    law = bwc.Contact("shccm", LAW, policy=policy) if contact is None else None
    times, heights, bounces = [], [], []
    force, v_in = 0.0, None
    while d.time < t_end:
        z, v = d.qpos[2], d.qvel[2]
        if law is not None:
            # The predicted step: semi-implicit Euler, as MuJoCo steps.
            v_pred = v + dt * (force / MASS - G)
            z_pred = z + dt * v_pred
            if law.in_contact or RADIUS - z_pred > law.onset_depth - 1e-6:
                trial = law.copy().advance_penetration(dt, RADIUS - z, -v, RADIUS - z_pred, -v_pred)
                d.xfrc_applied[ball, 2] = trial.impulse / dt
            else:
                d.xfrc_applied[ball, 2] = 0.0
        mujoco.mj_step(m, d)
        if law is not None:
            step = law.advance_penetration(dt, RADIUS - z, -v, RADIUS - d.qpos[2], -d.qvel[2])
            force = step.force
            if step.began_at is not None:
                v_in = G * step.began_at - v
            if step.separated_at is not None:
                bounces.append((v_in, d.qvel[2] + G * (dt - step.separated_at)))
        times.append(d.time)
        heights.append(d.qpos[2] - RADIUS)
    return np.array(times), np.array(heights), np.array(bounces)


def plot(path, h0=0.25, t_end=0.9):
    """The ball's height against time with the bwc law and with MuJoCo's default contact."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 3.6))
    for contact, label, style in [(None, "bwc law (BWSHCCM, Table 4)", "-"),
                                  ("mujoco", "MuJoCo's default soft contact", "--")]:
        t, h, _ = drop(h0=h0, t_end=t_end, dt=1e-5, contact=contact)
        ax.plot(t, h * 1e3, style, label=label)
    ax.set_xlabel("time (s)")
    ax.set_ylabel("height of the ball's lowest point (mm)")
    ax.set_title(f"A baseball dropped from {h0 * 1e3:.0f} mm in MuJoCo")
    ax.legend()
    fig.tight_layout()
    fig.savefig(path)


if __name__ == "__main__":
    _, _, bounces = drop()
    scene = {"model": "shccm", "sequence": {"h0": 0.05, "bounces": len(bounces)},
             "physical": {"m": MASS, **LAW}}
    reference = bwc.simulate(scene).runs[0].bounces
    print("Impact and rebound speeds (m/s) of a baseball dropped from 50 mm: MuJoCo with the bwc law")
    print("(RK4, 10 us steps) against bwc's [sequence] scene of the same law.")
    print("contact  v_in (MuJoCo)  v_in (bwc)  v_out (MuJoCo)  v_out (bwc)")
    for i, ((v_in, v_out), b) in enumerate(zip(bounces, reference), 1):
        print(f"{i:7d}  {v_in:13.6f}  {b.v_in:10.6f}  {v_out:14.6f}  {b.v_out:11.6f}")
    if len(sys.argv) > 1:
        plot(sys.argv[1])
