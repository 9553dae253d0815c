"""Generated bad input at the FMU's boundary (STABILITY.md, "Generated bad input at every
boundary"): CASES sessions of bwc_contact.fmu driven by FMPy, each a valid session (instantiate,
set the law, initialize, step) with one to four calls replaced or added by generated ones:
setReal, setInteger, setBoolean and setRealInputDerivatives on every value reference (and on
references the FMU does not have, and of the wrong type) with hostile values (NaN, infinities,
zero, negatives, huge and tiny numbers, int32 extremes), doStep with hostile times and steps,
the mode changes out of order, getReal on any reference, reset. A call passes when it succeeds,
or fails with fmi2Error (or fmi2Warning) after a log message that names the variable, value
reference or argument concerned and holds no internal text; anything else (a crash, fmi2Fatal,
an error without a message, a message naming nothing, "panicked") is a failure, counted by kind
and shown with its session. A session that ends in an error state is reset or freed, as a
master would.

    scripts/build-fmu target/fmu/bwc_contact.fmu && pip install fmpy
    python3 benches/fmu_fuzz.py [CASES] [SEED] [FMU]     # default 100000, seed 1
"""

import collections
import math
import pathlib
import random
import re
import sys
import time

from fmpy import calloc, extract, free, read_model_description
from fmpy.fmi2 import (FMU2Slave, fmi2CallbackAllocateMemoryTYPE, fmi2CallbackFreeMemoryTYPE,
                       fmi2CallbackFunctions, fmi2CallbackLoggerTYPE)

ROOT = pathlib.Path(__file__).resolve().parents[1]
LAW = {"k": 117080063.0, "c": 5854003.0, "n": 1.1, "p": 1.7, "alpha": 0.1, "beta": 981.05,
       "gamma": -961.4, "A": 0.925}
INTERNAL = ("panicked", "internal", "unwrap", "RUST_BACKTRACE", "Rust")
# What a message may name: a variable, a value reference, or an argument of the call.
ARGUMENTS = ("value reference", "communicationStepSize", "currentCommunicationPoint", "order",
             "in phase")


def hostile_real(rng):
    return rng.choice([
        math.nan, math.inf, -math.inf, 0.0, -0.0, -1.0, 1e308, -1e308, 5e-324, 1e-300,
        rng.uniform(-2, 2), -rng.uniform(0, 1e9), 10 ** rng.uniform(-320, 308),
    ])


def hostile_int(rng):
    return rng.choice([0, 1, 2, -1, 3, 7, 2**31 - 1, -2**31, rng.randrange(-100, 100)])


class Session:
    """One FMU instance driven as a master drives it, its log kept."""

    def __init__(self, fmu):
        self.md = read_model_description(str(fmu))
        self.unzipped = extract(str(fmu))
        self.vr = {v.name: v.valueReference for v in self.md.modelVariables}
        self.types = {v.valueReference: v.type for v in self.md.modelVariables}
        self.messages = []
        callbacks = fmi2CallbackFunctions()
        callbacks.logger = fmi2CallbackLoggerTYPE(
            lambda env, name, status, cat, msg: self.messages.append((status, msg.decode())))
        callbacks.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
        callbacks.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
        self.callbacks = callbacks
        self.slave = None
        self.fresh()

    def fresh(self):
        if self.slave is not None:
            try:
                self.slave.freeInstance()
            except Exception:
                pass
        self.slave = FMU2Slave(guid=self.md.guid, unzipDirectory=self.unzipped,
                               modelIdentifier=self.md.coSimulation.modelIdentifier,
                               instanceName="fuzz")
        self.slave.instantiate(callbacks=self.callbacks)

    def start(self, rng):
        """A valid start: reset, the law, initialized; or left before initialization."""
        s = self.slave
        s.reset()
        s.setupExperiment(startTime=0.0)
        s.setReal([self.vr[k] for k in LAW], list(LAW.values()))
        s.setInteger([self.vr["model"], self.vr["policy"]], [rng.randrange(2), rng.randrange(2)])
        if rng.random() < 0.8:
            s.enterInitializationMode()
            s.exitInitializationMode()
            return True
        return False


def generated_call(rng, session, t):
    """A call with hostile arguments: its name, a function running it, and what its message
    may name (variables and arguments)."""
    names = list(session.vr)
    refs = list(session.vr.values()) + [0, 11, 99, 4096, 2**32 - 1]
    vr = rng.choice(refs)
    name = next((n for n, r in session.vr.items() if r == vr), None)
    named = ([name] if name else []) + [str(vr)]
    s = session.slave
    pick = rng.randrange(9)
    if pick == 0:
        x = hostile_real(rng)
        return "setReal(%d, %r)" % (vr, x), lambda: s.setReal([vr], [x]), named
    if pick == 1:
        i = hostile_int(rng)
        return "setInteger(%d, %d)" % (vr, i), lambda: s.setInteger([vr], [i]), named
    if pick == 2:
        b = rng.random() < 0.5
        return "setBoolean(%d, %r)" % (vr, b), lambda: s.setBoolean([vr], [b]), named
    if pick == 3:
        order, x = rng.choice([1, 0, 2, -1, 7]), hostile_real(rng)
        return ("setRealInputDerivatives(%d, %d, %r)" % (vr, order, x),
                lambda: s.setRealInputDerivatives([vr], [order], [x]), named + ["order"])
    if pick == 4:
        t0, dt = rng.choice([t, hostile_real(rng)]), hostile_real(rng)
        return "doStep(%r, %r)" % (t0, dt), lambda: s.doStep(t0, dt), []
    if pick == 5:
        return "getReal(%d)" % vr, lambda: s.getReal([vr]), named
    if pick == 6:
        return "getInteger(%d)" % vr, lambda: s.getInteger([vr]), named
    if pick == 7:
        call = rng.choice(["enterInitializationMode", "exitInitializationMode", "terminate"])
        return call, getattr(s, call), []
    delta, rate = hostile_real(rng), hostile_real(rng)
    return ("setReal(delta, delta_dot = %r, %r)" % (delta, rate),
            lambda: s.setReal([session.vr["delta"], session.vr["delta_dot"]], [delta, rate]),
            ["delta", "delta_dot"])


def judge(session, before, named):
    """The kind of failure of a call that raised (None when its message is as it should be)."""
    new = session.messages[before:]
    if not new:
        return "an error without a message"
    status, text = new[-1]
    if status >= 4:
        return "fmi2Fatal"
    if any(word in text for word in INTERNAL):
        return "internal text"
    names = any(("`%s`" % n) in text or re.search(r"\b%s\b" % re.escape(n), text) and n.isdigit()
                for n in named)
    if not (names or any(a in text for a in ARGUMENTS) or re.search(r"`\w+`", text)):
        return "a message naming nothing"
    return None


def main():
    cases = int(sys.argv[1]) if len(sys.argv) > 1 else 100_000
    seed = int(sys.argv[2]) if len(sys.argv) > 2 else 1
    fmu = pathlib.Path(sys.argv[3]) if len(sys.argv) > 3 else ROOT / "target/fmu/bwc_contact.fmu"
    rng = random.Random(seed)
    session = Session(fmu)
    failures = collections.Counter()
    examples = {}
    calls = errors = 0
    clock = time.perf_counter()
    for case in range(cases):
        try:
            initialized = session.start(rng)
        except Exception:
            session.fresh()
            initialized = session.start(rng)
        t, log = 0.0, []
        for _ in range(rng.randint(1, 4)):
            if initialized and rng.random() < 0.3:
                s = session.slave
                log.append("doStep(%r, 1e-6)" % t)
                try:
                    s.setReal([session.vr["delta"], session.vr["delta_dot"]], [1e-6, 1.0])
                    s.doStep(t, 1e-6)
                    t += 1e-6
                    continue
                except Exception:
                    pass
            what, call, named = generated_call(rng, session, t)
            log.append(what)
            before = len(session.messages)
            calls += 1
            try:
                call()
            except Exception:
                errors += 1
                kind = judge(session, before, named)
                if kind is not None:
                    failures[kind] += 1
                    examples.setdefault(kind, (log[:], session.messages[before:][-1:]))
                break
    seconds = time.perf_counter() - clock
    print("bwc_contact.fmu %8d sessions %8d generated calls %8d refused %6d failures"
          % (cases, calls, errors, sum(failures.values())))
    print("%.0f s" % seconds)
    for kind, count in failures.most_common():
        calls_made, message = examples[kind]
        print("FAIL %s: %d calls, e.g. %s" % (kind, count, message))
        print("    session %s" % "; ".join(calls_made))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
