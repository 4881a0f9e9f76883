"""``BifurcationCurve`` and ``CoexistenceMap``: what :func:`pounding.bifurcation_curve` and
:func:`pounding.coexistence_map` return."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Sequence

import numpy as np
import pandas as pd

from .._errors import Status
from ._through_sweeps import STEP_COLUMNS
from .branch import FollowedTable

if TYPE_CHECKING:  # pragma: no cover
    from ..model import Oscillator
    from ._curve import CurvePoint
    from .branch import Bifurcation, Branch

CURVE_COLUMNS = ("freq_hz", "a_g", "alpha", "excursion_m", "displacement_max_m", "displacement_min_m",
                 "max_abs_multiplier", "critical_multiplier", "contacts_per_period", "test", "residual",
                 "phase_rad")


@dataclass(frozen=True, eq=False)
class BifurcationCurve(FollowedTable):
    """A fold or a grazing followed in (a_G, f).

    Attributes
    ----------
    oscillator : Oscillator, Structure or Adjacent
        The system.
    kind : {"fold", "grazing"}
        What is followed: a fold (a multiplier is 1) or a grazing (the orbit just touches a contact).
    side : str
        The contact of a grazing (:attr:`Bifurcation.side`: ``"wall0_left"``, ``"wall0_right"`` for a
        single mass's bumpers), else ``""``.
    period_multiple : int
        The orbits' period, in forcing periods.
    freqs_hz, a_g : (float, float)
        The box it was followed in: frequencies, Hz, and table accelerations, g.
    data : DataFrame
        One row per point in the curve's order (see :meth:`to_dataframe`).
    states : ndarray, shape (points, state length)
        Each point's orbit at its section (time 0, the forcing's angle ``phase_rad``).
    status : Status
        ``SUCCESS`` when both ends reached the box's edge or the curve closed, ``STEP_FAILED``
        when the corrector failed at the smallest step, ``BUDGET`` at ``max_points``,
        ``INTERRUPTED`` on Ctrl-C.
    message : str
        What happened, for people.
    start : Bifurcation
        The bifurcation it was followed from.

    Examples
    --------
    The fold at 2.014 Hz of the damped paper system's branch at a_G = 0.05, followed in (f, a_G):
    a stronger shaking moves it to a higher frequency.

    >>> import pounding
    >>> osc = pounding.presets.paper_damped()
    >>> fold = pounding.continuation(osc, 0.05, (1.5, 2.5)).folds()[0]
    >>> curve = pounding.bifurcation_curve(osc, fold, a_g=(0.045, 0.055),
    ...                                    freqs_hz=(1.5, 2.5), max_step=0.1)
    >>> curve.kind, curve.status.name, curve.passes(fold)
    ('fold', 'SUCCESS', True)
    >>> df = curve.to_dataframe()
    >>> print(f"{df['freq_hz'].iloc[0]:.3f} Hz at a_G {df['a_g'].iloc[0]:.3f}, "
    ...       f"{df['freq_hz'].iloc[-1]:.3f} Hz at a_G {df['a_g'].iloc[-1]:.3f}")
    1.881 Hz at a_G 0.045, 2.146 Hz at a_G 0.055
    """

    oscillator: "Oscillator" = field(repr=False)
    kind: str
    side: str
    period_multiple: int
    freqs_hz: tuple[float, float]
    a_g: tuple[float, float]
    data: pd.DataFrame = field(repr=False)
    states: np.ndarray = field(repr=False)
    status: Status
    message: str
    start: "Bifurcation" = field(repr=False)

    def to_xarray(self) -> Any:
        """The table of :meth:`to_dataframe` as a Dataset along ``point``."""
        from .._tables import frame_to_xarray

        return frame_to_xarray(self.to_dataframe(), "point", {"kind": self.kind, "side": self.side,
                                                              "status": self.status.name})

    def to_dataframe(self) -> pd.DataFrame:
        """One row per point: ``freq_hz``, ``a_g``, ``alpha``, ``excursion_m``,
        ``displacement_max_m``, ``displacement_min_m``, ``max_abs_multiplier``,
        ``critical_multiplier`` (the real multiplier nearest 1: 1 on a fold curve),
        ``contacts_per_period``, ``test`` (the test function: multiplier - 1, or the clearance
        to the bumper over the orbit's length), ``residual``, ``phase_rad``."""
        return self.data.copy()

    def passes(self, bif: "Bifurcation", within: float = 2e-3) -> bool:
        """Whether ``bif`` (same kind and side) lies on this curve: its (f, a_G) within ``within`` of
        the curve's polyline, each over the box's ranges."""
        if bif.kind != self.kind or bif.side != self.side or len(self) == 0:
            return False
        fs, as_ = self.freqs_hz[1] - self.freqs_hz[0], self.a_g[1] - self.a_g[0]
        pts = np.column_stack((self.data["freq_hz"] / fs, self.data["a_g"] / as_))
        q = np.array([bif.freq_hz / fs, bif.a_g / as_])
        if len(pts) == 1:
            return bool(np.linalg.norm(pts[0] - q) <= within)
        a, b = pts[:-1], pts[1:]
        d = b - a
        t = np.clip(np.einsum("ij,ij->i", q - a, d) / np.maximum(np.einsum("ij,ij->i", d, d), 1e-300), 0.0,
                    1.0)
        return bool(np.min(np.linalg.norm(a + t[:, None] * d - q, axis=1)) <= within)

    def plot(self, ax: Any = None, **kwargs: Any) -> Any:
        """The curve in the (f, a_G) plane; returns its Figure."""
        from ..plots.curves import plot_curves
        from ..plots import figure_of

        return figure_of(plot_curves([self], ax=ax, **kwargs), ax)

    def __repr__(self) -> str:
        return (f"BifurcationCurve({self.kind}{' ' + self.side if self.side else ''}, {len(self)} points, f "
                f"{self.data['freq_hz'].min():.6g}-{self.data['freq_hz'].max():.6g} Hz, a_g "
                f"{self.data['a_g'].min():.6g}-{self.data['a_g'].max():.6g}; {self.status.name}: "
                f"{self.message})"
                if len(self)
                else f"BifurcationCurve({self.kind}, no points; {self.status.name}: {self.message})")


@dataclass(frozen=True, eq=False)
class CoexistenceMap:
    """Branches at a_G levels, their folds and grazings in (a_G, f), and the test matrix.

    Attributes
    ----------
    oscillator : Oscillator, Structure or Adjacent
        The system.
    a_g, freqs_hz : (float, float)
        The map's box: table accelerations, g, and frequencies, Hz.
    levels : tuple of float
        The branches' a_G.
    branches : tuple of Branch
        One per level, over ``freqs_hz``.
    curves : tuple of BifurcationCurve
        Each fold and grazing of the branches, followed once.
    matrix : DataFrame
        The test matrix, each point judged by its witnesses (:func:`coexistence_map`): ``a_g``,
        ``freq_hz``, ``stable_orbits`` (stable period-1 orbits on the level's branch there; NaN where
        it did not reach), ``branch_reached``, ``sweep_responses`` and ``basin_responses`` (the
        distinct responses the sweeps and the basin sample show; NaN: none), ``basin_not_settled``,
        ``responses`` (the most any witness shows), ``verdict`` ("coexist", "one", "one on the
        branch", "not assessed") and ``evidence`` (in words).
    notes : tuple of str
        The bifurcations not followed, and why (e.g. a branch that turns at a grazing, where no
        multiplier is 1); a branch started at the high end of the range (none settled at the low end).
    seeded : tuple of Branch
        With sweeps: the short branches started at the settled steps the level's branch does not pass
        through (from the step to half way to its neighbours, both ways).
    steps : DataFrame
        With sweeps: one row per step (``a_g``, ``direction``, ``freq_hz``, ``alpha``, ``excursion_m``,
        ``period_multiple``, ``steady``, ``on_branch``, ``branch``: "level" or "seeded", and ``why``
        a step lies off every branch: another period, not settled, no orbit solved from it).

    Examples
    --------
    The damped paper system's branch at a_G = 0.05 and its two folds, followed in (f, a_G): from
    1.7 to 2.0 Hz two stable responses coexist, where up and down sweeps differ.

    >>> import pounding
    >>> m = pounding.coexistence_map(pounding.presets.paper_damped(),
    ...                              a_g=(0.04, 0.06), freqs_hz=(1.5, 2.5),
    ...                              levels=[0.05], kinds=["fold"], max_step=0.05)
    >>> len(m.branches), [c.kind for c in m.curves]
    (1, ['fold', 'fold'])
    >>> m.coexisting()["freq_hz"].tolist()
    [1.7, 1.8, 1.9, 2.0]
    """

    oscillator: "Oscillator" = field(repr=False)
    a_g: tuple[float, float]
    freqs_hz: tuple[float, float]
    levels: tuple[float, ...]
    branches: tuple["Branch", ...] = field(repr=False)
    curves: tuple[BifurcationCurve, ...] = field(repr=False)
    matrix: pd.DataFrame = field(repr=False)
    notes: tuple[str, ...] = ()
    seeded: tuple["Branch", ...] = field(default=(), repr=False)
    steps: pd.DataFrame = field(default_factory=lambda: pd.DataFrame(columns=list(STEP_COLUMNS)), repr=False)

    def to_xarray(self) -> Any:
        """The test matrix on (``a_g``, ``freq_hz``): each point's witnesses, responses and verdict."""
        return self.matrix.set_index(["a_g", "freq_hz"]).to_xarray()

    def to_dataframe(self) -> pd.DataFrame:
        """The curves' points, one row each, with ``curve`` (its index), ``kind`` and ``side``."""
        frames = [c.to_dataframe().assign(curve=i, kind=c.kind, side=c.side) for i,
                  c in enumerate(self.curves)]
        cols = ["curve", "kind", "side", *CURVE_COLUMNS]
        return pd.concat(frames, ignore_index=True)[cols] if frames else pd.DataFrame(columns=cols)

    def coexisting(self) -> pd.DataFrame:
        """The test matrix's points where two or more responses coexist (some witness shows it)."""
        return self.matrix[self.matrix["verdict"] == "coexist"].reset_index(drop=True)

    def not_assessed(self) -> pd.DataFrame:
        """The test matrix's points whose number of responses no witness settles (with why)."""
        return self.matrix[self.matrix["verdict"] == "not assessed"].reset_index(drop=True)

    def plot(self, ax: Any = None, **kwargs: Any) -> Any:
        """The curves in the (f, a_G) plane over the test matrix (points where two stable
        responses coexist filled); returns its Figure."""
        from ..plots.curves import plot_curves
        from ..plots import figure_of

        kwargs.setdefault("box", (self.freqs_hz, self.a_g))
        return figure_of(plot_curves(list(self.curves), ax=ax, matrix=self.matrix, **kwargs), ax)

    def __repr__(self) -> str:
        kinds = ", ".join(f"{c.kind}{' ' + c.side if c.side else ''}" for c in self.curves) or "none"
        return (f"CoexistenceMap(a_g {self.a_g[0]:g}-{self.a_g[1]:g}, f "
                f"{self.freqs_hz[0]:g}-{self.freqs_hz[1]:g} Hz, {len(self.branches)} branches, curves: "
                f"{kinds}; {len(self.coexisting())} of {len(self.matrix)} test points with coexisting "
                f"responses, {len(self.not_assessed())} not assessed)")


def curve_table(pts: Sequence["CurvePoint"], shooter: Any = None) -> tuple[pd.DataFrame, np.ndarray]:
    """The curve's rows (``shooter``: its family's, which reads each orbit's run: one mass's or a
    structure's) and the states at their sections."""
    rows = []
    for p in pts:
        run = p.run
        view = shooter.summary(run, run.excitation)
        mult = p.mult
        crit = mult[int(np.argmin(np.abs(mult - 1.0)))].real if mult.size else math.nan
        rows.append({"freq_hz": p.f, "a_g": p.a, **{k: view[k] for k in ("alpha", "excursion_m",
                                                                           "displacement_max_m",
                                                                           "displacement_min_m",
                                                                           "contacts_per_period")},
                     "max_abs_multiplier": float(np.abs(mult).max()) if mult.size else math.nan,
                     "critical_multiplier": float(crit),
                     "test": p.g, "residual": float(np.max(np.abs(p.r), initial=0.0)), "phase_rad": p.phase})
    states = np.array([p.vec for p in pts]) if pts else np.zeros((0, 0))
    return pd.DataFrame(rows, columns=list(CURVE_COLUMNS)), states
