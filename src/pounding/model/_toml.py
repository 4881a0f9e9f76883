"""TOML in and out for the model's frozen dataclasses: one implementation for every class that has
``to_dict`` and ``from_dict`` (the oscillator, a structure, two adjacent structures)."""

from __future__ import annotations

from pathlib import Path
from typing import Any, Optional, TypeVar, Union

import tomli_w

from .._checks import instance_of, parse_toml, read_text
from .._errors import InputError, Problem, warn_renamed

PathLike = Union[str, Path]
T = TypeVar("T", bound="TomlFile")


class TomlFile:
    """``from_toml``/``to_toml`` (and their ``_text`` forms) from the class's ``to_dict``/``from_dict``.

    A ``[meta]`` table holds notes about a file (who wrote it, whether it is partial); ``from_dict`` skips
    it.  Files are written atomically (complete or not at all) and read back identically."""

    def to_dict(self) -> dict[str, Any]:  # pragma: no cover  (each class has its own)
        raise NotImplementedError

    @classmethod
    def from_dict(cls: type[T], table: dict[str, Any]) -> T:  # pragma: no cover  (each class has its own)
        raise NotImplementedError

    @classmethod
    def from_toml(cls: type[T], path: PathLike) -> T:
        """Read it from a TOML file (the ``examples/`` folder has some)."""
        text = read_text("path", path)
        try:
            return cls.from_toml_text(text)
        except InputError as exc:
            if exc.problem is Problem.BAD_TOML:
                raise exc.relabel("text", str(path)) from None
            raise

    @classmethod
    def from_toml_text(cls: type[T], text: str) -> T:
        """Read it from TOML text (e.g. a saved result's ``system`` attribute)."""
        instance_of("text", text, str, "str")
        return cls.from_dict(parse_toml("text", text))

    def to_toml_text(self, meta: Optional[dict[str, Any]] = None) -> str:
        """The TOML text of :meth:`to_toml`."""
        table = self.to_dict()
        if meta:
            table["meta"] = dict(meta)
        return tomli_w.dumps(table)

    def to_toml(self, path: PathLike, meta: Optional[dict[str, Any]] = None) -> Path:
        """Write it to a TOML file that :meth:`from_toml` reads back identically.

        ``meta``: notes written as a ``[meta]`` table (e.g. ``{"partial": True}``); readers skip it.
        The file is written atomically (complete or not at all)."""
        from .._io import output_file, write_text

        return write_text(output_file("path", path, (".toml",)), self.to_toml_text(meta))


def renamed_keys(table: Any, prefix: str, renamed: dict[str, str]) -> Any:
    """A TOML table with its keys' names before (``renamed``: old -> new) read as the new ones, each with a
    ``FutureWarning`` naming it (``prefix`` + key); both spellings of one key is an error."""
    if not isinstance(table, dict) or not any(k in table for k in renamed):
        return table
    out = dict(table)
    for old, new in renamed.items():
        if old in out:
            if new in out:
                raise InputError(Problem.BAD_STATE, prefix + old, out[old],
                                 why=f"is given as well as {prefix + new}, its new name",
                                 fix=f"keep {prefix + new} only")
            warn_renamed(prefix + old, prefix + new, stacklevel=4)
            out[new] = out.pop(old)
    return out
