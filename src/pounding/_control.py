"""The run control every compiled kernel takes: Ctrl-C and a work budget, shared by the engine,
the spectrum kernel and the task runner.

A compiled kernel holds no Python frame, so Python's own Ctrl-C handling cannot reach it until
it returns.  Every kernel therefore takes a small ``int64`` control array: it polls
``CTL_STOP`` once per sub-interval (or record) and stops with ``Status.INTERRUPTED``, and it
counts its work in ``CTL_WORK`` against ``CTL_BUDGET`` (``Status.BUDGET``).
:func:`run_interruptibly` runs a kernel on a helper thread while the main thread waits, so that
Ctrl-C lands in Python at once and sets ``CTL_STOP``; the kernels release the GIL, so the wait
costs nothing.
"""

from __future__ import annotations

import threading
from collections.abc import Callable, Sequence
from typing import Any, TypeVar

import numpy as np

R = TypeVar("R")
CTL_STOP = 0     # set to 1 by Python (Ctrl-C): kernels return with INTERRUPTED at once
CTL_WORK = 1     # work done so far (sub-intervals), added to by every kernel call sharing the array
CTL_BUDGET = 2   # kernels return with BUDGET once CTL_WORK would pass it
CTL_EVALS = 3    # evaluations of the trajectory at an instant inside a sub-interval (the cost of events)
CTL_SERIES = 4   # a linear phase's sub-intervals whose power series was made (the dearest part of their work)
CTL_AUDITED = 5  # (the tests' audit of the extrema's screen: the extrema it cleared, found all the same)
CTL_ESCAPES = 6  # (and those outside the range its bound gives)
CTL_WHOLE = 7    # a record's steps taken whole (the screen cleared them of every event and extremum inside)
CTL_OWN = 8      # a record's samples at its step taken by their own (no event, no extremum inside: run.cpp)
CTL_LEN = 9
DEFAULT_MAX_STEPS = 100_000_000  # about 1-3 minutes of one core


def new_control(budget: int) -> np.ndarray:
    """A fresh control array: not stopped, no work done, ``budget`` sub-intervals allowed."""
    ctl = np.zeros(CTL_LEN, dtype=np.int64)
    ctl[CTL_BUDGET] = budget
    return ctl


def request_stop(controls: Sequence[np.ndarray]) -> None:
    """Ask every kernel running on these control arrays to stop at its next sub-interval."""
    for ctl in controls:
        ctl[CTL_STOP] = 1


def stop_requested(ctl: np.ndarray) -> bool:
    return bool(ctl[CTL_STOP])


def run_interruptibly(call: Callable[[], R], controls: Sequence[np.ndarray], direct: bool = False) -> R:
    """``call()``, with Ctrl-C turned into a stop request to the kernels it runs.

    From the main thread ``call`` runs on a helper thread and the main thread waits: a
    Ctrl-C sets ``CTL_STOP`` in each of ``controls`` and the wait goes on until the kernel
    has returned (within one sub-interval; more Ctrl-C meanwhile change nothing).  The
    caller sees the kernel's ``INTERRUPTED`` status, not an exception.  From any other
    thread (a campaign's workers) ``call`` runs directly: the thread that owns the
    controls sets them.  ``direct``: run it here anyway, for a call known to return within
    a fraction of a second (a helper thread costs about 0.1 ms: a sixth of a 60-s run).
    """
    if direct or threading.current_thread() is not threading.main_thread():
        return call()
    box: dict[str, Any] = {}
    finished = threading.Event()  # (not Thread.join: one interrupted by Ctrl-C can leave
    # is_alive() False while the thread still runs)

    def target() -> None:
        try:
            box["out"] = call()
        except BaseException as exc:  # re-raised in the caller's thread
            box["exc"] = exc
        finally:
            finished.set()

    threading.Thread(target=target, name="pounding-kernel", daemon=True).start()
    while not finished.is_set():
        try:
            finished.wait()
        except KeyboardInterrupt:
            request_stop(controls)
    if "exc" in box:
        raise box["exc"]
    return box["out"]
