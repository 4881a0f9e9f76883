"""The PEER NGA ``.AT2`` format: four header lines, then the accelerations in g, several a line.

The layouts met in the PEER databases (all read here)::

    PEER NGA STRONG MOTION DATABASE RECORD
    IMPERIAL VALLEY 05/19/40 0437, EL CENTRO ARRAY #9, 180
    ACCELERATION TIME SERIES IN UNITS OF G
    NPTS=  2688, DT=   .0100 SEC                       (NGA-West1; NGA-West2 adds a comma after SEC)
    2688    .0100    NPTS, DT                          (the older database)

then values in E-format (``-.1234567E-02``), five or eight a line, the last line partial.  Values
run together without a space (``.1E-01-.2E-01``) are split at their signs; Fortran's three-digit
exponent without its E (``.1234-100``) is an exponent.
"""

from __future__ import annotations

import math
import re

import numpy as np

from .._errors import InputError, Problem

NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[EeDd][-+]?\d+|[-+]\d{3}(?!\d))?")
NPTS_DT = re.compile(r"NPTS\s*=\s*(\d+)\s*,?\s*DT\s*=\s*(" + NUMBER.pattern + ")", re.IGNORECASE)
OLD_NPTS_DT = re.compile(r"^\s*(\d+)\s+(" + NUMBER.pattern + r")\s+NPTS\s*,\s*DT", re.IGNORECASE)
HEADER_LINES = 10  # the NPTS line is looked for among the first lines
UNITS_CM = re.compile(r"UNITS OF\s+CM", re.IGNORECASE)
DATE = re.compile(r"[\s,]+(\d{1,2}/\d{1,2}/\d{2,4})\b.*$")


def _numbers(line: str, number: int, field: str, source: str) -> list[float]:
    """The numbers of a data line; anything else in it is an error naming the line."""
    out, at = [], 0
    for m in NUMBER.finditer(line):
        gap = line[at:m.start()]
        if gap.strip():
            raise InputError(Problem.BAD_CELL, field, source, line=number, column="value", token=gap.strip(),
                             hint="")
        token = m.group().replace("D", "E").replace("d", "e")
        if re.search(r"\d[-+]\d{3}$", token) and "E" not in token.upper():
            token = token[:-4] + "E" + token[-4:]
        value = float(token)
        if not math.isfinite(value):
            raise InputError(Problem.BAD_CELL, field, source, line=number, column="value", token=m.group(),
                             hint=" (beyond the range of a float)")
        out.append(value)
        at = m.end()
    if line[at:].strip():
        raise InputError(Problem.BAD_CELL, field, source, line=number, column="value",
                         token=line[at:].strip(), hint="")
    return out


def parse_at2(text: str, field: str, source: str) -> tuple[np.ndarray, float, str, dict]:
    """The accelerations (in the file's unit), the time step (s), the unit ("g" or "cm/s2") and the
    header's metadata of an AT2 file's text."""
    lines = text.splitlines()
    at = None
    for i, line in enumerate(lines[:HEADER_LINES]):
        m = NPTS_DT.search(line) or OLD_NPTS_DT.search(line)
        if m:
            at = i
            npts, dt = int(m.group(1)), float(m.group(2))
            break
    if at is None:
        raise InputError(Problem.BAD_HEADER, field, source, line=min(4, max(len(lines), 1)),
                         why="no 'NPTS= ..., DT= ...' line in the header",
                         fix="give a PEER .AT2 file (its 4th line reads like 'NPTS=  4000, DT=   .0050 "
                             "SEC'); for other text use Record.from_csv")
    header = [ln.strip() for ln in lines[:at]]
    units_line = " ".join(header).upper()
    if "VELOCITY" in units_line or "DISPLACEMENT" in units_line:
        raise InputError(Problem.BAD_HEADER, field, source, line=max(at, 1),
                         why="the header says this is not an acceleration time series",
                         fix="give the .AT2 file (accelerations), not the .VT2 or .DT2")
    unit = "cm/s2" if UNITS_CM.search(units_line) else "g"
    if dt <= 0.0:
        raise InputError(Problem.BAD_HEADER, field, source, line=at + 1, why=f"DT = {dt:g} s is not > 0",
                         fix="correct the time step in the header")
    if dt * npts > 1e7:
        raise InputError(Problem.BAD_HEADER, field, source, line=at + 1,
                         why=f"NPTS x DT = {npts * dt:.3g} s (longer than any record)",
                         fix="correct DT, in s, in the header")
    if npts < 2:
        raise InputError(Problem.BAD_HEADER, field, source, line=at + 1, why=f"NPTS = {npts} (fewer than 2)",
                         fix="give a record of at least 2 samples")
    values: list[float] = []
    last = at + 1
    for number, line in enumerate(lines[at + 1:], start=at + 2):
        if not line.strip():
            continue
        values.extend(_numbers(line, number, field, source))
        last = number
    if len(values) != npts:
        fix = ("the file is cut short: download it again, or correct NPTS" if len(values) < npts
               else "correct NPTS, or remove the values after the record")
        raise InputError(Problem.NPTS_MISMATCH, field, source, got=len(values), expected=npts,
                         where=f" (line {at + 1}; the values end at line {last})", fix=fix)
    meta: dict = {"header": header, "npts": npts, "dt_s": dt, "unit": unit}
    if len(header) >= 2:
        parts = [p.strip() for p in header[1].split(",")]
        if len(parts) >= 3:
            event = ", ".join(parts[:-2])
            date = DATE.search(event)  # (NGA-West2: "Event, 5/19/1940"; older: "EVENT 05/19/40 0437")
            if date:
                meta["date"] = date.group(1)
                event = event[:date.start()].strip(" ,")
            meta.update(event=event, station=parts[-2], component=parts[-1])
    return np.asarray(values, dtype=float), dt, unit, meta
