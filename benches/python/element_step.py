"""The contact element's cost from Python: the bounce of benches/src/bin/element-step.rs (a
baseball, Table 4's laws, at 2 m/s on a fixed floor, a predictor-corrector host in Python with
bwc.Contact: a copy and two element steps per host step), and bwc.Contacts advancing 10,000
contacts at once (one step each, the first 10 us of contacts at 1-3 m/s). Medians of seven
rounds.

    python benches/python/element_step.py      (with the bwc package installed)
"""

import statistics
import time

import numpy as np

import bwc

M, G, V_IN = 0.145, 9.81, 2.0
LAWS = {
    "shccm": {"k": 117080063.0, "c": 5854003.0, "n": 1.1, "p": 1.7, "alpha": 0.1, "beta": 981.05,
              "gamma": -961.4, "A": 0.925},
    "mcm": {"k": 253000000.0, "c": 2811.0, "n": 1.2, "p": 1.8, "alpha": 0.15, "beta": 1200.0,
            "gamma": -1200.0, "A": 1.01},
}


def bounce(model, dt):
    contact = bwc.Contact(model, LAWS[model])
    v, force, steps = -V_IN, 0.0, 0
    while True:
        guess = v + (force / M - G) * dt
        first = contact.copy().advance(dt, v, guess)
        nxt = v + first.impulse / M - G * dt
        step = contact.advance(dt, v, nxt)
        steps += 2
        if step.separated_at is not None:
            return steps
        v, force = nxt, step.force


def median_time(f, rounds=7):
    times = []
    for _ in range(rounds):
        t0 = time.perf_counter()
        f()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def main():
    print("model  dt (s)  element steps  us per step (host loop)  us per contact (batch of 10,000)")
    n = 10_000
    speeds = np.linspace(1.0, 3.0, n)
    for model in LAWS:
        for dt in (1e-4, 1e-5, 1e-6):
            steps = bounce(model, dt)
            t_bounce = median_time(lambda: bounce(model, dt))

            def batch():
                many = bwc.Contacts(model, LAWS[model], n)
                many.advance(dt, -speeds, -speeds)

            t_batch = median_time(batch)
            print(f"{model:<6} {dt:<7.0e} {steps:>14} {t_bounce * 1e6 / steps:>24.2f} {t_batch * 1e6 / n:>33.3f}")


if __name__ == "__main__":
    main()
