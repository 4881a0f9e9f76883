"""Run control: Ctrl-C and the work budget of the compiled kernels, and the up-front estimate.

A compiled kernel holds no Python frame, so Python's own Ctrl-C handling cannot reach it
until it returns.  Every kernel therefore takes a small ``int64`` control array
(``_layout.CTL_*``): it polls ``CTL_STOP`` once per sub-interval and stops with
``Status.INTERRUPTED``, and it counts its sub-intervals in ``CTL_WORK`` against
``CTL_BUDGET`` (``Status.BUDGET``).  :func:`run_interruptibly` runs a kernel on a helper
thread while the main thread waits, so that Ctrl-C lands in Python at once and sets
``CTL_STOP``; the kernels release the GIL, so the wait costs nothing.

:func:`isolator_rate` and :func:`steps_per_second` give a lower bound of the kernels' work
rate: a request that cannot finish within its budget is refused before any work starts.
"""

from __future__ import annotations

import math
import threading
from collections.abc import Callable, Sequence
from typing import Any, TypeVar

import numpy as np

from .._errors import InputError, Problem
from ..model import Oscillator
from ._kernel import SUBINTERVALS_PER_PERIOD
from ._layout import CTL_BUDGET, CTL_LEN, CTL_STOP

R = TypeVar("R")
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


def isolator_rate(oscillator: Oscillator) -> tuple[float, str]:
    """The fastest rate of the isolated mass out of contact, rad/s, and what sets it.

    Out of contact the kernel cuts time into ``SUBINTERVALS_PER_PERIOD`` sub-intervals per
    period of the fastest of this motion (the frequency on the isolator's stiffest branch,
    or its decay rate when overdamped) and the forcing; contacts and events only add, so
    ``SUBINTERVALS_PER_PERIOD * max(rate, omega) / (2 pi)`` bounds the work per second below.
    """
    iso = oscillator.isolator
    k = max(abs(s) for s in iso.slopes)
    if iso.bouc_wen is not None:  # (its initial stiffness, in parallel)
        k += iso.bouc_wen.a * iso.bouc_wen.stiffness
    c = iso.damping
    m = oscillator.mass
    rate = max(math.sqrt(k / m + (0.5 * c / m) ** 2), c / m)
    return rate, (
        f"the isolator's fastest motion {rate:.3g} rad/s: stiffness {k:.3g} N/m, damping "
        f"{c:.3g} N s/m, mass {m:.3g} kg"
    )


def contact_rate(oscillator: Oscillator) -> float:
    """An upper bound of the fastest rate of any phase, rad/s: the isolator's stiffest tangent
    and both linear bumpers at once (inf for a nonlinear law, which is integrated numerically)."""
    iso = oscillator.isolator
    k = max(abs(s) for s in iso.slopes) if iso.hysteresis == "elastic" else (
        abs(iso.slopes[-1]) + sum(abs(a - b) for a, b in zip(iso.slopes, iso.slopes[1:])))
    if iso.bouc_wen is not None:
        k += iso.bouc_wen.a * iso.bouc_wen.stiffness
    c = iso.damping
    b = oscillator.bumpers
    if b is not None:
        for law in (b.left, b.right):
            form = law._linear_form()
            if form is None:  # (several linear branches, or a nonlinear law)
                return math.inf
            k += form[0]
            c += form[1]
    m = oscillator.mass
    return max(math.sqrt(k / m + (0.5 * c / m) ** 2), c / m)


def steps_per_second(rate_rad_s: float, omega_rad_s: Any) -> Any:
    """Least sub-intervals per simulated second at isolator rate and forcing ``omega_rad_s``."""
    return SUBINTERVALS_PER_PERIOD * np.maximum(rate_rad_s, omega_rad_s) / (2.0 * math.pi)


def check_budget(field: str, value: Any, estimate: float, budget: int, why: str, fix: str) -> None:
    """Refuse, naming ``field``, a request whose estimated sub-intervals exceed ``budget``."""
    if estimate > budget:
        raise InputError(
            Problem.OVER_BUDGET,
            field,
            value,
            estimate=f"{estimate:.3g}",
            budget=f"{budget:.3g}",
            why=why,
            fix=fix,
        )
