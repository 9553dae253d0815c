"""Studies that outgrow one machine, on a ``dask.distributed`` cluster.

Each task is a pure function of its inputs (one CoR sweep of one parameter set, one
identification of one config with one seed), run on one thread of a worker, so the results are
identical to local runs whatever the number of workers. With ``checkpoint=`` (a file the client
writes), each finished task is recorded as it arrives and a study run again with the same file
takes what it holds: a study stopped part way (the client killed, the cluster lost) resumes to
the result an uninterrupted one gives. Point ``client`` at any cluster:

    from dask.distributed import Client, LocalCluster
    client = Client(LocalCluster(n_workers=2, processes=True))   # or Client("tcp://scheduler:8786")
    sweeps = bwc.dask.cor_sweep("shccm", params_list, v0, client)
"""

import json
import warnings

import bwc
from bwc._checkpoint import chain_of_record, chain_record, open_checkpoint, run_recorded


def _cor_task(model, params, v0, input, solver, sweep):
    """The sweep, and the messages of the ``BwcWarning``s it issued (a worker's warnings would
    otherwise stay in its log)."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", bwc.BwcWarning)
        out = bwc.cor(model, params, v0, input=input, solver=solver, sweep=sweep, threads=1)
    return out, [str(w.message) for w in caught if issubclass(w.category, bwc.BwcWarning)]


def _chain_record_task(scene):
    """The chain's result as :func:`bwc.simulate_many` gives it (its provenance included), as
    the text a checkpoint records."""
    source = bwc._source(scene, "scene")
    [out] = bwc._native.simulate_chains_json([source.get("path")], [source.get("scene_json")],
                                             threads=1)
    return chain_record(*out)


def simulate_many(scenes, client, *, checkpoint=None):
    """``bwc.simulate(scene)`` for every ``[chain]`` scene of ``scenes`` (a path readable by the
    workers, or a dict), one task each on ``client``: the results in the order of ``scenes``,
    equal to :func:`bwc.simulate_many`'s. A ``checkpoint`` is the one :func:`bwc.simulate_many`
    keeps: a study begun on one resumes on the other."""
    scenes = list(scenes)
    journal = open_checkpoint(checkpoint, "simulate_many")
    if journal is None:
        records = client.gather(client.map(_chain_record_task, scenes, pure=False))
        return [bwc._chain_value(*chain_of_record(r)) for r in records]
    prints = [bwc._scene_fingerprint(**bwc._source(s, "scene")) for s in scenes]
    keys = [str(i) for i in range(len(scenes))]
    records = run_recorded(client, journal, keys, prints, _chain_record_task,
                           [(s,) for s in scenes])
    return [bwc._chain_value(*chain_of_record(r)) for r in records]


def _identify_task(config, seed):
    return bwc._identify(seed=seed, threads=1, **bwc._source(config, "config"))


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


def identify_many(configs, client, seeds=None, *, checkpoint=None):
    """``bwc.identify(config, seed=seed)`` for every config (a path readable by the workers, or
    a dict) and seed (default 0 each), one task each on ``client``; the list of results in the
    order of ``configs``, their warnings issued here. With a ``checkpoint``, each finished
    identification is recorded and those it holds for the same config, data and seed are
    taken."""
    configs = list(configs)
    seeds = [0] * len(configs) if seeds is None else list(seeds)
    if len(seeds) != len(configs):
        raise bwc.BwcError("identify_many: %d seeds for %d configs" % (len(seeds), len(configs)))
    seeds = [bwc._integer(s, "seeds[%d]" % i, 0) for i, s in enumerate(seeds)]
    journal = open_checkpoint(checkpoint, "dask identify_many")
    keys = [str(i) for i in range(len(configs))]
    if journal is None:
        texts = client.gather(client.map(_identify_task, configs, seeds, pure=False))
    else:
        prints = [bwc._native.config_fingerprint(json.dumps({"seed": seed}),
                                                 **bwc._source(config, "config"))
                  for config, seed in zip(configs, seeds)]
        texts = run_recorded(client, journal, keys, prints, _identify_task,
                             list(zip(configs, seeds)))
    results = []
    for text in texts:
        value = bwc._wrap(json.loads(text), bwc.Identification, {"fits": bwc.Fit})
        bwc._warn_fits(value["fits"])
        results.append(value)
    return results


def _coverage_task(config, first_seed, replicates, noise, fit):
    return bwc._coverage(replicates=replicates, first_seed=first_seed, noise=noise, fit=fit,
                         threads=1, **bwc._source(config, "config"))


def coverage(config, client, *, replicates=40, first_seed=1, chunk=5, noise=None, fit=None,
             checkpoint=None):
    """``bwc.coverage`` split into tasks of ``chunk`` consecutive seeds on ``client``, merged:
    the replicates in seed order and the coverage over all of them, as a local run gives. With
    a ``checkpoint``, each finished task is recorded, and the tasks it holds for the same
    config, data, noise, fit and seeds (``chunk`` unchanged) are taken."""
    replicates = bwc._integer(replicates, "replicates", 1, 100_000)
    first_seed = bwc._integer(first_seed, "first_seed", 0)
    chunk = bwc._integer(chunk, "chunk", 1, 100_000)
    noise = bwc._noise(noise)
    starts = list(range(first_seed, first_seed + replicates, chunk))
    sizes = [min(chunk, first_seed + replicates - s) for s in starts]
    n = len(starts)
    journal = open_checkpoint(checkpoint, "dask coverage")
    if journal is None:
        futures = client.map(_coverage_task, [config] * n, starts, sizes, [noise] * n, [fit] * n,
                             pure=False)
        texts = client.gather(futures)
    else:
        study = bwc._native.config_fingerprint(json.dumps({"noise": noise}), fit=fit,
                                               **bwc._source(config, "config"))
        keys = ["%d+%d" % (s, k) for s, k in zip(starts, sizes)]
        prints = [study] * n
        texts = run_recorded(client, journal, keys, prints, _coverage_task,
                             [(config, s, k, noise, fit) for s, k in zip(starts, sizes)])
    parts = [bwc._wrap(json.loads(t), bwc.Coverage) for t in texts]
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


def posterior(config, client, *, fit=None, seed=0, particles=None, runs=None, threads=None,
              checkpoint=None):
    """``bwc.posterior`` with its independent runs spread over ``client``, one task per fit and
    run, pooled here: the same posterior, bit for bit, as a local run with the same seed (each
    run depends only on the config, the seed and its index). ``runs`` defaults to
    ``[fit.posterior].runs``; pass it to use more workers. With a ``checkpoint``, each finished
    run is recorded, and the runs it holds for the same config, data, seed and sizes are
    taken."""
    names = bwc._native.fit_names(**bwc._source(config, "config"))
    if fit is not None:
        if fit not in names:
            raise bwc.BwcError("fit = %r names no [[fit]]: one of %r" % (fit, names))
        names = [fit]
    counts = [runs or _configured_runs(config, name) for name in names]
    tasks = [(name, k) for name, count in zip(names, counts) for k in range(count)]
    journal = open_checkpoint(checkpoint, "dask posterior")
    if journal is None:
        futures = client.map(
            _posterior_run_task, [config] * len(tasks), [t[0] for t in tasks],
            [t[1] for t in tasks], [int(seed)] * len(tasks), [particles] * len(tasks),
            [runs] * len(tasks), pure=False,
        )
        texts = client.gather(futures)
    else:
        arguments = json.dumps({"seed": int(seed), "particles": particles, "runs": runs})
        print_of = {name: bwc._native.config_fingerprint(arguments, fit=name,
                                                         **bwc._source(config, "config"))
                    for name in names}
        prints = [print_of[name] for name, _ in tasks]
        keys = ["%s/%d" % t for t in tasks]
        texts = run_recorded(client, journal, keys, prints, _posterior_run_task,
                             [(config, name, k, int(seed), particles, runs) for name, k in tasks])
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
