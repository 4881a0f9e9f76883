"""What a task and its run are (the runner's ways of running share them)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

GUARD = ("in a script, run it under if __name__ == '__main__': (each worker process imports the "
         "script first, as Python's multiprocessing does)")


@dataclass(frozen=True)
class Context:
    """What a task sees of the run: see ``pounding._runner``'s docstring."""

    advance: Callable[[int], None]
    stopped: Callable[[], bool]
    control: np.ndarray


@dataclass(frozen=True, eq=False)
class TaskRun:
    """How a run of tasks ended.

    Attributes
    ----------
    values : list
        Per task, in order: its value (a partial one for a task in ``partial``), or None for a task
        that did not run or failed.
    errors : dict of int to BaseException
        The tasks that failed, by index, with their exceptions.
    partial : set of int
        The tasks stopped part way (their value holds what they finished).
    interrupted : bool
        Ctrl-C (or a task's own interruption) stopped the run.
    ended : set of int
        The tasks that ran to their end (whatever they returned, None included).
    """

    values: list
    errors: dict = field(default_factory=dict)
    partial: set = field(default_factory=set)
    interrupted: bool = False
    ended: set = field(default_factory=set)

    @property
    def complete(self) -> bool:
        """Every task ran to its end (a Ctrl-C that came after the last one changes nothing)."""
        return len(self.ended) == len(self.values) and not self.errors and not self.partial

    def raise_first_error(self, name: Callable[[int], str] | None = None) -> None:
        """Raise the error of the first task that failed, if any, as it was (its type, so that an
        ``InputError`` stays one), with a note naming the task (``name(i)``, e.g. "the YBs sweep at
        a_G 0.05 g, up") and how many others failed; a traceback shows the note."""
        if not self.errors:
            return
        first = min(self.errors)
        exc = self.errors[first]
        if name is not None:
            more = len(self.errors) - 1
            exc.add_note(f"(in {name(first)}" + (f"; {more} other task{'s' if more > 1 else ''} failed too)"
                                               if more else ")"))
        raise exc


@dataclass
class Tally:
    """What a run on remote workers (processes, Dask) has so far; ``run`` makes its ``TaskRun``."""

    values: list
    errors: dict = field(default_factory=dict)
    partial: set = field(default_factory=set)
    ended: set = field(default_factory=set)

    def take(self, i: int, result: tuple[Any, int, bool], advance: Callable[[int], None],
             counted: bool) -> None:
        """Record task ``i``'s ``remote`` result and report its progress (a step per task when
        ``counted``, else the steps it reported)."""
        self.values[i], steps, was_partial = result
        (self.partial if was_partial else self.ended).add(i)
        advance(1 if counted else steps)

    def run(self, interrupted: bool) -> TaskRun:
        return TaskRun(self.values, self.errors, self.partial, interrupted, self.ended)


def remote(fn: Callable[[Any, Context], Any], task: Any, budget: int) -> tuple[Any, int, bool]:
    """``fn(task, ctx)`` where the caller's thread cannot reach (a worker process, a Dask worker):
    ``(value, steps it reported, whether it was partial)``; its progress travels back with it."""
    from .._errors import Interrupted
    from .._control import new_control

    steps = [0]

    def advance(n: int) -> None:
        steps[0] += n

    try:
        return fn(task, Context(advance, lambda: False, new_control(budget))), steps[0], False
    except Interrupted as stop:
        return stop.partial, steps[0], True
