"""Tasks on worker processes, forked from a server that has pounding loaded (the ``forkserver``
start method; ``spawn`` where there is none): a clean interpreter each, started in a fraction of a
spawn's time, the compiled kernels loaded once in the server, not per task.

Ctrl-C (or a task's error, with ``on_error="stop"``): the workers are stopped; what had finished
is kept, the tasks in flight are lost (None).  A worker that ends abruptly (killed, out of memory, a
script without a main guard) is named as such.
"""

from __future__ import annotations

import concurrent.futures as cf
import os
import threading
from collections.abc import Callable
from typing import Any

from .._errors import InputError, Problem
from ._tasks import GUARD, Tally, TaskRun, remote

_PRELOAD = ("pounding._worker_boot",)


def on_processes(fn: Callable, tasks: list, n_workers: int, advance: Callable[[int], None], budgets: list,
                 on_error: str, counted: bool, preload: tuple[str, ...], executor: Any = None) -> TaskRun:
    """``executor``: a pool kept by the caller for many runs (a ``task_pool``'s): its workers
    start once."""
    tally = Tally([None] * len(tasks))
    pool = executor or new_pool(n_workers, preload)
    try:
        futures = {pool.submit(remote, fn, task, budgets[i]): i for i, task in enumerate(tasks)}
        pending = set(futures)
        while pending:
            done, pending = cf.wait(pending, timeout=0.2, return_when=cf.FIRST_COMPLETED)
            for fut in done:
                i = futures[fut]
                exc = fut.exception()
                if isinstance(exc, cf.process.BrokenProcessPool):
                    raise exc
                if exc is not None:
                    tally.errors[i] = exc
                    if on_error == "stop":
                        stop_pool(pool)
                        return tally.run(False)
                    continue
                tally.take(i, fut.result(), advance, counted)
    except cf.process.BrokenProcessPool:
        stop_pool(pool)
        raise InputError(Problem.BAD_STATE, "scheduler", "processes",
                         why="a worker process ended abruptly (killed, out of memory, or it failed to start)",
                         fix=GUARD + "; if memory ran out, give fewer workers") from None
    except KeyboardInterrupt:
        stop_pool(pool)
        return tally.run(True)
    except BaseException:
        stop_pool(pool)
        raise
    if executor is None:
        pool.shutdown(wait=True)
    return tally.run(False)


def new_pool(n_workers: int, preload: tuple[str, ...] = ()) -> cf.ProcessPoolExecutor:
    return cf.ProcessPoolExecutor(max_workers=n_workers, mp_context=process_context(preload),
                                  initializer=exit_with_parent)


def stop_pool(pool: Any) -> None:
    for proc in list(getattr(pool, "_processes", {}).values()):
        proc.terminate()  # (mid-task: nothing of theirs is kept)
    pool.shutdown(wait=False, cancel_futures=True)


def process_context(preload: tuple[str, ...] = ()) -> Any:
    """The forkserver context, its server importing what the tasks need once (then each worker is
    a fork of it), or spawn where there is no forkserver (Windows)."""
    import multiprocessing as mp
    import multiprocessing.forkserver as mpf

    if "forkserver" not in mp.get_all_start_methods():  # pragma: no cover (Windows)
        return mp.get_context("spawn")
    ctx = mp.get_context("forkserver")
    # (added to what is preloaded already, '__main__' by default, as every forkserver user expects)
    have = list(getattr(getattr(mpf, "_forkserver", None), "_preload_modules", ["__main__"]))
    ctx.set_forkserver_preload(have + [m for m in (*_PRELOAD, *preload) if m not in have])
    return ctx


def exit_with_parent() -> None:
    """In a worker process: exit when the caller's process is gone (killed with SIGKILL, its pool
    cannot say so), instead of computing on for nobody."""
    import multiprocessing as mp

    parent = mp.parent_process()
    if parent is None:  # pragma: no cover (not a worker)
        return

    def watch() -> None:
        parent.join()  # (its sentinel: a pipe the caller's process holds, closed when it dies)
        os._exit(1)

    threading.Thread(target=watch, daemon=True, name="pounding-parent-watch").start()
