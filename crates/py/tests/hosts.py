"""A host stepping a contact element: a body of mass m meeting a fixed floor at v0, the
element advanced with the relative velocity by a predictor-corrector of step dt (the
prediction tried on a copy). Used by the tests of the element laws."""


def rebound(contact, m, v0, dt, steps=100_000):
    """The rebound speed (m/s) of the host's body, on the last step's line at the
    separation."""
    v, force = -v0, 0.0
    for _ in range(steps):
        predicted = v + force / m * dt
        trial = contact.copy().advance(dt, v, predicted)
        corrected = v + trial.impulse / m
        step = contact.advance(dt, v, corrected)
        if step.separated_at is not None:
            return v + (corrected - v) * step.separated_at / dt
        v, force = corrected, step.force
    raise AssertionError("no separation within %d steps of %g s" % (steps, dt))
