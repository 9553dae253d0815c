"""The result types of ``bwc``: dicts (the command-line tools' JSON, so ``result["key"]`` and
``json.dumps`` work as before) whose keys are also attributes, with a ``repr`` that reads."""

import numpy as np


class Result(dict):
    """A result: a ``dict`` whose keys are also attributes (``r.e`` is ``r["e"]``).

    The keys are those of the command-line tools' JSON; nested objects are results too.
    """

    __slots__ = ()

    def __getattr__(self, name):
        try:
            return self[name]
        except KeyError:
            raise AttributeError(
                "%s has no %r; its keys: %s" % (type(self).__name__, name, ", ".join(map(str, self)))
            ) from None

    def __dir__(self):
        return sorted(set(super().__dir__()) | {k for k in self if isinstance(k, str) and k.isidentifier()})

    def __repr__(self):
        return _fields_repr(self)


# The order parameters are shown in: base, nondimensional, physical (as the paper lists them).
_ORDER = ("B_b", "Gamma_b", "B", "Gamma", "m", "k", "c", "kappa", "sigma_b", "sigma", "n", "p",
          "alpha", "beta", "gamma", "A", "U_b", "T_b", "U")


class Params(Result):
    """Parameters (base ``B_b, Gamma_b, kappa, sigma_b, n, p, U_b, T_b``, nondimensional or
    physical), as ``bwc.cor`` and ``bwc.simulate`` take them back: ``None`` marks an unused
    ``U_b`` or ``T_b``."""

    __slots__ = ()

    def __repr__(self):
        keys = sorted(self, key=lambda k: _ORDER.index(k) if k in _ORDER else len(_ORDER))
        fields = ", ".join("%s=%s" % (k, _short(self[k])) for k in keys if self[k] is not None)
        return "Params(%s)" % fields


class Run(Result):
    """One run of ``bwc.simulate``: ``v0``, ``e``, ``t_s``, ``t_d``, ``check``, ``outcome``
    and the rest of the tool's JSON for a run."""

    __slots__ = ()

    def __repr__(self):
        main = ("name", "v0", "e", "t_s", "t_d", "check", "outcome")
        fields = ", ".join("%s=%s" % (k, _short(self[k])) for k in main if self.get(k) is not None)
        return "Run(%s)" % fields


class Cor(Result):
    """What ``bwc.cor`` returns: per speed ``e``, ``t_s``, ``t_d``, ``check``, ... as numpy
    arrays (or as scalars for a scalar speed)."""

    __slots__ = ()

    def __repr__(self):
        main = ("e", "t_s", "t_d", "e_error", "check", "outcome")
        fields = ", ".join("%s=%s" % (k, _short(self[k])) for k in main if k in self)
        count = np.size(self["e"]) if "e" in self else 0
        speeds = "" if np.ndim(self.get("e")) == 0 else "%d speeds: " % count
        return "Cor(%s%s)" % (speeds, fields)


class Fit(Result):
    """One fit of ``bwc.identify``: ``name``, ``model``, ``params``, ``J1``, ``J2``,
    ``warnings`` and the rest of the tool's JSON for a fit."""

    __slots__ = ()

    def __repr__(self):
        costs = ", ".join(
            "%s=%s" % (k, _short(self[k])) for k in ("J1", "J2", "J_drop") if self.get(k) is not None
        )
        warned = len(self.get("warnings", []))
        return "Fit(%r, model=%r, %s, params=%r%s)" % (
            self.get("name"),
            self.get("model"),
            costs,
            self.get("params"),
            ", %d warning%s" % (warned, "" if warned == 1 else "s") if warned else "",
        )


class Identification(Result):
    """What ``bwc.identify`` returns: ``fits`` (a list of :class:`Fit`), ``units``,
    ``config`` and the provenance."""

    __slots__ = ()

    def __repr__(self):
        fits = self.get("fits", [])
        lines = ["  %r" % f for f in fits]
        return "Identification(%d fit%s:\n%s)" % (len(fits), "" if len(fits) == 1 else "s", "\n".join(lines))


class Simulation(Result):
    """What ``bwc.simulate`` returns: ``runs`` (each a :class:`Result`), ``units``, ``scene``
    and the provenance; for a ``[chain]`` scene ``chain`` in place of ``runs``."""

    __slots__ = ()

    def __repr__(self):
        chain = self.get("chain")
        if chain is not None:
            contacts = chain.get("contacts", [])
            return "Simulation(chain: %s at t = %s s, %d bodies, %d contacts, momentum %s kg m/s)" % (
                chain.get("outcome"), _short(chain.get("t_end_s")), len(chain.get("bodies", [])),
                len(contacts), _short(chain.get("momentum_kg_m_s")),
            )
        runs = self.get("runs", [])
        shown = ["  %r" % r for r in runs[:5]]
        more = ["  ... %d more" % (len(runs) - 5)] if len(runs) > 5 else []
        return "Simulation(%d run%s:\n%s)" % (len(runs), "" if len(runs) == 1 else "s", "\n".join(shown + more))


class Coverage(Result):
    """What ``bwc.coverage`` returns: ``coverage`` (one :class:`Result` per fit) and the
    provenance."""

    __slots__ = ()


class Posterior(Result):
    """One fit's posterior: ``log_evidence`` and ``log_evidence_error``, ``marginals`` (per
    sampled quantity ``median``, ``lo``, ``hi``, ``mean``, ``sd``, ``unit``), ``band`` (the 95 %
    credible band of ``e`` and ``t_d`` on a speed grid), ``noise``, ``priors``, ``stages`` and
    ``samples``: the weighted sample as numpy arrays, one per column (``B_b`` ... ``T_b``, the
    sampled noise scales), with ``weight``, ``run`` and ``log_likelihood``."""

    __slots__ = ()

    def __repr__(self):
        return "Posterior(name=%r, log_evidence=%.4g +- %.2g, particles=%d, ess=%.0f)" % (
            self.get("name"), self.get("log_evidence", float("nan")),
            self.get("log_evidence_error", float("nan")), len(self["samples"]["weight"]),
            self.get("ess", float("nan")),
        )


class Posteriors(Result):
    """What ``bwc.posterior`` returns: ``posteriors`` (one :class:`Posterior` per fit), the
    config as parsed and the provenance."""

    __slots__ = ()


def samples_as_arrays(posterior):
    """Turns a posterior's ``samples`` (JSON columns) into a :class:`Result` of numpy arrays."""
    raw = posterior["samples"]
    out = Result({name: np.asarray(col, dtype=float) for name, col in zip(raw["columns"], raw["values"])})
    out["weight"] = np.asarray(raw["weight"], dtype=float)
    out["run"] = np.asarray(raw["run"], dtype=np.int64)
    out["log_likelihood"] = np.asarray(
        [float("-inf") if v is None else v for v in raw["log_likelihood"]], dtype=float)
    posterior["samples"] = out


def wrap(value, cls=Result, kinds=None):
    """``value`` (parsed JSON) with its dicts as results: the top one as ``cls``, those under a
    key of ``kinds`` as the class given there (lists element by element), ``params`` as
    :class:`Params` and the rest as :class:`Result`."""
    kinds = {"params": Params, **(kinds or {})}
    if isinstance(value, dict):
        out = cls()
        for k, v in value.items():
            out[k] = wrap(v, kinds.get(k, Result), kinds)
        return out
    if isinstance(value, list):
        return [wrap(v, cls, kinds) for v in value]
    return value


# The longest a result nested two deep is shown in a repr; past it, its keys.
_NESTED = 240


def _fields_repr(result, depth=0):
    """``Name(key=value, ...)``: numbers to 4 digits, short lists in full, long ones by their
    length, the results nested in it in full, and those nested deeper in full where short and by
    their keys where long."""
    fields = []
    for k, v in result.items():
        if isinstance(v, dict):
            if type(v).__repr__ is not Result.__repr__:
                inner = repr(v)
            else:
                inner = _fields_repr(v if isinstance(v, Result) else Result(v), depth + 1)
            if depth > 0 and len(inner) > _NESTED:
                inner = "<%s: %s>" % (type(v).__name__, ", ".join(map(str, v)))
            fields.append("%s=%s" % (k, inner))
        elif isinstance(v, list) and len(v) > 4:
            fields.append("%s=<%d items>" % (k, len(v)))
        else:
            fields.append("%s=%s" % (k, _short(v)))
    return "%s(%s)" % (type(result).__name__, ", ".join(fields))


def _short(v):
    """A value in a repr: numbers to 4 significant digits, arrays abridged."""
    if isinstance(v, (float, np.floating)):
        return "%.4g" % v
    if isinstance(v, np.ndarray):
        if v.ndim == 0:
            return _short(v.item())
        with np.printoptions(precision=4, threshold=6, edgeitems=2):
            return np.array2string(v, separator=", ")
    if isinstance(v, list):
        return "[" + ", ".join(_short(x) for x in v) + "]"
    if isinstance(v, dict):
        return repr(v) if isinstance(v, Result) else _fields_repr(Result(v))
    return repr(v)
