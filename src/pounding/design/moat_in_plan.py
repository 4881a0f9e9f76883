"""A moat's gap for a building in plan: its bearings' largest displacement in plan under a suite of pairs,
each at its most critical orientation, against the code's total maximum displacement with its torsion.

ASCE 7-16 (17.6.3.3) and EN 1998-1 (4.3.3.4.3) take the mean of the peak responses over seven pairs or more
(the largest over fewer); the isolation system's displacement is the vector sum of its two directions at each
instant, and the moat's gap is at least the total maximum displacement (ASCE 7-16 17.2.5.2), which adds
torsion to the centre's displacement: ``D_TM = D_M [1 + (y / P_T^2) 12 e / (b^2 + d^2)]`` (17.5-3), at least
``1.15 D_M``.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field
from typing import Any, Optional

import numpy as np
import pandas as pd

from .._checks import at_most, instance_of, non_negative, one_of, one_or_more, plausible, positive
from .._errors import InputError, Interrupted, PoundingWarning, Problem
from .._units import GRAVITY_M_S2
from .._runner import Progress
from ..excitation.pair import RecordPair
from ..model.plan import (ACCIDENTAL, ACCIDENTAL_CASE_NAMES, MAX_ACCIDENTAL, PLAUSIBLE_ACCIDENTAL,
                          PlanBuilding)

MIN_PAIRS_FOR_MEAN = 7  # ASCE 7-16 17.6.3.3, EN 1998-1 4.3.3.4.3: the mean of seven pairs or more


def asce7_torsion(building: PlanBuilding, d_m_m: float, element: str = "bearing") -> dict[str, float]:
    """ASCE 7-16's total maximum displacement of a building's farthest bearing (or its farthest edge), with
    the torsion of its actual and accidental eccentricity (17.5-3), along x and along y.

    For the motion along x: ``y`` the farthest bearing (or edge of the base) from the bearings' centre of
    stiffness across x, ``e`` the base's centre of mass as built (its ``accidental_eccentricity`` left out:
    the code adds its own) from it across x plus 5 % of the plan's side across x (the accidental
    eccentricity); the same along y.  The centre of stiffness is the bearings' effective one at ``D_M``
    (each bearing's secant stiffness there: its backbone's force at ``D_M`` over ``D_M``), as the code's
    properties at the maximum displacement ask.  ``b`` and ``d`` the base's shorter and longer sides, ``P_T``
    the ratio of the isolation system's translational to torsional period, ``sqrt(sum(x_i^2 + y_i^2) / N) /
    r_I`` (bearings from the centre of mass; ``r_I`` the rectangle's radius of gyration), at least 1.

    Parameters
    ----------
    building : PlanBuilding
        The building (its base: floor 0, and its bearings).
    d_m_m : float
        The maximum displacement ``D_M`` at the centre (m): :func:`asce7_displacement`'s, or a run's.
    element : {"bearing", "edge"}
        The element of interest: the farthest bearing (the isolation system's ``D_TM``), or the base's
        farthest edge (a moat's clearance, 17.2.5.2: the edge moves further than the bearings inside it).

    Returns
    -------
    dict
        ``d_tm_x_m``, ``d_tm_y_m`` (each at least ``1.15 D_M``), ``d_tm_m`` (the larger), ``p_t``, and
        ``rigidity_m`` (the effective centre of stiffness, x and y).  (:func:`asce7_displacement`'s
        ``d_tm_m`` is the least the code allows, ``1.15 D_M``; this one adds the building's torsion.)

    Examples
    --------
    >>> import pounding
    >>> from pounding import Bearing, Floor, PlanBuilding, design
    >>> iso = pounding.Isolator(slopes_n_m=[1.2e7, 1.2e6], breakpoints_m=[0.01])
    >>> b = PlanBuilding([Floor(6.0e5, (24.0, 16.0), centre_m=(1.2, 0.0))],
    ...                  [Bearing((sx * 10.0, sy * 6.0), iso)
    ...                   for sx in (-1, 1) for sy in (-1, 1)])
    >>> out = design.asce7_torsion(b, 0.30)
    >>> round(out["p_t"], 3), round(out["d_tm_x_m"], 4), round(out["d_tm_y_m"], 4)
    (1.408, 0.345, 0.3524)
    """
    instance_of("building", building, PlanBuilding, "pounding.PlanBuilding")
    d_m = positive("d_m_m", d_m_m, "m")
    element = one_of("element", element, ("bearing", "edge"))
    base = building.floors[0]
    centre = np.array(base.centre_m)
    at = np.array([b.at_m for b in building.bearings]).reshape(-1, 2)
    rigidity = np.zeros(2)
    for axis in (0, 1):  # (lines along x place the centre's y: the bearings' secant stiffnesses at D_M)
        k = np.array([_secant(b.laws[axis], d_m) for b in building.bearings])
        rigidity[1 - axis] = float(np.sum(k * at[:, 1 - axis]) / np.sum(k))
    sides = np.array(base.size_m)
    b_short, d_long = float(sides.min()), float(sides.max())
    r_i = math.sqrt((b_short**2 + d_long**2) / 12.0)
    p_t = max(1.0, math.sqrt(float(np.mean(np.sum((at - centre) ** 2, axis=1)))) / r_i)
    out = {}
    for axis, name in ((0, "x"), (1, "y")):
        across = 1 - axis  # (the motion along x: distances and eccentricity across it, along y)
        y = (float(np.max(np.abs(at[:, across] - rigidity[across]))) if element == "bearing"
             else 0.5 * float(sides[across]) + abs(float(rigidity[across])))
        e = abs(float(centre[across] - rigidity[across])) + ACCIDENTAL * float(sides[across])
        factor = 1.0 + (y / p_t**2) * 12.0 * e / (b_short**2 + d_long**2)
        out[f"d_tm_{name}_m"] = max(d_m * factor, 1.15 * d_m)
    out["d_tm_m"] = max(out["d_tm_x_m"], out["d_tm_y_m"])
    out["p_t"] = p_t
    out["rigidity_m"] = (float(rigidity[0]), float(rigidity[1]))
    return out


def asce7_bearings_displacement(building: PlanBuilding, s_m1_g: float, *, rtol: float = 1e-10,
                                max_iterations: int = 500) -> dict[str, float]:
    """ASCE 7-16's maximum displacement ``D_M`` at the centre of a building in plan from its bearings'
    effective properties at ``D_M`` (17.5-1, 17.5-2, 17.8.5), along x and along y.

    At a trial ``D``: the effective stiffness ``K_M`` is the bearings' secant stiffness on their backbones,
    ``T_M = 2 pi sqrt(m / K_M)`` (``m`` the floors' masses), the effective damping ``beta_M = E_M / (2 pi K_M
    D^2)`` with ``E_M`` the energy of a cycle at ``D``: each kinematic (Masing) bearing's loop,
    ``8 int_0^D F - 4 F(D) D`` (a bilinear one's ``4 Q (D - D_y)``), and each dashpot's ``pi c (2 pi / T_M)
    D^2``; then ``D_M = g S_M1 T_M / (4 pi^2 B_M)`` (:func:`asce7_displacement`), until ``D`` stops moving.

    Parameters
    ----------
    building : PlanBuilding
        The building (its floors' masses and its bearings' laws).
    s_m1_g : float
        The MCE_R spectral acceleration at 1 s, g (``1.5 S_D1``).
    rtol : float
        The iteration stops when ``D`` moves by less than this fraction of itself.
    max_iterations : int
        A bound on the iterations (refused beyond: no fixed point found).

    Returns
    -------
    dict
        ``d_m_m`` (the larger of the two axes'), and per axis ``d_m_x_m``, ``t_m_x_s``, ``beta_m_x``,
        ``k_m_x_n_m`` (and ``_y_``).  ``beta_m_x`` is the loops' own; ``B_M`` takes it up to 0.5, as the
        code's table ends there.  On flat sliders, which have no restoring force (ASCE 7-16 17.2.4.4 asks
        for one), a PoundingWarning says so: the value is the formulas', not the code's.

    Examples
    --------
    >>> import pounding
    >>> from pounding import Bearing, Floor, PlanBuilding, design
    >>> iso = pounding.Isolator(slopes_n_m=[1.2e7, 1.2e6], breakpoints_m=[0.01])
    >>> b = PlanBuilding([Floor(6.0e5, (24.0, 16.0))],
    ...                  [Bearing((sx * 10.0, sy * 6.0), iso)
    ...                   for sx in (-1, 1) for sy in (-1, 1)])
    >>> out = design.asce7_bearings_displacement(b, 0.9)
    >>> round(out["d_m_m"], 4), round(out["t_m_x_s"], 3), round(out["beta_m_x"], 4)
    (0.3445, 1.978, 0.128)
    """
    from .._checks import integer
    from .spectra import asce7_displacement

    instance_of("building", building, PlanBuilding, "pounding.PlanBuilding")
    s_m1 = positive("s_m1_g", s_m1_g, "g")
    tol = positive("rtol", rtol, "(a fraction)")
    bound = integer("max_iterations", max_iterations, 1, 100_000)
    for q, b in enumerate(building.bearings):
        for axis, law in enumerate(b.laws):
            if law.bouc_wen is not None:
                raise InputError(Problem.WRONG_CONFIGURATION, f"building.bearings[{q}].laws[{axis}].bouc_wen",
                                 law.bouc_wen, got="a Bouc-Wen spring, whose effective stiffness and damping "
                                                   "at D_M are not on a backbone",
                                 fix="give D_M from design.asce7_displacement with the effective period and "
                                     "damping of its tests (t_m_s and beta_m in a design file)")
    mass = sum(f.mass_kg for f in building.floors)
    out: dict[str, float] = {}
    for axis, name in ((0, "x"), (1, "y")):
        laws = [b.laws[axis] for b in building.bearings]
        post = sum(law.slopes_n_m[-1] for law in laws)
        if post <= 0.0:  # (flat sliders, a perfectly plastic last slope: their secant at 0.1 m instead)
            if axis == 0:
                warnings.warn("building.bearings: they have no restoring force (flat sliders), which ASCE "
                              "7-16 17.2.4.4 asks of an isolation system: the D_M found is the formulas', "
                              "not the code's", PoundingWarning, stacklevel=2)
            post = sum(_secant(law, 0.1) for law in laws)
        d = GRAVITY_M_S2 * s_m1 * 2.0 * math.pi * math.sqrt(mass / post) / (4.0 * math.pi**2)  # (a start)
        for _ in range(bound):
            k = sum(_secant(law, d) * d for law in laws) / d
            t = 2.0 * math.pi * math.sqrt(mass / k)
            energy = sum(_loop_energy(law, d) + math.pi * law.damping_n_s_m * (2.0 * math.pi / t) * d * d
                         for law in laws)
            beta = energy / (2.0 * math.pi * k * d * d)
            new = asce7_displacement(s_m1, t, min(beta, 0.5))["d_m_m"]
            done = abs(new - d) <= tol * new
            d = 0.5 * (d + new)  # (relaxed: the secant softens as D grows)
            if done:
                break
        else:
            raise InputError(Problem.NO_FIT, "building", f"bearings along {name}",
                             why=f"found no D_M in {bound} iterations (last {d:.6g} m)",
                             fix="give D_M from asce7_displacement with the period and damping you chose")
        out.update({f"d_m_{name}_m": d, f"t_m_{name}_s": t, f"beta_m_{name}": beta, f"k_m_{name}_n_m": k})
    out["d_m_m"] = max(out["d_m_x_m"], out["d_m_y_m"])
    return out


def _loop_energy(isolator: Any, d: float) -> float:
    """The energy of one cycle of amplitude ``d`` (m) of a bearing's law, J: a kinematic (Masing) loop's
    ``8 int_0^d F - 4 F(d) d`` on its backbone; none for an elastic one."""
    if isolator.hysteresis == "elastic":
        return 0.0
    area, force, before = 0.0, 0.0, 0.0
    for k, edge in zip(isolator.slopes_n_m, (*isolator.breakpoints_m, math.inf)):
        upto = min(d, edge)
        area += force * (upto - before) + 0.5 * k * (upto - before) ** 2
        force += k * (upto - before)
        before = upto
        if upto >= d:
            break
    return max(0.0, 8.0 * area - 4.0 * force * d)


def _secant(isolator: Any, d_m: float) -> float:
    """An isolator's secant stiffness at ``d_m`` (m) on its backbone, N/m: the force there over ``d_m``."""
    force, before = 0.0, 0.0
    for k, edge in zip(isolator.slopes_n_m, (*isolator.breakpoints_m, math.inf)):
        upto = min(d_m, edge)
        force += k * (upto - before)
        before = upto
        if upto >= d_m:
            break
    return force / d_m


@dataclass(frozen=True, eq=False)
class MoatDesign:
    """A moat's gap from a suite of pairs (:func:`moat_design`).

    Attributes
    ----------
    data : pandas.DataFrame
        One row per pair and angle (index ``pair``, ``angle_deg``; with the accidental eccentricity
        ``pair``, ``eccentricity``, ``angle_deg``, the case one of ``"+x+y"``, ``"+x-y"``, ``"-x+y"``,
        ``"-x-y"``): the run's peaks (:meth:`PlanRun.quantities`: ``disp_max_m`` the largest bearing
        displacement in plan, ...).
    critical : pandas.DataFrame
        One row per pair: its most critical angle and its largest bearing displacement in plan there
        (``angle_deg``, ``disp_max_m``); and where the runs have it, the largest demand on the moat over the
        angles and its angle (``moat_demand_m``, ``demand_angle_deg``: the moat's floor's corners' largest
        displacement towards a wall, or a ring's: their largest distance from its centre less their own,
        :meth:`PlanRun.quantities`); with the accidental eccentricity, each
        one's case too (``eccentricity``, ``demand_eccentricity``).
    design_displacement_m : float
        The mean of the pairs' critical displacements (seven pairs or more), or their largest (fewer), m:
        the isolation system's, as the codes ask.
    moat_demand_m : float
        The same rule over the pairs' demands on the moat, m: the gap a moat of equal gaps (or a ring)
        needs (its corners reach further than the bearings when the building turns; NaN where the runs
        lack it).
    code : dict
        The code's total maximum displacement with torsion (:func:`asce7_torsion`) from ``d_m_m``, when given.
    attrs : dict
        What else is known (``rule``: ``"mean"`` or ``"largest"``; ``complete``).

    Examples
    --------
    >>> import pandas as pd
    >>> from pounding.design import MoatDesign
    >>> runs = [("a", 0.0), ("a", 90.0), ("b", 0.0), ("b", 90.0)]
    >>> index = pd.MultiIndex.from_tuples(runs, names=["pair", "angle_deg"])
    >>> data = pd.DataFrame({"disp_max_m": [0.2, 0.3, 0.25, 0.22]}, index=index)
    >>> found = MoatDesign.of(data, None)
    >>> found.critical["disp_max_m"].tolist()  # m, each pair's critical
    [0.3, 0.25]
    >>> found.design_displacement_m  # m: two pairs, their largest
    0.3
    """

    data: pd.DataFrame
    critical: pd.DataFrame
    design_displacement_m: float
    moat_demand_m: float = math.nan
    code: dict = field(default_factory=dict)
    attrs: dict = field(default_factory=dict, repr=False)

    @classmethod
    def of(cls, data: pd.DataFrame, code: dict | None, complete: bool = True) -> "MoatDesign":
        """The design from the runs' peaks (``data``, indexed by pair, the accidental case if any, and
        angle)."""
        rows = []
        columns = [c for c in ("disp_max_m", "moat_demand_m") if c in data]
        cased = "eccentricity" in data.index.names  # (the accidental cases: each critical run's named)
        for name, group in data.groupby(level="pair", sort=False):
            row: list = [name]
            for column in columns:
                values = group[column].to_numpy(dtype=float)
                at = int(np.nanargmax(values)) if np.isfinite(values).any() else 0
                row += [float(group.index.get_level_values("angle_deg")[at]), float(values[at])]
                if cased:
                    row.append(str(group.index.get_level_values("eccentricity")[at]))
            rows.append(row)
        heads = {"disp_max_m": ["angle_deg", "disp_max_m", *(["eccentricity"] if cased else [])],
                 "moat_demand_m": ["demand_angle_deg", "moat_demand_m",
                                   *(["demand_eccentricity"] if cased else [])]}
        critical = pd.DataFrame(rows, columns=["pair", *(h for c in columns for h in heads[c])])
        critical = critical.set_index("pair")
        rule = "mean" if len(critical) >= MIN_PAIRS_FOR_MEAN else "largest"

        def by_rule(column: str) -> float:
            if column not in critical:
                return math.nan
            peaks = critical[column].to_numpy()
            return float(np.mean(peaks) if rule == "mean" else np.max(peaks))

        return cls(data, critical, by_rule("disp_max_m"), moat_demand_m=by_rule("moat_demand_m"),
                   code=dict(code or {}), attrs={"rule": rule, "complete": int(complete)})

    def to_dataframe(self) -> pd.DataFrame:
        """:attr:`data` (a copy)."""
        return self.data.copy()

    def to_xarray(self) -> Any:
        """:attr:`data` as a Dataset along ``pair`` (``eccentricity``) and ``angle_deg``, the design
        displacement as an attribute."""
        import xarray as xr

        return xr.Dataset.from_dataframe(self.data).assign_attrs(
            design_displacement_m=self.design_displacement_m, moat_demand_m=self.moat_demand_m, **self.attrs,
            **{k: v for k, v in self.code.items()})

    def plot(self, ax: Any = None, gap_m: Optional[float] = None) -> Any:
        """Each pair's critical bearing displacement in plan, the design value and the code's, as bars, and
        a moat's gap (m) across when given (:func:`pounding.plots.plot_moat_design`); returns the Figure."""
        from ..plots import figure_of
        from ..plots.plan import plot_moat_design

        return figure_of(plot_moat_design(self, ax=ax, gap_m=gap_m), ax)

    def __repr__(self) -> str:
        code = f", code D_TM {self.code['d_tm_m']:.4g} m" if self.code else ""
        return (f"MoatDesign({len(self.critical)} pairs, {self.attrs['rule']} "
                f"{self.design_displacement_m:.4g} m{code})")


def moat_design(building: PlanBuilding, pairs: Any, angles_deg: Any = None, duration_s: float | None = None,
                *, d_m_m: float | None = None, accidental: float = 0.0, workers: int | None = None,
                scheduler: Any = None, progress: Progress = False, max_steps: int = 10_000_000) -> MoatDesign:
    """The moat's gap a building in plan needs under a suite of pairs: each pair at each orientation
    (:func:`pounding.orientations`), its most critical one, and the suite's design value.

    Parameters
    ----------
    building : PlanBuilding
        The building; its moat, if any, is taken away for the runs (the gap is what they find; a ring is
        moved out of reach, so that its demand is found: the gap a ring around the building needs).
    pairs : RecordPair or sequence of RecordPair
        The suite (seven or more: their mean; fewer: their largest), scaled as the design asks.
    angles_deg : array_like, optional
        The orientations, degrees (default: every 15 degrees from 0 to 165: without the moat, a pair
        turned by 180 degrees is the motion reversed, and the bearings' laws are symmetric).
    duration_s : float, optional
        Each run's length, s (default: each pair's).
    d_m_m : float, optional
        The code's maximum displacement at the centre, m (:func:`asce7_displacement`): its total maximum
        displacement with torsion at the base's farthest edge (:func:`asce7_torsion`, ``element="edge"``:
        the moat's clearance) is given beside, as ``code``.
    accidental : float
        The accidental eccentricity, a fraction of each floor's sides (the codes' 0.05; 0, the default: the
        building as built): each pair at each orientation is run at the four cases of
        :meth:`PlanBuilding.accidental_cases` (every centre of mass moved by that fraction of its sides along
        x and y, each of the four signs), and each pair's critical run is the largest over the angles and
        the cases (ASCE 7-16 17.6.3.3 asks for the mass so shifted in a response history analysis).  The
        building must then have no ``accidental_eccentricity`` of its own.
    workers : int, optional
        Threads or processes (default: every core).
    scheduler : str or dask.distributed.Client, optional
        As :func:`pounding.orientations`'s.
    progress : bool or callable
        A progress bar, or a callable taking the runs finished (each pair's).
    max_steps : int
        Each run's budget of engine sub-intervals.

    Returns
    -------
    MoatDesign
        Every run's peaks, each pair's critical orientation, the design displacement, the code's.

    Raises
    ------
    InputError
        A bad argument (named).
    Interrupted
        On Ctrl-C: ``partial`` holds the pairs done.

    Examples
    --------
    >>> import pounding
    >>> from pounding import Bearing, Floor, PlanBuilding, design
    >>> iso = pounding.Isolator(slopes_n_m=[1.2e7, 1.2e6], breakpoints_m=[0.01])
    >>> b = PlanBuilding([Floor(6.0e5, (24.0, 16.0), centre_m=(1.2, 0.0))],
    ...                  [Bearing((sx * 10.0, sy * 6.0), iso)
    ...                   for sx in (-1, 1) for sy in (-1, 1)])
    >>> quake = pounding.records.el_centro().scaled(pga_g=0.4)
    >>> pairs = [pounding.RecordPair(quake, quake.scaled(factor=f))
    ...          for f in (0.5, 0.8)]
    >>> found = design.moat_design(b, pairs, [0.0, 45.0, 90.0], duration_s=10.0,
    ...                            d_m_m=0.1)
    >>> found.critical["angle_deg"].tolist()  # each pair's critical orientation
    [0.0, 45.0]
    >>> found.critical["disp_max_m"].round(3).tolist()  # m
    [0.1, 0.12]
    >>> round(found.design_displacement_m, 3), found.attrs["rule"]  # m
    (0.12, 'largest')
    >>> round(found.code["d_tm_m"], 4)  # m: D_TM at the edge, with torsion
    0.121
    """
    from ..protocols.orientations import orientations

    instance_of("building", building, PlanBuilding, "pounding.PlanBuilding")
    suite = one_or_more("pairs", pairs, RecordPair, "pounding.RecordPair")
    code = None if d_m_m is None else asce7_torsion(building, d_m_m, "edge")
    if duration_s is not None:
        positive("duration_s", duration_s, "s")
    cases = _cases(building, accidental)
    if angles_deg is None:
        angles_deg = np.arange(0.0, 180.0, 15.0)
    names: list[str] = []
    for p in suite:  # (each pair named once: a suite may repeat a record's name)
        name, k = p.name or "pair", 2
        while (name if k == 2 else f"{name} ({k - 1})") in names:
            k += 1
        names.append(name if k == 2 else f"{name} ({k - 1})")
    tables: list[pd.DataFrame] = []
    done = 0
    for name, p in zip(names, suite):
        for case, free in cases:
            label = {} if case is None else {"eccentricity": case}
            try:
                found = orientations(free, p, angles_deg, duration_s, workers=workers, scheduler=scheduler,
                                     progress=progress, max_steps=max_steps)
            except Interrupted as stop:
                if stop.partial is not None:
                    tables.append(stop.partial.data.assign(pair=name, **label))
                partial = MoatDesign.of(_joined(tables), code, complete=False) if tables else None
                raise Interrupted(partial, done, len(suite), "pairs") from None
            tables.append(found.data.assign(pair=name, **label))
        done += 1
    return MoatDesign.of(_joined(tables), code)


def accidental_fraction(value: Any, field: str = "accidental") -> float:
    """An accidental eccentricity as a fraction of the sides, checked: in [0, 0.25], a warning beyond 0.1."""
    fraction = non_negative(field, value, "")
    at_most(field, fraction, MAX_ACCIDENTAL, "", "give a fraction of the sides (the codes' 5 % is 0.05)")
    plausible(field, fraction, 0.0, PLAUSIBLE_ACCIDENTAL, "a fraction of the sides (the codes' 5 % is 0.05)")
    return fraction


def _cases(building: PlanBuilding, accidental: float) -> list[tuple[Optional[str], PlanBuilding]]:
    """The buildings a design runs (:meth:`PlanBuilding.moat_out_of_reach`), each with its case's name
    (None: as built)."""
    fraction = accidental_fraction(accidental)
    if fraction == 0.0:
        return [(None, building.moat_out_of_reach())]
    if any(building.accidental_eccentricity):
        raise InputError(Problem.BAD_STATE, "accidental", fraction,
                         why=f"is given to a building with its own accidental_eccentricity "
                             f"{list(building.accidental_eccentricity)}: they would count twice",
                         fix="give the building as built (accidental_eccentricity (0, 0)), or accidental 0")
    try:
        shifted = building.accidental_cases(fraction)
    except InputError as exc:  # (a centre of mass moved off its floor)
        raise InputError(Problem.BAD_STATE, "accidental", fraction,
                         why=f"shifts a centre of mass off its floor in one of its four cases "
                             f"({exc.field} {exc.value!r})",
                         fix="give a smaller fraction, or the floors' centres of mass nearer their middle") \
            from None
    return [(name, b.moat_out_of_reach()) for name, b in zip(ACCIDENTAL_CASE_NAMES, shifted)]


def _joined(tables: list[pd.DataFrame]) -> pd.DataFrame:
    """The pairs' tables as one, indexed by pair (and accidental case) and angle."""
    if not tables:
        raise InputError(Problem.EMPTY, "pairs", [], hint=" (one pair or more)")
    data = pd.concat(tables).reset_index()
    return data.set_index(["pair", *(["eccentricity"] if "eccentricity" in data else []), "angle_deg"])


__all__ = ["MIN_PAIRS_FOR_MEAN", "MoatDesign", "asce7_bearings_displacement", "asce7_torsion", "moat_design"]
