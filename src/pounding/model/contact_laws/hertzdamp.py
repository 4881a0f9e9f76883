"""The contact law :class:`Hertzdamp`: its checks and what the engine asks of it (its C++ side:
``src/core/laws.cpp``)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..._docs import fill_doc
from ..._checks import at_most, non_negative, real
from ..._errors import InputError, Problem
from . import law_states
from ._base import HERTZDAMP, MAX_DAMPING_RATIO, coefficient, engine_needs, exponent_value, padded


@engine_needs("hertzdamp", law_states.hertzdamp, linear=False, law_id=HERTZDAMP)
@fill_doc
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
    {pushed_run}
    >>> run.impacts["restitution"].round(2).tolist()
    [0.68, 0.69, 0.73]
    """

    stiffness: float
    xi_norm: float
    exponent: float = 1.5


    def __post_init__(self) -> None:
        object.__setattr__(self, "stiffness", coefficient("law.stiffness", self.stiffness, "N/m^n", True))
        xi = non_negative("law.xi_norm", self.xi_norm, "(a ratio)")
        xi = at_most("law.xi_norm", xi, MAX_DAMPING_RATIO, "",
                     "xi_norm is a ratio: 0.3 gives a restitution of about 0.84")
        object.__setattr__(self, "xi_norm", xi)
        object.__setattr__(self, "exponent", exponent_value(self.exponent))

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
        return padded([self.stiffness, self.xi_norm, self.exponent])
