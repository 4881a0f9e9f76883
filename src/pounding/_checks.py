"""Validation helpers shared by every constructor: each raises :class:`InputError`."""

from __future__ import annotations

import math
import tomllib
from collections.abc import Iterable, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from ._errors import InputError, Problem


def real(field: str, value: Any) -> float:
    """Return ``value`` as a finite float, or raise naming ``field``."""
    if isinstance(value, bool):
        raise InputError(Problem.NOT_A_NUMBER, field, value)
    try:
        out = float(value)
    except (TypeError, ValueError):
        raise InputError(Problem.NOT_A_NUMBER, field, value) from None
    if not math.isfinite(out):
        raise InputError(Problem.NOT_FINITE, field, value)
    return out


def positive(field: str, value: Any, unit: str) -> float:
    out = real(field, value)
    if out <= 0.0:
        raise InputError(Problem.NOT_POSITIVE, field, value, unit=unit)
    return out


def non_negative(field: str, value: Any, unit: str) -> float:
    out = real(field, value)
    if out < 0.0:
        raise InputError(Problem.NEGATIVE, field, value, unit=unit)
    return out


def real_tuple(field: str, values: Any) -> tuple[float, ...]:
    """A sequence of finite floats as a tuple (a scalar counts as one value)."""
    if isinstance(values, (str, bytes)):
        raise InputError(Problem.NOT_A_NUMBER, field, values)
    if np.ndim(values) == 0:
        values = [values]
    if np.ndim(values) != 1:
        raise InputError(Problem.NOT_1D, field, values)
    return tuple(real(f"{field}[{i}]", v) for i, v in enumerate(values))


def increasing(field: str, values: Sequence[float]) -> None:
    if any(b <= a for a, b in zip(values, values[1:])):
        raise InputError(Problem.NOT_INCREASING, field, list(values))


def one_of(field: str, value: Any, choices: Iterable[str]) -> str:
    choices = tuple(choices)
    if value not in choices:
        raise InputError(Problem.NOT_ONE_OF, field, value, choices=", ".join(map(repr, choices)))
    return value


def float_array(field: str, values: Any, min_len: int = 1) -> np.ndarray:
    """A finite one-dimensional float64 array of at least ``min_len`` values."""
    try:
        arr = np.asarray(values, dtype=np.float64)
    except (TypeError, ValueError):
        raise InputError(Problem.NOT_A_NUMBER, field, values) from None
    if arr.ndim != 1:
        raise InputError(Problem.NOT_1D, field, f"array of shape {arr.shape}")
    if arr.size < min_len:
        raise InputError(Problem.TOO_SHORT, field, f"array of {arr.size}", got=arr.size, expected=min_len)
    bad = np.flatnonzero(~np.isfinite(arr))
    if bad.size:
        i = int(bad[0])
        raise InputError(Problem.NOT_FINITE, f"{field}[{i}]", float(arr[i]))
    return arr


def integer(field: str, value: Any, minimum: int) -> int:
    """Return ``value`` as an int >= ``minimum`` (bools and fractions refused)."""
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        if isinstance(value, (float, np.floating)) and float(value).is_integer():
            value = int(value)
        else:
            raise InputError(Problem.NOT_INTEGER, field, value, minimum=minimum)
    if value < minimum:
        raise InputError(Problem.NOT_INTEGER, field, value, minimum=minimum)
    return int(value)


def read_toml(field: str, path: Any, keys: Sequence[str]) -> dict:
    """The top-level table of the TOML file ``path``, whose keys must be among ``keys``.

    Raises :class:`InputError` naming ``field`` for a missing file, the file for bad TOML,
    and the key for an unknown one.
    """
    path = Path(path)
    if not path.is_file():
        raise InputError(Problem.NO_FILE, field, str(path))
    try:
        table = tomllib.loads(path.read_text(encoding="utf-8"))
    except tomllib.TOMLDecodeError as exc:
        raise InputError(Problem.BAD_TOML, str(path), "...", detail=str(exc)) from None
    for key in table:
        if key not in keys:
            raise InputError(Problem.UNKNOWN_KEY, key, table[key], choices=", ".join(keys))
    return table
