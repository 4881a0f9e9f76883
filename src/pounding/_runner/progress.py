"""Progress reporting for long runs: a Rich bar, a user callback, or nothing."""

from __future__ import annotations

import contextlib
import threading
from collections.abc import Callable, Iterator
from typing import Any, Union

from .._errors import InputError, Problem

Progress = Union[bool, Callable[[int], None]]


@contextlib.contextmanager
def progress_reporter(progress: Progress, total: int, description: str,
                      completed: int = 0) -> Iterator[Callable[[int], None]]:
    """Yield ``advance(n)``: it moves a Rich bar (``progress=True``), calls the user's
    callable with ``n`` (the number of steps just finished), or does nothing (False).
    ``completed``: steps done before (a resumed study's), where the bar starts.

    ``advance`` is thread-safe.
    """
    if progress is False or progress is None:
        yield lambda n: None
        return
    if callable(progress):
        lock = threading.Lock()

        def advance(n: int) -> None:
            with lock:
                progress(n)

        yield advance
        return
    if progress is not True:
        raise InputError(Problem.WRONG_TYPE, "progress", progress, got=type(progress).__name__,
                         expected="bool or a callable taking the number of steps finished")
    from rich.progress import (BarColumn, MofNCompleteColumn, Progress as RichProgress, ProgressColumn,
                               TextColumn, TimeElapsedColumn, TimeRemainingColumn)
    from rich.text import Text

    class Rate(ProgressColumn):
        """Steps per second over the last half minute (Rich's estimate)."""

        def render(self, task: Any) -> Text:
            speed = task.speed
            return Text("" if speed is None else f"{speed:.3g}/s", style="progress.data.speed")

    columns = (TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(), Rate(),
               TimeElapsedColumn(), TimeRemainingColumn())
    with RichProgress(*columns, transient=False) as bar:
        task = bar.add_task(description, total=total, completed=completed)
        lock = threading.Lock()

        def advance(n: int) -> None:
            with lock:
                bar.advance(task, n)

        yield advance
