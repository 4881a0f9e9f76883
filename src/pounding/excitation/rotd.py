"""Orientation-independent spectra of a pair of components: RotD50 and RotD100 (Boore 2010), each
direction's response exact between samples."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from .._checks import one_or_more, plausible, positive
from .._errors import InputError, Interrupted, Problem
from ._spectrum_run import damping_ratio_value, pair_peaks, periods_array
from .pair import RecordPair


def check_pairs(pairs: Any) -> list[RecordPair]:
    """``pairs`` (one :class:`RecordPair` or a non-empty sequence of them) as a list, or an InputError
    naming the entry that is none."""
    return one_or_more("pairs", pairs, RecordPair, "pounding.RecordPair")


MIN_STEP_DEG = 0.05  # the finest step between directions: 3600 of them
COARSE_STEP_DEG = 15.0  # coarser steps miss the largest direction by a few percent (30 degrees: up to 3 %)


def rotation_angles(angle_step_deg: Any) -> np.ndarray:
    """The directions 0, step, ..., up to 180 (not included), degrees: ``angle_step_deg`` in [0.05, 90]
    dividing 180 (a step over 15 degrees warns: RotD100 falls short)."""
    step = positive("angle_step_deg", angle_step_deg, "degrees")
    count = 180.0 / step
    if not MIN_STEP_DEG <= step <= 90.0 or abs(count - round(count)) > 1e-9 * count:
        raise InputError(Problem.OUT_OF_RANGE, "angle_step_deg", step,
                         range=f"[{MIN_STEP_DEG:g}, 90] dividing 180",
                         hint=" (1 degree is the definition's; 180 / step directions)")
    plausible("angle_step_deg", step, MIN_STEP_DEG, COARSE_STEP_DEG,
              "so few directions miss the largest one: RotD100 falls short (at 30 degrees by up to 3 %, "
              "at 90 it is the larger component's); 1 degree is the definition's")
    return step * np.arange(int(round(count)))


def rotd_spectrum(pairs: RecordPair | Sequence[RecordPair], periods_s: Any, damping_ratio: float = 0.05, *,
                  angle_step_deg: float = 1.0) -> Any:
    """RotD50 and RotD100 spectra: the median and the largest over the directions of a linear
    oscillator's peak response to the pair's motion along each direction.

    The motion along the direction ``a`` (degrees, from x towards y) is ``cos(a) x + sin(a) y``; the
    oscillator's response to it is exact (linear between samples) and its peak is found between samples, as
    :func:`pounding.response_spectrum` does, in each of the directions 0, ``angle_step_deg``, ... below 180.
    Pseudo-spectral accelerations are ``omega^2 Sd``; at a period 0 the peak ground acceleration along the
    direction.

    Parameters
    ----------
    pairs : RecordPair or sequence of RecordPair
        The ground motions, e.g. :func:`pounding.records.fema_p695_pairs`.
    periods_s : array_like, shape (p,)
        Natural periods (s), >= 0 and increasing.
    damping_ratio : float
        Fraction of critical damping, in [0, 1).
    angle_step_deg : float
        The step between directions, degrees, dividing 180 (1, the definition's, by default).

    Returns
    -------
    xarray.Dataset
        ``sd_m`` and ``psa_g`` along each direction, dims ``(pair, period_s, angle_deg)``; dims ``(pair,
        period_s)``: ``rotd50_sd_m``, ``rotd100_sd_m``, ``rotd50_psa_g``, ``rotd100_psa_g`` (the median
        and the largest over the directions) and ``rotd100_angle_deg`` (where the largest is); ``pga_g``
        of each pair's components and ``peak_vector_g`` per pair; attributes ``damping_ratio`` and
        ``angle_step_deg``.  ``pair`` is the pairs' names (or their index where one is missing or
        repeated).

    Raises
    ------
    InputError
        A bad argument, or more work than about a minute of one core.
    Interrupted
        On Ctrl-C: ``partial`` holds the spectra of the pairs done (the others NaN).

    Examples
    --------
    A pair whose second component is the first: along 45 degrees the motion is sqrt(2) times either, and
    its RotD100 is sqrt(2) times the component's spectrum:

    >>> import numpy as np
    >>> import pounding
    >>> quake = pounding.records.el_centro()
    >>> pair = pounding.RecordPair(quake, quake)
    >>> spec = pounding.rotd_spectrum(pair, [0.5, 1.0, 2.0])
    >>> one = pounding.response_spectrum(quake, [0.5, 1.0, 2.0])
    >>> ratio = spec["rotd100_psa_g"] / one["psa_g"].values
    >>> ratio.values.round(6), spec["rotd100_angle_deg"].values
    (array([[1.414214, 1.414214, 1.414214]]), array([[45., 45., 45.]]))
    """
    recs = check_pairs(pairs)
    periods = periods_array(periods_s)
    zeta = damping_ratio_value(damping_ratio)
    angles = rotation_angles(angle_step_deg)
    peaks, done = pair_peaks([(p.t, p.x.accel, p.y.accel) for p in recs], periods, zeta, np.radians(angles))
    out = _dataset(recs, periods, zeta, angles, peaks)
    if done < len(recs):
        raise Interrupted(out, done, len(recs), "pairs")
    return out


def _dataset(recs: list[RecordPair], periods: np.ndarray, zeta: float, angles: np.ndarray,
             peaks: np.ndarray) -> Any:
    import xarray as xr

    from .spectrum import record_names

    rigid = periods == 0.0
    omega = 2.0 * math.pi / np.where(rigid, 1.0, periods)
    g = np.array([p.g for p in recs])[:, None, None]
    sd = np.where(rigid[None, :, None], 0.0, peaks)
    psa = np.where(rigid[None, :, None], peaks, omega[None, :, None] ** 2 * peaks) / g
    finite = np.isfinite(peaks).all(axis=2)
    at = np.where(finite, np.argmax(np.where(np.isfinite(psa), psa, -np.inf), axis=2), 0)
    three, two = ("pair", "period_s", "angle_deg"), ("pair", "period_s")

    def named(units: str, long_name: str) -> dict:
        return {"units": units, "long_name": long_name}

    return xr.Dataset(
        {"sd_m": (three, sd, named("m", "peak relative displacement along the direction")),
         "psa_g": (three, psa, named("g", "pseudo-acceleration omega^2 Sd along the direction")),
         "rotd50_sd_m": (two, np.median(sd, axis=2), named("m", "RotD50 displacement")),
         "rotd100_sd_m": (two, sd.max(axis=2), named("m", "RotD100 displacement")),
         "rotd50_psa_g": (two, np.median(psa, axis=2), named("g", "RotD50 pseudo-acceleration")),
         "rotd100_psa_g": (two, psa.max(axis=2), named("g", "RotD100 pseudo-acceleration")),
         "rotd100_angle_deg": (two, np.where(finite, angles[at], np.nan),
                               named("degrees", "the direction of RotD100, from x towards y")),
         "pga_g": (("pair", "component"), np.array([p.pga_g for p in recs]), {"units": "g"}),
         "peak_vector_g": (("pair",), np.array([p.peak_vector_g for p in recs]), {"units": "g"})},
        coords={"pair": record_names(recs), "period_s": periods, "angle_deg": angles,
                "component": ["x", "y"]},
        attrs={"damping_ratio": zeta, "angle_step_deg": 180.0 / angles.size,
               "method": "exact along each direction: closed form between samples, peaks between samples "
                         "found"})
