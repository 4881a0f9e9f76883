"""Validation helpers shared by every constructor: each raises :class:`InputError`."""

from __future__ import annotations

import math
import os
import tomllib
import warnings
from collections.abc import Iterable, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from ._errors import InputError, PoundingWarning, Problem

# Integers beyond this are no count anyone means (cycles, events, iterations): refused, so
# that no array or loop is sized from them.
MAX_COUNT = 10**12


def instance_of(field: str, value: Any, types: type | tuple[type, ...], expected: str) -> Any:
    """Return ``value`` if it is an instance of ``types``, or raise naming ``field``, its type and
    ``expected`` (what to give instead, in words)."""
    if not isinstance(value, types):
        raise InputError(Problem.WRONG_TYPE, field, value, got=type(value).__name__, expected=expected)
    return value


def one_or_more(field: str, value: Any, kind: type, expected: str, entry: str | None = None) -> list:
    """``value`` (one ``kind``, or a non-empty sequence of them) as a list; an entry that is none is named
    ``<entry>[i]`` (``entry`` defaults to ``field``)."""
    if isinstance(value, kind):
        return [value]
    if isinstance(value, Sequence) and not isinstance(value, (str, bytes)) and len(value) > 0:
        for i, v in enumerate(value):
            instance_of(f"{entry or field}[{i}]", v, kind, expected)
        return list(value)
    raise InputError(Problem.WRONG_TYPE, field, value, got=type(value).__name__,
                     expected=f"{expected} or a non-empty list of them")


def sequence_of(field: str, items: Any, kind: type, expected: str) -> tuple:
    """``items`` (a sequence of ``kind``, each checked and named ``field[i]``) as a tuple; ``expected`` says
    what one is, in words (``"pounding.Storey"``)."""
    if isinstance(items, (str, bytes, dict)) or not hasattr(items, "__iter__"):
        raise InputError(Problem.WRONG_TYPE, field, items, got=type(items).__name__,
                         expected=f"sequence of {kind.__name__}")
    items = tuple(items)
    for i, item in enumerate(items):
        instance_of(f"{field}[{i}]", item, kind, expected)
    return items


def real(field: str, value: Any) -> float:
    """Return ``value`` as a finite float, or raise naming ``field``."""
    if isinstance(value, (bool, str, bytes)):  # (text that reads as a number is still text)
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
    if values is None or isinstance(values, (str, bytes, dict)):
        raise InputError(Problem.NOT_A_NUMBER, field, values)
    if isinstance(values, np.ndarray):
        if values.ndim > 1:
            raise InputError(Problem.NOT_1D, field, f"array of shape {values.shape}")
        items = list(values.reshape(-1))
    elif isinstance(values, (list, tuple)):
        items = list(values)
    else:
        items = [values]
    for i, v in enumerate(items):
        if isinstance(v, (list, tuple, dict, np.ndarray)):
            raise InputError(Problem.NOT_1D, f"{field}[{i}]", v)
    return tuple(real(f"{field}[{i}]", v) for i, v in enumerate(items))


def increasing(field: str, values: Sequence[float]) -> None:
    if any(b <= a for a, b in zip(values, values[1:])):
        raise InputError(Problem.NOT_INCREASING, field, list(values))


def one_of(field: str, value: Any, choices: Iterable[str]) -> str:
    choices = tuple(choices)
    if not isinstance(value, str) or value not in choices:
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


def integer(field: str, value: Any, minimum: int, maximum: int = MAX_COUNT, fix: str = "") -> int:
    """Return ``value`` as an int in ``[minimum, maximum]`` (bools and fractions refused).

    ``fix`` says what to do instead of a value above ``maximum``.
    """
    given = value
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        if isinstance(value, (float, np.floating)) and math.isfinite(value) and float(value).is_integer():
            value = int(value)
        else:
            raise InputError(Problem.NOT_INTEGER, field, given, minimum=minimum)
    if value < minimum:
        raise InputError(Problem.NOT_INTEGER, field, given, minimum=minimum)
    if value > maximum:
        raise InputError(Problem.TOO_LARGE, field, given, maximum=maximum, what="",
                         fix=fix or f"give at most {maximum:g}")
    return int(value)


def at_most(field: str, value: float, maximum: float, what: str, fix: str) -> float:
    """``value`` if ``|value| <= maximum``, else an error (magnitudes beyond any real system)."""
    if abs(value) > maximum:
        raise InputError(Problem.TOO_LARGE, field, value, maximum=maximum, what=what, fix=fix)
    return value


def at_least(field: str, value: float, minimum: float, unit: str, fix: str) -> float:
    """``value`` if ``value >= minimum``, else an error (magnitudes below any real system's, which
    overflow the arithmetic: a mass of 1e-300 kg, a record step of 1e-300 s)."""
    if not value >= minimum:
        raise InputError(Problem.TOO_SMALL, field, value, minimum=f"{minimum:g}{unit}", hint=f" ({fix})")
    return value


def plausible(field: str, value: float, low: float, high: float, meant: str) -> None:
    """Warn (:class:`PoundingWarning`) when ``value`` is outside ``[low, high]``.

    ``meant`` says what was probably meant, e.g. "gaps are in m: 15 mm is 0.015".
    """
    if not low <= value <= high:
        warnings.warn(f"{field} = {value!r} is outside the plausible range [{low:g}, {high:g}]: {meant}.",
                      PoundingWarning, stacklevel=4)


def boolean(field: str, value: Any) -> bool:
    """A true bool (TOML ``true``/``false``): strings such as ``"false"`` are refused."""
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    raise InputError(Problem.WRONG_TYPE, field, value, got=type(value).__name__,
                     expected="boolean (true or false, unquoted in TOML)")


def input_path(field: str, path: Any) -> Path:
    """An existing file to read: its type, existence and kind are checked."""
    if not isinstance(path, (str, os.PathLike)):
        raise InputError(Problem.WRONG_TYPE, field, path, got=type(path).__name__,
                         expected="path (str or pathlib.Path)")
    path = Path(path)
    if path.is_dir():
        raise InputError(Problem.NOT_A_FILE, field, str(path))
    if not path.is_file():
        raise InputError(Problem.NO_FILE, field, str(path), cwd=os.getcwd())
    return path


def read_text(field: str, path: Any) -> str:
    """The UTF-8 text of the file ``path`` (bad paths and encodings raise naming ``field``)."""
    path = input_path(field, path)
    try:
        return path.read_text(encoding="utf-8")
    except UnicodeDecodeError as exc:
        raise InputError(Problem.BAD_ENCODING, field, str(path),
                         detail=f"byte {exc.start}: {exc.object[exc.start:exc.start + 1]!r}") from None


def parse_toml(name: str, text: str) -> dict:
    """TOML text as a table; syntax errors name ``name`` (the file) and the place."""
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(Problem.BAD_TOML, name, "...", detail=str(exc)) from None


def read_toml(field: str, path: Any, keys: Sequence[str]) -> dict:
    """The top-level table of the TOML file ``path``, whose keys must be among ``keys``.

    Raises :class:`InputError` naming ``field`` for a missing file, the file for bad TOML,
    and the key for an unknown one.
    """
    text = read_text(field, path)
    table = parse_toml(str(path), text)
    for key in table:
        if key not in keys:
            raise InputError(Problem.UNKNOWN_KEY, key, table[key], choices=", ".join(keys))
    return table


def backbone(prefix: str, slopes: Any, breakpoints: Any, max_slope: float, slope_what: str, slope_fix: str,
             max_break: float, break_fix: str, names: tuple[str, str] = ("slopes", "breakpoints"),
             ) -> tuple[tuple[float, ...], tuple[float, ...]]:
    """A multi-linear backbone's ``(slopes, breakpoints)``, checked: slopes in N/m (the first
    > 0, the others >= 0, each at most ``max_slope``), one breakpoint fewer, in m, > 0, at most
    ``max_break`` and increasing.  ``prefix`` and ``names`` name the fields (``isolator.slopes_n_m``,
    ``law.slopes``)."""
    s_name, b_name = (f"{prefix}.{name}" for name in names)
    out_slopes = real_tuple(s_name, slopes)
    if not out_slopes:
        raise InputError(Problem.EMPTY, s_name, list(out_slopes))
    positive(f"{s_name}[0]", out_slopes[0], "N/m")
    for j, k in enumerate(out_slopes):
        non_negative(f"{s_name}[{j}]", k, "N/m")
        at_most(f"{s_name}[{j}]", k, max_slope, slope_what, slope_fix)
    out_breaks = real_tuple(b_name, breakpoints)
    if len(out_breaks) != len(out_slopes) - 1:
        raise InputError(Problem.BREAKPOINT_COUNT, b_name, list(out_breaks),
                         got=len(out_breaks), expected=len(out_slopes) - 1)
    for j, d in enumerate(out_breaks):
        positive(f"{b_name}[{j}]", d, "m")
        at_most(f"{b_name}[{j}]", d, max_break, " m", break_fix)
    increasing(b_name, out_breaks)
    return out_slopes, out_breaks


def gap_total(field: str, value: Any) -> float:
    """A total gap ``Delta`` in m, checked (> 0, at most 10 m)."""
    return at_most(field, positive(field, value, "m"), 10.0, " m", "give the gap in m (30 mm is 0.03)")
