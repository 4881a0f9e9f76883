"""The parts of a building in plan (:class:`pounding.model.plan.PlanBuilding`): a rigid floor, a lateral
line (a frame or a wall) placed in plan, a bearing at a plan position (its moat: :mod:`pounding.model.moats`).

Plan coordinates: x and y in metres from the centre of the floors' rectangles; a rotation ``theta``
(rad) turns x towards y.  A point ``(p_x, p_y)`` of a floor whose centre of mass ``(c_x, c_y)`` moves
by ``(u, v)`` and turns by ``theta`` moves by ``(u - (p_y - c_y) theta, v + (p_x - c_x) theta)``
(small rotations)."""

from __future__ import annotations

import warnings

from dataclasses import dataclass
from typing import Any, ClassVar, Optional

from .._checks import (at_most, instance_of, integer, non_negative, one_of, plausible, positive, real,
                       real_tuple)
from .._errors import InputError, PoundingWarning, Problem
from .friction import PRESLIP_IN_PLAN, FrictionIsolator
from .isolator import Isolator
from .structure_parts import (MAX_STOREY_STIFFNESS, MAX_STOREYS, check_backbone_after,
                              check_mass)

AXES = ("x", "y")
FRICTION_CIRCLES = ("plastic", "bouc_wen")  # (a friction bearing's circle in plan: Bearing.friction_circle)
MAX_PLAN_M = 1e3  # a floor's side, m, refused beyond (a unit error)


def _pair(field: str, value: Any) -> tuple[float, float]:
    """Two finite numbers (a point or a size in plan, m) as a tuple."""
    out = real_tuple(field, value)
    if len(out) != 2:
        raise InputError(Problem.LENGTH_MISMATCH, field, list(out), got=len(out), expected=2,
                         hint=" (x then y, in m)")
    return out  # type: ignore[return-value]


@dataclass(frozen=True)
class Floor:
    """A rigid floor in plan: its mass, its rectangle and where its mass is.

    Parameters
    ----------
    mass_kg : float
        The floor's mass, kg, > 0.
    size_m : (float, float)
        Its plan's sides along x and y, m, > 0: a rectangle centred on the plan's origin (its corners
        are where it strikes a moat).
    inertia_kg_m2 : float, optional
        Its rotational inertia about its centre of mass, kg m^2, > 0; default: a uniform rectangle's,
        ``mass_kg (a^2 + b^2) / 12``.
    centre_m : (float, float)
        Its centre of mass in plan, m (default the rectangle's centre): the actual eccentricity.

    Examples
    --------
    A floor of 400 t, 30 m by 12 m, its mass 1.5 m off the centre along x:

    >>> import pounding
    >>> f = pounding.Floor(4.0e5, (30.0, 12.0), centre_m=(1.5, 0.0))
    >>> round(f.inertia_kg_m2 / 1e6, 1)  # kg m^2, millions: a uniform slab's
    34.8
    >>> f.corners_m()[3]  # m
    (15.0, 6.0)
    """

    mass_kg: float
    size_m: tuple
    inertia_kg_m2: Optional[float] = None
    centre_m: tuple = (0.0, 0.0)

    FIELDS: ClassVar[tuple[str, ...]] = ("mass_kg", "size_m", "inertia_kg_m2", "centre_m")

    def __post_init__(self) -> None:
        m = check_mass("floor.mass_kg", self.mass_kg)
        object.__setattr__(self, "mass_kg", m)
        size = _pair("floor.size_m", self.size_m)
        for j, side in enumerate(size):
            positive(f"floor.size_m[{j}]", side, "m")
            at_most(f"floor.size_m[{j}]", side, MAX_PLAN_M, " m", "give the plan's sides in m")
            plausible(f"floor.size_m[{j}]", side, 1.0, 300.0, "a plan's sides are in m (30 m is 30.0)")
        object.__setattr__(self, "size_m", size)
        centre = _pair("floor.centre_m", self.centre_m)
        for j, (c, side) in enumerate(zip(centre, size)):
            if abs(c) > side / 2:
                raise InputError(Problem.OUT_OF_RANGE, f"floor.centre_m[{j}]", c,
                                 range=f"[{-side / 2:g}, {side / 2:g}] m",
                                 hint=" (the centre of mass is inside the floor's rectangle, centred on 0)")
        object.__setattr__(self, "centre_m", centre)
        density = m / (size[0] * size[1])
        if not 50.0 <= density <= 1e4:  # (a building's floors: some 500 to 1500 kg per m^2 of plan)
            warnings.warn(f"floor.mass_kg = {m!r} is {density:.3g} kg per m^2 of its {size[0]:g} m by "
                          f"{size[1]:g} m plan, outside the plausible [50, 1e4] kg/m^2: masses are in kg "
                          "(500 t is 5.0e5)", PoundingWarning, stacklevel=3)
        if self.inertia_kg_m2 is None:
            inertia = m * (size[0] ** 2 + size[1] ** 2) / 12.0
        else:
            inertia = positive("floor.inertia_kg_m2", self.inertia_kg_m2, "kg m^2")
            at_most("floor.inertia_kg_m2", inertia, 1e12 * MAX_PLAN_M**2, " kg m^2",
                    "give the inertia in kg m^2")
            ratio = inertia / (m * (size[0] ** 2 + size[1] ** 2) / 12.0)
            plausible("floor.inertia_kg_m2", ratio, 0.1, 10.0,
                      "an inertia in kg m^2 near a uniform floor's mass_kg (a^2 + b^2) / 12")
        object.__setattr__(self, "inertia_kg_m2", float(inertia))

    def corners_m(self) -> tuple[tuple[float, float], ...]:
        """The rectangle's corners, m: (-x, -y), (-x, +y), (+x, -y), (+x, +y)."""
        a, b = self.size_m
        return tuple((sx * a / 2, sy * b / 2) for sx in (-1.0, 1.0) for sy in (-1.0, 1.0))

    def to_dict(self) -> dict[str, Any]:
        # (a uniform slab's inertia is left out: it follows the mass and the size wherever they are changed,
        # as a study's grid changes them)
        slab = self.mass_kg * (self.size_m[0] ** 2 + self.size_m[1] ** 2) / 12.0
        return {"mass_kg": self.mass_kg, "size_m": list(self.size_m), "centre_m": list(self.centre_m),
                **({} if self.inertia_kg_m2 == slab else {"inertia_kg_m2": self.inertia_kg_m2})}


@dataclass(frozen=True)
class Frame:
    """A lateral line of a storey (a frame or a wall) placed in plan: it resists the storey's drift along
    its axis at its place.

    Parameters
    ----------
    storey : int
        The storey it stands in, >= 1: between floor ``storey`` and the floor below it.
    axis : {"x", "y"}
        The direction it resists.
    at_m : float
        Where it stands across its axis, m: a line along x at ``y = at_m``, along y at ``x = at_m``.
    stiffness_n_m : float
        Its lateral stiffness, N/m, > 0.
    damping_n_s_m : float
        Its dashpot, N s/m, >= 0.
    slopes_after_n_m : sequence of float
        A multi-linear frame: its backbone's slopes after the first, N/m, as a :class:`pounding.Storey`'s.
    breakpoints_m : sequence of float
        The drifts where the slope changes, m.
    hysteresis : {"kinematic", "elastic"}
        How a multi-linear frame unloads.
    height_m : float
        The storey's height, m, > 0 (for drift ratios; default 3 m).

    Examples
    --------
    A shear wall along y at x = -15 m in the first storey, and a frame along x at y = 6 m that yields at
    a drift of 1 cm:

    >>> import pounding
    >>> wall = pounding.Frame(1, "y", -15.0, 9.0e8)
    >>> frame = pounding.Frame(1, "x", 6.0, 4.0e8, slopes_after_n_m=[4.0e7],
    ...                        breakpoints_m=[0.01])
    >>> wall.is_linear, frame.is_linear
    (True, False)
    """

    storey: int
    axis: str
    at_m: float
    stiffness_n_m: float
    damping_n_s_m: float = 0.0
    slopes_after_n_m: tuple = ()
    breakpoints_m: tuple = ()
    hysteresis: str = "kinematic"
    height_m: float = 3.0

    FIELDS: ClassVar[tuple[str, ...]] = ("storey", "axis", "at_m", "stiffness_n_m", "damping_n_s_m",
                                         "slopes_after_n_m", "breakpoints_m", "hysteresis", "height_m")

    def __post_init__(self) -> None:
        object.__setattr__(self, "storey", integer("frame.storey", self.storey, 1, MAX_STOREYS))
        one_of("frame.axis", self.axis, AXES)
        at = real("frame.at_m", self.at_m)
        at_most("frame.at_m", abs(at), MAX_PLAN_M, " m", "give its place in m")
        object.__setattr__(self, "at_m", at)
        k = positive("frame.stiffness_n_m", self.stiffness_n_m, "N/m")
        at_most("frame.stiffness_n_m", k, MAX_STOREY_STIFFNESS, " N/m", "give the stiffness in N/m")
        object.__setattr__(self, "stiffness_n_m", k)
        c = non_negative("frame.damping_n_s_m", self.damping_n_s_m, "N s/m")
        at_most("frame.damping_n_s_m", c, MAX_STOREY_STIFFNESS, " N s/m", "give the damping in N s/m")
        object.__setattr__(self, "damping_n_s_m", c)
        check_backbone_after(self, "frame", k)
        h = positive("frame.height_m", self.height_m, "m")
        at_most("frame.height_m", h, 1e3, " m", "give the height in m")
        plausible("frame.height_m", h, 0.1, 20.0, "heights are in m (a storey of 3 m is 3.0)")
        object.__setattr__(self, "height_m", h)

    @property
    def is_linear(self) -> bool:
        """A linear frame (no breakpoints)."""
        return not self.breakpoints_m

    def to_dict(self) -> dict[str, Any]:
        return {f: (list(v) if isinstance(v, tuple) else v) for f in self.FIELDS
                if (v := getattr(self, f)) != ()}


@dataclass(frozen=True)
class Bearing:
    """An isolation bearing at a plan position under the base: a law on each axis, or one in the plane.

    Parameters
    ----------
    at_m : (float, float)
        Where it stands, m.
    isolator : Isolator or FrictionIsolator
        Its law along x, and along y unless ``isolator_y`` is given (a rubber bearing's backbone and
        hysteresis, uncoupled; and its Bouc-Wen spring if it has one, see ``bidirectional``).  A
        :class:`pounding.FrictionIsolator` (a friction pendulum or a flat slider) needs an elastic
        pre-slip in plan (``preslip_m > 0``); its friction may depend on the velocity (``mu_fast``;
        on its friction circle see ``friction_circle``); its weight, unless given
        (``weight_n``), is its share of the building's (``g`` times every floor's mass) as a rigid base
        shares it among equally stiff bearings, balanced at the centre of mass
        (:class:`pounding.PlanBuilding`), and stays that load (overturning, vertical motion and uplift do
        not change it).
    isolator_y : Isolator or FrictionIsolator, optional
        Its law along y (a friction bearing's is its ``isolator``'s: leave it out).
    bidirectional : bool
        Whether its Bouc-Wen spring is one spring in the plane (default), yielding under the resultant of
        its two components (Park, Wen and Ang's: both axes must carry the same :class:`pounding.BoucWen`),
        or one along each axis, each yielding under its own component (False).  Without a Bouc-Wen spring
        it changes nothing.  A friction bearing's default is the friction circle: it slips along its
        velocity once the force in the plane reaches ``mu W`` (``friction_circle``), beside the pendulum's
        ``W / R`` along each axis; False: one bilinear friction along each axis, each slipping under its
        own component at ``mu W`` (a bearing on a line's law).
    friction_circle : {"plastic", "bouc_wen"}
        A friction bearing's circle (``bidirectional``), its force ``mu W z`` (``|z| <= 1``, ``z`` moving
        by the bearing's displacement over ``preslip_m``).  ``"plastic"`` (the default): elastic-perfectly
        plastic: it sticks (elastic, ``z' = u' / preslip_m``: exact phases) while the force stays inside
        ``mu W`` and slips on the circle (the force ``mu W`` along the slip, integrated numerically) while
        the motion pushes outwards, its every stick and slip located as an event (``circle_slip``,
        ``circle_stick``).
        ``"bouc_wen"``: Constantinou, Mokha and Reinhorn's (1990) smooth model, SAP2000's and
        3D-BASIS's: a bidirectional Bouc-Wen spring of stiffness ``mu W / preslip_m``, yield displacement
        ``preslip_m``, ``a = 1``, ``beta = gamma = 1/2`` and ``n = 2``, which never quite sticks.  With a
        velocity-dependent friction (the isolator's ``mu_fast``) either circle's force is ``W mu(s) z``
        (:meth:`pounding.FrictionIsolator.friction_at` at ``s``), ``s`` the slip's rate: ``z . u'`` while
        the plastic circle slips (its sticks stay exact, at ``mu``), the bearing's speed ``|u'|`` on the
        Bouc-Wen circle.  Other bearings: unused.

    Examples
    --------
    A lead-rubber bearing near a corner, bilinear along both axes:

    >>> import pounding
    >>> lrb = pounding.Isolator(slopes_n_m=[1.2e7, 1.2e6], breakpoints_m=[0.01])
    >>> b = pounding.Bearing((14.0, 5.0), lrb)
    >>> b.laws[0] is b.laws[1]  # the same law along x and y
    True
    """

    at_m: tuple
    isolator: Any
    isolator_y: Optional[Any] = None
    bidirectional: bool = True
    friction_circle: str = "plastic"

    FIELDS: ClassVar[tuple[str, ...]] = ("at_m", "isolator", "isolator_y", "bidirectional",
                                         "friction_circle")

    def __post_init__(self) -> None:
        at = _pair("bearing.at_m", self.at_m)
        for j, p in enumerate(at):
            at_most(f"bearing.at_m[{j}]", abs(p), MAX_PLAN_M, " m", "give its place in m")
        object.__setattr__(self, "at_m", at)
        for name in ("isolator", "isolator_y"):
            iso = getattr(self, name)
            if iso is None and name == "isolator_y":
                continue
            if not isinstance(iso, (Isolator, FrictionIsolator)):
                raise InputError(Problem.WRONG_TYPE, f"bearing.{name}", iso, got=type(iso).__name__,
                                 expected="pounding.Isolator or pounding.FrictionIsolator (a bearing's law; "
                                          "a triple friction pendulum in plan is not supported yet)")
        instance_of("bearing.bidirectional", self.bidirectional, bool, "true or false")
        if self.friction_circle not in FRICTION_CIRCLES:
            raise InputError(Problem.NOT_ONE_OF, "bearing.friction_circle", self.friction_circle,
                             choices=FRICTION_CIRCLES)
        if self.friction_circle != "plastic" and not (self.is_friction and self.bidirectional):
            raise InputError(Problem.WRONG_CONFIGURATION, "bearing.friction_circle", self.friction_circle,
                             got="for a bearing without a friction circle (a rubber bearing's law, or one "
                                 "friction along each axis: bidirectional false)",
                             fix="leave friction_circle out: it is a friction bearing's in the plane's")
        if self.is_friction or isinstance(self.isolator_y, FrictionIsolator):
            self._check_friction()
        springs = [law.bouc_wen for law in self.laws]
        if self.bidirectional and springs[0] != springs[1]:
            raise InputError(Problem.WRONG_CONFIGURATION, "bearing.isolator_y.bouc_wen", springs[1],
                             got=f"whose Bouc-Wen spring along y differs from x's ({springs[0]}): a "
                                 "bidirectional spring is one spring in the plane",
                             fix="give both axes the same BoucWen, or bidirectional=False (false in a "
                                 "TOML file) for one spring along each axis")

    def _check_friction(self) -> None:
        """A friction bearing in plan: one law for both axes, with an elastic pre-slip."""
        if self.isolator_y is not None:
            why = ("is a friction isolator" if isinstance(self.isolator_y, FrictionIsolator) else
                   "is given beside a friction isolator")
            raise InputError(Problem.BAD_STATE, "bearing.isolator_y", self.isolator_y,
                             why=f"{why} (a sliding bearing's friction is the same along x and y)",
                             fix="leave isolator_y out and give a friction isolator as isolator (it serves "
                                 "both axes)")
        iso = self.isolator
        if not iso.preslip_m > 0.0:
            raise InputError(Problem.BAD_STATE, "bearing.isolator.preslip_m", iso.preslip_m,
                             why="is a rigid stick, which a bearing in plan cannot have", fix=PRESLIP_IN_PLAN)
        if self.bidirectional and iso.preslip_m < 1e-4:  # (the circle's z relaxes at |v| / preslip_m)
            warnings.warn(f"bearing.isolator.preslip_m = {iso.preslip_m!r} is below 0.1 mm: the friction "
                          "circle's elastic stiffness (mu W / preslip_m) is then large and its runs take "
                          "many short steps (0.5 mm is usual)", PoundingWarning, stacklevel=3)

    @property
    def is_friction(self) -> bool:
        """Whether it is a sliding bearing (a :class:`pounding.FrictionIsolator`)."""
        return isinstance(self.isolator, FrictionIsolator)

    @property
    def coupled(self) -> bool:
        """Whether its two axes share one bidirectional spring: a Bouc-Wen spring's, or a friction bearing's
        circle."""
        return self.bidirectional and (self.is_friction or self.isolator.bouc_wen is not None)

    @property
    def plastic_circle(self) -> bool:
        """Whether its two axes share an elastic-perfectly-plastic friction circle (a friction bearing's,
        ``bidirectional``, ``friction_circle = "plastic"``)."""
        return self.is_friction and self.bidirectional and self.friction_circle == "plastic"

    def kernel_arrays(self, axis: int) -> tuple:
        """Its law along ``axis`` (0: x, 1: y) as the engine takes it (``Isolator.kernel_arrays``'s four
        arrays): a friction bearing's circle in plan its Bouc-Wen form
        (:meth:`pounding.FrictionIsolator.kernel_arrays_in_plane`)."""
        law = self.laws[axis]
        circle = self.is_friction and self.bidirectional
        return law.kernel_arrays_in_plane() if circle else law.kernel_arrays()

    @property
    def kernel_friction(self) -> dict[str, float]:
        """A friction bearing's velocity dependence as the engine takes it on each axis's element: its
        circle's (:attr:`pounding.FrictionIsolator.kernel_friction_in_plane`), or its pre-slip's along each
        axis (``bidirectional`` false: :attr:`pounding.FrictionIsolator.kernel_friction`); none for others."""
        if not self.is_friction:
            return {}
        law = self.isolator
        return law.kernel_friction_in_plane if self.bidirectional else law.kernel_friction

    @property
    def laws(self) -> tuple[Any, Any]:
        """Its law along x and along y."""
        return self.isolator, self.isolator if self.isolator_y is None else self.isolator_y

    def to_dict(self) -> dict[str, Any]:
        out: dict[str, Any] = {"at_m": list(self.at_m), "isolator": self.isolator.to_dict()}
        if self.isolator_y is not None:
            out["isolator_y"] = self.isolator_y.to_dict()
        if not self.bidirectional:
            out["bidirectional"] = False
        if self.friction_circle != "plastic":
            out["friction_circle"] = self.friction_circle
        return out


__all__ = ["AXES", "Bearing", "FRICTION_CIRCLES", "Floor", "Frame"]
