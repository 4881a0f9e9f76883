"""Columns of numbers from delimited text (CSV, TSV, semicolons or whitespace), with errors that
name the line and the column: what recordings (``pounding.lab.read_test``) and records
(``Record.from_csv``) are read with.

The delimiter is the first of comma, tab and semicolon found in the first line (the header, where
there is one), else runs of whitespace; fields may be quoted.  Lines starting with ``#`` and blank
lines are skipped.  The first line is a header when any of its fields is not a number.  Every line has as many
fields as the first (a decimal comma or
a stray delimiter is an error, not a shifted column).  An empty field, ``nan`` or ``NaN`` is a
missing value (NaN).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from ._checks import read_text
from ._errors import InputError, Problem

COMMENT = "#"
DELIMITERS = (",", "\t", ";")
MISSING = {"", "nan", "NaN", "NAN"}


def delimiter_of(line: str) -> str | None:
    """The delimiter a text record's line uses (one of ``DELIMITERS``), None for runs of whitespace."""
    for d in DELIMITERS:
        if d in line:
            return d
    return None  # runs of whitespace


def split_fields(line: str, delimiter: str | None) -> list[str]:
    """A line's fields, each stripped of blanks and quotes."""
    fields = line.split(delimiter) if delimiter is not None else line.split()
    return [f.strip().strip('"').strip("'").strip() for f in fields]  # (quoted fields, as spreadsheets write)


def _is_number(token: str) -> bool:
    try:
        float(token)
    except ValueError:
        return token in MISSING
    return True


def read_columns(field: str, path: Any, columns: dict[str, Any],
                 required: tuple[str, ...] = ()) -> tuple[dict[str, np.ndarray], dict[str, str], np.ndarray]:
    """Read the columns ``columns`` (role -> column name or 0-based index) of a delimited file; the roles
    in ``required`` may not miss a value (an empty field or ``nan`` there is an error quoting it).

    Returns
    -------
    values : dict
        role -> float64 array, shape (n_rows,) (NaN where a field is missing).
    names : dict
        role -> the column's name (its header, or ``"column <i>"``).
    line_numbers : ndarray of int, shape (n_rows,)
        The 1-based line of the file each row came from.

    Raises
    ------
    InputError
        A missing file, no data, a column that is not in the file (by name or index), a line
        with too few fields, a field that is not a number: naming the line and the column.
    """
    text = read_text(field, path)
    lines = [(i + 1, ln) for i, ln in enumerate(text.splitlines())
             if ln.strip() and not ln.lstrip().startswith(COMMENT)]
    if not lines:
        raise InputError(Problem.EMPTY, field, str(path))
    delimiter = delimiter_of(lines[0][1])
    first = split_fields(lines[0][1], delimiter)
    header = None if all(_is_number(t) for t in first) else first
    rows = lines[1:] if header is not None else lines
    if not rows:
        raise InputError(Problem.EMPTY, field, str(path))
    index: dict[str, int] = {}
    names: dict[str, str] = {}
    for role, col in columns.items():
        if isinstance(col, str):
            if header is None or col not in header:
                choices = (", ".join(repr(h) for h in header) if header is not None
                           else f"a column index 0 to {len(first) - 1} (the file has no header line)")
                raise InputError(Problem.NO_COLUMN, role, col, choices=choices)
            index[role] = header.index(col)
        elif isinstance(col, (int, np.integer)) and not isinstance(col, bool):
            if not 0 <= int(col) < len(first):
                raise InputError(Problem.OUT_OF_RANGE, role, col, range=f"0 to {len(first) - 1}",
                                 hint=f" (the file's {len(first)} columns, counted from 0)")
            index[role] = int(col)
        else:
            raise InputError(Problem.WRONG_TYPE, role, col, got=type(col).__name__,
                             expected="a column name (str) or a 0-based index (int)")
        names[role] = header[index[role]] if header is not None else f"column {index[role]}"
    needed = max(index.values()) + 1
    out = {role: np.empty(len(rows)) for role in columns}
    for r, (number, line) in enumerate(rows):
        fields = split_fields(line, delimiter)
        if len(fields) < needed:
            missing = next(role for role, i in index.items() if i >= len(fields))
            raise InputError(Problem.SHORT_LINE, field, str(path), line=number, got=len(fields),
                             column=names[missing])
        if len(fields) != len(first):
            raise InputError(Problem.FIELD_COUNT, field, str(path), line=number, got=len(fields),
                             expected=len(first), first="header" if header is not None else "first line")
        for role, i in index.items():
            token = fields[i]
            try:
                value = float(token)
            except ValueError:
                if token not in MISSING:
                    raise InputError(Problem.BAD_CELL, field, str(path), line=number, column=names[role],
                                     token=token, hint=_hint(token)) from None
                value = math.nan
            if role in required and not math.isfinite(value):
                raise InputError(Problem.BAD_CELL, field, str(path), line=number, column=names[role],
                                 token=token, hint=" (this column cannot miss a value: fill or remove it)")
            out[role][r] = value
    return out, names, np.array([number for number, _ in rows])


def _hint(token: str) -> str:
    if "," in token or token.count(".") > 1:
        return " (a decimal comma? pounding reads a point: 0.05)"
    return ""


def as_columns(field: str, spec: Any) -> list[Any]:
    """One column spec or a sequence of them as a non-empty list."""
    if isinstance(spec, (str, int, np.integer)) and not isinstance(spec, bool):
        return [spec]
    if isinstance(spec, Sequence) and not isinstance(spec, (str, bytes)) and len(spec) > 0:
        return list(spec)
    raise InputError(Problem.WRONG_TYPE, field, spec, got=type(spec).__name__,
                     expected="a column name or index, or a non-empty list of them")
