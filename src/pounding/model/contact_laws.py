"""Bumper contact laws: the one place where a law is defined.

A law relates the bumper's compression ``d`` (m, >= 0) and compression rate ``dd`` (m/s)
to the force it pushes with (N).  Bumpers are massless, so out of contact a bumper relaxes
by ``force(d, dd) = 0``; in contact ``d`` follows the mass, and contact ends when the force
would become a pull.  Adding a law means: a frozen dataclass here with a ``LAW_ID``,
``params()``, its ``STATE_CHECK`` (what its block of the state may hold, ``_law_states``) and
``LINEAR`` (whether its force is ``stiffness d + damping dd`` everywhere), a line in :data:`LAWS`;
and its C++ side in ``src/core/laws.cpp`` (its id in ``laws.hpp``'s ``LawId`` and a branch in each
``law_*`` function there, the one place the core tests a law's kind).  Nothing else needs to change.

Laws whose force is linear in ``(d, dd)`` on each branch (:class:`KelvinVoigt`,
:class:`MultilinearBumper`, :class:`ElasticPlastic`) keep every phase of motion a linear ODE,
which the engine solves in closed form; the others are integrated numerically during contact.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields
from collections.abc import Callable
from typing import Any, ClassVar, Optional, Union

import numpy as np

from .._checks import at_most, backbone, instance_of, non_negative, positive, real
from .._errors import InputError, Problem
from . import _law_states
from .._core import LAW_IDS, LAYOUT
from .._core import law_force_many  # noqa: F401  (the core's: a law's forces along a path)
from .rigid_stop import RigidStop, is_rigid, refuse_clamp  # noqa: F401  (what the engine and models ask)

# each law's id, as the core's laws (src/core/laws.cpp, the law's C++ side) know it
KELVIN_VOIGT, HUNT_CROSSLEY, JANKOWSKI, MULTILINEAR, ELASTIC_PLASTIC, HERTZDAMP, MULTILINEAR_KINEMATIC = (
    LAW_IDS[k] for k in ("kelvin_voigt", "hunt_crossley", "jankowski", "multilinear", "elastic_plastic",
                         "hertzdamp", "multilinear_kinematic"))
N_LAW_PARAMS = LAYOUT["N_LAW_PARAMS"]  # a law's parameters as the core reads them
N_LAW_STATE = LAYOUT["N_LAW_STATE"]    # the numbers of its state in the engine's state vector
MAX_BRANCHES = 4  # slopes of a multi-linear law (its parameters hold 4 slopes and 3 breakpoints)

MAX_LAW_COEFFICIENT = 1e18  # stiffness or damping beyond any bumper (N/m^n, N s/m^(n+1)): refused
MAX_EXPONENT = 10.0
MAX_DAMPING_RATIO = 100.0  # Jankowski's xi: 10 already gives a restitution of about 0.03


def _coefficient(field: str, value: Any, unit: str, strict: bool) -> float:
    out = positive(field, value, unit) if strict else non_negative(field, value, unit)
    return at_most(field, out, MAX_LAW_COEFFICIENT, f" {unit}", f"give it in {unit}")


def _padded(values: list[float]) -> np.ndarray:
    """A law's parameters as the compiled kernels take them, shape (N_LAW_PARAMS,)."""
    out = np.zeros(N_LAW_PARAMS)
    out[: len(values)] = values
    return out


def _exponent(value: Any) -> float:
    exponent = real("law.exponent", value)
    if not 1.0 <= exponent <= MAX_EXPONENT:
        raise InputError(Problem.OUT_OF_RANGE, "law.exponent", value,
                         range=f"[1, {MAX_EXPONENT:g}]", hint=" (1.5 is Hertzian contact)")
    return exponent


@dataclass(frozen=True)
class KelvinVoigt:
    """Linear spring in parallel with a linear dashpot (the paper's bumper).

    Force ``F = stiffness * d + damping * dd`` for compression ``d >= 0``.  Out of contact
    the bumper relaxes as ``d(t) = d0 exp(-t stiffness / damping)``.

    Parameters
    ----------
    stiffness : float
        Spring constant ``K_b`` in N/m, > 0.
    damping : float
        Dashpot constant ``C_b`` in N s/m, >= 0 (0: the bumper recovers instantly).

    Examples
    --------
    The paper's EPDM bumpers (Sect. 5): nearly elastic impacts, hit first at 0.6 m/s:

    >>> import pounding
    >>> epdm = pounding.KelvinVoigt(stiffness=1.46e6, damping=5.0)
    >>> f"{epdm.relaxation_time_s:.2e} s"
    '3.42e-06 s'
    >>> osc = pounding.Oscillator(500.0, pounding.presets.paper_damped().isolator,
    ...                           pounding.Bumpers(0.015, 0.015, epdm))
    >>> push = pounding.State.at_rest(osc, velocity_m_s=0.6)
    >>> run = pounding.simulate(osc, pounding.Harmonic(a_g=0.05, freq_hz=2.2),
    ...                         duration=0.5, state=push)
    >>> run.impacts["restitution"].round(2).tolist()
    [0.95, 0.95, 0.93, 0.93]
    """

    stiffness: float
    damping: float = 0.0

    TYPE: ClassVar[str] = "kelvin_voigt"
    # what the engine asks of the law (model/_law_states.py): its state check, and whether its force
    # is stiffness d + damping dd at every compression (the exact monodromy and the rate bound need it)
    STATE_CHECK: ClassVar[Callable] = staticmethod(_law_states.stateless)
    LINEAR: ClassVar[bool] = True
    LAW_ID: ClassVar[int] = KELVIN_VOIGT

    def __post_init__(self) -> None:
        object.__setattr__(self, "stiffness", _coefficient("law.stiffness", self.stiffness, "N/m", True))
        object.__setattr__(self, "damping", _coefficient("law.damping", self.damping, "N s/m", False))

    def params(self) -> np.ndarray:
        """Parameters as the compiled kernels take them, shape (N_LAW_PARAMS,)."""
        return _padded([self.stiffness, self.damping])

    @property
    def relaxation_time_s(self) -> float:
        """Time constant ``C_b / K_b`` of the free recovery, s."""
        return self.damping / self.stiffness


@dataclass(frozen=True)
class HuntCrossley:
    """Hunt-Crossley law: ``F = stiffness * d**exponent + damping * d**exponent * dd``.

    The dashpot grows with the indentation, so the force starts at zero on contact and
    the contact dissipates more at higher impact velocity.  Out of contact the massless
    bumper recovers at the constant rate ``stiffness / damping`` (m/s).

    Parameters
    ----------
    stiffness : float
        ``k`` in N/m**exponent, > 0.
    exponent : float
        ``n`` >= 1 (1.5: Hertz contact).
    damping : float
        ``c`` in N s/m**(exponent + 1), >= 0.

    Examples
    --------
    Hertzian bumpers in place of the paper's, hit first at 0.6 m/s: the slower the impact, the
    less it dissipates (the restitution rises as the impacts weaken):

    >>> import pounding
    >>> law = pounding.HuntCrossley(stiffness=1.46e7, exponent=1.5, damping=2.0e7)
    >>> osc = pounding.Oscillator(500.0, pounding.presets.paper_damped().isolator,
    ...                           pounding.Bumpers(0.015, 0.015, law))
    >>> push = pounding.State.at_rest(osc, velocity_m_s=0.6)
    >>> run = pounding.simulate(osc, pounding.Harmonic(a_g=0.05, freq_hz=2.2),
    ...                         duration=0.5, state=push)
    >>> run.impacts["restitution"].round(2).tolist()
    [0.66, 0.77, 0.84]
    """

    stiffness: float
    exponent: float = 1.5
    damping: float = 0.0

    TYPE: ClassVar[str] = "hunt_crossley"
    STATE_CHECK: ClassVar[Callable] = staticmethod(_law_states.stateless)
    LINEAR: ClassVar[bool] = False
    LAW_ID: ClassVar[int] = HUNT_CROSSLEY

    def __post_init__(self) -> None:
        object.__setattr__(self, "stiffness", _coefficient("law.stiffness", self.stiffness, "N/m^n", True))
        object.__setattr__(self, "exponent", _exponent(self.exponent))
        object.__setattr__(self, "damping", _coefficient("law.damping", self.damping, "N s/m^(n+1)", False))

    def params(self) -> np.ndarray:
        """Parameters as the compiled kernels take them, shape (N_LAW_PARAMS,)."""
        return _padded([self.stiffness, self.damping, self.exponent])


@dataclass(frozen=True)
class Jankowski:
    """Jankowski's nonlinear viscoelastic impact law (OpenSees' ``JankowskiImpact``).

    ``F = stiffness * d**exponent + c(d) * dd`` while the bumper is compressed further
    (``dd > 0``, the approach) and ``F = stiffness * d**exponent`` while it recovers: the
    dashpot ``c(d) = 2 damping_ratio sqrt(effective_mass * stiffness * d**(exponent - 1))``
    works on the approach only, so the force never pulls and the contact ends when the
    compression is back to zero.  Out of contact the massless bumper recovers at once.

    Parameters
    ----------
    stiffness : float
        ``k_h`` in N/m**exponent, > 0.
    damping_ratio : float
        ``xi`` >= 0; :meth:`from_restitution` gives the one of a target restitution.
    effective_mass : float
        ``m1 m2 / (m1 + m2)`` in kg, > 0: the impacting mass ``M`` for a bumper on a rigid stand.
    exponent : float
        ``n`` in [1, 10] (1.5: Hertz contact, Jankowski's choice).

    Notes
    -----
    R. Jankowski, Earthquake Engng Struct. Dyn. 34 (2005) 595-611 and 35 (2006) 517-524.

    Examples
    --------
    Bumpers meant to give a restitution of 0.7 to the 500 kg mass, hit first at 0.6 m/s: the
    restitution stays near 0.7 as the impacts weaken (the isolator's forces make it differ a little):

    >>> import pounding
    >>> law = pounding.Jankowski.from_restitution(stiffness=1.46e7, restitution=0.7,
    ...                                           effective_mass=500.0)
    >>> round(law.damping_ratio, 3)
    0.298
    >>> osc = pounding.Oscillator(500.0, pounding.presets.paper_damped().isolator,
    ...                           pounding.Bumpers(0.015, 0.015, law))
    >>> push = pounding.State.at_rest(osc, velocity_m_s=0.6)
    >>> run = pounding.simulate(osc, pounding.Harmonic(a_g=0.05, freq_hz=2.2),
    ...                         duration=0.5, state=push)
    >>> run.impacts["restitution"].round(2).tolist()
    [0.68, 0.69, 0.71]
    """

    stiffness: float
    damping_ratio: float
    effective_mass: float
    exponent: float = 1.5

    TYPE: ClassVar[str] = "jankowski"
    STATE_CHECK: ClassVar[Callable] = staticmethod(_law_states.stateless)
    LINEAR: ClassVar[bool] = False
    LAW_ID: ClassVar[int] = JANKOWSKI

    def __post_init__(self) -> None:
        object.__setattr__(self, "stiffness", _coefficient("law.stiffness", self.stiffness, "N/m^n", True))
        object.__setattr__(self, "exponent", _exponent(self.exponent))
        ratio = non_negative("law.damping_ratio", self.damping_ratio, "(a ratio)")
        ratio = at_most("law.damping_ratio", ratio, MAX_DAMPING_RATIO, "",
                        "xi is a ratio: 0.35 gives a restitution of about 0.65")
        object.__setattr__(self, "damping_ratio", ratio)
        mass = positive("law.effective_mass", self.effective_mass, "kg")
        mass = at_most("law.effective_mass", mass, MAX_LAW_COEFFICIENT, " kg", "give it in kg")
        object.__setattr__(self, "effective_mass", mass)

    @classmethod
    def from_restitution(cls, stiffness: float, restitution: float, effective_mass: float,
                         exponent: float = 1.5) -> Jankowski:
        """The law whose damping ratio gives restitution ``e`` in (0, 1] (Jankowski 2006):
        ``xi = 9 sqrt(5) / 2 * (1 - e^2) / (e (e (9 pi - 16) + 16))``."""
        e = real("restitution", restitution)
        if not 0.0 < e <= 1.0:
            raise InputError(Problem.OUT_OF_RANGE, "restitution", restitution, range="(0, 1]",
                             hint=" (1: no loss)")
        xi = 4.5 * math.sqrt(5.0) * (1.0 - e * e) / (e * (e * (9.0 * math.pi - 16.0) + 16.0))
        return cls(stiffness, xi, effective_mass, exponent)

    def params(self) -> np.ndarray:
        """Parameters as the compiled kernels take them, shape (N_LAW_PARAMS,): stiffness, the
        dashpot's factor ``2 xi sqrt(m_eff k)``, the exponent."""
        c0 = 2.0 * self.damping_ratio * math.sqrt(self.effective_mass * self.stiffness)
        return _padded([self.stiffness, c0, self.exponent])


@dataclass(frozen=True)
class MultilinearBumper:
    """A bumper whose spring is multi-linear in compression, with a dashpot in parallel.

    ``F = R(d) + damping * dd`` while loaded from the unloaded state: the backbone ``R`` has
    slope ``slopes[j]`` between ``breakpoints[j - 1]`` and ``breakpoints[j]`` (from 0, on to any
    depth).  The paper's D-shaped hollow EPDM bumper (Fig. 3): an initial branch, a soft one
    (even flat) while the hole collapses, a steep one once it has closed.  Piecewise linear, so
    every phase of motion stays closed-form, as with :class:`KelvinVoigt` (one slope is exactly
    Kelvin-Voigt, with either hysteresis).

    ``hysteresis="elastic"``: unloading follows the backbone back.  ``"kinematic"``: Masing's
    rule, as the kinematic isolator has it: each softening of the backbone (a slope lower than the
    one before) is a spring that slips once strained by its breakpoint (Iwan's parallel springs),
    so the bumper unloads along the backbone turned over at twice the scale from the turning
    point, and reloads likewise (a backbone that only softens: exactly); each hardening (a
    steeper slope, the closed hole) is an elastic ramp added to that, without a loop.
    A loop dissipates nothing while its springs stay elastic (an impact that compresses an
    unloaded bumper less than its first softening breakpoint is elastic but for the dashpot; a
    loop from a turning point, less than twice that) and more the deeper it goes: restitution
    falls and contacts lengthen with the impact velocity.  The
    springs keep their slips between contacts, so a bumper unloaded from its soft branch keeps a
    set (its springs' forces cancel above zero compression) and the next contact reloads it from
    there.  It needs ``slopes[0]`` at least the sum of the softening steps (else the unloaded
    bumper would pull).

    Out of contact the massless bumper recovers by ``damping * dd = -F(d)``, piece by piece in
    closed form (with no dashpot, at once).

    Parameters
    ----------
    slopes : sequence of float, shape (n,)
        ``n`` from 1 to 4 slopes, N/m: the first > 0, the others >= 0.
    breakpoints : sequence of float, shape (n - 1,)
        Compressions where the slope changes, m, > 0 and increasing.
    damping : float
        Dashpot constant in N s/m, >= 0 (0: the bumper recovers instantly).
    hysteresis : {"elastic", "kinematic"}
        How the bumper unloads (above).

    Examples
    --------
    A D-shaped hollow bumper: stiff at first, soft from 4 mm while the hole collapses, steep from
    12 mm once it has closed; with Masing hysteresis it keeps a set after a deep impact:

    >>> import pounding
    >>> law = pounding.MultilinearBumper(slopes=[4.0e5, 5.0e4, 2.0e6],
    ...                                  breakpoints=[0.004, 0.012],
    ...                                  damping=200.0, hysteresis="kinematic")
    >>> law.backbone([0.002, 0.008, 0.015]).round(1).tolist()  # N
    [800.0, 1800.0, 8000.0]
    >>> osc = pounding.Oscillator(500.0, pounding.presets.paper_damped().isolator,
    ...                           pounding.Bumpers(0.015, 0.015, law))
    >>> push = pounding.State.at_rest(osc, velocity_m_s=0.6)
    >>> run = pounding.simulate(osc, pounding.Harmonic(a_g=0.05, freq_hz=2.2),
    ...                         duration=0.5, state=push)
    >>> round(float(run.impacts["restitution"][0]), 2)
    0.67
    >>> # sets, mm (left, right)
    >>> [round(1e3 * d, 1) for d in run.final_state.bumper_compression_m]
    [5.9, 11.4]
    """

    slopes: tuple[float, ...]
    breakpoints: tuple[float, ...] = ()
    damping: float = 0.0
    hysteresis: str = "elastic"

    TYPE: ClassVar[str] = "multilinear"
    STATE_CHECK: ClassVar[Callable] = staticmethod(_law_states.multilinear)
    LINEAR: ClassVar[bool] = False
    HYSTERESIS: ClassVar[tuple[str, ...]] = ("elastic", "kinematic")
    OPTIONAL_KEYS: ClassVar[tuple[str, ...]] = ("hysteresis",)  # (files from before it was: elastic)

    def __post_init__(self) -> None:
        slopes, breakpoints = backbone("law", self.slopes, self.breakpoints, MAX_LAW_COEFFICIENT, " N/m",
                                       "give the slopes in N/m", 10.0,
                                       "give the breakpoints in m (5 mm is 0.005)")
        if len(slopes) > MAX_BRANCHES:
            raise InputError(Problem.OUT_OF_RANGE, "law.slopes", list(slopes),
                             range=f"1 to {MAX_BRANCHES} slopes", hint=" (one per branch of the backbone)")
        object.__setattr__(self, "slopes", slopes)
        object.__setattr__(self, "breakpoints", breakpoints)
        object.__setattr__(self, "damping", _coefficient("law.damping", self.damping, "N s/m", False))
        if self.hysteresis not in self.HYSTERESIS:
            raise InputError(Problem.NOT_ONE_OF, "law.hysteresis", self.hysteresis,
                             choices=", ".join(map(repr, self.HYSTERESIS)))
        if self.hysteresis == "kinematic":
            softening = sum(max(a - b, 0.0) for a, b in zip(slopes[:-1], slopes[1:]))
            if softening > slopes[0] * (1.0 + 1e-12):
                raise InputError(Problem.OUT_OF_RANGE, "law.slopes", list(slopes),
                                 range=f"a first slope of at least the softening steps' sum "
                                       f"{softening:g} N/m",
                                 hint=" (kinematic hysteresis: every softening is a spring that slips, in "
                                      "parallel with what is left of the first slope; soften once, or use "
                                      "hysteresis='elastic')")

    @property
    def LAW_ID(self) -> int:  # noqa: N802  (the name every law's id has)
        """The compiled kernels' id: the elastic or the kinematic multi-linear law."""
        return MULTILINEAR_KINEMATIC if self.hysteresis == "kinematic" else MULTILINEAR

    def params(self) -> np.ndarray:
        """Parameters as the compiled kernels take them, shape (N_LAW_PARAMS,): damping, the
        number of slopes, the slopes (4 places), the breakpoints (3 places)."""
        out = _padded([self.damping, float(len(self.slopes))])
        out[2:2 + len(self.slopes)] = self.slopes
        out[6:6 + len(self.breakpoints)] = self.breakpoints
        return out

    def backbone(self, compression_m: Any) -> np.ndarray:
        """``R(d)`` in N at compressions ``d`` (m, >= 0), shape as given."""
        d = np.asarray(compression_m, dtype=float)
        edges = np.concatenate([[0.0], self.breakpoints])
        forces = np.concatenate([[0.0], np.cumsum(np.diff(edges) * np.array(self.slopes[:-1]))])
        j = np.clip(np.searchsorted(edges, d, side="right") - 1, 0, len(self.slopes) - 1)
        return forces[j] + np.array(self.slopes)[j] * (d - edges[j])


@dataclass(frozen=True)
class ElasticPlastic:
    """An elastic-plastic impact law: yield in compression, stiffer elastic unloading
    (the bilinear law of OpenSees' ``ImpactMaterial``, Muthukumar and DesRoches 2006).

    The force starts along ``stiffness * d``; past ``yield_compression`` it follows the yield
    line ``stiffness * dy + post_yield_stiffness * (d - dy)``; it unloads with ``stiffness``
    down to the line ``post_yield_stiffness * d`` and along that back to zero.  Between the two
    lines it moves elastically, ``stiffness * (d - z)`` with ``z`` the plastic offset.  So an
    impact below the yield velocity ``dy sqrt(stiffness / M)`` is elastic (restitution 1); one
    above it lasts the longer the faster it comes, and its restitution falls to a least value
    and then rises slowly back towards 1 (the yield line dissipates ``(K1 - K2) dy`` per metre
    of compression, while the energy brought grows as the square of the velocity: for
    ``K2 = K1 / 20``, 0.48 at 3 yield velocities, 0.67 at 10, 0.92 at 50; :meth:`restitution`).  No dashpot:
    the force is rate-independent, never pulls, and the
    contact ends when the compression is back to zero; out of contact the bumper is unloaded
    (the next contact starts from ``z = 0``).  Piecewise linear, so every phase of motion stays
    closed-form.

    Parameters
    ----------
    stiffness : float
        ``K1``, the elastic (initial and unloading) stiffness, N/m, > 0.
    post_yield_stiffness : float
        ``K2``, N/m, with 0 < ``K2`` < ``K1``.
    yield_compression : float
        ``delta_y``, the compression where it first yields, m, > 0.

    Examples
    --------
    A bumper that yields at 2 mm, ``K2 = K1 / 20``: the restitution of the 500 kg mass hitting it
    at 0.05 (below the yield velocity), 0.3 and 1.0 m/s:

    >>> import pounding
    >>> law = pounding.ElasticPlastic(stiffness=2.0e6, post_yield_stiffness=1.0e5,
    ...                               yield_compression=0.002)
    >>> round(law.yield_velocity_m_s(500.0), 3)  # m/s
    0.126
    >>> law.restitution(500.0, [0.05, 0.3, 1.0]).round(2).tolist()
    [1.0, 0.51, 0.62]
    """

    stiffness: float
    post_yield_stiffness: float
    yield_compression: float

    TYPE: ClassVar[str] = "elastic_plastic"
    STATE_CHECK: ClassVar[Callable] = staticmethod(_law_states.elastic_plastic)
    LINEAR: ClassVar[bool] = False
    LAW_ID: ClassVar[int] = ELASTIC_PLASTIC

    def __post_init__(self) -> None:
        k1 = _coefficient("law.stiffness", self.stiffness, "N/m", True)
        k2 = _coefficient("law.post_yield_stiffness", self.post_yield_stiffness, "N/m", True)
        if not k2 < k1:
            raise InputError(Problem.OUT_OF_RANGE, "law.post_yield_stiffness", self.post_yield_stiffness,
                             range=f"(0, {k1:g}) N/m",
                             hint=" (below the elastic stiffness: the yield line is the softer one)")
        dy = positive("law.yield_compression", self.yield_compression, "m")
        dy = at_most("law.yield_compression", dy, 10.0, " m", "give it in m (2 mm is 0.002)")
        object.__setattr__(self, "stiffness", k1)
        object.__setattr__(self, "post_yield_stiffness", k2)
        object.__setattr__(self, "yield_compression", dy)

    def params(self) -> np.ndarray:
        """Parameters as the compiled kernels take them, shape (N_LAW_PARAMS,): K1, K2, delta_y."""
        return _padded([self.stiffness, self.post_yield_stiffness, self.yield_compression])

    def yield_velocity_m_s(self, mass_kg: float) -> float:
        """Impact velocity (m/s) of a free mass ``mass_kg`` below which the contact is elastic."""
        return self.yield_compression * math.sqrt(self.stiffness / positive("mass_kg", mass_kg, "kg"))

    def restitution(self, mass_kg: float, velocity_m_s: Any) -> np.ndarray:
        """Coefficient of restitution of a free mass hitting the bumper at ``velocity_m_s``
        (m/s, >= 0, any shape): 1 below the yield velocity, then
        ``sqrt(E_back / (M v^2 / 2))`` with ``E_back`` the elastic energy at the deepest compression."""
        m = positive("mass_kg", mass_kg, "kg")
        try:
            v = np.asarray(velocity_m_s, dtype=float)
        except (TypeError, ValueError):
            raise InputError(Problem.NOT_A_NUMBER, "velocity_m_s", velocity_m_s) from None
        bad = ~np.isfinite(v) | (v < 0.0)
        if bad.any():
            first = float(v[bad][0]) if v.ndim else float(v)
            if not np.isfinite(first):
                raise InputError(Problem.NOT_FINITE, "velocity_m_s", first)
            raise InputError(Problem.NEGATIVE, "velocity_m_s", first, unit="m/s (an impact speed)")
        k1, k2, dy = self.stiffness, self.post_yield_stiffness, self.yield_compression
        energy = 0.5 * m * v * v
        # deepest compression: 1/2 k1 dy^2 + k1 dy s + 1/2 k2 s^2 = energy, s = d_max - dy >= 0
        e_y = 0.5 * k1 * dy * dy
        s = np.where(energy > e_y, (-k1 * dy + np.sqrt((k1 * dy) ** 2 + 2.0 * k2 * np.maximum(energy - e_y,
                                                                                              0.0)))
                     / k2, 0.0)
        f = k1 * dy + k2 * s
        dp = (k1 - k2) * s / k1
        back = 0.5 * f * f / k1 + 0.5 * k1 * k2 * dp * dp / (k1 - k2)
        with np.errstate(invalid="ignore", divide="ignore"):
            return np.where(energy > e_y, np.sqrt(back / np.where(energy > 0, energy, 1.0)), 1.0)


@dataclass(frozen=True)
class Hertzdamp:
    """Hertz contact with damping set by each impact's velocity (OpenSees' ``Hertzdamp``).

    ``F = (stiffness + xi * dd) * d**exponent`` with ``xi = xi_norm * stiffness / v_in``, ``v_in``
    the compression rate when the contact starts: a Hunt-Crossley law whose damping is chosen
    anew at every impact, so that the restitution hardly depends on the impact velocity
    (Ye, Li and Zhu 2009: ``xi_norm = 8 (1 - e) / (5 e)``, :meth:`from_restitution`).  A contact
    met at rest has ``xi = 0``.  Unlike OpenSees' material, which pulls until the gap reopens and
    then resets, the contact ends when the force would pull, as for every law here; out of
    contact the bumper recovers at ``stiffness / xi`` m/s (as Hunt-Crossley's, with its last ``xi``).

    Parameters
    ----------
    stiffness : float
        ``K_h`` in N/m**exponent, > 0.
    xi_norm : float
        The normalised damping, >= 0 (0: elastic).
    exponent : float
        ``n`` in [1, 10] (1.5: Hertz contact, the default).

    Examples
    --------
    Bumpers meant to give a restitution of 0.7, hit first at 0.6 m/s by the 500 kg mass:

    >>> import pounding
    >>> law = pounding.Hertzdamp.from_restitution(stiffness=1.46e7, restitution=0.7)
    >>> round(law.xi_norm, 3)
    0.686
    >>> osc = pounding.Oscillator(500.0, pounding.presets.paper_damped().isolator,
    ...                           pounding.Bumpers(0.015, 0.015, law))
    >>> push = pounding.State.at_rest(osc, velocity_m_s=0.6)
    >>> run = pounding.simulate(osc, pounding.Harmonic(a_g=0.05, freq_hz=2.2),
    ...                         duration=0.5, state=push)
    >>> run.impacts["restitution"].round(2).tolist()
    [0.68, 0.69, 0.73]
    """

    stiffness: float
    xi_norm: float
    exponent: float = 1.5

    TYPE: ClassVar[str] = "hertzdamp"
    STATE_CHECK: ClassVar[Callable] = staticmethod(_law_states.hertzdamp)
    LINEAR: ClassVar[bool] = False
    LAW_ID: ClassVar[int] = HERTZDAMP

    def __post_init__(self) -> None:
        object.__setattr__(self, "stiffness", _coefficient("law.stiffness", self.stiffness, "N/m^n", True))
        xi = non_negative("law.xi_norm", self.xi_norm, "(a ratio)")
        xi = at_most("law.xi_norm", xi, MAX_DAMPING_RATIO, "",
                     "xi_norm is a ratio: 0.3 gives a restitution of about 0.84")
        object.__setattr__(self, "xi_norm", xi)
        object.__setattr__(self, "exponent", _exponent(self.exponent))

    @classmethod
    def from_restitution(cls, stiffness: float, restitution: float, exponent: float = 1.5) -> Hertzdamp:
        """The law of Ye et al.'s estimate for restitution ``e`` in (0, 1]:
        ``xi_norm = 8 (1 - e) / (5 e)``."""
        e = real("restitution", restitution)
        least = 1.6 / (1.6 + MAX_DAMPING_RATIO)  # (xi_norm at most MAX_DAMPING_RATIO)
        if not least <= e <= 1.0:
            raise InputError(Problem.OUT_OF_RANGE, "restitution", restitution, range=f"[{least:.3g}, 1]",
                             hint=" (1: no loss)")
        return cls(stiffness, 1.6 * (1.0 - e) / e, exponent)

    def params(self) -> np.ndarray:
        """Parameters as the compiled kernels take them, shape (N_LAW_PARAMS,): stiffness, xi_norm,
        the exponent (the damping itself is the bumper's state, set at each contact's start)."""
        return _padded([self.stiffness, self.xi_norm, self.exponent])


def linear_form(law: Any) -> Optional[tuple[float, float]]:
    """``(stiffness N/m, damping N s/m)`` of a law whose force is ``stiffness d + damping dd`` at
    every compression (its ``LINEAR``), else None."""
    return (law.stiffness, law.damping) if law.LINEAR else None


ContactLaw = Union[KelvinVoigt, HuntCrossley, Jankowski, MultilinearBumper, ElasticPlastic, Hertzdamp,
                   RigidStop]
LAWS: dict[str, type] = {KelvinVoigt.TYPE: KelvinVoigt, HuntCrossley.TYPE: HuntCrossley,
                         Jankowski.TYPE: Jankowski, MultilinearBumper.TYPE: MultilinearBumper,
                         ElasticPlastic.TYPE: ElasticPlastic, Hertzdamp.TYPE: Hertzdamp,
                         RigidStop.TYPE: RigidStop}


def law_to_dict(law: ContactLaw) -> dict[str, Any]:
    """The law as a TOML-ready table: ``type`` plus its fields."""
    out: dict[str, Any] = {"type": law.TYPE}
    for f in fields(law):
        value = getattr(law, f.name)
        out[f.name] = list(value) if isinstance(value, tuple) else value
    return out


def law_from_dict(table: dict[str, Any], field: str) -> ContactLaw:
    """Build a law from a TOML table with a ``type`` key; unknown and missing keys are errors.

    Every field of the law must be given, defaults included: a table whose ``type`` was
    changed would otherwise be read with the new law's defaults filling what it lacks.  (But a
    multi-linear law's ``hysteresis``, added later, which files written before it lack.)
    """
    instance_of(field, table, dict, "table")
    kind = table.get("type")
    if kind not in LAWS:
        raise InputError(Problem.NOT_ONE_OF, f"{field}.type", kind, choices=", ".join(map(repr, LAWS)))
    cls = LAWS[kind]
    allowed = {f.name for f in fields(cls)}
    required = [f.name for f in fields(cls) if f.name not in getattr(cls, "OPTIONAL_KEYS", ())]
    for key in table:
        if key != "type" and key not in allowed:
            raise InputError(Problem.UNKNOWN_KEY, f"{field}.{key}", table[key],
                             choices=", ".join(sorted(allowed | {"type"})))
    for key in required:
        if key not in table:
            raise InputError(Problem.MISSING_KEY, f"{field}.{key}", None,
                             choices=", ".join(sorted(allowed)) + f" (a {kind} law needs every one of them)")
    try:
        return cls(**{k: v for k, v in table.items() if k != "type"})
    except InputError as exc:  # name the field by its place in the file
        raise exc.relabel("law", field) from None


def check_law(field: str, value: Any) -> None:
    """Refuse anything but a contact law for ``field`` (``bumpers.law``, ``wall.law_right``)."""
    instance_of(field, value, tuple(LAWS.values()),
                "contact law (" + ", ".join(cls.__name__ for cls in LAWS.values()) + ")")
