"""Elastic response spectra of records, exact for their piecewise-linear accelerations."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from .._checks import one_or_more
from .._errors import Interrupted
from ._spectrum_run import MAX_INTERVALS, damping_ratio_value, periods_array, spectrum_peaks  # noqa: F401
from .record import Record


def check_records(records: Any) -> list[Record]:
    """``records`` (one :class:`Record` or a non-empty sequence of them) as a list, or an InputError naming
    the entry that is none."""
    return one_or_more("record", records, Record, "pounding.Record", entry="records")


def response_spectrum(record: Record | Sequence[Record], periods_s: Any, damping_ratio: float = 0.05) -> Any:
    """Elastic response spectra: the peaks of a linear oscillator's response to each record.

    Exact for the record as the engine sees it (linear between samples), peaks between samples
    included (the core's spectrum.cpp); the oscillator starts at rest at
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
    recs = check_records(record)
    periods = periods_array(periods_s)
    zeta = damping_ratio_value(damping_ratio)
    peaks, done = spectrum_peaks([(r.t, r.accel) for r in recs], periods, zeta)
    if done < len(recs):
        raise Interrupted(_dataset(recs, periods, zeta, peaks), done, len(recs), "records")
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
