"""Record suites scaled to a target spectrum.

Two rules, as codes and FEMA P695 use them:

- **to a period**: each record times its own factor, so that its pseudo-spectral acceleration
  at the period equals the target's there;
- **over a period range**: the whole suite times one factor, the smallest with which the
  suite's mean pseudo-spectral acceleration is nowhere below ``not_below`` times the target in
  the range (ASCE 7-16 17.3.3 asks this of isolated structures over 0.75 T_M to 1.25 T_M).

A suite of pairs of components is scaled by its maximum-direction spectra (RotD100,
:func:`pounding.rotd_spectrum`), each pair's two components by one factor, as ASCE 7-16 17.3.3 asks.
The spectra are exact for the records as the engine sees them
(:func:`pounding.response_spectrum`); a linear oscillator's response scales with its input,
so each record's spectrum is computed once and multiplied.
"""

from __future__ import annotations

import warnings
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from .._checks import instance_of, integer, one_or_more, positive, real
from .._errors import InputError, PoundingWarning, Problem
from ..excitation.pair import RecordPair
from ..excitation.record import Record
from ..excitation.spectrum import check_records, response_spectrum
from .spectra import DesignSpectrum

PLOT_PERIODS_S = np.geomspace(0.02, 6.0, 60)  # where the scaled spectra are drawn
FACTOR_PLAUSIBLE = (0.2, 5.0)  # factors outside this distort the records' content (a warning)
METHODS = ("period", "range")


@dataclass(frozen=True, eq=False)
class ScaledSuite:
    """A record suite scaled to a target spectrum (:func:`scale_suite`).

    Attributes
    ----------
    records : tuple of Record or of RecordPair, shape (r,)
        The scaled records or pairs (``meta["scale_factor"]`` says by how much).
    factors : numpy.ndarray, shape (r,)
        The factor of each record (all equal over a period range).
    target : DesignSpectrum
    method : {"period", "range"}
    period_range_s : tuple of float
        The range the rule held over (both ends equal for a single period).
    not_below : float
        The fraction of the target the mean was kept above (range rule).
    spectra : xarray.Dataset
        The scaled records' spectra (:func:`pounding.response_spectrum`'s variables; a pair's: its
        RotD100 ``psa_g`` and ``sd_m``, its peak vector as ``pga_g``) at ``PLOT_PERIODS_S`` and the
        rule's periods, dims ``(record, period_s)``.

    Examples
    --------
    >>> import pounding
    >>> from pounding import design
    >>> suite = design.scale_suite(pounding.records.el_centro(),
    ...                            design.asce7_spectrum(1.0, 0.6), period_s=2.0)
    >>> row = suite.to_dataframe().round(3).iloc[0]
    >>> [float(row[k]) for k in ("scale_factor", "pga_g", "psa_g_at_2_s")]
    [2.183, 0.696, 0.3]
    """

    records: tuple[Record | RecordPair, ...]
    factors: np.ndarray
    target: DesignSpectrum
    method: str
    period_range_s: tuple[float, float]
    not_below: float
    spectra: Any

    @property
    def damping_ratio(self) -> float:
        return float(self.spectra.attrs["damping_ratio"])

    def mean_psa_g(self) -> Any:
        """The suite's mean pseudo-spectral acceleration (g) over ``spectra``'s periods."""
        return self.spectra["psa_g"].mean("record")

    def shortfall(self) -> float:
        """The smallest ratio of the mean to the target over the rule's periods (>= ``not_below``
        for the range rule, up to the arithmetic's rounding)."""
        lo, hi = self.period_range_s
        mean = self.mean_psa_g().sel(period_s=slice(lo, hi))
        return float((mean / self.target.sa_g(mean["period_s"].values)).min())

    def to_xarray(self) -> Any:
        """The table of :meth:`to_dataframe` as a Dataset along ``record``."""
        from .._tables import frame_to_xarray

        return frame_to_xarray(self.to_dataframe(), "record")

    def to_dataframe(self) -> Any:
        """One row per record: ``record``, ``scale_factor``, ``pga_g`` (scaled), ``psa_g`` at the
        rule's periods' ends."""
        import pandas as pd

        lo, hi = self.period_range_s
        psa = self.spectra["psa_g"]
        out = {
            "record": list(self.spectra["record"].values),
            "scale_factor": self.factors,
            "pga_g": self.spectra["pga_g"].values,
            f"psa_g_at_{lo:g}_s": psa.sel(period_s=lo).values,
        }
        if hi != lo:
            out[f"psa_g_at_{hi:g}_s"] = psa.sel(period_s=hi).values
        return pd.DataFrame(out)

    def plot(self, ax: Any = None) -> Any:
        """Each scaled spectrum (thin), their mean and the target, the rule's periods shaded.
        Returns its Figure."""
        from ..plots.design import plot_scaled_suite
        from ..plots import figure_of

        return figure_of(plot_scaled_suite(self, ax=ax), ax)

    def __repr__(self) -> str:
        lo, hi = self.period_range_s
        where = f"at {lo:g} s" if lo == hi else f"over {lo:g}-{hi:g} s"
        what = "pairs" if isinstance(self.records[0], RecordPair) else "records"
        return (
            f"ScaledSuite({len(self.records)} {what} {where}, factors {self.factors.min():.3g}-"
            f"{self.factors.max():.3g}, target {self.target.name!r})"
        )


def scale_suite(
    records: Record | RecordPair | Sequence[Record] | Sequence[RecordPair],
    target: DesignSpectrum,
    *,
    period_s: float | None = None,
    period_range_s: Sequence[float] | None = None,
    not_below: float = 1.0,
    damping_ratio: float | None = None,
    n_periods: int = 41,
) -> ScaledSuite:
    """Scale a record suite to a target spectrum, at a period or over a period range.

    Parameters
    ----------
    records : Record, RecordPair or a sequence of either
        The suite (e.g. :func:`pounding.records.fema_p695`), or a suite of pairs
        (:func:`pounding.records.fema_p695_pairs`), scaled by their RotD100 spectra.
    target : DesignSpectrum
        From :func:`asce7_spectrum`, :func:`ec8_spectrum` or :func:`user_spectrum`.
    period_s : float, optional
        Scale each record to the target's Sa at this period (s), by a factor of its own.
    period_range_s : (float, float), optional
        Scale the suite by one factor so that its mean pseudo-spectral acceleration is not below
        ``not_below`` times the target at ``n_periods`` periods spread evenly (in log) over the
        range (s), ends included.  Give this or ``period_s``.
    not_below : float
        The fraction of the target the mean must reach (1.0; ASCE 7-16 chapter 16 uses 0.9).
    damping_ratio : float, optional
        The spectra's damping (default: the target's, 0.05 for the code spectra).
    n_periods : int
        Periods checked in the range (>= 2).

    Returns
    -------
    ScaledSuite

    Raises
    ------
    InputError
        A bad argument, or a suite that no factor brings to the target (a record, or the suite's
        mean, with no spectral acceleration at a period of the rule).

    Examples
    --------
    El Centro to the UPS site's MCE_R spectrum at 2 s:

    >>> import pounding
    >>> from pounding import design
    >>> mce = design.asce7_spectrum(1.0, 0.6, level="mce")
    >>> suite = design.scale_suite(pounding.records.el_centro(), mce, period_s=2.0)
    >>> round(float(suite.factors[0]), 3)
    3.275
    """
    pairs = isinstance(records, RecordPair) or (isinstance(records, Sequence) and len(records) > 0
                                                 and isinstance(records[0], RecordPair))
    recs = (one_or_more("records", records, RecordPair, "pounding.RecordPair (a suite is all pairs or all "
                        "records)") if pairs else check_records(records))
    instance_of("target", target, DesignSpectrum,
                "pounding.design.DesignSpectrum (asce7_spectrum, ec8_spectrum, ...)")
    if (period_s is None) == (period_range_s is None):
        raise InputError(
            Problem.MISSING_INPUT,
            "period_s",
            period_s,
            what="either period_s= (each record to the target there) or period_range_s=(lo, hi) "
            "(one factor for the suite)",
        )
    zeta = target.damping_ratio if damping_ratio is None else real("damping_ratio", damping_ratio)
    if period_s is not None:
        lo = hi = positive("period_s", period_s, "s")
        rule = np.array([lo])
        method = "period"
    else:
        lo, hi = _range(period_range_s)
        n = integer("n_periods", n_periods, 2, 10_000)
        rule = np.geomspace(lo, hi, n)
        method = "range"
    fraction = positive("not_below", not_below, "(a fraction of the target)")
    if fraction > 2.0:
        raise InputError(
            Problem.OUT_OF_RANGE,
            "not_below",
            not_below,
            range="(0, 2]",
            hint=" (a fraction of the target: 0.9 is 90 %)",
        )
    wanted = target.sa_g(rule)
    periods = np.unique(np.concatenate([PLOT_PERIODS_S, rule]))
    raw = _rotd100(recs, periods, zeta) if pairs else response_spectrum(recs, periods, zeta)
    psa = raw["psa_g"].sel(period_s=rule).values  # (records, rule periods)
    names = list(raw["record"].values)
    if method == "period":
        zero = np.flatnonzero(psa[:, 0] <= 0.0)
        if zero.size:
            raise InputError(
                Problem.NO_FIT,
                f"records[{zero[0]}]",
                names[zero[0]],
                why=f"has no spectral acceleration at {lo:g} s, so no factor scales it to the target",
                fix="leave it out of the suite",
            )
        factors = wanted[0] / psa[:, 0]
    else:
        mean = psa.mean(axis=0)
        if np.any(mean <= 0.0):
            t_bad = float(rule[np.flatnonzero(mean <= 0.0)[0]])
            raise InputError(
                Problem.NO_FIT,
                "records",
                f"{len(recs)} records",
                why=f"have no spectral acceleration at {t_bad:g} s, so no factor brings their mean "
                "to the target",
                fix="choose other records or another period range",
            )
        factors = np.full(len(recs), float(np.max(fraction * wanted / mean)))
    odd = np.flatnonzero((factors < FACTOR_PLAUSIBLE[0]) | (factors > FACTOR_PLAUSIBLE[1]))
    if odd.size:
        warnings.warn(
            f"scale factors outside [{FACTOR_PLAUSIBLE[0]:g}, {FACTOR_PLAUSIBLE[1]:g}] "
            f"({', '.join(f'{names[i]}: {factors[i]:.3g}' for i in odd[:5])}"
            f"{', ...' if odd.size > 5 else ''}): records scaled that far no longer resemble the "
            "site's shaking; choose records closer to the target",
            PoundingWarning,
            stacklevel=2,
        )
    scaled = tuple(_scaled(r, f) for r, f in zip(recs, factors))
    spectra = raw.copy()
    for var in ("sd_m", "sv_m_s", "sa_m_s2", "psv_m_s", "psa_m_s2", "sa_g", "psa_g"):
        if var in raw:
            spectra[var] = raw[var] * factors[:, None]
    spectra["pga_g"] = raw["pga_g"] * factors
    spectra["scale_factor"] = ("record", factors)
    return ScaledSuite(scaled, factors, target, method, (lo, hi), fraction, spectra)


def _rotd100(pairs: list[RecordPair], periods: np.ndarray, zeta: float) -> Any:
    """The pairs' maximum-direction spectra as a suite's: ``psa_g`` and ``sd_m`` their RotD100, ``pga_g``
    their peak vector, dims ``(record, period_s)``."""
    import xarray as xr

    from ..excitation.rotd import rotd_spectrum

    rot = rotd_spectrum(pairs, periods, zeta)
    dims = ("record", "period_s")
    return xr.Dataset({"psa_g": (dims, rot["rotd100_psa_g"].values, {"units": "g"}),
                       "sd_m": (dims, rot["rotd100_sd_m"].values, {"units": "m"}),
                       "pga_g": ("record", rot["peak_vector_g"].values, {"units": "g"})},
                      coords={"record": rot["pair"].values, "period_s": rot["period_s"].values},
                      attrs={**rot.attrs, "measure": "RotD100"})


def _range(period_range_s: Any) -> tuple[float, float]:
    if (
        isinstance(period_range_s, (str, bytes))
        or not isinstance(period_range_s, (Sequence, np.ndarray))
        or len(period_range_s) != 2
    ):
        raise InputError(
            Problem.LENGTH_MISMATCH,
            "period_range_s",
            period_range_s,
            got=len(period_range_s) if isinstance(period_range_s, (Sequence, np.ndarray)) else 1,
            expected=2,
            hint=" (lo, hi) in s, e.g. (0.75 T_M, 1.25 T_M)",
        )
    lo = positive("period_range_s[0]", period_range_s[0], "s")
    hi = positive("period_range_s[1]", period_range_s[1], "s")
    if hi <= lo:
        raise InputError(Problem.NOT_INCREASING, "period_range_s", [lo, hi])
    return lo, hi


def _scaled(record: Record | RecordPair, factor: float) -> Record | RecordPair:
    if isinstance(record, RecordPair):
        return record.scaled(float(factor))
    return record.scaled(factor=float(factor))


def stripe_factors(
    records: Record | Sequence[Record], levels_g: Any, period_s: float, damping_ratio: float = 0.05
) -> np.ndarray:
    """The factors that bring each record's pseudo-spectral acceleration at ``period_s`` to each
    intensity level (multiple-stripe analysis): shape ``(levels, records)``.

    Parameters
    ----------
    records : Record or sequence of Record, shape (r,)
        The suite.
    levels_g : array_like, shape (s,)
        The stripes' pseudo-spectral accelerations (g), > 0.
    period_s : float
        The period (s) of the intensity measure, > 0.
    damping_ratio : float
        The spectra's damping.

    Returns
    -------
    numpy.ndarray, shape (s, r)
        The factor of each record at each level.

    Examples
    --------
    >>> import pounding
    >>> from pounding import design
    >>> rec = pounding.records.el_centro()
    >>> design.stripe_factors(rec, [0.1, 0.2], 2.0).round(3)
    array([[0.728],
           [1.456]])
    """
    recs = check_records(records)
    levels = np.atleast_1d(np.asarray(levels_g, dtype=float))
    for i, v in enumerate(levels):
        positive(f"levels_g[{i}]", v, "g")
    period = positive("period_s", period_s, "s")
    psa = response_spectrum(recs, [period], real("damping_ratio", damping_ratio))["psa_g"].values[:, 0]
    zero = np.flatnonzero(psa <= 0.0)
    if zero.size:
        raise InputError(
            Problem.NO_FIT,
            f"records[{zero[0]}]",
            recs[zero[0]].name or zero[0],
            why=f"has no spectral acceleration at {period:g} s",
            fix="leave it out of the suite",
        )
    return levels[:, None] / psa[None, :]
