"""bwc: Bouc-Wen collision models (BWSHCCM, BWMCM) from Python.

CoR sweeps as numpy arrays, scenes and identification configs run exactly as the command-line
tools ``bwc-simulate`` and ``bwc-identify`` run them: the same parsing, the same error messages,
the same JSON. The work happens in Rust, in parallel, with the GIL released.

    >>> import bwc
    >>> out = bwc.cor("shccm", {"B": 0, "Gamma": 0, "kappa": 0.5, "sigma": 0.5, "n": 1, "p": 1.5})
    >>> round(float(out["e"][0]), 12)   # Hunt-Crossley closed form: 0.748434931597
    0.748434931597
"""

import json
import os

import numpy as np

from ._native import BwcError, BwcWarning, cor as _cor, coverage_json as _coverage, identify_json as _identify
from ._native import simulate_json as _simulate

__all__ = ["BwcError", "BwcWarning", "cor", "simulate", "identify", "coverage"]

# The outcome of each run, indexed by the codes the native sweep returns (a numpy string array
# without a Python object per speed).
_OUTCOMES = np.array(["separated", "settled", "horizon", "failed"])
# What each CoR's check against ``e_tol`` found, indexed by the codes the native sweep returns.
_CHECKS = np.array(["off", "met", "unmet", "unverified", "none"])
# Why the double-double retry of an unmet check reported nothing, indexed the same way.
_DECLINED = np.array(["none", "stiff", "no-path", "failed", "steps-grew", "disagreed"])
# Why a sweep simulated a speed it tried to interpolate, indexed the same way.
_GAVE_UP = np.array(["none", "noise", "too-few-speeds", "not-smooth", "budget"])

_NONDIMENSIONAL = {"B", "Gamma", "kappa", "sigma", "n", "p", "U"}
_BASE = {"B_b", "Gamma_b", "kappa", "sigma_b", "n", "p", "U_b", "T_b"}
_PHYSICAL = {"m", "k", "c", "n", "p", "alpha", "beta", "gamma", "A"}


def _table(params):
    """The scene table a parameter dict describes, by its keys."""
    keys = set(params)
    if "B" in keys or "Gamma" in keys or "sigma" in keys:
        return "nondimensional"
    if "B_b" in keys or "Gamma_b" in keys or "sigma_b" in keys:
        return "base"
    if "k" in keys:
        return "physical"
    raise BwcError(
        "params: cannot tell the description from the keys %s: nondimensional (B, Gamma, kappa, "
        "sigma, n, p, U), base (B_b, Gamma_b, kappa, sigma_b, n, p, U_b, T_b) or physical (m, k, c, "
        "n, p, alpha, beta, gamma, A)" % sorted(keys)
    )


def _plain(value):
    """numpy scalars and arrays as plain Python numbers and lists (JSON-ready)."""
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if isinstance(value, np.ndarray):
        return [_plain(v) for v in value.tolist()]
    if isinstance(value, np.generic):
        return value.item()
    return value


def cor(model, params, v0=None, *, input=None, solver=None, sweep=None, threads=None):
    """Coefficient of restitution, separation time and duration at each impact speed.

    ``model`` is ``"shccm"`` or ``"mcm"``; ``params`` a dict whose keys say the description
    (nondimensional ``B, Gamma, kappa, sigma, n, p`` and optional ``U``; base ``B_b, Gamma_b,
    kappa, sigma_b, n, p`` with ``U_b, T_b``; physical ``m, k, c, n, p, alpha, beta, gamma, A``
    in SI units); ``v0`` a speed or an array of speeds in m/s (``None`` for a nondimensional
    description, which starts at ``V = -1``); ``input``, ``solver`` and ``sweep`` dicts as the
    scene's ``[input]``, ``[solver]`` and ``[sweep]`` tables.

    Returns a dict of numpy arrays, one entry per speed: ``e`` (0 without separation),
    ``t_s`` (separation time: s, or nondimensional for nondimensional descriptions and base
    ones without ``T_b``; NaN without separation), ``t_d`` (contact duration in s, NaN where
    there is no time scale), ``separated`` (bool), ``e_error`` (the estimate of the error in
    ``e``: by default each CoR is checked against a run at 100 times its tolerance, to
    ``solver["e_tol"]`` = 1e-10; NaN for interpolated speeds and with ``e_tol = 0``),
    ``check`` (what that check found: ``"met"``, ``"unmet"`` (the estimate stayed above
    ``e_tol`` at the tightest tolerance), ``"unverified"`` (no run at another tolerance
    finished), ``"off"`` (one run, ``e_tol = 0``) or ``"none"`` (an interpolated speed)),
    ``tighter_failed_rtol`` (the tolerance of a tighter run of that check that failed, so that
    the check stopped at the run before it; NaN where none did), ``tighter_out_of_steps``
    (bool: that run needed more than ``solver["max_steps"]`` steps, and a larger value lets it
    finish), ``double_double`` (bool: where double precision could not meet ``e_tol``, the CoR
    was computed again in double-double arithmetic and that run is reported; on by default,
    ``solver["double_double"] = False`` turns it off), ``double_double_declined`` (where the
    check stayed ``"unmet"``, why that retry reported nothing: ``"stiff"`` (not tried: a run
    switched to RODAS4, and the double-double path is explicit), ``"no-path"``, ``"failed"``,
    ``"steps-grew"`` (a tighter run needed far more steps than the one before it) or
    ``"disagreed"``; ``"none"`` otherwise), ``phase`` (bool: the CoR came from the phase
    path, quadratures without time steps, which ``solver["phase"] = True`` asks for where the
    input is zero; its ``rhs_evals`` are 0), ``rhs_evals`` (int, of every run behind a
    CoR), ``interpolated`` (bool), ``sweep_gave_up`` (for a speed the sweep tried to
    interpolate and simulated instead, why: ``"noise"`` (values noisier than
    ``sweep["tolerance"]``), ``"too-few-speeds"`` (a kink or steep stretch: more speeds help),
    ``"not-smooth"`` (runs without a separation split the range) or ``"budget"``; ``"none"``
    otherwise), ``outcome``
    (strings ``"separated"``, ``"settled"``, ``"horizon"``).

    Many speeds (from about 140 up, under a constant input) are served by Chebyshev
    interpolants in ``ln v0`` where those are verified against simulations to
    ``sweep["tolerance"]`` (default a tenth of ``solver["e_tol"]``, 1e-11: absolute in ``e``,
    relative in ``t_s``); ``interpolated`` marks those
    speeds, whose ``rhs_evals`` are 0. ``sweep={"interpolate": False}`` simulates every speed.

    A ``BwcWarning`` (a ``UserWarning``, one per kind for all speeds) says what ``bwc-simulate``
    warns of on stderr, with the setting that helps: runs that met ``solver["t_max"]`` before
    separating (``e`` is then 0), CoRs that did not meet ``solver["e_tol"]``, and a sweep for
    which no interpolant held (every speed simulated, on top of the trials: values too noisy for
    ``sweep["tolerance"]``, or a kink in ``e(v0)`` that wants more speeds).

    Raises ``BwcError`` (a ``ValueError``) for a bad description or a failed run, with the
    message the command-line tools give.
    """
    table = _table(params)
    scene = {"model": model, table: _plain(dict(params))}
    if v0 is not None:
        speeds = np.atleast_1d(np.asarray(v0, dtype=float))
        scene["v0"] = speeds.tolist()
    if input is not None:
        scene["input"] = _plain(dict(input))
    if solver is not None:
        scene["solver"] = _plain(dict(solver))
    if sweep is not None:
        scene["sweep"] = _plain(dict(sweep))
    out = _cor(json.dumps(scene), threads)
    out["outcome"] = _OUTCOMES[out["outcome"]]
    out["check"] = _CHECKS[out["check"]]
    out["double_double_declined"] = _DECLINED[out["double_double_declined"]]
    out["sweep_gave_up"] = _GAVE_UP[out["sweep_gave_up"]]
    return out


def _source(description, what):
    """A path (str or os.PathLike) or a dict as the arguments of the native calls."""
    if isinstance(description, (str, os.PathLike)):
        return {"path": os.fspath(description)}
    if isinstance(description, dict):
        return {what + "_json": json.dumps(_plain(description))}
    raise BwcError("%s: give a path or a dict, not %s" % (what, type(description).__name__))


def simulate(scene, *, threads=None):
    """Runs a scene (a path to a TOML file, or a dict shaped like one) and returns the object
    ``bwc-simulate run --json`` prints: ``{"runs": [...], "units", "scene", ...}``. Where the
    scene asks for trajectories (``[output] trajectory`` or ``loops``), each run also has
    ``"trajectory"``: numpy arrays ``t, x, v, u, F`` and the model's states (``z``, or
    ``r, y, z``), in the units of ``"units"``. The warnings of ``cor`` come as
    ``BwcWarning``s here too."""
    text, trajectories = _simulate(threads=threads, **_source(scene, "scene"))
    value = json.loads(text)
    for run, samples in zip(value["runs"], trajectories):
        if samples is not None:
            run["trajectory"] = samples
    return value


def identify(config, *, seed=None, threads=None):
    """Fits every ``[[fit]]`` of a config (a path, or a dict shaped like one; data paths are
    relative to the config's folder, or to the working directory for a dict) and returns the
    object ``bwc-identify run --json`` prints. ``seed`` defaults to 0, as on the command line."""
    seed = 0 if seed is None else int(seed)
    return json.loads(_identify(seed=seed, threads=threads, **_source(config, "config")))


def coverage(config, *, replicates=40, first_seed=1, noise=None, fit=None, threads=None):
    """The coverage study of the 95 % band of each CoR-only fit of a config (a path or a dict):
    synthetic data from ``[fit.params]`` (or the fit's optimum) with Gaussian noise, refitted
    per replicate (seeds ``first_seed .. first_seed + replicates``). Returns the object
    ``bwc-identify coverage --json`` prints: ``{"coverage": [{"name", "coverage", "replicates",
    ...}]}``. Replicate ``k`` depends only on the config and its seed, so studies split by seed
    ranges (``bwc.dask.coverage``)."""
    text = _coverage(replicates=int(replicates), first_seed=int(first_seed), noise=noise, fit=fit,
                     threads=threads, **_source(config, "config"))
    return json.loads(text)
