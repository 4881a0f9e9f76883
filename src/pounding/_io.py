"""Writing results safely: output paths checked before any work, files written atomically.

* :func:`output_file` / :func:`output_dir` check an output path up front (type, parent
  folder exists and is writable, not a directory where a file is meant, a known format from
  the extension), so that no computation is lost to a bad path at the end.
* :func:`atomic_write` writes through a temporary name in the same folder and renames it
  over the target: an interrupt or an error leaves the complete old file or the complete
  new one, never a truncated one.
* :func:`interrupts_deferred` holds Ctrl-C off while results are saved: a Ctrl-C then is
  noted and reported after the files are complete.
"""

from __future__ import annotations

import contextlib
import os
import signal
import threading
from collections.abc import Callable, Iterable, Iterator
from pathlib import Path
from typing import Any

from ._errors import InputError, OutputError, Problem

FIGURE_SUFFIXES = (".png", ".pdf", ".svg", ".jpg", ".jpeg", ".eps", ".ps", ".tif", ".tiff", ".webp")


def _as_path(field: str, path: Any) -> Path:
    if not isinstance(path, (str, os.PathLike)) or str(path) == "":
        raise InputError(
            Problem.WRONG_TYPE,
            field,
            path,
            got=type(path).__name__,
            expected="path (a non-empty str or pathlib.Path)",
        )
    return Path(path)


def _writable_parent(field: str, path: Path) -> None:
    parent = path.parent if str(path.parent) else Path(".")
    if not parent.is_dir():
        raise InputError(
            Problem.BAD_OUTPUT,
            field,
            str(path),
            why=f"is in a folder that does not exist ({parent})",
            fix="create the folder first or give another path",
        )
    if not os.access(parent, os.W_OK | os.X_OK):
        raise InputError(
            Problem.BAD_OUTPUT,
            field,
            str(path),
            why=f"is in a folder you cannot write to ({parent})",
            fix="give a path in a writable folder",
        )


def output_file(field: str, path: Any, suffixes: Iterable[str] | None = None) -> Path:
    """``path`` as a file that can be written, checked before any work.

    Parameters
    ----------
    field : str
        The option or argument's name, for the error.
    path : str or Path
        Where the file will go.
    suffixes : iterable of str, optional
        The formats known from the extension (e.g. ``(".csv",)``); None accepts any.
    """
    path = _as_path(field, path)
    if path.is_dir():
        example = path / ("out" + next(iter(suffixes or [".csv"])))
        raise InputError(
            Problem.BAD_OUTPUT,
            field,
            str(path),
            why="is a directory",
            fix=f"give a file name, e.g. {example}",
        )
    if suffixes is not None:
        suffixes = tuple(suffixes)
        if path.suffix.lower() not in suffixes:
            raise InputError(
                Problem.BAD_OUTPUT,
                field,
                str(path),
                why=f"has the extension {path.suffix or '(none)'!r}, not a format written here",
                fix="end the name with one of " + ", ".join(suffixes),
            )
    if path.exists() and not os.access(path, os.W_OK):
        raise InputError(
            Problem.BAD_OUTPUT,
            field,
            str(path),
            why="exists and cannot be overwritten",
            fix="give another path or make it writable",
        )
    _writable_parent(field, path)
    return path


def output_dir(field: str, path: Any) -> Path:
    """``path`` as a directory that exists or can be created, checked before any work."""
    path = _as_path(field, path)
    if path.exists() and not path.is_dir():
        raise InputError(
            Problem.BAD_OUTPUT,
            field,
            str(path),
            why="is a file, not a directory",
            fix="give a directory (it is created if missing)",
        )
    probe = path
    while not probe.exists():
        probe = probe.parent
    if not probe.is_dir() or not os.access(probe, os.W_OK | os.X_OK):
        raise InputError(
            Problem.BAD_OUTPUT,
            field,
            str(path),
            why=f"cannot be created in {probe}",
            fix="give a directory in a writable place",
        )
    return path


def atomic_write(path: str | os.PathLike, write: Callable[[Path], Any]) -> Path:
    """Call ``write(tmp)`` to write a temporary file beside ``path``, then rename it over ``path``.

    The temporary file keeps ``path``'s extension (writers that pick the format from it
    still do).  On any exception, Ctrl-C included, it is removed and ``path`` is untouched; an
    ``OSError`` (a full disk, a folder made read-only) becomes an :class:`OutputError` naming
    ``path``.
    """
    path = Path(path)
    tmp = path.with_name(f".{path.stem}.{os.getpid()}.{threading.get_ident()}.tmp{path.suffix}")
    try:
        write(tmp)
        os.replace(tmp, path)
    except OSError as exc:
        # (the output's own write or rename: a full disk, a folder made read-only; an error of
        # something else the writer touched, e.g. an input it reads, stays as it was)
        if isinstance(exc, OutputError) or exc.filename not in (None, str(tmp), str(path)):
            raise
        raise OutputError(str(path), exc) from exc
    finally:
        with contextlib.suppress(FileNotFoundError):
            tmp.unlink()
    return path


def write_text(path: str | os.PathLike, text: str) -> Path:
    """Write UTF-8 text to ``path`` atomically."""
    return atomic_write(path, lambda tmp: tmp.write_text(text, encoding="utf-8"))


@contextlib.contextmanager
def interrupts_deferred() -> Iterator[list]:
    """Hold Ctrl-C off inside the block; yields a list that gets one entry per Ctrl-C held.

    Outside the main thread (where Python receives no signals) it does nothing.
    """
    held: list = []
    if threading.current_thread() is not threading.main_thread():
        yield held
        return
    previous = signal.getsignal(signal.SIGINT)
    signal.signal(signal.SIGINT, lambda signum, frame: held.append(signum))
    try:
        yield held
    finally:
        signal.signal(signal.SIGINT, previous)
