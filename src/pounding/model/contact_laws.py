"""Bumper contact laws: the one place where a law is defined.

A law relates the bumper's compression ``d`` (m, >= 0) and compression rate ``dd`` (m/s)
to the force it pushes with (N).  Bumpers are massless, so out of contact a bumper relaxes
by ``force(d, dd) = 0``; in contact ``d`` follows the mass, and contact ends when the force
would become a pull.  Adding a law means: a frozen dataclass here with a ``LAW_ID`` and
``params()``, a line in :data:`LAWS`, and a branch in each compiled ``law_*`` function below.
Nothing else in the package needs to change.

Laws whose force is linear in ``(d, dd)`` (:class:`KelvinVoigt`) keep every phase of motion
a linear ODE, which the engine solves in closed form; the others are integrated numerically
during contact.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields
from typing import Any, ClassVar, Union

import numpy as np

from .._checks import at_most, non_negative, positive, real
from .._errors import InputError, Problem
from .._jit import jit, jit_entry

KELVIN_VOIGT = 0
HUNT_CROSSLEY = 1
JANKOWSKI = 2
N_LAW_PARAMS = 4
MIN_NORMAL = 2.2250738585072014e-308  # the smallest normal double
EXP_NORMAL_LIMIT = 708.39  # exp(-x) is below it for larger x
# The compiled ``law_*`` functions read a law's parameters at ``p[o:o + N_LAW_PARAMS]``
# (``o`` an offset, so that the engine passes its phase record without slicing it: a
# slice costs a reference-count increment and decrement on every call).
AT_START = np.int64(0)  # the offset of a bare parameter array (typed: see engine/_layout.py)
MAX_LAW_COEFFICIENT = 1e18  # stiffness or damping beyond any bumper (N/m^n, N s/m^(n+1)): refused
MAX_EXPONENT = 10.0
MAX_DAMPING_RATIO = 100.0  # Jankowski's xi: 10 already gives a restitution of about 0.03


def _coefficient(field: str, value: Any, unit: str, strict: bool) -> float:
    out = positive(field, value, unit) if strict else non_negative(field, value, unit)
    return at_most(field, out, MAX_LAW_COEFFICIENT, f" {unit}", f"give it in {unit}")


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
    """

    stiffness: float
    damping: float = 0.0

    TYPE: ClassVar[str] = "kelvin_voigt"
    LAW_ID: ClassVar[int] = KELVIN_VOIGT

    def __post_init__(self) -> None:
        object.__setattr__(self, "stiffness", _coefficient("law.stiffness", self.stiffness, "N/m", True))
        object.__setattr__(self, "damping", _coefficient("law.damping", self.damping, "N s/m", False))

    def params(self) -> np.ndarray:
        """Parameters as the compiled kernels take them, shape (4,)."""
        return np.array([self.stiffness, self.damping, 0.0, 0.0])

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
    """

    stiffness: float
    exponent: float = 1.5
    damping: float = 0.0

    TYPE: ClassVar[str] = "hunt_crossley"
    LAW_ID: ClassVar[int] = HUNT_CROSSLEY

    def __post_init__(self) -> None:
        object.__setattr__(self, "stiffness", _coefficient("law.stiffness", self.stiffness, "N/m^n", True))
        object.__setattr__(self, "exponent", _exponent(self.exponent))
        object.__setattr__(self, "damping", _coefficient("law.damping", self.damping, "N s/m^(n+1)", False))

    def params(self) -> np.ndarray:
        """Parameters as the compiled kernels take them, shape (4,)."""
        return np.array([self.stiffness, self.damping, self.exponent, 0.0])


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
    """

    stiffness: float
    damping_ratio: float
    effective_mass: float
    exponent: float = 1.5

    TYPE: ClassVar[str] = "jankowski"
    LAW_ID: ClassVar[int] = JANKOWSKI

    def __post_init__(self) -> None:
        object.__setattr__(self, "stiffness", _coefficient("law.stiffness", self.stiffness, "N/m^n", True))
        object.__setattr__(self, "exponent", _exponent(self.exponent))
        ratio = non_negative("law.damping_ratio", self.damping_ratio, "(a ratio)")
        object.__setattr__(self, "damping_ratio", at_most("law.damping_ratio", ratio, MAX_DAMPING_RATIO, "",
                                                          "xi is a ratio: 0.35 gives a restitution of about 0.65"))
        mass = positive("law.effective_mass", self.effective_mass, "kg")
        object.__setattr__(self, "effective_mass", at_most("law.effective_mass", mass, MAX_LAW_COEFFICIENT, " kg",
                                                           "give it in kg"))

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
        """Parameters as the compiled kernels take them, shape (4,): stiffness, the dashpot's
        factor ``2 xi sqrt(m_eff k)``, the exponent."""
        c0 = 2.0 * self.damping_ratio * math.sqrt(self.effective_mass * self.stiffness)
        return np.array([self.stiffness, c0, self.exponent, 0.0])


ContactLaw = Union[KelvinVoigt, HuntCrossley, Jankowski]
LAWS: dict[str, type] = {KelvinVoigt.TYPE: KelvinVoigt, HuntCrossley.TYPE: HuntCrossley,
                         Jankowski.TYPE: Jankowski}


def law_to_dict(law: ContactLaw) -> dict[str, Any]:
    """The law as a TOML-ready table: ``type`` plus its fields."""
    out: dict[str, Any] = {"type": law.TYPE}
    out.update({f.name: getattr(law, f.name) for f in fields(law)})
    return out


def law_from_dict(table: dict[str, Any], field: str) -> ContactLaw:
    """Build a law from a TOML table with a ``type`` key; unknown and missing keys are errors.

    Every field of the law must be given, defaults included: a table whose ``type`` was
    changed would otherwise be read with the new law's defaults filling what it lacks.
    """
    if not isinstance(table, dict):
        raise InputError(Problem.WRONG_TYPE, field, table, got=type(table).__name__, expected="table")
    kind = table.get("type")
    if kind not in LAWS:
        raise InputError(Problem.NOT_ONE_OF, f"{field}.type", kind, choices=", ".join(map(repr, LAWS)))
    cls = LAWS[kind]
    allowed = {f.name for f in fields(cls)}
    required = [f.name for f in fields(cls)]
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


# --------------------------------------------------------------------------- compiled side
@jit
def law_is_linear(law):
    """True when the force is linear in (d, dd): every phase stays a linear ODE."""
    return law == KELVIN_VOIGT


@jit
def law_switches_at_rest(law):
    """True when the force changes form where the compression rate changes sign (Jankowski's
    dashpot works on the approach only): the engine ends a numerical step there."""
    return law == JANKOWSKI


@jit
def law_linear_coefficients(law, p):
    """(stiffness N/m, damping N s/m) of a linear law."""
    return p[0], p[1]


@jit
def law_force(law, p, o, d, dd):
    """Force of the bumper at compression ``d`` (m) and rate ``dd`` (m/s).

    Returns ``(force, elastic_part, dforce/dd, dforce/d(dd))``.
    """
    k, c = p[o], p[o + 1]
    if law == KELVIN_VOIGT:
        return k * d + c * dd, k * d, k, c
    dpos = d if d > 0.0 else 0.0
    n = p[o + 2]
    dn = dpos**n
    if dpos > 0.0:
        slope = n * dpos ** (n - 1.0)
    else:
        slope = 1.0 if n == 1.0 else 0.0
    if law == HUNT_CROSSLEY:
        return dn * (k + c * dd), k * dn, slope * (k + c * dd), c * dn
    # JANKOWSKI: the dashpot c d^((n-1)/2) on the approach only
    if dd <= 0.0 or dpos <= 0.0:
        return k * dn, k * dn, k * slope, 0.0
    root = dpos ** (0.5 * (n - 1.0))
    return (k * dn + c * root * dd, k * dn, k * slope + 0.5 * (n - 1.0) * c * root / dpos * dd, c * root)


@jit
def law_energy(law, p, d):
    """Elastic energy stored at compression ``d`` (J)."""
    if law == KELVIN_VOIGT:
        return 0.5 * p[0] * d * d
    dpos = d if d > 0.0 else 0.0  # (Hunt-Crossley and Jankowski: the spring k d^n)
    return p[0] * dpos ** (p[2] + 1.0) / (p[2] + 1.0)


@jit
def law_relax(law, p, o, d0, tau):
    """Free recovery of a massless bumper: compression and its rate ``tau`` s after ``d0``."""
    if d0 <= 0.0:
        return 0.0, 0.0
    if law == KELVIN_VOIGT:
        if p[o + 1] <= 0.0:
            return 0.0, 0.0
        rate = p[o] / p[o + 1]
        x = rate * tau
        # relaxed below the smallest normal double: exactly 0 (else exp() takes its slow
        # underflow path, and subnormal arithmetic slows every event value after it)
        if x > EXP_NORMAL_LIMIT:
            return 0.0, 0.0
        d = d0 * math.exp(-x)
        if d < MIN_NORMAL:
            return 0.0, 0.0
        return d, -rate * d
    if law == JANKOWSKI or p[o + 1] <= 0.0:  # (Jankowski's recovery has no dashpot)
        return 0.0, 0.0
    speed = p[o] / p[o + 1]
    d = d0 - speed * tau
    if d <= 0.0:
        return 0.0, 0.0
    return d, -speed


@jit
def law_release(law, p, o, d, dd, ddd):
    """A smooth function that crosses zero downwards when the force would turn into a pull.

    Returns ``(value, rate)`` for compression ``d``, rate ``dd`` and acceleration ``ddd``.
    """
    if law == KELVIN_VOIGT:
        return p[o] * d + p[o + 1] * dd, p[o] * dd + p[o + 1] * ddd
    if law == JANKOWSKI:  # never pulls: the contact ends with the compression
        return 1.0, 0.0
    return p[o] + p[o + 1] * dd, p[o + 1] * ddd


@jit_entry
def law_force_many(law, p, d, dd, out):
    """``law_force`` at each ``(d[i], dd[i])`` into ``out[i]`` (N): arrays of one shape (n,)."""
    for i in range(d.size):
        out[i] = law_force(law, p, AT_START, d[i], dd[i])[0]
