"""bwc: Bouc-Wen collision models (BWSHCCM, BWMCM) from Python.

CoR sweeps as numpy arrays, scenes and identification configs run exactly as the command-line
tools ``bwc-simulate`` and ``bwc-identify`` run them: the same parsing, the same warnings, the
same JSON. The work happens in Rust, in parallel, with the GIL released.

Results are dicts of the tools' JSON whose keys are also attributes, and a fit's parameters go
straight back into :func:`cor` and :func:`simulate`.

Examples
--------
>>> import bwc
>>> out = bwc.cor("shccm", {"B": 0, "Gamma": 0, "kappa": 0.5, "sigma": 0.5, "n": 1, "p": 1.5})
>>> round(float(out.e[0]), 12)   # Hunt-Crossley closed form: 0.748434931597
0.748434931597
"""

import json as _json
from collections.abc import Mapping as _Mapping
import math as _math
import os as _os
import warnings as _warnings

import numpy as _np

from ._native import BwcError, BwcWarning, __version__, cor as _cor, coverage_json as _coverage
from ._native import identify_json as _identify, simulate_json as _simulate
from ._native import simulate_file_json as _simulate_file
from ._native import simulate_chain_json as _simulate_chain
from ._native import simulate_chains_json as _simulate_chains
from ._native import posterior_json as _posterior
from ._native import materials_json as _materials
from ._native import Contact, Contacts, Step
from ._results import Cor, Coverage, Fit, Identification, Params, Posterior, Posteriors, Result, Run
from ._results import Simulation
from ._results import samples_as_arrays as _samples_as_arrays, wrap as _wrap
from ._checkpoint import chain_of_record as _chain_of_record, chain_record as _chain_record
from ._checkpoint import checkpoint_path as _checkpoint_path, open_checkpoint as _open_checkpoint
from ._native import scene_fingerprint as _scene_fingerprint

__all__ = [
    "BwcError",
    "BwcWarning",
    "Contact",
    "Contacts",
    "Cor",
    "Coverage",
    "Fit",
    "Identification",
    "Params",
    "Posterior",
    "Posteriors",
    "Result",
    "Run",
    "Simulation",
    "Step",
    "__version__",
    "cor",
    "coverage",
    "identify",
    "materials",
    "posterior",
    "simulate",
    "simulate_many",
]

# The outcome of each run, indexed by the codes the native sweep returns (a numpy string array
# without a Python object per speed).
_OUTCOMES = _np.array(["separated", "settled", "horizon", "failed"])
# What each CoR's check against ``e_tol`` found, indexed by the codes the native sweep returns.
_CHECKS = _np.array(["off", "met", "unmet", "unverified", "none"])
# Why the double-double retry of an unmet check reported nothing, indexed the same way.
_DECLINED = _np.array(["none", "stiff", "no-path", "failed", "steps-grew", "disagreed"])
# Why a sweep simulated a speed it tried to interpolate, indexed the same way.
_GAVE_UP = _np.array(["none", "noise", "too-few-speeds", "not-smooth", "budget"])

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
    """numpy scalars and arrays as plain Python numbers and lists (JSON-ready); ``None`` values
    of a dict left out (a TOML file has no null: an unused ``U_b`` is a key not given)."""
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items() if v is not None}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if isinstance(value, _np.ndarray):
        return [_plain(v) for v in value.tolist()]
    if isinstance(value, _np.generic):
        return value.item()
    return value


def _finite(value, where):
    """Raises :class:`BwcError` naming the first number in ``value`` (a dict, list, array or
    number) that is NaN or infinite: ``where`` and the keys or indices that lead to it."""
    if isinstance(value, dict):
        for k, v in value.items():
            _finite(v, "%s[%r]" % (where, k))
    elif isinstance(value, (list, tuple, _np.ndarray)):
        for i, v in enumerate(value):
            _finite(v, "%s[%d]" % (where, i))
    elif isinstance(value, (float, _np.floating)) and not _math.isfinite(value):
        raise BwcError("%s = %r is not admissible: a finite number" % (where, float(value)))


def _integer(value, name, lo, hi=2**64 - 1, none=None):
    """``value`` as an int in ``[lo, hi]`` (``None`` passes where ``none`` says what it means),
    else :class:`BwcError` naming the argument and the admissible range."""
    if value is None and none is not None:
        return None
    if isinstance(value, (bool, _np.bool_)) or not isinstance(value, (int, _np.integer)):
        raise BwcError("%s = %r is not admissible: an integer in [%d, %d]%s"
                       % (name, value, lo, hi, " (or None: %s)" % none if none else ""))
    if not lo <= int(value) <= hi:
        raise BwcError("%s = %d is not admissible: an integer in [%d, %d]%s"
                       % (name, value, lo, hi, " (or None: %s)" % none if none else ""))
    return int(value)


def _mapping(value, name, what):
    """``value`` as a dict with string keys (``None`` passes as ``None``), else
    :class:`BwcError` naming the argument and what it holds."""
    if value is None:
        return None
    if not isinstance(value, _Mapping) or not all(isinstance(k, str) for k in value):
        raise BwcError("%s = %s is not admissible: %s" % (name, _shown(value), what))
    return dict(value)


def _shown(value):
    """``repr(value)``, cut to a line."""
    text = repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


def _model(model):
    """The model argument: ``"shccm"`` or ``"mcm"``."""
    if not isinstance(model, str) or model not in ("shccm", "mcm"):
        raise BwcError('model = %s is not admissible: "shccm" (BWSHCCM) or "mcm" (BWMCM)'
                       % _shown(model))
    return model


def _threads(threads):
    """The worker threads argument: None (all cores) or 1 to 1024, as ``--threads``."""
    return _integer(threads, "threads", 1, 1024, none="all cores")


def cor(model, params, v0=None, *, input=None, solver=None, sweep=None, threads=None):
    """Coefficient of restitution, separation time and duration at each impact speed.

    Parameters
    ----------
    model : {"shccm", "mcm"}
        The BWSHCCM (states ``x, z, v``) or the BWMCM (``r, y, z, v``).
    params : dict
        The parameters; their keys say the description: nondimensional ``B, Gamma, kappa,
        sigma, n, p`` (and ``U``), base ``B_b, Gamma_b, kappa, sigma_b, n, p`` (and ``U_b,
        T_b``; ``None`` for an unused one, as a fit reports them), or physical ``m, k, c, n,
        p, alpha, beta, gamma, A`` in SI units. A fit's ``params`` pass as they are.
    v0 : float or array_like, optional
        Impact speed(s) in m/s. A scalar gives scalars; ``None`` (a nondimensional
        description, which starts at ``V = -1``) gives arrays of one.
    input, solver, sweep : dict, optional
        As a scene's ``[input]``, ``[solver]`` and ``[sweep]`` tables (see the user guide's
        scene reference): the external force, the accuracy (``e_tol`` = 1e-10 by default)
        and the interpolation of long sweeps.
    threads : int, optional
        Worker threads (default: all cores). Results do not depend on it.

    Returns
    -------
    Cor
        A dict whose keys are also attributes, one value per speed:

        - ``e``: the CoR (0 without separation);
        - ``t_s``: separation time (s; nondimensional for nondimensional descriptions and base
          ones without ``T_b``; NaN without separation); ``t_d``: contact duration (s, NaN
          without a time scale); ``separated`` (bool); ``outcome``: ``"separated"``,
          ``"settled"`` or ``"horizon"``;
        - ``e_error``: the estimate of the error in ``e`` (each CoR is checked against a run at
          100 times its tolerance; NaN for interpolated speeds and with ``e_tol = 0``);
          ``check``: ``"met"``, ``"unmet"``, ``"unverified"``, ``"off"`` or ``"none"`` (an
          interpolated speed);
        - ``tighter_failed_rtol``, ``tighter_out_of_steps``: a tighter run of the check that
          failed (NaN / False where none did; out of steps: raise ``solver["max_steps"]``);
        - ``double_double`` (bool: the reported run is the double-double retry of an unmet
          check), ``double_double_declined``: why that retry reported nothing (``"stiff"``,
          ``"no-path"``, ``"failed"``, ``"steps-grew"``, ``"disagreed"`` or ``"none"``);
        - ``phase`` (bool: the phase path served it, ``solver["phase"] = True``);
          ``rhs_evals``; ``interpolated`` (bool: from a verified Chebyshev interpolant of a
          long sweep, ``sweep["interpolate"]``); ``sweep_gave_up``: why a speed the sweep
          tried to interpolate was simulated (``"noise"``, ``"too-few-speeds"``,
          ``"not-smooth"``, ``"budget"`` or ``"none"``).

    Raises
    ------
    BwcError
        A ``ValueError`` for a bad description (naming the dict key, e.g.
        ``params["kappa"]``, and what is admissible) or a failed run.

    Warns
    -----
    BwcWarning
        One per kind for all speeds, as ``bwc-simulate`` warns on stderr, with the setting
        that helps: runs that met ``solver["t_max"]`` before separating, CoRs that did not meet
        ``solver["e_tol"]``, a sweep for which no interpolant held, and speeds whose magnitude
        suggests a unit slip.

    Examples
    --------
    The Hunt-Crossley limit of the NDBWSHCCM (``B = Gamma = 0``, ``n = 1``) at one impact:

    >>> import bwc
    >>> out = bwc.cor("shccm", {"B": 0, "Gamma": 0, "kappa": 0.5, "sigma": 0.5, "n": 1, "p": 1.5})
    >>> round(float(out.e[0]), 12), str(out.check[0])
    (0.748434931597, 'met')

    Base parameters at a scalar speed give scalars:

    >>> base = {"B_b": 2.38, "Gamma_b": -2.38, "kappa": 0.677, "sigma_b": 0.0348, "n": 2.93,
    ...         "p": 2.62, "U_b": None, "T_b": None}
    >>> out = bwc.cor("shccm", base, 3.0)
    >>> round(out.e, 4), out.outcome
    (0.7655, 'separated')
    """
    model = _model(model)
    params = _mapping(params, "params", "a dict of parameters by name")
    if params is None:
        raise BwcError("params = None is not admissible: a dict of parameters by name")
    input = _mapping(input, "input", "a dict as a scene's [input] table, or None")
    solver = _mapping(solver, "solver", "a dict as a scene's [solver] table, or None")
    sweep = _mapping(sweep, "sweep", "a dict as a scene's [sweep] table, or None")
    table = _table(params)
    _finite(params, "params")
    scene = {"model": model, table: _plain(params)}
    scalar = v0 is not None and _np.ndim(v0) == 0
    if v0 is not None:
        try:
            speeds = _np.atleast_1d(_np.asarray(v0, dtype=float))
        except (TypeError, ValueError):
            raise BwcError("v0 = %s is not admissible: a speed or a 1-D array of speeds (m/s)"
                           % _shown(v0)) from None
        if speeds.ndim != 1:
            raise BwcError("v0: an array of shape %s: give a scalar or a 1-D array of speeds (m/s)"
                           % (speeds.shape,))
        for i, v in enumerate(speeds):
            if not _math.isfinite(v):
                raise BwcError("v0[%d] = %r is not admissible: a finite impact speed > 0 (m/s)"
                               % (i, float(v)))
        scene["v0"] = speeds.tolist()
    for name, table_ in (("input", input), ("solver", solver), ("sweep", sweep)):
        if table_ is not None:
            _finite(table_, name)
            scene[name] = _plain(table_)
    out = _cor(_json.dumps(scene), _threads(threads))
    out["outcome"] = _OUTCOMES[out["outcome"]]
    out["check"] = _CHECKS[out["check"]]
    out["double_double_declined"] = _DECLINED[out["double_double_declined"]]
    out["sweep_gave_up"] = _GAVE_UP[out["sweep_gave_up"]]
    if scalar:
        out = {k: v[0].item() for k, v in out.items()}
    return Cor(out)


def _source(description, what):
    """A path (str or os.PathLike) or a dict as the arguments of the native calls."""
    if isinstance(description, (str, _os.PathLike)):
        return {"path": _os.fspath(description)}
    if isinstance(description, dict):
        _finite(description, what)
        return {what + "_json": _json.dumps(_plain(description))}
    raise BwcError("%s: give a path or a dict, not %s" % (what, type(description).__name__))


def simulate(scene, *, threads=None):
    """Runs a scene, as ``bwc-simulate run --json`` does.

    Parameters
    ----------
    scene : str, os.PathLike or dict
        A scene file (TOML), or a dict shaped like one (``None`` values are keys not given,
        so a fit's ``params`` go in as ``scene["base"]``).
    threads : int, optional
        Worker threads (default: all cores). Results do not depend on it.

    Returns
    -------
    Simulation
        The tool's JSON object with attribute access: ``runs`` (one :class:`Run` each:
        ``e``, ``t_s``, ``check``, ...), ``units``, ``scene`` and the provenance. Where the
        scene asks for trajectories (``[output] trajectory`` or ``loops``), each run also has
        ``trajectory``: numpy arrays ``t, x, v, u, F`` and the model's states (``z``, or
        ``r, y, z``), in the units of ``units``.

        A ``[chain]`` scene (bodies on a line, a law per pair) gives ``chain`` instead of
        ``runs``: ``outcome``, ``t_end_s``, ``bodies`` (each ``body``, ``mass_kg``,
        ``velocity_m_s``, ...), ``contacts`` (each ``pair``, ``onset_s``, ``separation_s``,
        ``rebound``, ``dissipated_J``, ...), ``ledger`` and ``momentum_kg_m_s``; with
        ``[output] dt`` also ``samples``: numpy arrays ``t``, ``x`` and ``v`` (samples by
        bodies), ``gap`` and ``F`` (samples by pairs), ``kinetic``, ``stored``, ``dissipated``
        and ``work``.

    Raises
    ------
    BwcError
        A bad scene (naming the file and line, or the dict key) or a failed run.

    Warns
    -----
    BwcWarning
        As :func:`cor`.

    Examples
    --------
    >>> import bwc
    >>> out = bwc.simulate({"model": "shccm", "v0": [1.0, 2.0],
    ...                     "base": {"B_b": 2.38, "Gamma_b": -2.38, "kappa": 0.677,
    ...                              "sigma_b": 0.0348, "n": 2.93, "p": 2.62}})
    >>> [round(r.e, 4) for r in out.runs]
    [0.8461, 0.7964]
    """
    source = _source(scene, "scene")
    if "path" in source:
        # A file is read once and run as the kind of scene it is.
        chain, text, extra = _simulate_file(source["path"], _threads(threads))
    else:
        chain = "chain" in scene
        run = _simulate_chain if chain else _simulate
        text, extra = run(threads=_threads(threads), **source)
    if chain:
        value = _wrap(_json.loads(text), Simulation)
        if extra is not None:
            value["samples"] = Result(extra)
        return value
    trajectories = extra
    value = _wrap(_json.loads(text), Simulation, {"runs": Run})
    for run, samples in zip(value["runs"], trajectories):
        if samples is not None:
            run["trajectory"] = Result(samples)
    return value


def simulate_many(scenes, *, threads=None, checkpoint=None):
    """Runs many ``[chain]`` scenes (a parameter study) in parallel, as :func:`simulate` runs
    each: the list of results in the order of ``scenes``, identical on any number of threads.

    Parameters
    ----------
    scenes : iterable of str, os.PathLike or dict
        Chain scene files, or dicts shaped like them.
    threads : int, optional
        Worker threads (default: all cores).
    checkpoint : str or os.PathLike, optional
        A file (JSON Lines, created if absent) in which the result of each scene is recorded
        (the scenes then run a batch at a time: four per thread), and from which the results it
        holds for these scenes are taken: an interrupted study run again with it resumes.

    Raises
    ------
    BwcError
        A bad scene (naming its index in ``scenes`` and the key) or a failed run.

    Examples
    --------
    >>> import bwc
    >>> scene = {"model": "shccm", "physical": {"k": 1e7, "c": 0.0, "n": 1.0, "p": 1.5,
    ...          "alpha": 0.5, "beta": 0.0, "gamma": 0.0, "A": 1.0},
    ...          "chain": {"mass": [0.1, 0.2], "position": [0.0, 0.03], "length": 0.02,
    ...                    "velocity": [1.0, 0.0], "horizon": 0.1}}
    >>> study = bwc.simulate_many([scene, {**scene, "chain": {**scene["chain"], "mass": [0.2, 0.2]}}])
    >>> [round(r.chain.bodies[1].velocity_m_s, 6) for r in study]
    [0.666667, 1.0]
    """
    sources = [_source(scene, "scene") for scene in scenes]
    paths = [s.get("path") for s in sources]
    texts = [s.get("scene_json") for s in sources]
    threads = _threads(threads)
    journal = _open_checkpoint(checkpoint, "simulate_many")
    if journal is None:
        return [_chain_value(text, samples)
                for text, samples in _simulate_chains(paths, texts, threads=threads)]
    prints = [_scene_fingerprint(**s) for s in sources]
    records = [journal.get(str(i), prints[i]) for i in range(len(sources))]
    results = [None if r is None else _chain_value(*_chain_of_record(r)) for r in records]
    pending = [i for i, r in enumerate(results) if r is None]
    batch = 4 * (threads or _os.cpu_count() or 1)
    for start in range(0, len(pending), batch):
        part = pending[start:start + batch]
        outs = _simulate_chains([paths[i] for i in part], [texts[i] for i in part],
                                threads=threads, indices=part)
        for i, (text, samples) in zip(part, outs):
            journal.record(str(i), prints[i], _chain_record(text, samples))
            results[i] = _chain_value(text, samples)
    return results


def _chain_value(text, samples):
    """A chain's result as :class:`Simulation`, from its summary's JSON text and samples."""
    value = _wrap(_json.loads(text), Simulation)
    if samples is not None:
        value["samples"] = Result(samples)
    return value



# What a fit's warning is about, by a phrase the tools' messages carry: one ``BwcWarning`` per
# kind and fit.
_WARNING_KINDS = (
    ("bounds", ("on its upper bound", "on its lower bound", "on the constraint", "is on a bound")),
    ("search", ("starts reached the best cost",)),
    ("intervals", ("no intervals",)),
    ("reference", ("the reference (",)),
    ("units", ("unit slip", "looks like")),
    ("sampler", ("runs disagree on", "effective size is")),
)


def _warn_fits(fits):
    """Each fit's warnings as ``BwcWarning``s, one per kind (bounds, search, intervals,
    reference, units, sampler, data) and fit, attributed to the caller of the package's function."""
    for fit in fits:
        grouped = {}
        for text in fit.get("warnings", []):
            kind = next((k for k, phrases in _WARNING_KINDS if any(p in text for p in phrases)), "data")
            grouped.setdefault(kind, []).append(text)
        for texts in grouped.values():
            _warnings.warn("; ".join(texts), BwcWarning, stacklevel=3)


def identify(config, *, seed=None, threads=None, checkpoint=None):
    """Fits every ``[[fit]]`` of a config, as ``bwc-identify run --json`` does.

    Parameters
    ----------
    config : str, os.PathLike or dict
        A config file (TOML; data paths relative to its folder), or a dict shaped like one
        (data paths relative to the working directory).
    seed : int, optional
        Base seed, combined with each fit's own (default 0, as on the command line).
    threads : int, optional
        Worker threads (default: all cores). Results do not depend on it.
    checkpoint : str or os.PathLike, optional
        A file (JSON Lines, created if absent) in which each finished fit's search is recorded,
        and from which the searches it holds for the same fit, data and seed are taken: an
        interrupted run of many fits run again with it resumes, to the result of an
        uninterrupted run (as ``bwc-identify run --checkpoint``).

    Returns
    -------
    Identification
        The tool's JSON object with attribute access: ``fits`` (one :class:`Fit` each:
        ``name``, ``model``, ``params``, ``J1``, ``J2``, ``convergence``, ``identifiability``,
        ``intervals``, ``predictions``, ``reference``, ``warnings``, ...), ``units``,
        ``config`` and the provenance. A fit's ``params`` pass straight to :func:`cor`.

    Raises
    ------
    BwcError
        A bad config or data file (every mistake found, one per line) or a failed fit.

    Warns
    -----
    BwcWarning
        What ``bwc-identify`` warns of on stderr, one warning per kind and fit: parameters on
        a bound, starts that did not agree, missing intervals, a reference that fits better,
        values that suggest a unit slip, and suspicious data.

    Examples
    --------
    >>> import bwc
    >>> import warnings
    >>> with warnings.catch_warnings():
    ...     warnings.simplefilter("ignore", bwc.BwcWarning)
    ...     result = bwc.identify("fixtures/kharaz.toml")
    >>> fit = result.fits[0]
    >>> fit.name, fit.J1 < 1e-8, fit.reference.standing
    ('DSS NDBWSHCCM', True, 'fit_lower')
    >>> round(bwc.cor(fit.model, fit.params, 3.0).e, 3)
    0.762
    """
    seed = 0 if seed is None else _integer(seed, "seed", 0)
    text = _identify(seed=seed, threads=_threads(threads), checkpoint=_checkpoint_path(checkpoint),
                     **_source(config, "config"))
    value = _wrap(_json.loads(text), Identification, {"fits": Fit})
    _warn_fits(value["fits"])
    return value


def materials(description, *, fit=None, seed=0):
    """A law from materials and geometry, as ``bwc-identify materials --json`` derives it.

    Parameters
    ----------
    description : str, os.PathLike or dict
        A file with a ``[materials]`` table, or a dict ``{"materials": {"body1": {...},
        "body2": {...}, "v0": [...]}}``. Each body names a ``material`` of the table and/or
        gives ``youngs_modulus`` (Pa), ``poisson``, ``density`` (kg/m^3), ``yield_strength``
        or ``yield_pressure`` (Pa), ``radius`` (m; absent for a flat) and ``mass`` (kg;
        absent: a sphere's from its radius and density, or immovable for a flat).
    fit : str or os.PathLike, optional
        A folder: the BWSHCCM and the BWMCM are fitted to the reference law's CoR and
        duration and to its loops, as ``bwc-identify materials --fit --out`` does, and
        ``reference.csv``, ``reference_loop_*.csv``, ``fit.toml`` and ``summary.json``
        written there.
    seed : int, default 0
        The fits' seed.

    Returns
    -------
    Result
        ``bodies``, ``derived`` (``E_star``, ``R_star``, ``m_star``, ``k``, ``p_y``,
        ``yields_first``, ``delta_y``, ``F_y``, ``a_y``, ``v_y``, ``T_b``), ``laws`` (the
        Hertz and Thornton laws as :class:`Contact` and ``[[fit]]`` families take them),
        ``cor`` (per speed ``v0``, ``e``, ``t_d``, ``delta_max``, ``F_max``, ``a_over_R``),
        ``units`` and ``notes``; with ``fit``, ``fits`` (per model fitted to the CoR and the
        duration: ``params``, its ``SI`` law and mass, ``e_error``, ``t_d_error``,
        ``F_max_error``, ``stops_following``) and ``loop_fits`` (per model fitted to the
        reference's loops: ``SI``, ``loop_cost``, ``e_error``, ``t_d_error``, ``F_max_error``).

    Raises
    ------
    BwcError
        An unknown material (the known ones listed) or an inadmissible value, named with its
        key and what is admissible.

    Examples
    --------
    >>> import bwc
    >>> law = bwc.materials({"materials": {
    ...     "body1": {"material": "alumina", "radius": 2.5e-3},
    ...     "body2": {"material": "aluminium-6082-t6"}}})
    >>> law.derived.yields_first, round(law.derived.v_y, 4)
    (2, 0.0224)
    >>> thornton = law.laws.thornton.element
    >>> contact = bwc.Contact("thornton", {"k": thornton.k, "delta_y": thornton.delta_y})
    """
    out = None if fit is None else _os.fspath(fit)
    seed = _integer(seed, "seed", 0)
    text = _materials(out=out, seed=seed, **_source(description, "materials"))
    return _wrap(_json.loads(text), Result, {})


def coverage(config, *, replicates=40, first_seed=1, noise=None, fit=None, threads=None,
             checkpoint=None):
    """The coverage study of the 95 % band of each CoR-only fit of a config, as
    ``bwc-identify coverage --json`` runs it.

    Parameters
    ----------
    config : str, os.PathLike or dict
        A config file or a dict shaped like one.
    replicates : int, default 40
        Synthetic datasets per fit.
    first_seed : int, default 1
        Replicate ``k`` has seed ``first_seed + k`` and depends only on the config and its
        seed, so studies split by seed ranges (``bwc.dask.coverage``).
    noise : float, optional
        The noise's standard deviation in ``e`` (default: the fit's residual scale).
    fit : str, optional
        Only the fit of this name.
    threads : int, optional
        Worker threads (default: all cores).
    checkpoint : str or os.PathLike, optional
        A file (JSON Lines, created if absent) in which each finished replicate is recorded,
        and from which the replicates it holds for this design are taken: an interrupted study
        run again with it resumes, to the result of an uninterrupted run (as
        ``bwc-identify coverage --checkpoint``).

    Returns
    -------
    Coverage
        ``coverage``: one :class:`Result` per fit (``name``, ``coverage``, ``replicates``,
        ...), and the provenance. The truth of each replicate is ``[fit.params]`` (or the
        fit's optimum), with Gaussian noise.

    Raises
    ------
    BwcError
        A bad config or a failed fit.

    Examples
    --------
    >>> import bwc
    >>> study = bwc.coverage("fixtures/kharaz.toml", replicates=2, fit="DSA NDBWSHCCM")
    >>> study.coverage[0].name, len(study.coverage[0].replicates)
    ('DSA NDBWSHCCM', 2)
    """
    text = _coverage(replicates=_integer(replicates, "replicates", 1, 100_000),
                     first_seed=_integer(first_seed, "first_seed", 0), noise=_noise(noise),
                     fit=fit, threads=_threads(threads), checkpoint=_checkpoint_path(checkpoint),
                     **_source(config, "config"))
    return _wrap(_json.loads(text), Coverage)


def _noise(noise):
    """The ``noise`` argument of a coverage study: None or a finite standard deviation > 0."""
    if noise is not None and not (isinstance(noise, (int, float, _np.number))
                                  and _math.isfinite(noise) and noise > 0):
        raise BwcError("noise = %r is not admissible: a finite standard deviation in e, > 0 (or "
                       "None: the fit's residual scale)" % (noise,))
    return noise


def _posteriors(text):
    """The JSON text of posteriors as :class:`Posteriors`, samples as numpy arrays, each
    posterior's warnings issued."""
    value = _wrap(_json.loads(text), Posteriors, {"posteriors": Posterior})
    for p in value["posteriors"]:
        _samples_as_arrays(p)
    _warn_fits(value["posteriors"])
    return value


def posterior(config, *, fit=None, seed=0, particles=None, runs=None, threads=None,
              checkpoint=None):
    """The posterior of each fit's searched quantities, as ``bwc-identify posterior --json``
    samples it: sequential Monte Carlo over the bounds (uniform on each quantity's search scale,
    or the priors of ``[fit.prior]``) with a Gaussian likelihood of the CoRs (and durations).

    Parameters
    ----------
    config : str, os.PathLike or dict
        A config file or a dict shaped like one; ``[fit.posterior]`` sets the sampler.
    fit : str, optional
        Only the fit of this name.
    seed : int, default 0
        Base seed, combined with each fit's own. Results do not depend on ``threads``.
    particles, runs : int, optional
        Particles per run and independent runs (default: ``[fit.posterior]``, 500 and 4).
    threads : int, optional
        Worker threads (default: all cores).
    checkpoint : str or os.PathLike, optional
        A file (JSON Lines, created if absent) in which each finished sampler run is recorded,
        and from which the runs it holds for this fit, seed and sampler are taken: an
        interrupted study run again with it resumes, to the posterior of an uninterrupted run
        (as ``bwc-identify posterior --checkpoint``).

    Returns
    -------
    Posteriors
        ``posteriors``: one :class:`Posterior` per fit (``log_evidence``,
        ``log_evidence_error``, ``marginals``, ``band``, ``noise``, ``samples`` as numpy
        arrays, ...), the config and the provenance.

    Raises
    ------
    BwcError
        A bad config, data a posterior cannot use (one point, a noise column with zeros, a
        prior outside the bounds), or a sampler that does not reach the posterior.

    Examples
    --------
    >>> import bwc
    >>> import warnings
    >>> with warnings.catch_warnings():
    ...     warnings.simplefilter("ignore", bwc.BwcWarning)   # a small sample warns of its size
    ...     post = bwc.posterior("fixtures/kharaz.toml", fit="DSS NDBWSHCCM", particles=32, runs=2)
    >>> p = post.posteriors[0]
    >>> sorted(p.marginals)   # the searched quantities and the CoR's noise scale
    ['B_b', 'g', 'kappa', 'n', 'p', 'sigma_b', 'sigma_e']
    >>> bool(abs(p.samples.weight.sum() - 1) < 1e-9), len(p.samples.kappa)
    (True, 64)
    """
    particles = _integer(particles, "particles", 16, 1_000_000, none="[fit.posterior] or 500")
    runs = _integer(runs, "runs", 2, 10_000, none="[fit.posterior] or 4")
    text = _posterior(seed=_integer(seed, "seed", 0), fit=fit, particles=particles, runs=runs,
                      threads=_threads(threads), checkpoint=_checkpoint_path(checkpoint),
                      **_source(config, "config"))
    return _posteriors(text)
