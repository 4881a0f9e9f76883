"""Progress reporting for long runs: a Rich bar, a user callback, or nothing."""

from __future__ import annotations

import contextlib
import sys
import threading
import time
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
    from rich.console import Console

    console = Console(stderr=True)
    if not (console.is_terminal or console.is_jupyter):  # a log or a pipe: lines, which a bar would not leave
        with _lines(total, description, completed) as advance:
            yield advance
        return
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
    with RichProgress(*columns, transient=False, console=console) as bar:
        task = bar.add_task(description, total=total, completed=completed)
        lock = threading.Lock()

        def advance(n: int) -> None:
            with lock:
                bar.advance(task, n)

        yield advance


LINE_EVERY = 10  # percent: a line each time the work done crosses another tenth (and at the first step)


@contextlib.contextmanager
def _lines(total: int, description: str, completed: int = 0) -> Iterator[Callable[[int], None]]:
    """Progress as plain lines on stderr: ``description: 12/120 (10 %), 3.1 s``, at the first step, at every
    tenth of the work and at the end; a log shows how far a long run got, and the tests wait for them."""
    lock = threading.Lock()
    started = time.monotonic()
    state = {"done": completed, "shown": -1}

    def show() -> None:
        pct = 100.0 * state["done"] / total if total else 100.0
        print(f"{description}: {state['done']}/{total} ({pct:.0f} %), {time.monotonic() - started:.1f} s",
              file=sys.stderr, flush=True)

    def advance(n: int) -> None:
        with lock:
            state["done"] += n
            tenth = int(LINE_EVERY * state["done"] / max(total, 1) // 1) if total else 0
            if state["shown"] < 0 or tenth > state["shown"]:
                state["shown"] = tenth
                show()

    yield advance
    with lock:
        if state["shown"] < LINE_EVERY:
            show()


def announce(progress: Progress, text: str) -> None:
    """Say what a long call does next (one line on stderr) when ``progress`` is True: between its bars,
    no silence."""
    if progress is True:
        from rich.console import Console
        from rich.markup import escape

        Console(stderr=True).print(escape(text), soft_wrap=True)
