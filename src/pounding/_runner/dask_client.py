"""Tasks on Dask distributed: a ``LocalCluster`` started here (``"local"``), a scheduler's address,
or the caller's ``Client``.  Each task runs where the workers are and sends back its value.

Ctrl-C (or a task's error, with ``on_error="stop"``): the tasks not finished are cancelled; what
had finished is kept.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from .._errors import InputError, Problem
from ._tasks import Tally, TaskRun, remote


def dask_client(scheduler: Any, n_workers: int) -> tuple[Any, Any]:
    """(client, the cluster it started or None) for ``"local"``, an address, or a Client."""
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


def on_dask(fn: Callable, tasks: list, scheduler: Any, n_workers: int, advance: Callable[[int], None],
            budgets: list, on_error: str, counted: bool) -> TaskRun:
    from distributed import as_completed

    tally = Tally([None] * len(tasks))
    interrupted = False
    client, cluster = dask_client(scheduler, n_workers)
    futures: list = []
    try:
        futures = [client.submit(remote, fn, task, budgets[i], pure=False) for i, task in enumerate(tasks)]
        index = {fut.key: i for i, fut in enumerate(futures)}
        for fut in as_completed(futures):
            i = index[fut.key]
            if fut.status == "error":
                tally.errors[i] = fut.exception()
                if on_error == "stop":
                    client.cancel(futures)
                    break
                continue
            if fut.status == "cancelled":
                continue
            tally.take(i, fut.result(), advance, counted)
    except KeyboardInterrupt:
        interrupted = True
        client.cancel(futures)
    finally:
        if client is not scheduler:
            client.close()
        if cluster is not None:
            cluster.close()
    return tally.run(interrupted)
