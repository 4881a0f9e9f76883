"""One way to run many independent tasks: threads, processes or Dask, with progress, Ctrl-C,
budgets and worker errors handled the same for every caller (campaign, pounding spectrum, study,
identification).

A task is ``fn(task, ctx)``: ``fn`` a module-level function (it travels to worker processes and Dask
workers by reference), ``task`` plain data, ``ctx`` a :class:`Context`: ``ctx.advance(n)`` reports
``n`` finished steps, ``ctx.stopped()`` is True once the run is being stopped (finish the step in
hand, keep what is done: return it, or raise ``Interrupted(partial)``), ``ctx.control`` is the
engine's run control for this task (its budget; on threads a Ctrl-C sets its stop flag, and the
kernels return within a sub-interval).

:func:`run_tasks` returns a :class:`TaskRun`: every task's value (a partial one where a task was
stopped), the errors by task, and whether the run was interrupted.  The caller assembles its result
from it and decides what to raise.  Each way of running lives in its own file.
"""

from __future__ import annotations

import contextlib
import os
import re
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from .._checks import integer
from .._errors import InputError, Problem
from ._tasks import GUARD, Context, TaskRun, remote  # noqa: F401  (the runner's public names)
from .progress import Progress, progress_reporter

SCHEDULERS = ("serial", "threads", "processes", "local")
SCHEDULER_CHOICES = ("serial, threads, processes, local, a Dask scheduler's address such as tcp://host:8786 "
                     "(or, in Python, None or a dask.distributed.Client)")
ON_ERROR = ("stop", "finish")


def scheduler_kind(scheduler: Any) -> str:
    """``"serial"``, ``"threads"``, ``"processes"`` or ``"dask"`` for a ``scheduler`` argument
    (None: threads); an unknown one is refused with the choices."""
    if scheduler is None or scheduler == "threads":
        return "threads"
    if scheduler in ("serial", "processes"):
        return str(scheduler)
    if scheduler == "local" or (isinstance(scheduler, str) and re.fullmatch(r"(tcp|tls|inproc|ucx|ws|wss)://[^/\s]+",
                                                                           scheduler)):
        return "dask"
    if type(scheduler).__name__ == "Client" and type(scheduler).__module__.startswith("distributed"):
        return "dask"
    raise InputError(Problem.NOT_ONE_OF, "scheduler", scheduler, choices=SCHEDULER_CHOICES)


def worker_count(workers: Any) -> int:
    """``workers`` checked, or the machine's cores when None."""
    return integer("workers", (os.cpu_count() or 1) if workers is None else workers, 1)


def run_tasks(fn: Callable[[Any, Context], Any], tasks: Sequence[Any], *, scheduler: Any = None,
              workers: Any = None, progress: Progress = False, label: str = "tasks", total: int | None = None,
              completed: int = 0, budget: int | Sequence[int] | None = None, on_error: str = "stop",
              preload: tuple[str, ...] = (), pool: "TaskPool | None" = None) -> TaskRun:
    """Run ``fn(task, ctx)`` for every task and return how it ended (never raises a task's error).

    Parameters
    ----------
    fn : callable
        A module-level function ``fn(task, ctx)``.
    tasks : sequence
        The tasks, plain data each.
    scheduler : str or dask.distributed.Client, optional
        ``"serial"`` (in this thread), ``"threads"`` (default; the compiled kernels release the GIL),
        ``"processes"`` (worker processes forked from a server that has pounding loaded), ``"local"``
        (a Dask ``LocalCluster``, closed at the end), an address ``"tcp://host:8786"`` or a ``Client``.
    workers : int, optional
        Threads or processes (default: the machine's cores).
    progress : bool or callable
        A Rich bar of ``total`` steps (``label``), a callable taking finished steps, or nothing.
    label : str
        The bar's description.
    total : int, optional
        Steps the tasks report in all (default: one per task, reported as each ends).
    completed : int
        Steps done before (a resumed study's): where the bar starts.
    budget : int or sequence of int, optional
        Each task's work budget in engine sub-intervals (its ``ctx.control``); default unlimited.
    on_error : {"stop", "finish"}
        On a task's error: stop the others (they keep what they finished), or let them finish.
    preload : tuple of str
        Modules the worker processes' server imports once (what the tasks need), besides pounding.
    pool : TaskPool, optional
        Workers already started (:func:`task_pool`) for many runs: ``scheduler`` and ``workers``
        are the pool's.

    Returns
    -------
    TaskRun
    """
    from .._control import DEFAULT_MAX_STEPS

    if pool is not None:
        scheduler, workers = pool.scheduler, pool.workers
    kind = scheduler_kind(scheduler)
    n_workers = worker_count(workers)
    if on_error not in ON_ERROR:
        raise InputError(Problem.NOT_ONE_OF, "on_error", on_error, choices=", ".join(ON_ERROR))
    tasks = list(tasks)
    budgets = ([DEFAULT_MAX_STEPS if budget is None else int(budget)] * len(tasks)
               if budget is None or np.isscalar(budget) else [int(b) for b in budget])
    counted = total is None  # (then each task is one step, reported as it ends)
    steps = len(tasks) if counted else int(total)
    executor = pool.executor if pool is not None else None
    with progress_reporter(progress, steps + completed, label, completed=completed) as advance:
        if kind in ("serial", "threads"):
            from ._threads import on_threads

            return on_threads(fn, tasks, 1 if kind == "serial" else n_workers, advance, budgets, on_error,
                              counted, serial=kind == "serial", executor=executor)
        if kind == "processes":
            from ._processes import on_processes

            return on_processes(fn, tasks, n_workers, advance, budgets, on_error, counted, preload,
                                executor=executor)
        from .dask_client import on_dask

        return on_dask(fn, tasks, executor if executor is not None else scheduler, n_workers, advance,
                       budgets, on_error, counted)


@dataclass(frozen=True, eq=False)
class TaskPool:
    """Workers started once for many :func:`run_tasks` calls (see :func:`task_pool`)."""

    scheduler: Any
    workers: int
    executor: Any  # a ThreadPoolExecutor, a ProcessPoolExecutor, a Dask Client, or None (serial)


@contextlib.contextmanager
def task_pool(scheduler: Any = None, workers: Any = None,
              preload: tuple[str, ...] = ()) -> Iterator[TaskPool]:
    """Start the workers once, for many runs of tasks (an identification's generations): threads,
    processes (forked once from the server that has pounding loaded) or a Dask client (a
    ``LocalCluster`` started and closed here)."""
    kind = scheduler_kind(scheduler)
    n_workers = worker_count(workers)
    if kind == "serial":
        yield TaskPool(scheduler, n_workers, None)
        return
    if kind == "threads":
        import concurrent.futures as cf

        with cf.ThreadPoolExecutor(max_workers=n_workers, thread_name_prefix="pounding") as ex:
            yield TaskPool(scheduler, n_workers, ex)
        return
    if kind == "processes":
        from ._processes import new_pool, stop_pool

        ex = new_pool(n_workers, preload)
        try:
            yield TaskPool(scheduler, n_workers, ex)
        finally:
            stop_pool(ex)
        return
    from .dask_client import dask_client

    client, cluster = dask_client(scheduler, n_workers)
    try:
        yield TaskPool(scheduler, n_workers, client)
    finally:
        if client is not scheduler:
            client.close()
        if cluster is not None:
            cluster.close()


__all__ = ["Context", "TaskPool", "TaskRun", "run_tasks", "task_pool", "scheduler_kind", "worker_count",
           "SCHEDULERS", "GUARD"]
