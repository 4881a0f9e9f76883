"""Elastic response spectra of records, exact for their piecewise-linear accelerations."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from .._checks import float_array, real
from .._errors import InputError, Interrupted, Problem
from ._spectrum_kernel import DONE, INTERRUPTED, spectrum_kernel
from .record import Record

MAX_INTERVALS = 2_000_000_000  # periods x record intervals: about a minute of one core


def _records(records: Any) -> list[Record]:
    if isinstance(records, Record):
        return [records]
    if isinstance(records, Sequence) and not isinstance(records, (str, bytes)) and len(records) > 0:
        for i, r in enumerate(records):
            if not isinstance(r, Record):
                raise InputError(Problem.WRONG_TYPE, f"records[{i}]", r, got=type(r).__name__,
                                 expected="pounding.Record")
        return list(records)
    raise InputError(Problem.WRONG_TYPE, "record", records, got=type(records).__name__,
                     expected="pounding.Record or a non-empty list of them")


def periods_array(periods_s: Any) -> np.ndarray:
    """Validated periods (s): finite, >= 0, strictly increasing, shape (p,)."""
    periods = float_array("periods_s", periods_s)
    if (periods < 0.0).any():
        i = int(np.flatnonzero(periods < 0.0)[0])
        raise InputError(Problem.NEGATIVE, f"periods_s[{i}]", float(periods[i]), unit="s")
    if periods.size > 1 and (np.diff(periods) <= 0.0).any():
        raise InputError(Problem.NOT_INCREASING, "periods_s", periods.tolist()[:6])
    return periods


def damping_ratio_value(damping_ratio: Any) -> float:
    """A validated damping ratio in [0, 1)."""
    zeta = real("damping_ratio", damping_ratio)
    if not 0.0 <= zeta < 1.0:
        raise InputError(Problem.OUT_OF_RANGE, "damping_ratio", zeta, range="[0, 1)",
                         hint=" (a fraction of critical: 0.05 is 5 %)")
    return zeta


def response_spectrum(record: Record | Sequence[Record], periods_s: Any, damping_ratio: float = 0.05) -> Any:
    """Elastic response spectra: the peaks of a linear oscillator's response to each record.

    Exact for the record as the engine sees it (linear between samples), peaks between samples
    included (see :mod:`pounding.excitation._spectrum_kernel`); the oscillator starts at rest at
    the record's first sample and is followed to its last.

    Parameters
    ----------
    record : Record or sequence of Record
        The ground motion(s), e.g. :func:`pounding.records.el_centro` or a FEMA P695 set.
    periods_s : array_like, shape (p,)
        Natural periods (s), >= 0 and increasing; at 0 the oscillator is rigid (``Sa = PSa = PGA``).
    damping_ratio : float
        Fraction of critical damping, in [0, 1).

    Returns
    -------
    xarray.Dataset
        Dims ``(record, period_s)``: ``sd_m`` (peak relative displacement), ``sv_m_s`` (peak
        relative velocity), ``sa_m_s2`` (peak absolute acceleration), ``psv_m_s = omega Sd``,
        ``psa_m_s2 = omega^2 Sd``, and ``sa_g``, ``psa_g`` (in each record's g); ``record`` is the
        records' names (or their index where a name is missing or repeated), ``pga_g`` per record;
        attribute ``damping_ratio``.

    Raises
    ------
    InputError
        A bad argument, or more work than about a minute of one core (periods times samples).
    Interrupted
        On Ctrl-C: ``partial`` holds the spectra of the records done (the others NaN).

    Examples
    --------
    The 5 %-damped spectrum of El Centro 1940 N-S at three periods:

    >>> import pounding
    >>> spec = pounding.response_spectrum(pounding.records.el_centro(),
    ...                                   [0.5, 1.0, 2.0], damping_ratio=0.05)
    >>> spec["psa_g"].values.round(2)  # shape (records, periods)
    array([[0.92, 0.46, 0.14]])
    >>> spec["sd_m"].sel(period_s=1.0).values.round(3)  # m
    array([0.113])
    """
    from ..engine._control import new_control, run_interruptibly

    recs = _records(record)
    periods = periods_array(periods_s)
    zeta = damping_ratio_value(damping_ratio)
    # the kernel's work: every record interval, and every half period inside them (searched for peaks)
    half_periods = float(np.sum(2.0 / periods[periods > 0.0])) * math.sqrt(1.0 - zeta * zeta)
    work = sum(periods.size * (r.t.size - 1) + half_periods * (r.t[-1] - r.t[0]) for r in recs)
    if work > MAX_INTERVALS:
        raise InputError(Problem.TOO_MUCH_WORK, "periods_s", f"{periods.size} periods down to "
                         f"{periods[periods > 0.0].min() if (periods > 0.0).any() else 0.0:g} s",
                         estimate=f"{work:.3g}", unit="intervals and half periods",
                         budget=f"{MAX_INTERVALS:.3g}",
                         fix="fewer periods or records, or no periods far below the record's time step")
    rigid = periods == 0.0
    omegas = 2.0 * math.pi / periods[~rigid]
    peaks = np.full((len(recs), periods.size, 3), np.nan)
    ctl = new_control(MAX_INTERVALS)
    for i, r in enumerate(recs):
        out = np.zeros((omegas.size, 3))
        t, a = np.array(r.t, dtype=float), np.array(r.accel, dtype=float)
        status = run_interruptibly(lambda t=t, a=a, out=out: spectrum_kernel(t, a, omegas, zeta, out, ctl),
                                   [ctl])
        if status == INTERRUPTED:
            raise Interrupted(_dataset(recs, periods, zeta, peaks), i, len(recs), "records")
        if status != DONE:  # (the budget was checked above)
            raise RuntimeError(f"response_spectrum: the kernel stopped with status {status}")
        peaks[i, ~rigid] = out
        peaks[i, rigid] = (0.0, 0.0, float(np.abs(r.accel).max()))
    return _dataset(recs, periods, zeta, peaks)


def record_names(recs: Sequence[Record]) -> list[str]:
    """The records' names, or their index where a name is missing or repeated."""
    names = [r.name for r in recs]
    return [n if n and names.count(n) == 1 else f"{i}" for i, n in enumerate(names)]


def _dataset(recs: list[Record], periods: np.ndarray, zeta: float, peaks: np.ndarray) -> Any:
    import xarray as xr

    rigid = periods == 0.0
    omega = np.where(rigid, 0.0, 2.0 * math.pi / np.where(rigid, 1.0, periods))
    g = np.array([r.g for r in recs])[:, None]
    sd = peaks[..., 0]
    psa = omega[None, :] ** 2 * sd
    psa[:, rigid] = peaks[:, rigid, 2]
    dims = ("record", "period_s")
    return xr.Dataset(
        {"sd_m": (dims, sd, {"units": "m", "long_name": "peak relative displacement"}),
         "sv_m_s": (dims, peaks[..., 1], {"units": "m/s", "long_name": "peak relative velocity"}),
         "sa_m_s2": (dims, peaks[..., 2], {"units": "m/s^2", "long_name": "peak absolute acceleration"}),
         "psv_m_s": (dims, omega[None, :] * sd, {"units": "m/s", "long_name": "pseudo-velocity omega Sd"}),
         "psa_m_s2": (dims, psa, {"units": "m/s^2", "long_name": "pseudo-acceleration omega^2 Sd"}),
         "sa_g": (dims, peaks[..., 2] / g, {"units": "g"}),
         "psa_g": (dims, psa / g, {"units": "g"}),
         "pga_g": (("record",), np.array([r.pga_g for r in recs]), {"units": "g"})},
        coords={"record": record_names(recs), "period_s": periods},
        attrs={"damping_ratio": zeta,
               "method": "exact: closed form between samples, peaks between samples found"})
