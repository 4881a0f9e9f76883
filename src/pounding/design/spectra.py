"""Design spectra: ASCE 7-16, EN 1998-1 and a user's table, and ASCE 7-16's isolator displacements.

A :class:`DesignSpectrum` is the 5 %-damped (or damping-corrected) spectral acceleration a code
asks a design to resist, as a function of the period: a plain frozen record with ``.plot()`` and
``.to_dataframe()``; the code spectra are evaluated from their formulas at any period, not
interpolated.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from .._checks import float_array, non_negative, one_of, plausible, positive
from .._errors import InputError, PoundingWarning, Problem
from .._units import GRAVITY_M_S2

# EN 1998-1:2004, Tables 3.2 (Type 1) and 3.3 (Type 2): ground type -> (S, T_B, T_C, T_D) in s
EC8_GROUND = {
    1: {
        "A": (1.0, 0.15, 0.4, 2.0),
        "B": (1.2, 0.15, 0.5, 2.0),
        "C": (1.15, 0.20, 0.6, 2.0),
        "D": (1.35, 0.20, 0.8, 2.0),
        "E": (1.4, 0.15, 0.5, 2.0),
    },
    2: {
        "A": (1.0, 0.05, 0.25, 1.2),
        "B": (1.35, 0.05, 0.25, 1.2),
        "C": (1.5, 0.10, 0.25, 1.2),
        "D": (1.8, 0.10, 0.30, 1.2),
        "E": (1.6, 0.05, 0.25, 1.2),
    },
}
EC8_MAX_PERIOD_S = 4.0  # EN 1998-1 3.2.2.2 gives the elastic spectrum up to 4 s
ASCE_LEVELS = ("design", "mce")
MCE_FACTOR = 1.5  # ASCE 7-16 11.4.7: the MCE_R spectrum is 1.5 times the design spectrum
KINDS = ("asce7-16", "en1998-1", "user")
ASCE_PLOT_MAX_S = 6.0  # drawn to 1.25 T_M of the longest isolation periods in use (about 4.8 s)


@dataclass(frozen=True, eq=False)
class DesignSpectrum:
    """A design (target) spectrum: spectral acceleration in g against the period in s.

    Build one with :func:`asce7_spectrum`, :func:`ec8_spectrum` or :func:`user_spectrum`;
    :meth:`sa_g` evaluates it at any periods.

    Attributes
    ----------
    kind : str
        ``"asce7-16"``, ``"en1998-1"`` or ``"user"``.
    params : Mapping[str, float | str]
        What defines it (``s_ds_g``, ``t_l_s``, ... or ``source``), as given and derived
        (corner periods ``t_0_s``, ``t_s_s``; ``t_b_s``, ``t_c_s``, ``t_d_s``, ``soil_factor``,
        ``eta``).
    name : str
        A label for plots and reports.
    periods_s, values_g : numpy.ndarray, shape (p,)
        A user spectrum's table (empty for the code spectra).

    Examples
    --------
    >>> from pounding import design
    >>> target = design.asce7_spectrum(1.0, 0.6, level="mce")
    >>> target.sa_g([0.0, 1.0, 2.0]).round(3)
    array([0.6 , 0.9 , 0.45])
    >>> target.to_dataframe().shape[1]
    2
    """

    kind: str
    params: Mapping[str, Any]
    name: str = ""
    periods_s: np.ndarray = field(default_factory=lambda: np.empty(0))
    values_g: np.ndarray = field(default_factory=lambda: np.empty(0))

    def sa_g(self, period_s: Any) -> np.ndarray:
        """The spectral acceleration (g) at ``period_s`` (s, >= 0; scalar or array).

        A user spectrum is interpolated linearly between its periods and refuses periods
        outside them; EN 1998-1's is extended beyond 4 s by its last branch, with a warning.
        """
        scalar = np.ndim(period_s) == 0
        t = float_array("period_s", np.atleast_1d(period_s))
        bad = np.flatnonzero(t < 0.0)
        if bad.size:
            raise InputError(Problem.NEGATIVE, f"period_s[{bad[0]}]", float(t[bad[0]]), unit="s")
        if self.kind == "asce7-16":
            out = _asce7(t, self.params)
        elif self.kind == "en1998-1":
            if np.any(t > EC8_MAX_PERIOD_S):
                warnings.warn(
                    f"EN 1998-1 defines the elastic spectrum up to {EC8_MAX_PERIOD_S:g} s; "
                    f"beyond it (here up to {t.max():g} s) its last branch, a_g S eta 2.5 "
                    "T_C T_D / T^2, is extended",
                    PoundingWarning,
                    stacklevel=2,
                )
            out = _ec8(t, self.params)
        else:
            lo, hi = self.periods_s[0], self.periods_s[-1]
            outside = np.flatnonzero((t < lo) | (t > hi))
            if outside.size:
                i = int(outside[0])
                raise InputError(
                    Problem.OUT_OF_RANGE,
                    f"period_s[{i}]",
                    float(t[i]),
                    range=f"[{lo:g}, {hi:g}] s",
                    hint=f" (the periods of {self.name or 'the table'})",
                )
            out = np.interp(t, self.periods_s, self.values_g)
        return float(out[0]) if scalar else out

    @property
    def damping_ratio(self) -> float:
        """The damping the spectrum is for (0.05 unless corrected)."""
        return float(self.params.get("damping_ratio", 0.05))

    def default_periods(self) -> np.ndarray:
        """Periods (s) to draw or tabulate it at: its corners and a fine grid (its own table for a
        user spectrum)."""
        if self.kind == "user":
            return self.periods_s.copy()
        top = EC8_MAX_PERIOD_S if self.kind == "en1998-1" else ASCE_PLOT_MAX_S
        corners = [
            self.params[k]
            for k in ("t_0_s", "t_s_s", "t_l_s", "t_b_s", "t_c_s", "t_d_s")
            if k in self.params and self.params[k] <= top
        ]
        return np.unique(np.concatenate([np.linspace(0.0, top, 401), corners]))

    def to_xarray(self) -> Any:
        """The spectrum of :meth:`to_dataframe` as a Dataset on ``period_s``."""
        from .._tables import frame_to_xarray

        return frame_to_xarray(self.to_dataframe(), "row", index="period_s")

    def to_dataframe(self, periods_s: Any = None) -> Any:
        """``period_s`` and ``sa_g``, at ``periods_s`` or :meth:`default_periods`."""
        import pandas as pd

        t = self.default_periods() if periods_s is None else float_array("periods_s", periods_s)
        return pd.DataFrame({"period_s": t, "sa_g": self.sa_g(t)})

    def plot(self, ax: Any = None, **line: Any) -> Any:
        """The spectrum against the period, corner periods marked; returns its Figure."""
        from ..plots.design import plot_design_spectrum
        from ..plots import figure_of

        return figure_of(plot_design_spectrum(self, ax=ax, **line), ax)

    def __repr__(self) -> str:
        shown = ", ".join(
            f"{k}={v:g}" if isinstance(v, float) else f"{k}={v}"
            for k, v in self.params.items()
            if k in ("s_ds_g", "s_d1_g", "t_l_s", "level", "a_g", "ground_type", "spectrum_type", "source")
        )
        return f"DesignSpectrum({self.kind}, {shown})"


def _asce7(t: np.ndarray, p: Mapping[str, Any]) -> np.ndarray:
    """ASCE 7-16 11.4.6, times 1.5 at the MCE_R level (11.4.7)."""
    s_ds, s_d1, t0, ts, tl = p["s_ds_g"], p["s_d1_g"], p["t_0_s"], p["t_s_s"], p["t_l_s"]
    with np.errstate(divide="ignore", invalid="ignore"):
        sa = np.where(
            t < t0,
            s_ds * (0.4 + 0.6 * t / t0),
            np.where(t <= ts, s_ds, np.where(t <= tl, s_d1 / t, s_d1 * tl / (t * t))),
        )
    return sa * p["level_factor"]


def _ec8(t: np.ndarray, p: Mapping[str, Any]) -> np.ndarray:
    """EN 1998-1 3.2.2.2, equations (3.2)-(3.5)."""
    ag_s = p["a_g"] * p["soil_factor"]
    eta, tb, tc, td = p["eta"], p["t_b_s"], p["t_c_s"], p["t_d_s"]
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(
            t <= tb,
            ag_s * (1.0 + t / tb * (eta * 2.5 - 1.0)),
            np.where(
                t <= tc,
                ag_s * eta * 2.5,
                np.where(t <= td, ag_s * eta * 2.5 * tc / t, ag_s * eta * 2.5 * tc * td / (t * t)),
            ),
        )


def asce7_spectrum(
    s_ds_g: float, s_d1_g: float, t_l_s: float = 8.0, *, level: str = "design", name: str = ""
) -> DesignSpectrum:
    """The ASCE 7-16 design response spectrum (11.4.6), or the MCE_R one (1.5 times it, 11.4.7).

    ``T_0 = 0.2 S_D1 / S_DS``, ``T_S = S_D1 / S_DS``; ``Sa = S_DS (0.4 + 0.6 T / T_0)`` below
    ``T_0``, ``S_DS`` to ``T_S``, ``S_D1 / T`` to ``T_L`` and ``S_D1 T_L / T^2`` beyond.

    Parameters
    ----------
    s_ds_g, s_d1_g : float
        The design spectral accelerations at short periods and at 1 s (g), > 0.
    t_l_s : float
        The long-period transition period (s), from the code's maps (4 to 16 s); default 8.
    level : {"design", "mce"}
        The design spectrum, or the risk-targeted maximum considered earthquake's (isolated
        systems are checked at both).
    name : str
        A label (default from the level).

    Returns
    -------
    DesignSpectrum

    Examples
    --------
    The UPS example's site, S_DS = 1.0 g and S_D1 = 0.6 g:

    >>> from pounding import design
    >>> site = design.asce7_spectrum(1.0, 0.6)
    >>> mce = design.asce7_spectrum(1.0, 0.6, level="mce")
    >>> round(site.sa_g(2.0), 3), round(mce.sa_g(2.0), 3)
    (0.3, 0.45)
    """
    s_ds = positive("s_ds_g", s_ds_g, "g")
    s_d1 = positive("s_d1_g", s_d1_g, "g")
    tl = positive("t_l_s", t_l_s, "s")
    plausible("s_ds_g", s_ds, 0.01, 3.0, "S_DS is in g (1.0 is one g)")
    plausible("s_d1_g", s_d1, 0.01, 2.0, "S_D1 is in g")
    plausible("t_l_s", tl, 4.0, 16.0, "ASCE 7-16's maps give T_L from 4 to 16 s")
    level = one_of("level", level, ASCE_LEVELS)
    ts = s_d1 / s_ds
    if ts >= tl:
        raise InputError(
            Problem.BAD_STATE,
            "t_l_s",
            tl,
            why=f"is not above T_S = S_D1 / S_DS = {ts:g} s",
            fix="check S_DS, S_D1 (g) and T_L (s)",
        )
    params = {
        "s_ds_g": s_ds,
        "s_d1_g": s_d1,
        "t_l_s": tl,
        "level": level,
        "level_factor": MCE_FACTOR if level == "mce" else 1.0,
        "t_0_s": 0.2 * ts,
        "t_s_s": ts,
        "damping_ratio": 0.05,
    }
    label = name or f"ASCE 7-16 {'MCE_R' if level == 'mce' else 'design'} (S_DS {s_ds:g} g, S_D1 {s_d1:g} g)"
    return DesignSpectrum("asce7-16", params, label)


def ec8_spectrum(
    a_gr_g: float,
    ground_type: str = "B",
    spectrum_type: int = 1,
    *,
    importance: float = 1.0,
    damping_ratio: float = 0.05,
    name: str = "",
) -> DesignSpectrum:
    """The EN 1998-1 horizontal elastic response spectrum (3.2.2.2).

    ``a_g = importance a_gR``; ``eta = sqrt(10 / (5 + xi)) >= 0.55`` with ``xi`` in percent;
    ``S``, ``T_B``, ``T_C``, ``T_D`` from Table 3.2 (Type 1) or 3.3 (Type 2).

    Parameters
    ----------
    a_gr_g : float
        The reference peak ground acceleration on ground type A (g), > 0.
    ground_type : {"A", "B", "C", "D", "E"}
    spectrum_type : {1, 2}
        Type 1 (surface-wave magnitude above 5.5) or Type 2 (lower).
    importance : float
        The importance factor gamma_I (0.8 to 1.4 in the code), > 0.
    damping_ratio : float
        The viscous damping the spectrum is for (0.05 gives eta = 1), in (0, 1).
    name : str
        A label.

    Returns
    -------
    DesignSpectrum

    Examples
    --------
    >>> from pounding import design
    >>> ec8 = design.ec8_spectrum(0.25, "C", 1)
    >>> round(ec8.sa_g(0.4), 4)  # the plateau, a_g S 2.5
    0.7188
    """
    agr = positive("a_gr_g", a_gr_g, "g")
    plausible("a_gr_g", agr, 0.01, 1.0, "a_gR is in g (0.25 is a quarter of g)")
    ground = one_of(
        "ground_type",
        ground_type.upper() if isinstance(ground_type, str) else ground_type,
        tuple(EC8_GROUND[1]),
    )
    if isinstance(spectrum_type, bool) or spectrum_type not in (1, 2):
        raise InputError(Problem.NOT_ONE_OF, "spectrum_type", spectrum_type, choices="1, 2")
    gamma = positive("importance", importance, "(a factor)")
    plausible("importance", gamma, 0.8, 1.4, "EN 1998-1's importance factors are 0.8 to 1.4")
    xi = positive("damping_ratio", damping_ratio, "(a fraction of critical)")
    if xi >= 1.0:
        raise InputError(
            Problem.OUT_OF_RANGE,
            "damping_ratio",
            damping_ratio,
            range="(0, 1)",
            hint=" (a fraction: 5 % is 0.05)",
        )
    soil, tb, tc, td = EC8_GROUND[int(spectrum_type)][ground]
    eta = max(math.sqrt(10.0 / (5.0 + 100.0 * xi)), 0.55)
    params = {
        "a_gr_g": agr,
        "importance": gamma,
        "a_g": gamma * agr,
        "ground_type": ground,
        "spectrum_type": int(spectrum_type),
        "soil_factor": soil,
        "t_b_s": tb,
        "t_c_s": tc,
        "t_d_s": td,
        "eta": eta,
        "damping_ratio": xi,
    }
    label = name or f"EN 1998-1 Type {int(spectrum_type)}, ground {ground} (a_g {gamma * agr:g} g)"
    return DesignSpectrum("en1998-1", params, label)


def user_spectrum(
    periods_s: Any = None,
    sa_g: Any = None,
    *,
    path: str | Path | None = None,
    damping_ratio: float = 0.05,
    name: str = "",
) -> DesignSpectrum:
    """A spectrum given as a table: periods (s) and spectral accelerations (g).

    Give the two arrays, or ``path``: a CSV file whose first two columns are the period (s) and
    Sa (g), with or without a header line (``#`` starts a comment).  Periods must increase
    strictly; Sa must be >= 0.  Between periods the spectrum is linear.

    Parameters
    ----------
    periods_s : array_like, shape (p,), optional
        Periods (s), >= 0, strictly increasing, at least two.
    sa_g : array_like, shape (p,), optional
        Spectral accelerations (g), >= 0.
    path : str or Path, optional
        A CSV file instead of the arrays.
    damping_ratio : float
        The damping the spectrum is for (records are scaled with their spectra at it).
    name : str
        A label (default: the file's stem).

    Returns
    -------
    DesignSpectrum

    Examples
    --------
    >>> from pounding import design
    >>> mine = design.user_spectrum([0.0, 0.5, 1.0, 3.0], [0.4, 1.0, 0.6, 0.2])
    >>> float(mine.sa_g(2.0))
    0.4
    """
    if path is not None:
        if periods_s is not None or sa_g is not None:
            raise InputError(
                Problem.WRONG_MODE,
                "path",
                str(path),
                mode="a spectrum read from a file",
                fix="give either path= or periods_s and sa_g",
            )
        periods_s, sa_g, source = _read_spectrum_csv(path)
        name = name or Path(path).stem
    else:
        if periods_s is None or sa_g is None:
            raise InputError(
                Problem.MISSING_INPUT,
                "periods_s" if periods_s is None else "sa_g",
                None,
                what="the periods (s) and the spectral accelerations (g), or path= of a CSV",
            )
        source = "arrays"
    t = float_array("periods_s", periods_s, 2)
    sa = float_array("sa_g", sa_g, 2)
    if sa.size != t.size:
        raise InputError(
            Problem.SIZE_MISMATCH,
            "sa_g",
            f"array of {sa.size}",
            got=sa.size,
            expected=t.size,
            other="periods_s",
        )
    for i, v in enumerate(t):
        non_negative(f"periods_s[{i}]", v, "s")
    bad = np.flatnonzero(np.diff(t) <= 0.0)
    if bad.size:
        i = int(bad[0])
        raise InputError(Problem.NOT_INCREASING, "periods_s", f"... {t[i]:g}, {t[i + 1]:g} ... (at {i + 1})")
    for i, v in enumerate(sa):
        non_negative(f"sa_g[{i}]", v, "g")
    if sa.max() > 10.0:
        plausible("sa_g", float(sa.max()), 0.0, 10.0, "spectral accelerations are in g, not m/s^2")
    zeta = positive("damping_ratio", damping_ratio, "(a fraction of critical)")
    return DesignSpectrum("user", {"source": source, "damping_ratio": zeta}, name or "user spectrum", t, sa)


def _read_spectrum_csv(path: Any) -> tuple[np.ndarray, np.ndarray, str]:
    """The first two columns of a delimited file (a header line allowed; errors name the line)."""
    from .._delimited import read_columns

    values, _, _ = read_columns("path", path, {"x": 0, "y": 1})
    if values["x"].size < 2:
        raise InputError(Problem.TOO_SHORT, "path", str(path), got=values["x"].size, expected=2)
    return values["x"], values["y"], str(path)


# ASCE 7-16 Table 17.5-1: the damping coefficient B_M against the effective damping (fraction)
ASCE_B_M = ((0.02, 0.8), (0.05, 1.0), (0.10, 1.2), (0.20, 1.5), (0.30, 1.7), (0.40, 1.9), (0.50, 2.0))


def asce7_displacement(s_m1_g: float, period_s: float, damping_ratio: float = 0.05) -> dict[str, float]:
    """The isolation system's maximum and total maximum displacements of ASCE 7-16 17.5.3.

    ``D_M = g S_M1 T_M / (4 pi^2 B_M)`` (17.5-1), ``B_M`` from Table 17.5-1 (linear between its
    rows, 0.8 below 2 % and 2.0 above 50 %), and ``D_TM = 1.15 D_M``, the least the code lets the
    total maximum displacement be (17.5.3.3; torsion can ask more).  The moat or bumper gap of an
    isolated structure is at least ``D_TM`` (17.2.5.2).

    Parameters
    ----------
    s_m1_g : float
        The MCE_R spectral acceleration at 1 s (g), ``1.5 S_D1``.
    period_s : float
        The effective period at the maximum displacement, ``T_M`` (s).
    damping_ratio : float
        The effective damping at the maximum displacement, ``beta_M`` (a fraction).

    Returns
    -------
    dict
        ``d_m_m``, ``d_tm_m`` (m) and ``b_m``.

    Examples
    --------
    >>> from pounding import design
    >>> out = design.asce7_displacement(0.9, 2.0, 0.15)
    >>> round(out["b_m"], 3), round(out["d_m_m"], 4), round(out["d_tm_m"], 4)
    (1.35, 0.3313, 0.381)
    """
    s_m1 = positive("s_m1_g", s_m1_g, "g")
    t_m = positive("period_s", period_s, "s")
    beta = non_negative("damping_ratio", damping_ratio, "(a fraction of critical)")
    plausible("damping_ratio", beta, 0.0, 0.5, "the effective damping is a fraction (15 % is 0.15)")
    xs, ys = zip(*ASCE_B_M)
    b_m = float(np.interp(beta, xs, ys))
    d_m = GRAVITY_M_S2 * s_m1 * t_m / (4.0 * math.pi**2 * b_m)
    return {"d_m_m": d_m, "d_tm_m": 1.15 * d_m, "b_m": b_m}
