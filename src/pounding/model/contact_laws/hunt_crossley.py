"""The contact law :class:`HuntCrossley`: its checks and what the engine asks of it (its C++ side:
``src/core/laws.cpp``)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..._docs import fill_doc
from . import law_states
from ._base import HUNT_CROSSLEY, coefficient, engine_needs, exponent_value, padded


@engine_needs("hunt_crossley", law_states.stateless, linear=False, law_id=HUNT_CROSSLEY)
@fill_doc
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
    {pushed_run}
    >>> run.impacts["restitution"].round(2).tolist()
    [0.66, 0.77, 0.84]
    """

    stiffness: float
    exponent: float = 1.5
    damping: float = 0.0


    def __post_init__(self) -> None:
        object.__setattr__(self, "stiffness", coefficient("law.stiffness", self.stiffness, "N/m^n", True))
        object.__setattr__(self, "exponent", exponent_value(self.exponent))
        object.__setattr__(self, "damping", coefficient("law.damping", self.damping, "N s/m^(n+1)", False))

    def params(self) -> np.ndarray:
        """Parameters as the compiled kernels take them, shape (N_LAW_PARAMS,)."""
        return padded([self.stiffness, self.damping, self.exponent])
