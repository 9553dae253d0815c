"""Studies that outgrow one machine, on a ``dask.distributed`` cluster.

Each task is a pure function of its inputs (one CoR sweep of one parameter set, one
identification of one config with one seed), run on one thread of a worker, so the results are
identical to local runs whatever the number of workers. Point ``client`` at any cluster:

    from dask.distributed import Client, LocalCluster
    client = Client(LocalCluster(n_workers=2, processes=True))   # or Client("tcp://scheduler:8786")
    sweeps = bwc.dask.cor_sweep("shccm", params_list, v0, client)
"""

import warnings

import bwc


def _cor_task(model, params, v0, input, solver, sweep):
    """The sweep, and the messages of the ``BwcWarning``s it issued (a worker's warnings would
    otherwise stay in its log)."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", bwc.BwcWarning)
        out = bwc.cor(model, params, v0, input=input, solver=solver, sweep=sweep, threads=1)
    return out, [str(w.message) for w in caught if issubclass(w.category, bwc.BwcWarning)]


def _chain_task(scene):
    return bwc.simulate(scene, threads=1)


def simulate_many(scenes, client):
    """``bwc.simulate(scene)`` for every ``[chain]`` scene of ``scenes`` (a path readable by the
    workers, or a dict), one task each on ``client``: the results in the order of ``scenes``,
    equal to :func:`bwc.simulate_many`'s."""
    return client.gather(client.map(_chain_task, list(scenes), pure=False))


def _identify_task(config, seed):
    return bwc.identify(config, seed=seed, threads=1)


def cor_sweep(model, params_list, v0, client, *, input=None, solver=None, sweep=None):
    """``bwc.cor(model, params, v0)`` for every ``params`` of ``params_list``, one task each on
    ``client``; the list of result dicts in the order of ``params_list``. The ``BwcWarning``s
    of the tasks are issued again here, each prefixed with its ``params_list[i]``."""
    params_list = list(params_list)
    n = len(params_list)
    futures = client.map(
        _cor_task, [model] * n, params_list, [v0] * n, [input] * n, [solver] * n, [sweep] * n, pure=False
    )
    results = []
    for i, (out, messages) in enumerate(client.gather(futures)):
        for message in messages:
            warnings.warn("params_list[%d]: %s" % (i, message), bwc.BwcWarning, stacklevel=2)
        results.append(out)
    return results


def identify_many(configs, client, seeds=None):
    """``bwc.identify(config, seed=seed)`` for every config (a path readable by the workers, or
    a dict) and seed (default 0 each), one task each on ``client``; the list of results in the
    order of ``configs``."""
    configs = list(configs)
    seeds = [0] * len(configs) if seeds is None else list(seeds)
    if len(seeds) != len(configs):
        raise bwc.BwcError("identify_many: %d seeds for %d configs" % (len(seeds), len(configs)))
    futures = client.map(_identify_task, configs, seeds, pure=False)
    return client.gather(futures)


def _coverage_task(config, first_seed, replicates, noise, fit):
    return bwc.coverage(config, replicates=replicates, first_seed=first_seed, noise=noise, fit=fit, threads=1)


def coverage(config, client, *, replicates=40, first_seed=1, chunk=5, noise=None, fit=None):
    """``bwc.coverage`` split into tasks of ``chunk`` consecutive seeds on ``client``, merged:
    the replicates in seed order and the coverage over all of them, as a local run gives."""
    starts = list(range(first_seed, first_seed + replicates, chunk))
    sizes = [min(chunk, first_seed + replicates - s) for s in starts]
    n = len(starts)
    futures = client.map(_coverage_task, [config] * n, starts, sizes, [noise] * n, [fit] * n, pure=False)
    parts = client.gather(futures)
    merged = parts[0]
    for study_index, study in enumerate(merged["coverage"]):
        replicates_all = [r for part in parts for r in part["coverage"][study_index]["replicates"]]
        covered = sum(r["covered"] for r in replicates_all)
        points = sum(r["points"] for r in replicates_all)
        study["replicates"] = replicates_all
        study["coverage"] = covered / max(points, 1)
    return merged


def _posterior_run_task(config, fit, index, seed, particles, runs):
    source = bwc._source(config, "config")
    return bwc._native.posterior_run_json(fit, index, seed=seed, particles=particles, runs=runs, **source)


def posterior(config, client, *, fit=None, seed=0, particles=None, runs=None, threads=None):
    """``bwc.posterior`` with its independent runs spread over ``client``, one task per fit and
    run, pooled here: the same posterior, bit for bit, as a local run with the same seed (each
    run depends only on the config, the seed and its index). ``runs`` defaults to
    ``[fit.posterior].runs``; pass it to use more workers."""
    names = bwc._native.fit_names(**bwc._source(config, "config"))
    if fit is not None:
        if fit not in names:
            raise bwc.BwcError("fit = %r names no [[fit]]: one of %r" % (fit, names))
        names = [fit]
    counts = [runs or _configured_runs(config, name) for name in names]
    tasks = [(name, k) for name, count in zip(names, counts) for k in range(count)]
    futures = client.map(
        _posterior_run_task, [config] * len(tasks), [t[0] for t in tasks], [t[1] for t in tasks],
        [int(seed)] * len(tasks), [particles] * len(tasks), [runs] * len(tasks), pure=False,
    )
    texts = client.gather(futures)
    grouped, start = [], 0
    for count in counts:
        grouped.append(texts[start:start + count])
        start += count
    text = bwc._native.posterior_pool_json(names, grouped, seed=int(seed), threads=threads,
                                           **bwc._source(config, "config"))
    return bwc._posteriors(text)


def _configured_runs(config, name):
    """The runs ``[fit.posterior]`` of fit ``name`` asks for (as ``config`` echoes it)."""
    return bwc._native.posterior_runs(name, **bwc._source(config, "config"))
