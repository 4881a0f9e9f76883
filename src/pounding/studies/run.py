"""Parameter studies that outgrow one machine: a resumable Zarr store, filled by threads,
processes or Dask.

:func:`study` writes the store's template, then hands out its chunks (one batch each) to the
scheduler; each task computes the chunk's points that are not done and writes them itself
(:func:`.store.run_chunk`), so the results never travel back through the caller.  A rerun
computes only what is not done.
"""

from __future__ import annotations

import math
import os
from pathlib import Path
from typing import Any

import numpy as np

from .._checks import instance_of, integer
from .._errors import InputError, Interrupted, Problem, StoreError
from .._runner import GUARD, Context, run_tasks, scheduler_kind
from .._runner.dask_client import dask_client
from .._runner.progress import Progress
from .spec import StudySpec
from .store import (OTHER, STUDY, check_store, chunk_grid, chunk_shape, create, open_checked, open_dataset,
                    refuse_other, region, run_chunk, store_state)

_PRELOAD = ("pounding.studies.worker_preload",)  # (what a chunk needs, loaded once per worker server)
BATCHES_PER_WORKER = 8  # chunks a worker gets over a study, at least: balance against per-batch cost
MAX_BATCH = 256         # points in a chunk, at most


def batch_points(kind: str, size: int, workers: int) -> int:
    """Points in a chunk: one sweep (each takes seconds); runs in batches of up to ``MAX_BATCH``,
    at least ``BATCHES_PER_WORKER`` batches a worker."""
    if kind == "sweep":
        return 1
    return int(min(MAX_BATCH, max(1, math.ceil(size / (workers * BATCHES_PER_WORKER)))))


def study(
    spec: StudySpec | str | Path,
    store: str | Path,
    *,
    scheduler: Any = None,
    workers: int | None = None,
    resume: bool = True,
    progress: Progress = True,
    max_steps: int | None = None,
) -> "Any":
    """Run a parameter study into a Zarr store, resumably.

    Parameters
    ----------
    spec : StudySpec or path
        The study (a ``.toml`` path is read with :meth:`StudySpec.from_toml`).
    store : str or Path
        A Zarr folder (created; its parent must exist) or an fsspec URL (``s3://...``).
    scheduler : None, "serial", "threads", "processes", "local", dask.distributed.Client or str
        Where the points run (the shared task runner, as for ``campaign`` and
        ``pounding_spectrum``): this thread ("serial"); threads of this process (None,
        "threads"); worker processes ("processes"); a new Dask ``LocalCluster`` of ``workers``
        processes ("local"); an existing Dask client, or a scheduler's address
        ("tcp://host:8786").  Dask workers must
        reach the store (a shared file system or object storage).
    workers : int, optional
        Threads or processes (default: the machine's cores); with a Dask client, its workers.
    resume : bool
        True (default): an existing store of the same spec is completed, only the points not
        done are computed; a store of another spec is refused.  False: the store is written anew.
    progress : bool or callable
        A progress bar over the points (those done before count as done), or a callable given
        the number of points just finished.
    max_steps : int, optional
        Each run's work budget (``pounding.simulate``'s); a point over it is kept with status BUDGET.

    Returns
    -------
    xarray.Dataset
        The store opened with ``xarray.open_zarr``: dims the grid's axes, the quantities,
        ``done`` and ``session``.

    Raises
    ------
    InputError
        A bad spec (before any work), store or scheduler.
    Interrupted
        On Ctrl-C: the points finished are in the store (``partial`` is the store's Dataset).

    Examples
    --------
    Four harmonic runs (5 s at 1.5 Hz from rest): the left gap against a_G, on threads, into
    ``gaps.zarr`` in the current folder:

    >>> import pounding
    >>> spec = pounding.StudySpec(pounding.presets.paper_damped(),
    ...                           {"kind": "simulate", "freq_hz": 1.5,
    ...                            "duration_s": 5.0},
    ...                           {"bumpers.gap_left_m": [0.01, 0.02],
    ...                            "a_g": [0.03, 0.05]})
    >>> ds = pounding.study(spec, "gaps.zarr", progress=False)
    >>> print(ds["impacts"].to_pandas())
    a_g               0.03  0.05
    bumpers.gap_left_m
    0.01               7.0  10.0
    0.02               0.0  12.0

    Run again, it resumes: every point is done, nothing is computed (``session`` stays 1).

    >>> ds = pounding.study(spec, "gaps.zarr", progress=False)
    >>> int(ds["done"].sum()), int(ds["session"].max())
    (4, 1)
    """
    import multiprocessing as mp

    if getattr(mp.current_process(), "_inheriting", False):  # (multiprocessing's own test of this)
        raise InputError(Problem.BAD_STATE, "study", "started by a worker process importing the script",
                         why="a study in a script that is not guarded runs again in every worker process",
                         fix=GUARD)
    if isinstance(spec, (str, Path)):
        spec = StudySpec.from_toml(spec)
    instance_of("spec", spec, StudySpec, "pounding.StudySpec or the path of a study TOML file")
    store = check_store(store)
    instance_of("resume", resume, bool, "bool")
    if max_steps is not None:
        max_steps = integer("max_steps", max_steps, 1)
    kind_of_scheduler = scheduler_kind(scheduler)
    n_workers = integer("workers", (os.cpu_count() or 1) if workers is None else workers, 1)
    if not (progress is True or progress is False or progress is None or callable(progress)):
        raise InputError(Problem.WRONG_TYPE, "progress", progress, got=type(progress).__name__,
                         expected="bool or a callable taking the number of points finished")

    state = store_state(store)
    if state == OTHER:
        refuse_other(store)
    group = open_checked(store, spec) if resume and state == STUDY else None
    client, own = (None, None)
    if kind_of_scheduler == "dask":  # (connected before the template: a wrong address writes nothing)
        client, own = dask_client(scheduler, n_workers)
    try:
        if group is None:
            chunks = chunk_shape(spec.shape, batch_points(spec.kind, spec.size, n_workers))
            try:
                create(store, spec, chunks)
            except OSError as exc:  # (a folder the user may not write in after all: /proc, a full disk)
                raise InputError(Problem.BAD_OUTPUT, "store", store, why=f"cannot be written ({exc})",
                                 fix="give a folder you can write in") from None
            group = open_checked(store, spec)
        done = np.asarray(group["done"][...])
        session = int(np.asarray(group["session"][...]).max(initial=0)) + 1
        chunks = tuple(group["done"].chunks)
        todo = [c for c in chunk_grid(spec.shape, chunks) if not done[region(c, spec.shape, chunks)].all()]
        tasks = [(spec.to_json(), store, session, max_steps, c) for c in todo]
        finished = int(done.sum())
        ran = run_tasks(_chunk_task, tasks, scheduler=client if client is not None else scheduler,
                        workers=n_workers, progress=progress, label="study", total=spec.size - finished,
                        completed=finished, on_error="stop", preload=_PRELOAD)
        interrupted = ran.interrupted
        failed = ran.errors.get(min(ran.errors)) if ran.errors else None
        if isinstance(failed, OSError) and not isinstance(failed, StoreError):  # (a write: disk full, ...)
            raise StoreError(str(store), failed, _points_kept(store), spec.size) from None
        ran.raise_first_error(lambda i: f"the study's chunk {tuple(int(c) for c in todo[i])}")
    finally:
        if client is not None and client is not scheduler:
            client.close()
        if own is not None:
            own.close()
    while True:  # (reading the store back is short: a Ctrl-C meanwhile is taken as one during the points)
        try:
            ds = open_dataset(store)  # (each quantity by its name now, a store written before too)
            kept = int(ds["done"].sum())
            break
        except KeyboardInterrupt:
            interrupted = True
    if interrupted and kept < spec.size:  # (interrupted after the last point: the study is complete)
        raise Interrupted(ds, kept, spec.size, "points")
    return ds


def _points_kept(store: Any) -> int:
    """The points a store says are done (0 when it cannot even be read)."""
    import zarr

    try:
        return int(np.asarray(zarr.open_group(store, mode="r", zarr_format=2)["done"][...]).sum())
    except Exception:  # noqa: BLE001 - a count for a message, never a second failure
        return 0


def _chunk_task(task: tuple, ctx: Context) -> int:
    """One chunk of the store, computed and written where the task runs (the shared runner's task)."""
    spec_json, store, session, max_steps, index = task
    return run_chunk(spec_json, store, index, session, max_steps, ctx.stopped, ctx.advance)
