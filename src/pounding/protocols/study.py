"""Parameter studies that outgrow one machine: a resumable Zarr store, filled by threads,
processes or Dask.

:func:`study` writes the store's template, then hands out its chunks (one batch each) to the
scheduler; each task computes the chunk's points that are not done and writes them itself
(:func:`.study_store.run_chunk`), so the results never travel back through the caller.  A rerun
computes only what is not done.
"""

from __future__ import annotations

import concurrent.futures as cf
import math
import os
import re
import threading
from pathlib import Path
from typing import Any

import numpy as np

from .._checks import integer
from .._errors import InputError, Interrupted, Problem
from .._runner.progress import Progress, progress_reporter
from .study_spec import StudySpec
from .study_store import (OTHER, STUDY, check_store, chunk_grid, chunk_shape, create, open_checked,
                          refuse_other, region, run_chunk, store_state)

SCHEDULERS = ("threads", "processes", "local")
BATCHES_PER_WORKER = 8  # chunks a worker gets over a study, at least: balance against per-batch cost
MAX_BATCH = 256         # points in a chunk, at most
GUARD = ("in a script, run the study under if __name__ == '__main__': (each worker process imports the "
         "script first, as Python's multiprocessing does)")


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
    scheduler : None, "threads", "processes", "local", dask.distributed.Client or str
        Where the points run: threads of this process (None, "threads"); worker processes
        ("processes"); a new Dask ``LocalCluster`` of ``workers`` processes ("local"); an
        existing Dask client, or a scheduler's address ("tcp://host:8786").  Dask workers must
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
    ...                           {"bumpers.gap_left": [0.01, 0.02],
    ...                            "a_g": [0.03, 0.05]})
    >>> ds = pounding.study(spec, "gaps.zarr", progress=False)
    >>> print(ds["impacts"].to_pandas())
    a_g               0.03  0.05
    bumpers.gap_left
    0.01               7.0  10.0
    0.02               0.0  12.0

    Run again, it resumes: every point is done, nothing is computed (``session`` stays 1).

    >>> ds = pounding.study(spec, "gaps.zarr", progress=False)
    >>> int(ds["done"].sum()), int(ds["session"].max())
    (4, 1)
    """
    import multiprocessing as mp

    import xarray as xr

    if getattr(mp.current_process(), "_inheriting", False):  # (multiprocessing's own test of this)
        raise InputError(Problem.BAD_STATE, "study", "started by a worker process importing the script",
                         why="a study in a script that is not guarded runs again in every worker process",
                         fix=GUARD)
    if isinstance(spec, (str, Path)):
        spec = StudySpec.from_toml(spec)
    if not isinstance(spec, StudySpec):
        raise InputError(Problem.WRONG_TYPE, "spec", spec, got=type(spec).__name__,
                         expected="pounding.StudySpec or the path of a study TOML file")
    store = check_store(store)
    if not isinstance(resume, bool):
        raise InputError(Problem.WRONG_TYPE, "resume", resume, got=type(resume).__name__, expected="bool")
    if max_steps is not None:
        max_steps = integer("max_steps", max_steps, 1)
    kind_of_scheduler = _scheduler_kind(scheduler)
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
        client, own = _dask_client(scheduler, n_workers)
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
        args = (spec.to_json(), store, session, max_steps)
        interrupted = False
        with progress_reporter(progress, spec.size, "study", completed=int(done.sum())) as advance:
            try:
                if kind_of_scheduler == "threads":
                    _on_threads(args, todo, n_workers, advance)
                elif kind_of_scheduler == "processes":
                    _on_processes(args, todo, n_workers, advance)
                else:
                    _on_dask(args, todo, client, advance)
            except KeyboardInterrupt:
                interrupted = True
    finally:
        if client is not None and client is not scheduler:
            client.close()
        if own is not None:
            own.close()
    while True:  # (reading the store back is short: a Ctrl-C meanwhile is taken as one during the points)
        try:
            ds = xr.open_zarr(store, consolidated=True)
            kept = int(ds["done"].sum())
            break
        except KeyboardInterrupt:
            interrupted = True
    if interrupted and kept < spec.size:  # (interrupted after the last point: the study is complete)
        raise Interrupted(ds, kept, spec.size, "points")
    return ds


def _scheduler_kind(scheduler: Any) -> str:
    if scheduler is None or scheduler == "threads":
        return "threads"
    if scheduler == "processes":
        return "processes"
    if scheduler == "local" or (isinstance(scheduler, str) and re.fullmatch(r"(tcp|tls|inproc|ucx|ws|wss)://[^/\s]+",
                                                                           scheduler)):
        return "dask"
    if type(scheduler).__name__ == "Client" and type(scheduler).__module__.startswith("distributed"):
        return "dask"
    raise InputError(Problem.NOT_ONE_OF, "scheduler", scheduler,
                     choices="threads, processes, local, a Dask scheduler's address such as tcp://host:8786 "
                             "(or, in Python, None or a dask.distributed.Client)")


def _on_threads(args: tuple, todo: list, n_workers: int, advance: Any) -> None:
    """Chunks on threads of this process (the kernels release the GIL).  Ctrl-C: each thread
    writes the points it finished and stops before its next point."""
    spec_json, store, session, max_steps = args
    stop = threading.Event()
    with cf.ThreadPoolExecutor(max_workers=n_workers, thread_name_prefix="pounding-study") as pool:
        futures = [pool.submit(run_chunk, spec_json, store, c, session, max_steps, stop.is_set, advance)
                   for c in todo]
        try:
            _wait(futures)
        except BaseException:  # Ctrl-C, or a point's error: the others stop at their next point
            stop.set()
            for fut in futures:
                fut.cancel()
            cf.wait(futures)  # (the running ones write what they finished)
            raise


def _wait(futures: list) -> None:
    pending = set(futures)
    while pending:
        done, pending = cf.wait(pending, timeout=0.2, return_when=cf.FIRST_COMPLETED)
        for fut in done:
            fut.result()  # (a worker's error is the caller's)


def _on_processes(args: tuple, todo: list, n_workers: int, advance: Any) -> None:
    """Chunks on worker processes, forked from a server that has pounding imported (the
    ``forkserver`` start method; ``spawn`` where there is none): a clean interpreter each, started
    in a fraction of a spawn's time.  Ctrl-C: the workers are stopped; what they had finished and
    written stays, the chunks in flight are lost."""
    spec_json, store, session, max_steps = args
    pool = cf.ProcessPoolExecutor(max_workers=n_workers, mp_context=_process_context(),
                                  initializer=_exit_with_parent)
    try:
        futures = {pool.submit(run_chunk, spec_json, store, c, session, max_steps): c for c in todo}
        pending = set(futures)
        while pending:
            done, pending = cf.wait(pending, timeout=0.2, return_when=cf.FIRST_COMPLETED)
            for fut in done:
                advance(fut.result())
    except cf.process.BrokenProcessPool:
        _stop_pool(pool)
        raise InputError(Problem.BAD_STATE, "scheduler", "processes",
                         why="a worker process ended abruptly (killed, out of memory, or it failed to start)",
                         fix=GUARD + "; if memory ran out, give fewer workers") from None
    except BaseException:
        _stop_pool(pool)
        raise
    pool.shutdown(wait=True)


def _stop_pool(pool: Any) -> None:
    for proc in list(getattr(pool, "_processes", {}).values()):
        proc.terminate()  # (mid-point: nothing of theirs is marked done that is not written)
    pool.shutdown(wait=False, cancel_futures=True)


_PRELOAD = ("pounding.protocols._study_worker",)


def _process_context() -> Any:
    """The forkserver context, its server importing what a chunk needs once (then each worker is
    a fork of it), or spawn where there is no forkserver (Windows)."""
    import multiprocessing as mp
    import multiprocessing.forkserver as mpf

    if "forkserver" not in mp.get_all_start_methods():  # pragma: no cover (Windows)
        return mp.get_context("spawn")
    ctx = mp.get_context("forkserver")
    # (added to what is preloaded already, '__main__' by default, as every forkserver user expects)
    preload = list(getattr(getattr(mpf, "_forkserver", None), "_preload_modules", ["__main__"]))
    ctx.set_forkserver_preload(preload + [m for m in _PRELOAD if m not in preload])
    return ctx


def _exit_with_parent() -> None:
    """In a worker process: exit when the study's process is gone (killed with SIGKILL, its pool
    cannot say so), instead of computing on for nobody."""
    import multiprocessing as mp

    parent = mp.parent_process()
    if parent is None:  # pragma: no cover (not a worker)
        return

    def watch() -> None:
        parent.join()  # (its sentinel: a pipe the study's process holds, closed when it dies)
        os._exit(1)

    threading.Thread(target=watch, daemon=True, name="pounding-parent-watch").start()


def _dask_client(scheduler: Any, n_workers: int) -> tuple[Any, Any]:
    """(client, cluster it started or None)."""
    try:
        from distributed import Client, LocalCluster
    except ImportError:  # pragma: no cover
        raise InputError(Problem.MISSING_INPUT, "scheduler", scheduler,
                         what="Dask: pip install 'dask[distributed]'") from None
    if scheduler == "local":
        cluster = LocalCluster(n_workers=n_workers, threads_per_worker=1, processes=True,
                               dashboard_address=None)
        return Client(cluster), cluster
    if isinstance(scheduler, str):
        try:
            return Client(scheduler, timeout="20s"), None
        except (OSError, TimeoutError, ValueError) as exc:
            raise InputError(Problem.BAD_STATE, "scheduler", scheduler, why=f"cannot be reached ({exc})",
                             fix="start the scheduler (dask scheduler) and its workers, or check the "
                                 "address") from None
    return scheduler, None


def _on_dask(args: tuple, todo: list, client: Any, advance: Any) -> None:
    """Chunks as Dask tasks: each worker computes and writes its own chunks."""
    from distributed import as_completed

    spec_json, store, session, max_steps = args
    futures = []
    try:
        futures = [client.submit(run_chunk, spec_json, store, c, session, max_steps, pure=False)
                   for c in todo]
        for fut in as_completed(futures):
            advance(fut.result())
    except BaseException:
        client.cancel(futures)
        raise
