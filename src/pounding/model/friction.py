"""The friction isolator: a flat slider or a single friction pendulum, Coulomb friction with exact stick and
slip, constant or velocity-dependent.

Its engine form is the isolator's element with the friction rule (the core's ``RULE_FRICTION``, isolator.hpp):
a spring of the pendulum's restoring stiffness ``W / R`` in parallel with a friction force ``mu W`` that
sticks rigidly.  With an elastic pre-slip it is the kinematic rule's bilinear element instead (slopes
``mu W / preslip_m + W / R`` and ``W / R``, slipping at ``mu W``), what OpenSees' ``flatSliderBearing`` and
``singleFPBearing`` are.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any, ClassVar, Optional

import numpy as np

from .._checks import at_most, boolean, non_negative, plausible, positive
from .._errors import InputError, Problem
from .._units import GRAVITY_M_S2
from .isolator import BW_PARAMS, MAX_BREAKPOINT_M, MAX_DAMPING_N_S_M, MAX_STIFFNESS_N_M, BoucWen

RULE_KINEMATIC, RULE_FRICTION = 0, 2  # (the core's rules: isolator.hpp)
MAX_MU = 1.0
MAX_WEIGHT_N = 1e12
CIRCLE_N = 2.0  # the friction circle's Bouc-Wen sharpness in plan (Constantinou, Mokha and Reinhorn 1990)
PRESLIP_IN_PLAN = ("give preslip_m > 0 (0.0005 m is usual): in plan a friction bearing deforms elastically "
                   "up to it, as OpenSees' and SAP2000's do (several bearings stuck under one rigid floor "
                   "share their force in no one way without it)")


class CarriesWeight:
    """What a sliding isolator does with the weight it carries (``weight_n``, N, and ``weight_carried``,
    whether it is its system's): checked, bound to a system's mass, read."""

    weight_n: Optional[float]
    weight_carried: bool

    def _check_weight(self) -> Optional[float]:
        """Check ``weight_n`` and ``weight_carried`` (set on the frozen instance); the weight, or None."""
        object.__setattr__(self, "weight_carried", boolean("isolator.weight_carried", self.weight_carried))
        if self.weight_carried and self.weight_n is None:
            raise InputError(Problem.WRONG_CONFIGURATION, "isolator.weight_carried", True,
                             got="without a weight", fix="leave it False (a system sets it)")
        if self.weight_n is None:
            return None
        weight = positive("isolator.weight_n", self.weight_n, "N")
        at_most("isolator.weight_n", weight, MAX_WEIGHT_N, " N", "give the weight in N (mass times g)")
        object.__setattr__(self, "weight_n", weight)
        return weight

    def carrying(self, mass_kg: float) -> Any:
        """The same isolator carrying the weight of ``mass_kg`` (a ``weight_n`` given kept): what a system
        does with it."""
        if self.weight_n is not None and not self.weight_carried:
            return self
        return replace(self, weight_n=GRAVITY_M_S2 * float(mass_kg), weight_carried=True)  # type: ignore

    def _weight(self) -> float:
        if self.weight_n is None:
            raise InputError(Problem.WRONG_CONFIGURATION, "isolator.weight_n", None,
                             got="unknown until the isolator is put into a system",
                             fix="put it into a Structure or Oscillator (it carries their weight), or give "
                                 "weight_n")
        return self.weight_n


@dataclass(frozen=True)
class FrictionIsolator(CarriesWeight):
    """A sliding isolator: a flat slider, or a single friction pendulum of radius ``radius_m``.

    Its force on the base, at the base's displacement ``D`` relative to the ground, is::

        F = (W / R) D + f + C_d dD/dt,    |f| <= mu W

    with ``W`` the weight it carries and ``f`` Coulomb's friction: while the base slips, ``f = mu W`` against
    its velocity; while it sticks, ``f`` is what holding it needs.  A slip ends where the base comes to rest
    and the force needed to hold it is within ``mu W`` (else it slips back); a stick ends where that force
    reaches ``mu W``.  Both are events located on the exact trajectory: every phase is linear, and the
    engine steps over none of them (a stepping code smears the stick with a stiff initial branch).

    Parameters
    ----------
    mu : float
        The friction coefficient, > 0 and at most 1 (PTFE on polished steel: 0.03 to 0.12).
    radius_m : float, optional
        The pendulum's effective radius of curvature, m, > 0: its restoring stiffness is ``W / R``.
        None (the default): a flat slider, with no restoring force.
    damping_n_s_m : float
        A linear dashpot in parallel, N s/m, >= 0 (0: none; a slider's damping is its friction).
    preslip_m : float
        An elastic pre-slip, m, >= 0: the bearing deforms elastically up to ``preslip_m`` before it slips
        (its initial stiffness ``mu W / preslip_m``), as OpenSees' sliders do.  0 (the default): a rigid
        stick, exact.  A bearing in plan (:class:`pounding.Bearing`) needs one: there its friction is the
        friction circle of this yield displacement, elastic-perfectly-plastic or Constantinou's smooth
        Bouc-Wen spring (``Bearing.friction_circle``; :meth:`kernel_arrays_in_plane`).
    weight_n : float, optional
        The weight it carries, N.  None: the weight of the system it isolates, ``g`` times its whole mass
        (the structure's or the single mass's), set when it is put into one (``weight_carried`` then
        True: it follows the system's mass when the system is changed).
    weight_carried : bool
        Whether ``weight_n`` is the system's (set by the system; not written to TOML).
    mu_fast : float, optional
        A velocity-dependent friction (OpenSees' ``VelDependent``): a slip's friction coefficient is
        ``mu_fast - (mu_fast - mu) exp(-rate_s_m |v|)``, ``mu`` at rest (which still decides where a stick
        ends) and ``mu_fast`` fast (> 0, at most 1; larger or smaller than ``mu``).  Its slips are then
        integrated numerically, their ends still located as events.  With a pre-slip a slip starts where
        its force reaches ``mu W`` and its friction is then ``W mu(v)`` at the slip's rate ``v`` (a step
        where it starts fast; OpenSees' sliders let that threshold follow the bearing's velocity instead),
        ``mu W`` again where it ends; in plan the friction circle's (:class:`pounding.Bearing`).  None (the
        default): Coulomb's constant ``mu``.
    rate_s_m : float
        How fast the friction goes from ``mu`` to ``mu_fast``, s/m (> 0 with ``mu_fast``, 0 without; 20 to
        30 are usual for PTFE on steel: within 2 % of ``mu_fast`` from about 0.15 m/s).

    Examples
    --------
    A 20 t building on a friction pendulum of R = 2 m and mu = 0.06 shaken at 0.4 g, 1 Hz (a flat
    slider is the same without ``radius_m``):

    >>> import pounding
    >>> fps = pounding.FrictionIsolator(mu=0.06, radius_m=2.0)
    >>> building = pounding.Structure(8_000.0, fps,
    ...                               [pounding.Storey(12_000.0, 2.0e7, 4.0e4)], [])
    >>> iso = building.isolator  # (it carries the building's weight)
    >>> round(iso.friction_force_n), round(iso.period_s, 2)  # N, s
    (11772, 2.84)
    >>> run = pounding.simulate(building, pounding.Harmonic(a_g=0.4, freq_hz=1.0),
    ...                         duration=6.0)
    >>> f"{run.quantities()['disp_max_m']:.3f} m"
    '0.318 m'
    """

    mu: float
    radius_m: Optional[float] = None
    damping_n_s_m: float = 0.0
    preslip_m: float = 0.0
    weight_n: Optional[float] = None
    weight_carried: bool = False
    mu_fast: Optional[float] = None
    rate_s_m: float = 0.0

    FIELDS: ClassVar[tuple[str, ...]] = ("mu", "radius_m", "damping_n_s_m", "preslip_m", "weight_n",
                                         "mu_fast", "rate_s_m")
    OPTIONAL: ClassVar[tuple[str, ...]] = ("radius_m", "damping_n_s_m", "preslip_m", "weight_n", "mu_fast",
                                           "rate_s_m")
    RENAMED: ClassVar[dict[str, str]] = {}
    bouc_wen: ClassVar[None] = None  # (no Bouc-Wen spring: what readers of any isolator ask)

    def __post_init__(self) -> None:
        mu = positive("isolator.mu", self.mu, "")
        at_most("isolator.mu", mu, MAX_MU, "", "give the friction coefficient (0.05 is 5 %)")
        plausible("isolator.mu", mu, 0.005, 0.3, "a sliding bearing's friction coefficient (usually 0.03 "
                                                 "to 0.12)")
        object.__setattr__(self, "mu", mu)
        if self.radius_m is not None:
            radius = positive("isolator.radius_m", self.radius_m, "m")
            at_most("isolator.radius_m", radius, 1e4, " m", "give the radius in m (None: a flat slider)")
            plausible("isolator.radius_m", radius, 0.5, 10.0, "a friction pendulum's radius in m (1 to 4 "
                                                              "m are usual)")
            object.__setattr__(self, "radius_m", radius)
        damping = non_negative("isolator.damping_n_s_m", self.damping_n_s_m, "N s/m")
        at_most("isolator.damping_n_s_m", damping, MAX_DAMPING_N_S_M, " N s/m", "give the damping in N s/m")
        object.__setattr__(self, "damping_n_s_m", damping)
        preslip = non_negative("isolator.preslip_m", self.preslip_m, "m")
        at_most("isolator.preslip_m", preslip, MAX_BREAKPOINT_M, " m", "give the pre-slip in m")
        plausible("isolator.preslip_m", preslip, 0.0, 0.01, "an elastic pre-slip in m (1 mm is 0.001)")
        object.__setattr__(self, "preslip_m", preslip)
        self._check_velocity_dependence()
        weight = self._check_weight()
        if weight is not None:
            # (the field a stiffness too large is blamed on: the one the user gave beside the weight)
            for name, field, value, k, smallest in (
                    ("the restoring stiffness W / R", "isolator.radius_m", self.radius_m,
                     self.restoring_stiffness_n_m, weight / MAX_STIFFNESS_N_M),
                    ("the pre-slip stiffness mu W / preslip_m", "isolator.preslip_m", self.preslip_m,
                     self._preslip_stiffness(), self.mu * weight / MAX_STIFFNESS_N_M)):
                if math.isfinite(k) and k > MAX_STIFFNESS_N_M:  # (a rigid stick's is inf: no spring)
                    raise InputError(Problem.TOO_SMALL, field, value, minimum=smallest,
                                     hint=f" m under the weight {weight:g} N ({name} would be {k:g} N/m, "
                                          f"beyond {MAX_STIFFNESS_N_M:g})")

    def _check_velocity_dependence(self) -> None:
        rate = non_negative("isolator.rate_s_m", self.rate_s_m, "s/m")
        at_most("isolator.rate_s_m", rate, 1e4, " s/m", "give the rate in s/m (25 s/m: mu_fast reached, "
                                                        "within 2 %, at 0.16 m/s)")
        object.__setattr__(self, "rate_s_m", rate)
        if self.mu_fast is None:
            if rate > 0.0:
                raise InputError(Problem.WRONG_CONFIGURATION, "isolator.rate_s_m", rate,
                                 got="without mu_fast",
                                 fix="give mu_fast (the friction coefficient at high velocity) too, or leave "
                                     "rate_s_m 0 (Coulomb's constant mu)")
            return
        fast = positive("isolator.mu_fast", self.mu_fast, "")
        at_most("isolator.mu_fast", fast, MAX_MU, "", "give the friction coefficient (0.1 is 10 %)")
        plausible("isolator.mu_fast", fast, 0.005, 0.3, "a sliding bearing's friction coefficient at high "
                                                        "velocity (usually 0.05 to 0.15)")
        object.__setattr__(self, "mu_fast", fast)
        if not rate > 0.0:
            raise InputError(Problem.WRONG_CONFIGURATION, "isolator.mu_fast", fast, got="without rate_s_m",
                             fix="give rate_s_m > 0 (s/m: how fast mu goes from mu at rest to mu_fast; 20 to "
                                 "30 are usual), or leave mu_fast out (Coulomb's constant mu)")
        plausible("isolator.rate_s_m", rate, 1.0, 1000.0, "the rate at which friction reaches mu_fast, s/m "
                                                          "(20 to 30 are usual)")

    # ---------------------------------------------------------------- its numbers

    def _preslip_stiffness(self) -> float:
        return self.friction_force_n / self.preslip_m if self.preslip_m > 0.0 else math.inf

    @property
    def friction_force_n(self) -> float:
        """``mu W``, N: the force at which it slips."""
        return self.mu * self._weight()

    @property
    def friction_fast_force_n(self) -> float:
        """``mu_fast W``, N: the friction of a fast slip (``friction_force_n`` without a velocity
        dependence)."""
        return (self.mu if self.mu_fast is None else self.mu_fast) * self._weight()

    def friction_at(self, velocity_m_s: Any) -> np.ndarray:
        """The friction force of a slip at these velocities (m/s, any shape), N, its magnitude:
        ``W (mu_fast - (mu_fast - mu) exp(-rate_s_m |v|))`` (OpenSees' ``VelDependent``), ``mu W`` without
        a velocity dependence."""
        v = np.abs(np.asarray(velocity_m_s, dtype=float))
        if self.mu_fast is None:
            return np.full(v.shape, self.friction_force_n)
        fast = self.friction_fast_force_n
        return fast - (fast - self.friction_force_n) * np.exp(-self.rate_s_m * v)

    @property
    def restoring_stiffness_n_m(self) -> float:
        """``W / R``, N/m (0 for a flat slider)."""
        return self._weight() / self.radius_m if self.radius_m is not None else 0.0

    @property
    def period_s(self) -> float:
        """The sliding period ``2 pi sqrt(R / g)``, s (inf for a flat slider)."""
        if self.radius_m is None:
            return math.inf
        return 2.0 * math.pi * math.sqrt(self.radius_m / GRAVITY_M_S2)

    @property
    def hysteresis(self) -> str:
        """``"friction"`` (a rigid stick), or ``"kinematic"`` with an elastic pre-slip."""
        return "kinematic" if self.preslip_m > 0.0 else "friction"

    @property
    def slopes_n_m(self) -> tuple[float, ...]:
        """Its element's slopes, N/m: ``(W / R,)``; with a pre-slip ``(mu W / preslip_m + W / R, W / R)``."""
        k_r = self.restoring_stiffness_n_m
        return (self._preslip_stiffness() + k_r, k_r) if self.preslip_m > 0.0 else (k_r,)

    @property
    def initial_stiffness_n_m(self) -> float:
        """Its stiffness from rest, N/m: ``mu W / preslip_m + W / R`` (inf for a rigid stick)."""
        return self.slopes_n_m[0] if self.preslip_m > 0.0 else math.inf

    @property
    def breakpoints_m(self) -> tuple[float, ...]:
        """``(preslip_m,)`` with a pre-slip, else ``()``."""
        return (self.preslip_m,) if self.preslip_m > 0.0 else ()

    @property
    def n_branches(self) -> int:
        """Its element's branches: 1, or 2 with a pre-slip."""
        return len(self.slopes_n_m)

    @property
    def yield_forces(self) -> np.ndarray:
        """The force where it slips from rest, N, shape (1,): ``mu W`` (plus ``W / R`` times a pre-slip)."""
        return self.backbone(np.array([self.preslip_m]))

    def backbone(self, displacement: Any) -> np.ndarray:
        """The force of a monotonic slide from rest (N) at displacement(s) in m, any shape: ``W / R D +
        mu W sign(D)`` (with a pre-slip, elastic up to it); odd in the displacement."""
        d = np.asarray(displacement, dtype=float)
        a = np.abs(d)
        f = self.friction_force_n
        if self.preslip_m > 0.0:
            friction = np.minimum(self._preslip_stiffness() * a, f)
        else:
            friction = np.where(a > 0.0, f, 0.0)
        return np.sign(d) * (self.restoring_stiffness_n_m * a + friction)

    def to_dict(self) -> dict[str, Any]:
        """The constructor's fields as plain values, the unset ones left out (the TOML form)."""
        out: dict[str, Any] = {"mu": self.mu}
        if self.radius_m is not None:
            out["radius_m"] = self.radius_m
        out.update(damping_n_s_m=self.damping_n_s_m, preslip_m=self.preslip_m)
        if self.weight_n is not None and not self.weight_carried:
            out["weight_n"] = self.weight_n
        if self.mu_fast is not None:
            out.update(mu_fast=self.mu_fast, rate_s_m=self.rate_s_m)
        return out

    # ---------------------------------------------------------------- the engine's form

    def kernel_arrays(self) -> tuple[np.ndarray, np.ndarray, int, np.ndarray]:
        """``(slopes, breakpoints, rule, bouc_wen)`` as the compiled engine takes them: the friction rule
        (2), or the kinematic rule (0) with a pre-slip; no Bouc-Wen spring (zeros)."""
        rule = RULE_KINEMATIC if self.preslip_m > 0.0 else RULE_FRICTION
        return (np.array(self.slopes_n_m, dtype=float), np.array(self.breakpoints_m, dtype=float), rule,
                np.zeros(BW_PARAMS))

    def kernel_arrays_in_plane(self) -> tuple[np.ndarray, np.ndarray, int, np.ndarray]:
        """``(slopes, breakpoints, rule, bouc_wen)`` of one axis of a bearing in plan with the friction
        circle: the pendulum's ``W / R`` (0 for a flat slider) and a
        Bouc-Wen spring of stiffness ``mu W / preslip_m`` and yield displacement ``preslip_m`` (``a = 1``,
        ``beta = gamma = 1/2``: its force ``mu W z``, ``|z| <= 1``), which the bearing's two axes share
        (Constantinou, Mokha and Reinhorn 1990; the plastic circle takes the same numbers, its ``n`` unused:
        the engine's ``bw_plastic``).  It needs an elastic pre-slip."""
        if not self.preslip_m > 0.0:
            raise InputError(Problem.BAD_STATE, "isolator.preslip_m", self.preslip_m,
                             why="is a rigid stick, which the friction circle in plan cannot have",
                             fix=PRESLIP_IN_PLAN)
        return (np.array([self.restoring_stiffness_n_m]), np.zeros(0), RULE_KINEMATIC,
                self._circle_spring().kernel_array())

    def _circle_spring(self) -> BoucWen:
        return BoucWen(self.friction_force_n / self.preslip_m, self.preslip_m, 1.0, 0.5, 0.5, CIRCLE_N)

    @property
    def kernel_friction_in_plane(self) -> dict[str, float]:
        """A friction circle's velocity dependence as the engine takes it on each axis's element
        (``pounding._core.element``'s ``friction_fast_n``, N, and ``friction_rate_s_m``, s/m: its force
        ``mu W z`` scaled to ``friction_at`` the slip's rate); none without one."""
        if self.mu_fast is None:
            return {}
        # (its fast force on the circle's own force at rest, as the engine has it: mu_fast = mu is 1 exactly)
        at_rest = float(self._circle_spring().kernel_array()[0])
        return {"friction_fast_n": at_rest * (self.mu_fast / self.mu), "friction_rate_s_m": self.rate_s_m}

    @property
    def kernel_friction(self) -> dict[str, float]:
        """The friction the engine's friction rule takes (``pounding._core.element``'s ``friction_n``, N,
        at rest; ``friction_fast_n`` N and ``friction_rate_s_m`` s/m, a velocity dependence's, 0 without):
        with a pre-slip none (the kinematic rule has it in its slopes), or a velocity dependence's three (its
        slips' rest beyond the yield force ``mu W``)."""
        if self.preslip_m > 0.0 and self.mu_fast is None:
            return {}
        if self.mu_fast is None:
            return {"friction_n": self.friction_force_n}
        return {"friction_n": self.friction_force_n, "friction_fast_n": self.friction_fast_force_n,
                "friction_rate_s_m": self.rate_s_m}
