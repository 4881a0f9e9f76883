"""A base-isolated building in plan: rigid floors with x, y and rotation, storeys of lateral lines placed
in plan, bearings at plan positions and a moat (four walls or a ring); its matrices, centres of stiffness
and modes; TOML in and out.

Degrees of freedom: floor ``l`` (0 the base) has ``3 l`` (x of its centre of mass, m), ``3 l + 1`` (y, m) and
``3 l + 2`` (its rotation, rad), each relative to the ground.
"""

from __future__ import annotations

import dataclasses
import warnings
from dataclasses import dataclass
from typing import Any, ClassVar, Optional

import numpy as np

from .._checks import instance_of, one_of, plausible, real_tuple, sequence_of
from .._errors import InputError, PoundingWarning, Problem
from .._units import GRAVITY_M_S2
from ._toml import TomlFile
from .contact_laws import law_from_dict
from .oscillator import check_keys, isolator_from_dict
from .moats import CircularMoat, RectangularMoat
from .plan_parts import AXES, Bearing, Floor, Frame
from .structure import Modes
from .structure_parts import MAX_STOREYS

MAX_BEARINGS = 400  # refused beyond
DOF_NAMES = ("x", "y", "theta")  # a floor's three dofs, in order
ACCIDENTAL = 0.05  # the codes' accidental eccentricity, a fraction of the plan's side (ASCE 7, EN 1998)
MOAT_SHAPES = ("rectangle", "circle")  # (a file's moat.shape: RectangularMoat, CircularMoat)
MAX_ACCIDENTAL, PLAUSIBLE_ACCIDENTAL = 0.25, 0.1  # (a fraction of the side: refused, warned beyond)
ACCIDENTAL_SIGNS = ((1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0))  # (accidental_cases' four, in order)
ACCIDENTAL_CASE_NAMES = tuple("".join(("+" if s > 0 else "-") + axis for s, axis in zip(signs, "xy"))
                              for signs in ACCIDENTAL_SIGNS)  # ("+x+y", "+x-y", "-x+y", "-x-y")


def point_weights(floor: Floor, level: int, axis: int,
                  p: tuple[float, float]) -> tuple[tuple[int, float], ...]:
    """The motion of point ``p`` (m) of floor ``level`` along ``axis`` (0: x, 1: y) as weights on the dofs:
    ``((dof, 1), (rotation dof, arm_m))``, the arm ``-(p_y - c_y)`` along x and ``p_x - c_x`` along y."""
    cx, cy = floor.centre_m
    arm = -(p[1] - cy) if axis == 0 else p[0] - cx
    return ((3 * level + axis, 1.0), (3 * level + 2, arm))


def _isolator_from_dict(table: Any, prefix: str) -> Any:
    """A bearing's isolator from its TOML table, its own checks' errors named where the table stands."""
    try:
        return isolator_from_dict(table, prefix)
    except InputError as exc:
        raise exc.relabel("isolator.", prefix) from None


@dataclass(frozen=True)
class PlanBuilding(TomlFile):
    """A base-isolated building in plan: the base and the floors above it, each a rigid floor with x, y and
    rotation; the storeys' lateral lines (frames or walls) placed in plan; bearings under the base at plan
    positions; a moat, four walls or a ring.

    Equations of motion (``q``: each floor's x, y and rotation about its centre of mass, relative to the
    ground)::

        M q'' + C q' + K q + sum of bearing, frame and wall forces at their places = -M r (a_x, a_y)

    with ``M`` each floor's mass (twice) and rotational inertia, and ``r`` moving every floor's x with the
    ground's x component and its y with its y component.  Frames and bearings act at their places: a frame
    along x at ``y = y_f`` resists ``x - (y_f - c_y) theta`` of its floor less the same of the floor below,
    so a layout off the centre of mass couples the floor's translation and rotation (torsion).

    Parameters
    ----------
    floors : sequence of Floor
        The base (level 0, on the bearings) first, then one per storey upwards; at most 51.
    bearings : sequence of Bearing
        Under the base; at least one.
    frames : sequence of Frame
        Each storey's lateral lines: every storey needs lines along x and along y that resist its rotation
        too (two parallel lines apart, or lines along both axes off one point).
    moat : RectangularMoat or CircularMoat, optional
        The moat around a floor (the base by default): four walls, or a ring.
    accidental_eccentricity : (float, float)
        Each floor's centre of mass moved by these fractions of its sides along x and y (signed; the codes
        ask 0.05 of either sign: :meth:`accidental_cases`).

    Examples
    --------
    A two-storey building 30 m by 12 m on four bearings, its stiff walls on one side:

    >>> import pounding
    >>> from pounding import Bearing, Floor, Frame, PlanBuilding
    >>> floors = [Floor(4.0e5, (30.0, 12.0))] * 3
    >>> iso = pounding.Isolator(slopes_n_m=[3.0e6, 4.0e5], breakpoints_m=[0.02])
    >>> bearings = [Bearing((sx * 14.0, sy * 5.0), iso)
    ...             for sx in (-1, 1) for sy in (-1, 1)]
    >>> frames = [Frame(s, "x", y, 4.0e8) for s in (1, 2) for y in (-6.0, 6.0)]
    >>> frames += [Frame(s, "y", x, k) for s in (1, 2)
    ...            for x, k in ((-15.0, 9.0e8), (15.0, 3.0e8))]
    >>> b = PlanBuilding(floors, bearings, frames)
    >>> b.centres_of_stiffness_m().round(2).tolist()  # m: bearings', storeys'
    [[0.0, 0.0], [-7.5, 0.0], [-7.5, 0.0]]
    >>> b.modes().periods_s[:3].round(3).tolist()  # s: along x, along y, turning
    [1.995, 1.994, 1.251]
    """

    floors: tuple
    bearings: tuple
    frames: tuple = ()
    moat: Optional[RectangularMoat | CircularMoat] = None
    accidental_eccentricity: tuple = (0.0, 0.0)

    FIELDS: ClassVar[tuple[str, ...]] = ("floors", "bearings", "frames", "moat", "accidental_eccentricity")

    def __post_init__(self) -> None:
        for name, kind, most in (("floors", Floor, MAX_STOREYS + 1), ("bearings", Bearing, MAX_BEARINGS),
                                 ("frames", Frame, None)):
            items = sequence_of(name, getattr(self, name), kind, f"pounding.{kind.__name__}")
            if not items and name != "frames":
                raise InputError(Problem.EMPTY, name, [],
                                 hint=f" ({'the base' if name == 'floors' else 'one'})")
            if most is not None and len(items) > most:
                raise InputError(Problem.TOO_LARGE, name, len(items), maximum=most, what=f" {name}",
                                 fix=f"give at most {most}")
            object.__setattr__(self, name, items)
        for i, f in enumerate(self.frames):
            if len(self.floors) == 1:
                raise InputError(Problem.WRONG_CONFIGURATION, f"frames[{i}].storey", f.storey,
                                 got="of one floor, the base: it has no storey for a frame to stand in",
                                 fix="add the floors the storeys carry (floors: the base, then one per "
                                     "storey), or leave the frames out")
            if f.storey >= len(self.floors):
                raise InputError(Problem.OUT_OF_RANGE, f"frames[{i}].storey", f.storey,
                                 range=f"[1, {len(self.floors) - 1}]",
                                 hint=f" (a storey carries a floor above the base; there are "
                                      f"{len(self.floors)} floors)")
        if self.moat is not None:
            instance_of("moat", self.moat, (RectangularMoat, CircularMoat),
                        "pounding.RectangularMoat, pounding.CircularMoat or None")
            if self.moat.level >= len(self.floors):
                raise InputError(Problem.OUT_OF_RANGE, "moat.level", self.moat.level,
                                 range=f"[0, {len(self.floors) - 1}]", hint=" (a floor: 0 is the base)")
        ecc = real_tuple("accidental_eccentricity", self.accidental_eccentricity)
        if len(ecc) != 2:
            raise InputError(Problem.LENGTH_MISMATCH, "accidental_eccentricity", list(ecc), got=len(ecc),
                             expected=2, hint=" (fractions of the sides along x and y, such as (0.05, 0.0))")
        for j, e in enumerate(ecc):
            if abs(e) > MAX_ACCIDENTAL:
                raise InputError(Problem.OUT_OF_RANGE, f"accidental_eccentricity[{j}]", e,
                                 range=f"[-{MAX_ACCIDENTAL:g}, {MAX_ACCIDENTAL:g}]",
                                 hint=" (a fraction of the side: the codes' 5 % is 0.05)")
            plausible(f"accidental_eccentricity[{j}]", abs(e), 0.0, PLAUSIBLE_ACCIDENTAL,
                      "a fraction of the side (the codes' 5 % is 0.05)")
        object.__setattr__(self, "accidental_eccentricity", ecc)
        for level, f in enumerate(self.floors):  # (each centre of mass moved: still on its floor)
            moved = [c + e * side for c, e, side in zip(f.centre_m, ecc, f.size_m)]
            if any(abs(c) > side / 2 for c, side in zip(moved, f.size_m)):
                raise InputError(Problem.BAD_STATE, "accidental_eccentricity", list(ecc),
                                 why=f"moves floor {level}'s centre of mass to ({moved[0]:g}, {moved[1]:g}) "
                                     f"m, off its rectangle ({f.size_m[0]:g} m by {f.size_m[1]:g} m, "
                                     "centred on 0)",
                                 fix="give a smaller eccentricity, or the floors' centres of mass nearer "
                                     "their middle")
        self._share_weight()
        self._check_within()
        self._check_restrained()

    def _share_weight(self) -> None:
        """Each friction bearing without a weight of its own (``weight_n``) carries its share of the
        building's weight as a rigid base shares it among equally stiff bearings: ``W_i = a + b x_i + c y_i``
        over the bearings without one (rubber ones too), whose sum and moments balance what those given one
        leave of the building's weight at its centre of mass (every floor's, with the accidental
        eccentricity; by least squares where they stand on one line).  An InputError where a share is not
        positive (the centre of mass beyond the bearings, or weights given that leave none); a warning
        where every bearing has its own and they miss the building's by more than 10 %."""
        if not any(b.is_friction for b in self.bearings):
            return
        floors = self.placed_floors
        mass = sum(f.mass_kg for f in floors)
        total_n = GRAVITY_M_S2 * mass
        centre = sum(f.mass_kg * np.asarray(f.centre_m) for f in floors) / mass
        at = np.array([b.at_m for b in self.bearings])
        given = np.array([b.isolator.weight_n if b.is_friction and not b.isolator.weight_carried
                          and b.isolator.weight_n is not None else np.nan for b in self.bearings])
        rest = np.flatnonzero(np.isnan(given))
        known = ~np.isnan(given)
        force = total_n - given[known].sum()
        if rest.size == 0:
            if abs(force) > 0.1 * total_n:
                warnings.warn(f"bearings: their weights sum to {total_n - force:.6g} N, the building's is "
                              f"{total_n:.6g} N (g times every floor's mass): a weight_n in kg, or a bearing "
                              "left out?", PoundingWarning, stacklevel=4)
            return
        if force <= 0.0:
            raise InputError(Problem.BAD_STATE, "bearings", list(given[known]),
                             why=f"(the weights given, N) leave nothing of the building's {total_n:.6g} N "
                                 f"for the {rest.size} bearing(s) without one",
                             fix="give weights that sum to the building's weight, or leave weight_n out")
        moment = total_n * centre - given[known] @ at[known]
        a = np.vstack([np.ones(rest.size), at[rest, 0], at[rest, 1]])  # (the sum, its moments about x and y)
        rhs = np.array([force, *moment])
        shares = a.T @ np.linalg.lstsq(a @ a.T, rhs, rcond=None)[0]
        if abs(shares.sum() - force) > 1e-9 * total_n:  # (on one line, beside weights given: the sum kept)
            shares = np.full(rest.size, force / rest.size)
        size = max(1.0, float(np.max(np.abs(at))))
        if np.max(np.abs(a[1:] @ shares - moment)) > 1e-9 * total_n * size:
            warnings.warn(f"bearings: their loads cannot balance the building's weight at its centre of "
                          f"mass ({centre[0]:.4g}, {centre[1]:.4g}) m (the bearings without a weight_n stand "
                          "on one line): it turns as if its mass were elsewhere; give every bearing its "
                          "weight_n, or place them around the centre of mass", PoundingWarning, stacklevel=4)
        if np.any(shares <= 0.0):
            q = int(rest[np.argmin(shares)])
            raise InputError(Problem.BAD_STATE, f"bearings[{q}].at_m", list(self.bearings[q].at_m),
                             why=f"would carry {shares.min():.6g} N of the building's {total_n:.6g} N: the "
                                 f"centre of mass ({centre[0]:.4g}, {centre[1]:.4g}) m lies beyond what the "
                                 "bearings without a weight_n can hold without pulling",
                             fix="place bearings around the centre of mass, or give each bearing its "
                                 "weight_n")
        bearings = list(self.bearings)
        for i, share in zip(rest, shares):
            if bearings[i].is_friction:
                try:
                    iso = bearings[i].isolator.carrying(share / GRAVITY_M_S2)
                except InputError as exc:  # (a stiffness the weight makes too large: the bearing named)
                    raise exc.relabel("isolator.", f"bearings[{i}].isolator.") from None
                bearings[i] = dataclasses.replace(bearings[i], isolator=iso)
        object.__setattr__(self, "bearings", tuple(bearings))

    def _check_within(self) -> None:
        """Every bearing under the base's rectangle, every frame within its floors' (an InputError naming
        it)."""
        a, b = self.floors[0].size_m
        for i, bearing in enumerate(self.bearings):
            x, y = bearing.at_m
            if abs(x) > a / 2 or abs(y) > b / 2:
                raise InputError(Problem.OUT_OF_RANGE, f"bearings[{i}].at_m", [x, y],
                                 range=f"[-{a / 2:g}, {a / 2:g}] x [-{b / 2:g}, {b / 2:g}] m",
                                 hint=" (a bearing stands under the base's rectangle, centred on 0)")
        for i, f in enumerate(self.frames):
            across = min(self.floors[f.storey].size_m[1 - AXES.index(f.axis)],
                         self.floors[f.storey - 1].size_m[1 - AXES.index(f.axis)]) / 2
            if abs(f.at_m) > across:
                raise InputError(Problem.OUT_OF_RANGE, f"frames[{i}].at_m", f.at_m,
                                 range=f"[-{across:g}, {across:g}] m",
                                 hint=f" (a line along {f.axis} stands within the floors it joins, centred "
                                      "on 0)")

    def _check_restrained(self) -> None:
        """Every storey and the bearings resist x, y and rotation: the stiffness at rest is positive
        definite, storey by storey (else an InputError naming the storey and what it lacks)."""
        for s in range(len(self.floors)):
            k = self._storey_stiffness(s)
            d = np.sqrt(np.maximum(np.diag(k), 0.0))
            free = np.any(d == 0.0) or np.linalg.eigvalsh(k / np.outer(d, d))[0] <= 1e-9
            if free:
                what = "the bearings" if s == 0 else f"storey {s}'s frames"
                axes = [a for j, a in enumerate(AXES) if d[j] == 0.0]
                lacks = (f"nothing along {' and '.join(axes)}" if axes else
                         "nothing against rotation (its lines along x and y all meet at one point)")
                field_name = "bearings" if s == 0 else "frames"
                places = ([list(b.at_m) for b in self.bearings] if s == 0 else
                          [f"{f.axis} at {f.at_m:g} m" for f in self.frames if f.storey == s])
                raise InputError(Problem.WRONG_CONFIGURATION, field_name, places,
                                 got=f"where {what} resist {lacks}",
                                 fix="add lines along x and y away from one point (two parallel lines apart "
                                     "resist the floor's rotation)" if s else
                                     "give bearings at two places or more")

    # ------------------------------------------------------------------ geometry
    @property
    def n_levels(self) -> int:
        """The floors: the base and one per storey."""
        return len(self.floors)

    @property
    def n_dofs(self) -> int:
        """Three per floor: x, y and rotation."""
        return 3 * len(self.floors)

    @property
    def placed_floors(self) -> tuple[Floor, ...]:
        """The floors with their centres of mass moved by the accidental eccentricity (as the run takes
        them)."""
        ex, ey = self.accidental_eccentricity
        if ex == 0.0 and ey == 0.0:
            return self.floors
        return tuple(dataclasses.replace(f, centre_m=(f.centre_m[0] + ex * f.size_m[0],
                                                       f.centre_m[1] + ey * f.size_m[1]))
                     for f in self.floors)

    def accidental_cases(self, fraction: float = ACCIDENTAL) -> tuple["PlanBuilding", ...]:
        """The building with its centres of mass moved by ``fraction`` of each side, each of the four
        signs: ``(+x, +y), (+x, -y), (-x, +y), (-x, -y)`` (:data:`ACCIDENTAL_CASE_NAMES`)."""
        return tuple(dataclasses.replace(self, accidental_eccentricity=(sx * fraction, sy * fraction))
                     for sx, sy in ACCIDENTAL_SIGNS)

    # ------------------------------------------------------------------ matrices
    @property
    def mass_matrix(self) -> np.ndarray:
        """The floors' masses and inertias, (3 n, 3 n) diagonal: kg, kg, kg m^2 per floor."""
        return np.diag([v for f in self.floors for v in (f.mass_kg, f.mass_kg, f.inertia_kg_m2)])

    def lines(self) -> tuple[tuple[int, int, int, float, Any], ...]:
        """Every lateral line as ``(storey, axis, index, at_m, part)``: each bearing's two axes (storey 0,
        ``index`` the bearing's), then each frame (``index`` the frame's); ``at_m`` where it stands across
        its axis."""
        out = []
        for b, bearing in enumerate(self.bearings):
            for axis in (0, 1):
                out.append((0, axis, b, bearing.at_m[1 - axis], bearing))
        for i, f in enumerate(self.frames):
            out.append((f.storey, AXES.index(f.axis), i, f.at_m, f))
        return tuple(out)

    def line_weights(self, storey: int, axis: int, at_m: float) -> np.ndarray:
        """A line's drift as weights on the dofs, shape (3 n,): its floor's point at ``at_m`` along
        ``axis`` less the floor below's (the ground's for the bearings, storey 0)."""
        floors, w = self.placed_floors, np.zeros(self.n_dofs)
        p = (0.0, at_m) if axis == 0 else (at_m, 0.0)
        for level, sign in ((storey, 1.0), (storey - 1, -1.0)):
            if level >= 0:
                for dof, v in point_weights(floors[level], level, axis, p):
                    w[dof] += sign * v
        return w

    def _initial_stiffness(self, part: Any, axis: int) -> float:
        if isinstance(part, Bearing):
            return part.laws[axis].initial_stiffness_n_m
        return part.stiffness_n_m

    def stiffness_matrix(self, storey: Optional[int] = None) -> np.ndarray:
        """Every bearing and frame at its initial stiffness, (3 n, 3 n): N/m, N/rad, N m/rad; ``storey``:
        that storey's alone (0: the bearings)."""
        k = np.zeros((self.n_dofs, self.n_dofs))
        for s, axis, _, at, part in self.lines():
            if storey is None or s == storey:
                w = self.line_weights(s, axis, at)
                k += self._initial_stiffness(part, axis) * np.outer(w, w)
        return k

    def _storey_stiffness(self, storey: int) -> np.ndarray:
        """Storey ``storey``'s stiffness on its floor's three dofs (the floor below held)."""
        at = slice(3 * storey, 3 * storey + 3)
        return self.stiffness_matrix(storey)[at, at]

    def damping_matrix(self) -> np.ndarray:
        """Every bearing's and frame's dashpot at its place, (3 n, 3 n)."""
        c = np.zeros((self.n_dofs, self.n_dofs))
        for s, axis, _, at, part in self.lines():
            c_d = part.laws[axis].damping_n_s_m if isinstance(part, Bearing) else part.damping_n_s_m
            if c_d:
                w = self.line_weights(s, axis, at)
                c += c_d * np.outer(w, w)
        return c

    def centres_of_stiffness_m(self) -> np.ndarray:
        """Each storey's centre of stiffness in plan, m, shape (n_levels, 2): the bearings' first (their
        initial stiffnesses), then each storey's lines'."""
        out = np.zeros((self.n_levels, 2))
        for s in range(self.n_levels):
            for axis in (0, 1):  # (lines along x place the centre's y, lines along y its x)
                ks = [(self._initial_stiffness(part, a), at) for st, a, _, at, part in self.lines()
                      if st == s and a == axis]
                out[s, 1 - axis] = sum(k * at for k, at in ks) / sum(k for k, _ in ks)
        return out

    def eccentricities_m(self) -> np.ndarray:
        """Each storey's centre of stiffness less the centre of mass of the floor it carries, m, shape
        (n_levels, 2) (with the accidental eccentricity)."""
        return self.centres_of_stiffness_m() - np.array([f.centre_m for f in self.placed_floors])

    def modes(self, fixed_base: bool = False) -> Modes:
        """Undamped modes about rest, every bearing and frame at its initial stiffness: periods (s, longest
        first) and shapes (3 n, m), rows by dof (``x, y, theta`` per floor: m, m, rad), each column scaled
        so that its largest motion, a translation or the motion a rotation gives a floor's corner (the
        rotation times the floor's half-diagonal), is +1 m.  ``fixed_base``: the base held (the storeys
        alone)."""
        from scipy.linalg import eigh

        k, m = self.stiffness_matrix(), self.mass_matrix
        if fixed_base:
            k, m = k[3:, 3:], m[3:, 3:]
        if m.size == 0:
            return Modes(np.zeros(0), np.zeros((0, 0)))
        w2, shapes = eigh(k, m)
        periods = 2.0 * np.pi / np.sqrt(w2)
        floors = self.floors[1:] if fixed_base else self.floors
        reach = np.array([[1.0, 1.0, 0.5 * float(np.hypot(*f.size_m))] for f in floors]).ravel()
        big = np.argmax(np.abs(shapes) * reach[:, None], axis=0)  # (a rotation: the motion of a corner)
        columns = np.arange(shapes.shape[1])
        shapes = shapes / (shapes[big, columns] * reach[big])
        return Modes(periods, shapes)

    def without_bumpers(self) -> "PlanBuilding":
        """The building without its moat (no walls to strike), as :meth:`Structure.without_bumpers`."""
        return dataclasses.replace(self, moat=None)

    @property
    def moat_in_reach(self) -> bool:
        """Whether its corners can strike its moat: False without one, or with a ring out of reach
        (:meth:`moat_out_of_reach`)."""
        return self.moat is not None and not getattr(self.moat, "out_of_reach", False)

    def moat_out_of_reach(self) -> "PlanBuilding":
        """The building as a free run takes it, its demand on its own moat tracked: without its moat
        (:meth:`without_bumpers`: the corners' displacements towards four walls are tracked anyway), or
        with its ring moved out of reach (``CircularMoat.out_of_reach``: its radius ``OUT_OF_REACH_M``
        beyond the corners, never struck, their distances from its centre tracked; a run's
        ``quantities()`` give its ``moat_demand_m`` and no clearance)."""
        if not isinstance(self.moat, CircularMoat):
            return self.without_bumpers()
        return dataclasses.replace(self, moat=dataclasses.replace(self.moat, out_of_reach=True))

    # ------------------------------------------------------------------ TOML
    def to_dict(self) -> dict[str, Any]:
        """The building as nested tables with the constructor's field names."""
        out: dict[str, Any] = {"floors": [f.to_dict() for f in self.floors],
                               "bearings": [b.to_dict() for b in self.bearings]}
        if self.frames:
            out["frames"] = [f.to_dict() for f in self.frames]
        if self.moat is not None:
            out["moat"] = self.moat.to_dict()
        if self.accidental_eccentricity != (0.0, 0.0):
            out["accidental_eccentricity"] = list(self.accidental_eccentricity)
        return out

    @classmethod
    def from_dict(cls, table: dict[str, Any]) -> "PlanBuilding":
        """Build from nested tables; every key is checked and unknown keys are errors."""
        table = {k: v for k, v in table.items() if k != "meta"} if isinstance(table, dict) else table
        check_keys(table, "", cls.FIELDS, required=("floors", "bearings"))
        parts: dict[str, list] = {}
        for name, kind, required in (("floors", Floor, ("mass_kg", "size_m")),
                                     ("bearings", Bearing, ("at_m", "isolator")),
                                     ("frames", Frame, ("storey", "axis", "at_m", "stiffness_n_m"))):
            rows = table.get(name, [])
            instance_of(name, rows, list, f"array of tables ([[{name}]])")
            parts[name] = []
            for i, row in enumerate(rows):
                prefix = f"{name}[{i}]."
                check_keys(row, prefix, kind.FIELDS, required=required)
                if kind is Bearing:
                    row = {**row, **{k: _isolator_from_dict(row[k], prefix + k + ".")
                                     for k in ("isolator", "isolator_y") if k in row}}
                try:
                    parts[name].append(kind(**row))
                except InputError as exc:
                    raise exc.relabel(kind.__name__.lower() + ".", prefix) from None
        moat = None
        if "moat" in table:
            row = table["moat"]
            check_keys(row, "moat.", ("shape", *CircularMoat.FIELDS), required=("gap_m", "law"))
            shape = one_of("moat.shape", row.get("shape", "rectangle"), MOAT_SHAPES)
            kind = CircularMoat if shape == "circle" else RectangularMoat
            ring = {"out_of_reach": row["out_of_reach"]} if "out_of_reach" in row else {}
            if ring and kind is RectangularMoat:
                raise InputError(Problem.UNKNOWN_KEY, "moat.out_of_reach", row["out_of_reach"],
                                 choices="a rectangle's keys (out_of_reach is a ring's: shape = \"circle\")")
            moat = kind(row["gap_m"], law_from_dict(row["law"], "moat.law"), row.get("level", 0), **ring)
        return cls(tuple(parts["floors"]), tuple(parts["bearings"]), tuple(parts["frames"]), moat,
                   table.get("accidental_eccentricity", (0.0, 0.0)))


__all__ = ["ACCIDENTAL", "ACCIDENTAL_CASE_NAMES", "DOF_NAMES", "PlanBuilding", "point_weights"]
