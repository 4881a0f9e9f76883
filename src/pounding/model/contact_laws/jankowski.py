"""The contact law :class:`Jankowski`: its checks and what the engine asks of it (its C++ side:
``src/core/laws.cpp``)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..._docs import fill_doc
from ..._checks import at_most, non_negative, positive, real
from ..._errors import InputError, Problem
from . import law_states
from ._base import (JANKOWSKI, MAX_DAMPING_RATIO, MAX_LAW_COEFFICIENT, coefficient, engine_needs,
                    exponent_value, padded)


@engine_needs("jankowski", law_states.stateless, linear=False, law_id=JANKOWSKI)
@fill_doc
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
    {pushed_run}
    >>> run.impacts["restitution"].round(2).tolist()
    [0.68, 0.69, 0.71]
    """

    stiffness: float
    damping_ratio: float
    effective_mass: float
    exponent: float = 1.5


    def __post_init__(self) -> None:
        object.__setattr__(self, "stiffness", coefficient("law.stiffness", self.stiffness, "N/m^n", True))
        object.__setattr__(self, "exponent", exponent_value(self.exponent))
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
        return padded([self.stiffness, c0, self.exponent])
