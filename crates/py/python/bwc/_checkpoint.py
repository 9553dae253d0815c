"""Checkpoints of the studies the package runs a piece at a time: the file format of
``bwc-identify --checkpoint`` (``bwc._native.Checkpoint``), with each finished piece recorded as
its text, and the pieces' fingerprints (everything a piece's result depends on), so that an
interrupted study run again with the same checkpoint takes what was finished and computes the
rest, to the result an uninterrupted run gives."""

import json
import os

import numpy as np

from ._native import BwcError, Checkpoint


def checkpoint_path(path):
    """The ``checkpoint`` argument (None, str or os.PathLike) as the native calls take it."""
    if path is not None and not isinstance(path, (str, os.PathLike)):
        raise BwcError("checkpoint = %r is not admissible: a file path (str or os.PathLike), or "
                       "None" % (path,))
    return None if path is None else os.fspath(path)


def open_checkpoint(path, command):
    """The checkpoint at ``path`` of a study of ``command``, or ``None`` without a path."""
    path = checkpoint_path(path)
    return None if path is None else Checkpoint(path, command)


def chain_record(text, samples):
    """A chain's result (its summary's JSON text and its samples, a dict of numpy arrays or
    ``None``) as one text, every number as computed."""
    arrays = None if samples is None else {
        k: {"dtype": v.dtype.str, "shape": list(v.shape), "data": v.ravel().tolist()}
        for k, v in samples.items()
    }
    return json.dumps({"summary": text, "samples": arrays})


def chain_of_record(record):
    """The (summary text, samples) of :func:`chain_record`."""
    value = json.loads(record)
    arrays = value["samples"]
    samples = None if arrays is None else {
        k: np.asarray(a["data"], dtype=a["dtype"]).reshape(a["shape"]) for k, a in arrays.items()
    }
    return value["summary"], samples


def run_recorded(client, checkpoint, keys, prints, task, arguments):
    """The texts of tasks ``i``: from ``checkpoint`` where it holds ``keys[i]`` with
    ``prints[i]``, else ``task(*arguments[i])`` on ``client``, each recorded as it arrives, so
    that a study stopped part way keeps every task that finished. The first failure is raised
    after the tasks finished before it are recorded."""
    from distributed import as_completed

    texts = {i: checkpoint.get(k, p) for i, (k, p) in enumerate(zip(keys, prints))}
    futures = {client.submit(task, *arguments[i], pure=False): i
               for i, text in texts.items() if text is None}
    for future, text in as_completed(list(futures), with_results=True):
        i = futures[future]
        checkpoint.record(keys[i], prints[i], text)
        texts[i] = text
    return [texts[i] for i in range(len(keys))]
