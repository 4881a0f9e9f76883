"""Tasks on threads of this process (or one after another in this thread: ``serial``).

The compiled kernels release the GIL, so engine-bound tasks run in parallel.  Ctrl-C sets every
task's run control (the kernels return within a sub-interval) and ``ctx.stopped()``; the tasks keep
what they finished.  More Ctrl-C while they return change nothing: the wait goes on.
"""

from __future__ import annotations

import concurrent.futures as cf
import threading
from collections.abc import Callable
from typing import Any

from .._errors import Interrupted
from .._control import new_control, request_stop
from ._tasks import Context, TaskRun


def on_threads(fn: Callable, tasks: list, n_workers: int, advance: Callable[[int], None], budgets: list,
               on_error: str, counted: bool, serial: bool = False, executor: Any = None) -> TaskRun:
    """``executor``: a ThreadPoolExecutor kept by the caller for many runs (a ``task_pool``'s)."""
    controls = [new_control(b) for b in budgets]
    stop = threading.Event()
    steps = (lambda n: None) if counted else advance  # (counted: a step is a task, reported as it ends)
    values: list = [None] * len(tasks)
    errors: dict = {}
    partial: set = set()
    settled: set = set()  # (the tasks whose end is recorded: a task may return None)
    ended: set = set()
    interrupted = False

    def halt() -> None:
        stop.set()
        request_stop(controls)

    def settle(i: int, fut: Any) -> None:
        """Record task ``i``'s end (a failure or an interruption may stop the others)."""
        nonlocal interrupted
        if fut.cancelled() or i in settled:  # (never started: a stop came first; or recorded)
            return
        settled.add(i)
        exc = fut.exception()
        if exc is None:
            values[i] = fut.result()
            ended.add(i)
            if counted:
                advance(1)
        elif isinstance(exc, Interrupted):  # (stopped: by us, or by its own Ctrl-C, e.g. a callback's)
            values[i] = exc.partial
            partial.add(i)
            if not stop.is_set():
                interrupted = True
                halt()
        else:
            errors[i] = exc
            if on_error == "stop":
                halt()

    if serial:
        for i, task in enumerate(tasks):
            if stop.is_set():
                break
            fut: cf.Future = cf.Future()
            try:
                fut.set_result(fn(task, Context(steps, stop.is_set, controls[i])))
            except KeyboardInterrupt as exc:  # (an Interrupted is one: the task kept its part)
                if not isinstance(exc, Interrupted):
                    interrupted = True
                    break
                fut.set_exception(exc)
            except Exception as exc:  # noqa: BLE001 - a task's error is recorded, named by the caller
                fut.set_exception(exc)
            settle(i, fut)
        return TaskRun(values, errors, partial, interrupted, ended)

    pool = executor or cf.ThreadPoolExecutor(max_workers=n_workers, thread_name_prefix="pounding")
    futures: dict = {}
    try:
        futures = {pool.submit(fn, task, Context(steps, stop.is_set, controls[i])): i
                   for i, task in enumerate(tasks)}
        pending = set(futures)
        while pending:
            done, pending = cf.wait(pending, timeout=0.2, return_when=cf.FIRST_COMPLETED)
            for fut in done:
                settle(futures[fut], fut)
            if stop.is_set():
                for fut in pending:
                    fut.cancel()
    except KeyboardInterrupt:
        interrupted = True
    finally:
        while True:  # every running task returns within a sub-interval of a stop; more Ctrl-C: wait on
            try:
                if interrupted:
                    halt()
                if executor is None:
                    pool.shutdown(wait=True, cancel_futures=interrupted or stop.is_set())
                else:  # (the caller's pool stays: this run's tasks are waited for, or cancelled)
                    if interrupted or stop.is_set():
                        for fut in futures:
                            fut.cancel()
                    cf.wait(futures)
                break
            except KeyboardInterrupt:
                interrupted = True
    for fut, i in futures.items():  # (those that ended while the pool wound up)
        if fut.done():
            settle(i, fut)
    return TaskRun(values, errors, partial, interrupted, ended)
