"""Generated bad input at the Python boundary (STABILITY.md, "Generated bad input at every
boundary"): CASES calls per function of `bwc.cor`, `bwc.simulate` (a scene as a dict),
`bwc.Contact` (with one `advance`) and `bwc.Contacts`, each from a valid call with one to three
arguments or keys replaced by a generated value (NaN, infinities, zero, negatives, huge and tiny
numbers, strings, None, lists, nested dicts, arrays of the wrong shape, integers beyond 64 bits,
unknown keys). A call passes when it returns, raises `bwc.BwcError` whose message names the
argument or key that was changed (or one the change made invalid) and holds no internal text,
or raises Python's `TypeError` for a value of the wrong type naming that argument in Python's
words; anything else (another exception type, a message naming nothing, "internal",
"panicked", a JSON parser's position, the binding's `PyString`) is a failure, counted by kind
and shown with its input.

    pip install ./crates/py
    python3 benches/python_fuzz.py [CASES] [SEED]        # default 100000 per function, seed 1
"""

import random
import re
import sys
import time
import warnings

import numpy as np

import bwc

HUNT_CROSSLEY = {"B": 0.0, "Gamma": 0.0, "kappa": 0.5, "sigma": 0.5, "n": 1.0, "p": 1.5}
PAPER_DSS = {"B_b": 2.38, "Gamma_b": -2.38, "kappa": 0.677, "sigma_b": 0.0348, "n": 2.93, "p": 2.62}
LAW = {"k": 117080063.0, "c": 5854003.0, "n": 1.1, "p": 1.7, "alpha": 0.1, "beta": 981.05,
       "gamma": -961.4, "A": 0.925, "m": 0.145}
SOLVER = {"rtol": 1e-8, "e_tol": 0.0, "max_steps": 2000}
INTERNAL = ("internal", "panicked", "line 1 column", "not a JSON", "RuntimeError", "PyO3",
            "unwrap", "Rust")


def bad_value(rng):
    """A value a careless or hostile caller might pass."""
    pick = rng.randrange(18)
    return [
        lambda: float("nan"), lambda: float("inf"), lambda: -float("inf"), lambda: 0.0,
        lambda: -rng.uniform(1e-300, 1e300), lambda: 10.0 ** rng.uniform(-320, 308),
        lambda: rng.choice(["", "shccm", "mcm", "fast", "1.0", "nan", "\x00", "é"]),
        lambda: None, lambda: [], lambda: [rng.random(), None],
        lambda: {"kind": rng.choice(["constant", "sine", "nope"]), "value": rng.random()},
        lambda: np.ones((2, 2)), lambda: np.array([]), lambda: 2 ** rng.randrange(63, 80),
        lambda: -(2 ** rng.randrange(1, 70)), lambda: rng.randrange(-3, 5),
        lambda: True, lambda: rng.uniform(-2.0, 2.0),
    ][pick]()


def mutate(rng, args):
    """`args` (a dict of arguments) with one to three entries, or keys of dict entries, replaced
    or added; returns the arguments and the names changed."""
    args = {k: (dict(v) if isinstance(v, dict) else v) for k, v in args.items()}
    changed = []
    for _ in range(rng.randint(1, 3)):
        name = rng.choice(list(args))
        value = args[name]
        if isinstance(value, dict) and value and rng.random() < 0.7:
            key = rng.choice(list(value) + ["unknown_key"])
            value[key] = bad_value(rng)
            changed += [name, key]
        else:
            args[name] = bad_value(rng)
            changed.append(name)
    return args, changed


def check(call, args, changed, failures, label):
    """Runs one case; records a failure with its input."""
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            call(**args)
        return
    except bwc.BwcError as e:
        text = str(e)
        if any(bad in text for bad in INTERNAL):
            why = "internal text"
        elif not any(str(n) in text for n in changed) and not named_elsewhere(text) \
                and not path_named(args, text):
            why = "names no argument changed"
        else:
            return
    except TypeError as e:
        # Python's own treatment of a value of the wrong type, as long as it names the argument
        # and speaks Python (not the binding's `PyString`, `PyDict`).
        text = str(e)
        if re.search(r"\bPy[A-Z]", text):
            why = "binding's type names"
        elif not any("'%s'" % n in text for n in changed):
            why = "TypeError naming no argument changed"
        else:
            return
    except KeyboardInterrupt:
        raise
    except BaseException as e:  # noqa: BLE001 - a panic is a BaseException; every other kind fails
        why, text = "raised %s" % type(e).__name__, str(e)
    failures.append((label, why, text[:300], repr(args)[:400]))


def path_named(args, text):
    """Whether a scene given as a path (a string) is named by the message (a file not found)."""
    return isinstance(args.get("scene"), str) and args["scene"] in text


def named_elsewhere(text):
    """Whether the message names an argument, key or table at all (a changed value can make
    another one inadmissible, as a bound against its partner)."""
    return any(word in text for word in ("params", "v0", "model", "solver", "input", "sweep",
                                         "threads", "scene", "policy", "rtol", "atol", "count",
                                         "dt", "u_start", "u_end", "["))


def cases(rng):
    """One generated case per function, in turn."""
    base = {"model": "shccm", "params": dict(HUNT_CROSSLEY), "v0": None,
            "solver": dict(SOLVER), "threads": 1}
    if rng.random() < 0.5:
        base = {**base, "params": dict(PAPER_DSS), "v0": [0.5, 1.0]}
    if rng.random() < 0.3:
        base = {**base, "input": {"kind": "constant", "value": -0.1}}
    yield "bwc.cor", lambda **a: bwc.cor(**a), *mutate(rng, base)

    scene = {"model": "shccm", "v0": [1.0], "base": dict(PAPER_DSS),
             "solver": dict(SOLVER), "output": {"trajectory": False}}
    args, changed = mutate(rng, {"scene": scene, "threads": 1})
    if isinstance(args["scene"], dict):
        args["scene"], more = mutate(rng, args["scene"])
        changed += more
    yield "bwc.simulate", lambda **a: bwc.simulate(**a), args, changed

    law = {"model": rng.choice(["shccm", "mcm"]), "params": dict(LAW), "policy": "reset",
           "rtol": 1e-8, "dt": 1e-5, "u_start": -50.0, "u_end": -50.0}

    def contact(model, params, policy, rtol, dt, u_start, u_end):
        c = bwc.Contact(model, params, policy=policy, rtol=rtol)
        c.advance(dt, u_start, u_end)

    yield "bwc.Contact", contact, *mutate(rng, law)

    many = {**law, "count": 3, "u_start": [-50.0, 0.0, 1.0], "u_end": [-50.0, 0.0, 1.0]}

    def contacts(model, params, policy, rtol, dt, u_start, u_end, count):
        c = bwc.Contacts(model, params, count, policy=policy, rtol=rtol)
        c.advance(dt, u_start, u_end)

    yield "bwc.Contacts", contacts, *mutate(rng, many)


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 100_000
    rng = random.Random(int(sys.argv[2]) if len(sys.argv) > 2 else 1)
    failures, counts, start = [], {}, time.perf_counter()
    for _ in range(n):
        for label, call, args, changed in cases(rng):
            counts[label] = counts.get(label, 0) + 1
            check(call, args, changed, failures, label)
    wall = time.perf_counter() - start
    for label, count in counts.items():
        bad = sum(1 for f in failures if f[0] == label)
        print("%-14s %9d cases  %6d failures" % (label, count, bad))
    print("%.0f s" % wall)
    kinds = {}
    for f in failures:
        kinds.setdefault((f[0], f[1]), []).append(f)
    for (label, why), fs in sorted(kinds.items()):
        print("FAIL %s: %s: %d cases, e.g. %s\n    input %s" % (label, why, len(fs), fs[0][2], fs[0][3]))
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
