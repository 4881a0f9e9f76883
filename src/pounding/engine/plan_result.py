"""What a building in plan's run returns: :class:`PlanRun` (each floor's x, y and rotation, each bearing's
displacement in plan with its exact vector-sum largest, each frame's exact drift, each corner's exact
excursion and each moat wall's clearance, the contacts at the moat with where they struck, the energy
ledger)."""

from __future__ import annotations

import math

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Optional

import numpy as np
import pandas as pd

from .._errors import Status
from .layout import CONTACT_COLUMNS as CORE_CONTACT_COLUMNS
from .run_parts import EnergyLedger, Outcome, events_frame

if TYPE_CHECKING:
    from ..model.plan import PlanBuilding
    from .state import State

# the moat's contacts: its wall and the corner that struck it, where on the wall, then the core's columns
PLAN_CONTACT_COLUMNS = ("wall", "corner", "at_m", "t_start_s", "t_end_s", "v_in_m_s", "v_out_m_s",
                        "impulse_n_s", "peak_force_n", "max_compression_m", "bumper_dissipation_j")


@dataclass(frozen=True)
class PlanRun(Outcome):
    """A building in plan's run (:func:`pounding.simulate` of a
    :class:`~pounding.model.plan.PlanBuilding`).

    Attributes
    ----------
    t : ndarray, shape (k,)
        Sample times, s (the uniform samples, and one after each event).
    displacement, velocity : ndarray, shape (k, n_levels, 3)
        Each floor's centre of mass relative to the ground: x and y (m, m/s) and its rotation (rad,
        rad/s), in that order on the last axis.
    displacement_max, displacement_min : ndarray, shape (n_levels, 3)
        Their exact extrema over the run (not from the samples).
    displacement_max_time_s, displacement_min_time_s : ndarray, shape (n_levels, 3)
        When they were reached, s.
    abs_acceleration_max : ndarray, shape (n_levels, 3)
        Each floor's exact largest absolute acceleration along x and y (m/s^2) and rotational
        acceleration (rad/s^2).
    plan_displacement_max_m : ndarray, shape (n_levels,)
        Each floor's centre of mass's exact largest displacement in plan (the vector sum of its x and y at
        each instant), m.
    bearing_displacement : ndarray, shape (k, n_bearings, 2)
        Each bearing's displacement along x and y at its place, m.
    bearing_force : ndarray, shape (k, n_bearings, 2)
        Each bearing's force along x and y, N.
    bearing_displacement_max_m : ndarray, shape (n_bearings,)
        Each bearing's exact largest displacement in plan (the vector sum of its two directions at each
        instant), m.
    bearing_displacement_max_time_s : ndarray, shape (n_bearings,)
        When, s.
    bearing_displacement_at_max_m : ndarray, shape (n_bearings, 2)
        Its x and y then, m.
    bearing_axis_max_m, bearing_axis_min_m : ndarray, shape (n_bearings, 2)
        Each bearing's exact extrema along x and along y, m.
    frame_drift_max_m, frame_drift_min_m : ndarray, shape (n_frames,)
        Each frame's exact extrema of drift at its place (its floor's point less the floor below's), m.
    corner_displacement_max_m, corner_displacement_min_m : ndarray, shape (4, 2)
        The moat's floor's corners' exact extrema along x and y (the base's without a moat), m; corners
        in :meth:`Floor.corners_m`'s order.
    clearance_m : ndarray, shape (4,) or (1,)
        Each moat wall's (``-x, +x, -y, +y``) smallest clearance over the run (its gap less its corners'
        largest approach, exact; negative: struck), m; a circular moat's ring's (one: its radius less the
        corners' largest distance from its centre, exact).
    contact_force : ndarray, shape (k, n_contacts)
        Each wall's force at each corner, N (>= 0), in the order of ``contacts``'s slots.
    contact_table, event_table, chatter_table : ndarray
        The core's rows behind :attr:`contacts`, :attr:`events` and :attr:`chatters`.
    energy : EnergyLedger
        The energy ledger.
    final_state : State
        Pass as ``state`` to continue.
    status : Status
        How the run ended (``message`` says it in words).
    building : PlanBuilding
        What was run.
    excitation : RecordPair, Record or Harmonic
        What shook it.
    sample_rate_hz : float
        The uniform samples' rate, Hz (0: events only).
    contact_slots : tuple of (int, int)
        Each contact slot's moat wall (0 to 3: ``-x, +x, -y, +y``) and corner, in ``contact_force``'s
        column order.

    Examples
    --------
    A floor 24 m by 16 m, its mass 1.2 m off centre, on four bilinear bearings in a moat 8 cm wide,
    under El Centro at 0.5 g along 30 degrees:

    >>> import pounding
    >>> from pounding import Bearing, Floor, PlanBuilding, RectangularMoat
    >>> iso = pounding.Isolator(slopes_n_m=[1.2e7, 1.2e6], breakpoints_m=[0.01])
    >>> bearings = [Bearing((sx * 10.0, sy * 6.0), iso)
    ...             for sx in (-1, 1) for sy in (-1, 1)]
    >>> moat = RectangularMoat(0.08, pounding.KelvinVoigt(5.0e8, 1.0e6))
    >>> b = PlanBuilding([Floor(6.0e5, (24.0, 16.0), centre_m=(1.2, 0.0))],
    ...                  bearings, moat=moat)
    >>> el_centro = pounding.records.el_centro().scaled(pga_g=0.5)
    >>> quake = pounding.RecordPair.of_direction(el_centro, 30.0)
    >>> run = pounding.simulate(b, quake, 10.0)
    >>> run.bearings()["displacement_max_m"].round(3).tolist()  # m, in plan
    [0.093, 0.093, 0.094, 0.093]
    >>> run.clearance_m.round(3).tolist()  # m: walls -x, +x struck
    [-0.004, -0.004, 0.027, 0.03]
    >>> run.contacts[["wall", "corner", "at_m"]].round(2).head(2)
      wall  corner  at_m
    0   -x       0 -8.03
    1   +x       2 -7.95
    """

    building: "PlanBuilding"
    excitation: Any
    sample_rate_hz: float
    t: np.ndarray
    displacement: np.ndarray
    velocity: np.ndarray
    displacement_max: np.ndarray
    displacement_max_time_s: np.ndarray
    displacement_min: np.ndarray
    displacement_min_time_s: np.ndarray
    abs_acceleration_max: np.ndarray
    plan_displacement_max_m: np.ndarray
    bearing_displacement: np.ndarray
    bearing_force: np.ndarray
    bearing_displacement_max_m: np.ndarray
    bearing_displacement_max_time_s: np.ndarray
    bearing_displacement_at_max_m: np.ndarray
    bearing_axis_max_m: np.ndarray
    bearing_axis_min_m: np.ndarray
    frame_drift_max_m: np.ndarray
    frame_drift_min_m: np.ndarray
    corner_displacement_max_m: np.ndarray
    corner_displacement_min_m: np.ndarray
    clearance_m: np.ndarray
    contact_force: np.ndarray = field(repr=False)
    contact_slots: tuple = field(repr=False)
    contact_table: np.ndarray = field(repr=False)
    event_table: np.ndarray = field(repr=False)
    energy: Optional[EnergyLedger] = field(repr=False)
    final_state: Optional["State"] = field(repr=False)
    status: Status = Status.SUCCESS
    chatter_table: np.ndarray = field(default_factory=lambda: np.zeros((0, 5)), repr=False)

    # ------------------------------------------------------------------ tables
    @property
    def contacts(self) -> pd.DataFrame:
        """One row per contact at the moat: ``wall`` (``-x``, ``+x``, ``-y``, ``+y``; a circular moat's
        ``ring``), the ``corner`` that struck it (:meth:`Floor.corners_m`'s index), ``at_m`` where along the
        wall it struck (the corner's y for a wall across x, its x for one across y, m, in plan coordinates;
        on a ring the arc from its +x point counter-clockwise, m), ``t_start_s``, ``t_end_s``, the corner's
        velocities in and out ``v_in_m_s``, ``v_out_m_s`` (along the wall's axis; on a ring along its
        normal, outwards: positive coming in), ``impulse_n_s``, ``peak_force_n``, ``max_compression_m`` and
        ``bumper_dissipation_j`` (what the wall's law took)."""
        from ..model.moats import MOAT_SIDES, MOAT_WALLS, RING_WALL

        table = self.contact_table
        slots = table[:, CORE_CONTACT_COLUMNS["contact"]].astype(int)
        walls = [self.contact_slots[s][0] for s in slots]
        corners = [self.contact_slots[s][1] for s in slots]
        kinds = [RING_WALL] if self.clearance_m.size == 1 else list(MOAT_SIDES)  # (the moat's own walls)
        return pd.DataFrame({
            "wall": pd.Categorical([MOAT_WALLS[w] for w in walls], categories=kinds),
            "corner": np.array(corners, dtype=int),
            "at_m": np.array([self._struck_at(w, k, t) for w, k, t in
                              zip(walls, corners, table[:, CORE_CONTACT_COLUMNS["t_start_s"]])]),
            **{name: table[:, CORE_CONTACT_COLUMNS[name]] for name in PLAN_CONTACT_COLUMNS[3:]},
        })

    @property
    def chatters(self) -> pd.DataFrame:
        """A rigid moat's (:class:`pounding.RigidStop` walls or ring) chatter sequences, one row each:
        ``wall``, ``corner``, ``t_first_s`` (its first impact), ``t_end_s`` (where its impacts accumulated,
        or its last), ``impacts`` and ``accumulated`` (the corner's rebounds summed in closed form and the
        corner held on the wall from then on; see :class:`pounding.RigidStop`)."""
        from ..model.moats import MOAT_SIDES, MOAT_WALLS, RING_WALL

        table = np.asarray(self.chatter_table).reshape(-1, 5)
        slots = table[:, 0].astype(int)
        kinds = [RING_WALL] if self.clearance_m.size == 1 else list(MOAT_SIDES)  # (the moat's own walls)
        return pd.DataFrame({
            "wall": pd.Categorical([MOAT_WALLS[self.contact_slots[s][0]] for s in slots], categories=kinds),
            "corner": np.array([self.contact_slots[s][1] for s in slots], dtype=int),
            "t_first_s": table[:, 1], "t_end_s": table[:, 2],
            "impacts": table[:, 3].astype(int), "accumulated": table[:, 4] != 0.0,
        })

    def _struck_at(self, wall: int, corner: int, t_s: float) -> float:
        """Where along ``wall`` the ``corner`` was at ``t_s`` (the sample there: one follows every event):
        a side's, its coordinate along it; the ring's, the arc from its +x point counter-clockwise."""
        from ..model.moats import MOAT_SIDES

        building = self.building
        level = building.moat.level
        floor = building.placed_floors[level]
        p = building.floors[level].corners_m()[corner]
        q = min(int(np.searchsorted(self.t, t_s)), self.t.size - 1)
        u = self.displacement[q, level]
        x = p[0] + u[0] - (p[1] - floor.centre_m[1]) * u[2]
        y = p[1] + u[1] + (p[0] - floor.centre_m[0]) * u[2]
        if wall == len(MOAT_SIDES):
            return float(building.moat.radius_m(building.floors[level]) * (np.arctan2(y, x) % (2.0 * np.pi)))
        return float(y if wall < 2 else x)  # (a wall across x: the corner's y)

    @property
    def events(self) -> pd.DataFrame:
        """Every event: ``t_s``, what happened (``kind``) and the ``index`` of what it happened to: a
        contact slot (:attr:`contacts`'s order of walls and corners) for a contact's start or end, an
        element (each bearing's x then y, then each yielding frame) for a yield or a reversal; a friction
        bearing's plastic circle's ``circle_slip`` and ``circle_stick`` its x element's (twice the
        bearing's index)."""
        return events_frame(self.event_table)

    def peaks(self) -> pd.DataFrame:
        """One row per floor: the exact extrema of its centre's x and y (m), its rotation (rad) and the
        largest absolute accelerations (m/s^2, rad/s^2)."""
        names = (("x", "m"), ("y", "m"), ("theta", "rad"))
        data: dict[str, Any] = {"level": np.arange(self.displacement_max.shape[0])}
        for j, (name, unit) in enumerate(names):
            data[f"{name}_max_{unit}"] = self.displacement_max[:, j]
            data[f"{name}_min_{unit}"] = self.displacement_min[:, j]
        for j, (name, unit) in enumerate((("x", "m_s2"), ("y", "m_s2"), ("theta", "rad_s2"))):
            data[f"abs_acceleration_{name}_max_{unit}"] = self.abs_acceleration_max[:, j]
        return pd.DataFrame(data).set_index("level")

    def bearings(self) -> pd.DataFrame:
        """One row per bearing: its place (``at_x_m``, ``at_y_m``), its exact largest displacement in plan
        ``displacement_max_m`` (the vector sum), when, and its x and y then; its exact extrema along x and
        y (m)."""
        at = np.array([b.at_m for b in self.building.bearings]).reshape(-1, 2)
        return pd.DataFrame({
            "bearing": np.arange(at.shape[0]), "at_x_m": at[:, 0], "at_y_m": at[:, 1],
            "displacement_max_m": self.bearing_displacement_max_m,
            "displacement_max_time_s": self.bearing_displacement_max_time_s,
            "x_at_max_m": self.bearing_displacement_at_max_m[:, 0],
            "y_at_max_m": self.bearing_displacement_at_max_m[:, 1],
            "x_max_m": self.bearing_axis_max_m[:, 0], "x_min_m": self.bearing_axis_min_m[:, 0],
            "y_max_m": self.bearing_axis_max_m[:, 1], "y_min_m": self.bearing_axis_min_m[:, 1],
        }).set_index("bearing")

    def summary(self) -> pd.Series:
        """The run in a few numbers, each name with its unit: ``t_end_s``; the largest bearing
        displacement in plan ``bearing_displacement_max_m`` (exact, over every bearing) and which bearing;
        the base's largest rotation ``theta_max_rad``; ``contacts`` at the moat and ``clearance_min_m``
        (negative: struck); ``peak_force_max_n`` (inf with rigid impacts: their impulses are the
        contacts' ``impulse_n_s``; NaN without contacts); ``input_work_j`` and ``energy_residual_j``;
        ``status``."""
        nan = float("nan")
        b = int(np.argmax(self.bearing_displacement_max_m))
        energy = self.energy
        peaks = self.contact_table[:, CORE_CONTACT_COLUMNS["peak_force_n"]]
        # (a rigid impact's peak is NaN, an impulse's: inf, as a line's summary has it)
        peak = nan if not peaks.size else math.inf if np.isnan(peaks).any() else float(np.max(peaks))
        return pd.Series({
            "t_end_s": self.final_state.time_s if self.final_state is not None else nan,
            "bearing_displacement_max_m": float(self.bearing_displacement_max_m[b]),
            "bearing_of_max": b,
            "theta_max_rad": float(max(abs(self.displacement_max[0, 2]), abs(self.displacement_min[0, 2]))),
            "contacts": int(self.contact_table.shape[0]),
            "clearance_min_m": float(np.min(self.clearance_m)) if self.building.moat_in_reach else nan,
            "peak_force_max_n": peak,
            "input_work_j": energy.input_work if energy is not None else nan,
            "energy_residual_j": energy.residual if energy is not None else nan,
            "status": self.status.name,
        })

    @property
    def wall_demand_m(self) -> np.ndarray:
        """Towards each side (``-x, +x, -y, +y``), the largest displacement of the moat's floor's corners
        along its normal (the base's without a moat), m, exact: the gap a wall there needs not to be struck
        (with four walls, each one's gap less its clearance; a ring's demand is ``quantities()``'s
        ``moat_demand_m``), shape (4,)."""
        hi, lo = self.corner_displacement_max_m, self.corner_displacement_min_m
        return np.array([-lo[:, 0].min(), hi[:, 0].max(), -lo[:, 1].min(), hi[:, 1].max()])

    def quantities(self) -> dict[str, float]:
        """The run in a few peaks, as every run gives them (a protocol's: :func:`pounding.orientations`):
        ``disp_max_m`` the largest bearing displacement in plan (the isolation system's, the moat's demand),
        ``acc_max_g`` the largest absolute acceleration of a floor's centre along x or y (g), ``impacts``
        at the moat with their ``impact_force_max_n``, ``impact_speed_max_m_s`` and
        ``compression_max_m``, the top floor's centre's ``top_disp_max_m`` (in plan) and ``top_acc_max_g``,
        the frames' ``drift_ratio_max`` (NaN without storeys), and a building in plan's own:
        ``theta_max_rad`` (the base's largest rotation), ``clearance_min_m`` (NaN without a moat or with
        its ring out of reach, :meth:`PlanBuilding.moat_out_of_reach`) and
        ``moat_demand_m``, the moat's floor's corners' largest displacement towards any wall (the base's
        without a moat: :attr:`wall_demand_m`), the gap a moat of equal gaps needs not to be struck (a
        circular moat's: the gap its ring needs, its gap less its clearance); ``status``."""
        from .._tables import RunQuantities
        from .layout import force_max

        g = self.excitation.g
        rows, n = self.contact_table, self.contact_table.shape[0]
        speed, depth = CORE_CONTACT_COLUMNS["v_in_m_s"], CORE_CONTACT_COLUMNS["max_compression_m"]
        heights = np.array([f.height_m for f in self.building.frames])
        drift = np.maximum(np.abs(self.frame_drift_max_m), np.abs(self.frame_drift_min_m))
        return RunQuantities({
            "acc_max_g": float(np.max(self.abs_acceleration_max[:, :2])) / g,
            "disp_max_m": float(np.max(self.bearing_displacement_max_m)),
            "impacts": float(n),
            "impact_force_max_n": force_max(rows),
            "impact_speed_max_m_s": float(np.abs(rows[:, speed]).max()) if n else 0.0,
            "compression_max_m": float(rows[:, depth].max()) if n else 0.0,
            "top_disp_max_m": float(self.plan_displacement_max_m[-1]),
            "top_acc_max_g": float(np.max(self.abs_acceleration_max[-1, :2])) / g,
            "drift_ratio_max": float(np.max(drift / heights)) if heights.size else float("nan"),
            "theta_max_rad": float(max(abs(self.displacement_max[0, 2]), abs(self.displacement_min[0, 2]))),
            "clearance_min_m": (float(np.min(self.clearance_m)) if self.building.moat_in_reach
                                else float("nan")),
            "moat_demand_m": (self.building.moat.reach_m - float(self.clearance_m[0])
                              if self.clearance_m.size == 1 else float(np.max(self.wall_demand_m))),
            "status": float(self.status),
        })

    def to_dataframe(self) -> pd.DataFrame:
        """The samples, one row each: ``t_s``; each floor's ``level<l>_x_m``, ``_y_m``, ``_theta_rad``;
        each bearing's ``bearing<b>_x_m``, ``_y_m``."""
        data: dict[str, Any] = {"t_s": self.t}
        for level in range(self.displacement.shape[1]):
            for j, name in enumerate(("x_m", "y_m", "theta_rad")):
                data[f"level{level}_{name}"] = self.displacement[:, level, j]
        for b in range(self.bearing_displacement.shape[1]):
            for j, name in enumerate(("x_m", "y_m")):
                data[f"bearing{b}_{name}"] = self.bearing_displacement[:, b, j]
        return pd.DataFrame(data)

    def to_xarray(self) -> Any:
        """The histories and the exact extrema as a Dataset: along ``sample`` (its coordinate ``time_s``),
        ``level``, ``dof`` (``x``, ``y``, ``theta``: m, m and rad; m/s and rad/s), ``bearing``, ``axis``
        (``x``, ``y``), ``frame`` and ``wall`` (``-x``, ``+x``, ``-y``, ``+y``); each variable's unit in its
        ``units``; ``status`` and ``message`` as attributes."""
        import xarray as xr

        from ..model.moats import MOAT_SIDES, RING_WALL

        walls = [RING_WALL] if self.clearance_m.size == 1 else list(MOAT_SIDES)[:self.clearance_m.size]
        mixed = "m (x, y), rad (theta)"
        ds = xr.Dataset(
            {"displacement": (("sample", "level", "dof"), self.displacement, {"units": mixed}),
             "velocity": (("sample", "level", "dof"), self.velocity, {"units": "m/s (x, y), rad/s (theta)"}),
             "displacement_max": (("level", "dof"), self.displacement_max, {"units": mixed}),
             "displacement_min": (("level", "dof"), self.displacement_min, {"units": mixed}),
             "abs_acceleration_max": (("level", "dof"), self.abs_acceleration_max,
                                      {"units": "m/s^2 (x, y), rad/s^2 (theta)"}),
             "plan_displacement_max_m": ("level", self.plan_displacement_max_m, {"units": "m"}),
             "bearing_displacement_m": (("sample", "bearing", "axis"), self.bearing_displacement,
                                        {"units": "m"}),
             "bearing_force_n": (("sample", "bearing", "axis"), self.bearing_force, {"units": "N"}),
             "bearing_displacement_max_m": ("bearing", self.bearing_displacement_max_m, {"units": "m"}),
             "bearing_displacement_max_time_s": ("bearing", self.bearing_displacement_max_time_s,
                                                 {"units": "s"}),
             "frame_drift_max_m": ("frame", self.frame_drift_max_m, {"units": "m"}),
             "frame_drift_min_m": ("frame", self.frame_drift_min_m, {"units": "m"}),
             "clearance_m": ("wall", self.clearance_m, {"units": "m"})},
            coords={"time_s": ("sample", self.t, {"units": "s"}),
                    "level": np.arange(self.displacement_max.shape[0]), "dof": ["x", "y", "theta"],
                    "bearing": np.arange(self.bearing_displacement_max_m.size), "axis": ["x", "y"],
                    "frame": np.arange(self.frame_drift_max_m.size),
                    "wall": walls},
            attrs={"status": self.status.name, "message": self.message})
        return ds

    def plot(self, ax: Any = None) -> Any:
        """The orbit in plan: each corner of the moat's floor (or each bearing, without a moat) as it moved,
        the moat's clearance drawn around where the corners started, each bearing's largest displacement
        marked; returns the Figure."""
        from ..plots import figure_of
        from ..plots.plan import plot_plan_orbit

        return figure_of(plot_plan_orbit(self, ax=ax), ax)


__all__ = ["PLAN_CONTACT_COLUMNS", "PlanRun"]
