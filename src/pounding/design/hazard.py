"""The site's hazard curve: how often a spectral acceleration at one period is exceeded in a year."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from .._checks import float_array, non_negative, positive, real
from .._errors import InputError, Problem
from .spectra import _read_spectrum_csv


@dataclass(frozen=True, eq=False)
class HazardCurve:
    """How often a spectral acceleration is exceeded at a site: ``lambda(Sa)`` per year.

    Between its points it is linear in log-log (a power law), and beyond them it continues
    the end segments' power laws (:meth:`annual_frequency` says so with a warning where that
    matters: see :func:`pounding.design.annual_frequency`).

    Attributes
    ----------
    sa_g : numpy.ndarray, shape (n,)
        Spectral accelerations (g), > 0, increasing.
    annual_frequency_per_year : numpy.ndarray, shape (n,)
        Their mean annual frequencies of exceedance (1/year), > 0, decreasing.
    period_s : float
        The period (s) of the spectral acceleration (0: the peak ground acceleration).
    name : str
        A label.

    Examples
    --------
    A site's Sa(2 s) with return periods of 43, 475 and 2475 years:

    >>> from pounding import design
    >>> curve = design.HazardCurve.from_return_periods(
    ...     [0.1, 0.4, 1.2], [43, 475, 2475], period_s=2.0)
    >>> round(float(curve.annual_frequency(0.4)) * 475, 6)
    1.0
    >>> round(curve.sa_at(1 / 975), 3)  # the Sa of a 975-year return period
    0.646
    """

    sa_g: np.ndarray
    annual_frequency_per_year: np.ndarray
    period_s: float
    name: str = ""

    def __post_init__(self) -> None:
        sa = float_array("sa_g", self.sa_g, 2)
        lam = float_array("annual_frequency_per_year", self.annual_frequency_per_year, 2)
        if lam.size != sa.size:
            raise InputError(
                Problem.SIZE_MISMATCH,
                "annual_frequency_per_year",
                f"array of {lam.size}",
                got=lam.size,
                expected=sa.size,
                other="sa_g",
            )
        for name, arr, unit in (("sa_g", sa, "g"), ("annual_frequency_per_year", lam, "1/year")):
            bad = np.flatnonzero(arr <= 0.0)
            if bad.size:
                raise InputError(Problem.NOT_POSITIVE, f"{name}[{bad[0]}]", float(arr[bad[0]]), unit=unit)
        if np.any(np.diff(sa) <= 0.0):
            raise InputError(Problem.NOT_INCREASING, "sa_g", sa.tolist())
        if np.any(np.diff(lam) >= 0.0):
            i = int(np.flatnonzero(np.diff(lam) >= 0.0)[0])
            raise InputError(
                Problem.BAD_STATE,
                "annual_frequency_per_year",
                lam.tolist(),
                why=f"does not decrease at {i + 1} ({lam[i]:g} then {lam[i + 1]:g}): a larger "
                "Sa cannot be exceeded more often",
                fix="give the frequencies of exceedance in the order of sa_g",
            )
        period = non_negative("period_s", self.period_s, "s")
        object.__setattr__(self, "sa_g", sa)
        object.__setattr__(self, "annual_frequency_per_year", lam)
        object.__setattr__(self, "period_s", period)

    @classmethod
    def from_return_periods(
        cls, sa_g: Any, return_periods_yr: Any, period_s: float, name: str = ""
    ) -> "HazardCurve":
        """From the spectral accelerations (g) with return periods (years) of a hazard study
        (the frequency is their inverse)."""
        rp = float_array("return_periods_yr", return_periods_yr, 2)
        for i, v in enumerate(rp):
            positive(f"return_periods_yr[{i}]", v, "years")
        return cls(sa_g, 1.0 / rp, period_s, name)

    @classmethod
    def from_csv(cls, path: str | Path, period_s: float, name: str = "") -> "HazardCurve":
        """From a CSV whose first two columns are Sa (g) and the annual frequency of exceedance."""
        sa, lam, _ = _read_spectrum_csv(path)
        return cls(sa, lam, period_s, name or Path(path).stem)

    def annual_frequency(self, sa_g: Any) -> np.ndarray:
        """``lambda`` (1/year) at ``sa_g`` (g, > 0): log-log interpolation, power laws beyond."""
        values = np.asarray(sa_g, dtype=float)
        if np.any(~(values > 0.0)):
            raise InputError(
                Problem.NOT_POSITIVE, "sa_g", values.tolist() if values.ndim else float(values), unit="g"
            )
        x = np.log(values)
        lx, ly = np.log(self.sa_g), np.log(self.annual_frequency_per_year)
        y = np.interp(x, lx, ly)
        lo_slope = (ly[1] - ly[0]) / (lx[1] - lx[0])
        hi_slope = (ly[-1] - ly[-2]) / (lx[-1] - lx[-2])
        y = np.where(x < lx[0], ly[0] + lo_slope * (x - lx[0]), y)
        y = np.where(x > lx[-1], ly[-1] + hi_slope * (x - lx[-1]), y)
        return np.exp(y)

    def sa_at(self, annual_frequency_per_year: Any) -> np.ndarray:
        """The Sa (g) exceeded ``annual_frequency_per_year`` times a year (e.g. 1/2475 for 2 % in
        50 years), within the curve's range."""
        lam = np.atleast_1d(np.asarray(annual_frequency_per_year, dtype=float))
        lo, hi = self.annual_frequency_per_year[-1], self.annual_frequency_per_year[0]
        for i, v in enumerate(lam):
            real(f"annual_frequency_per_year[{i}]", v)
            if not lo <= v <= hi:
                raise InputError(
                    Problem.OUT_OF_RANGE,
                    "annual_frequency_per_year",
                    float(v),
                    range=f"[{lo:g}, {hi:g}] per year",
                    hint=" (the curve's range)",
                )
        out = np.exp(np.interp(-np.log(lam), -np.log(self.annual_frequency_per_year), np.log(self.sa_g)))
        return out if np.ndim(annual_frequency_per_year) else float(out[0])

    def to_xarray(self) -> Any:
        """The table of :meth:`to_dataframe` as a Dataset (one row per point)."""
        from .._tables import frame_to_xarray

        return frame_to_xarray(self.to_dataframe(), "point", {"period_s": self.period_s})

    def to_dataframe(self) -> Any:
        import pandas as pd

        return pd.DataFrame(
            {
                "sa_g": self.sa_g,
                "annual_frequency_per_year": self.annual_frequency_per_year,
                "return_period_yr": 1.0 / self.annual_frequency_per_year,
            }
        )

    def plot(self, ax: Any = None) -> Any:
        """The curve in log-log axes; returns its Figure."""
        from ..plots.design import plot_hazard_curve
        from ..plots import figure_of

        return figure_of(plot_hazard_curve(self, ax=ax), ax)


def probability_in_years(annual_frequency_per_year: Any, years: float = 50.0) -> Any:
    """The probability of at least one occurrence in ``years`` of a Poisson process of that rate:
    ``1 - exp(-lambda years)``.

    Parameters
    ----------
    annual_frequency_per_year : float or array_like
        The mean annual frequency (1/year), >= 0.
    years : float
        The exposure time (years), > 0.

    Returns
    -------
    float or numpy.ndarray
        The probability, of ``annual_frequency_per_year``'s shape.

    Examples
    --------
    The 475-year earthquake in 50 years: the "10 % in 50 years" of the codes.

    >>> from pounding import design
    >>> round(design.probability_in_years(1 / 475, 50.0), 4)
    0.0999
    """
    yrs = positive("years", years, "years")
    lam = np.asarray(annual_frequency_per_year, dtype=float)
    if np.any(~(lam >= 0.0)):
        raise InputError(
            Problem.NEGATIVE,
            "annual_frequency_per_year",
            lam.tolist() if lam.ndim else float(lam),
            unit="1/year",
        )
    out = -np.expm1(-lam * yrs)
    return float(out) if out.ndim == 0 else out
