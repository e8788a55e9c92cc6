"""The ``sweep`` experiment's grid on a Dask cluster (or any scheduler that maps a function).

A grid is a dict with the keys of a grid file (``experiments sweep --grid FILE.toml``):
``data``, ``resolution``, ``scheme``, ``curves``, ``solver``, ``segments``, the scheme
parameters (``beta``, ``c``, ``phong-alpha``), ``interior`` and ``estimate``; each a value or
a list. Its tasks are those of ``experiments sweep --list-tasks``; :func:`run_task` is the task
function the command line runs, returning the line it writes; the table is the command line's
``results.jsonl`` read by pandas, row for row::

    from dask.distributed import Client, LocalCluster
    import triwb.sweep

    grid = {"data": ["ring", "sphere"], "curves": ["chord", "optimized"], "solver": ["lm"]}
    with LocalCluster(n_workers=2, threads_per_worker=1) as cluster, Client(cluster) as client:
        table = triwb.sweep.run(grid, client)      # a pandas DataFrame, one row a task

On a real cluster, ``Client("tcp://scheduler:8786")`` instead of the local one; every worker
needs ``triwb`` installed, and mesh files named by absolute paths the workers can read (a task
reads its file relative to the worker's working directory).

Ray: the same task function, ``ray.remote`` around it::

    import ray
    task = ray.remote(triwb.sweep.run_task)
    ids = [t["task"] for t in triwb.sweep.tasks(grid)]
    results = ray.get([task.remote(grid, i) for i in ids])
    table = triwb.sweep.frame(triwb.sweep.merge(grid, results))
"""

import io
import json
import uuid

from . import _triwb


def manifest(grid):
    """The task manifest of ``grid`` (what ``experiments sweep --list-tasks`` prints)."""
    return _triwb.sweep_manifest(grid)


def tasks(grid):
    """The tasks of ``grid``, each a dict with its ``index``, its id ``task`` and parameters."""
    return manifest(grid)["tasks"]


def run_task(grid, task_id):
    """Runs one task of ``grid`` by id: the line ``experiments sweep --task ID`` writes.

    A plain Python function (pickled by reference), so a scheduler can ship it to workers.
    """
    return _triwb.sweep_task(grid, task_id)


def merge(grid, results):
    """``results`` (in any order) checked against ``grid``'s manifest and put in task order, as
    ``experiments merge`` does: every task exactly once, each line's identity its task's."""
    return _triwb.sweep_merge(manifest(grid), list(results))


def frame(results):
    """Result lines as the pandas DataFrame of the command line's ``results.jsonl``
    (``pandas.read_json(path, lines=True)``): the same columns, types and values."""
    import pandas

    text = "\n".join(json.dumps(r) for r in results)
    return pandas.read_json(io.StringIO(text), lines=True)


def run(grid, client=None, *, retries=0):
    """Runs every task of ``grid`` and returns the table (:func:`frame`).

    With a ``dask.distributed.Client``, one Dask task per sweep task (keys
    ``triwb-sweep-<run>-<index>``, ``<run>`` new for every call, so a cluster never answers
    with another run's results held under the same key), gathered and merged; without one,
    the tasks run here in order.
    A failing task raises its error (``triwb.WorkbenchError`` or ``triwb.UsageError``, with
    the command line's message) once the others are done or cancelled.
    """
    all_tasks = tasks(grid)
    ids = [t["task"] for t in all_tasks]
    if client is None:
        results = [run_task(grid, i) for i in ids]
    else:
        run_id = uuid.uuid4().hex[:12]
        futures = client.map(
            run_task,
            [grid] * len(ids),
            ids,
            key=[f"triwb-sweep-{run_id}-{t['index']}" for t in all_tasks],
            pure=False,
            retries=retries,
        )
        results = client.gather(futures)
    return frame(merge(grid, results))
