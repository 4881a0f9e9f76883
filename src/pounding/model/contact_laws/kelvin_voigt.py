"""The contact law :class:`KelvinVoigt`: its checks and what the engine asks of it (its C++ side:
``src/core/laws.cpp``)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..._docs import fill_doc
from . import law_states
from ._base import KELVIN_VOIGT, coefficient, engine_needs, padded


@engine_needs("kelvin_voigt", law_states.stateless, linear=True, law_id=KELVIN_VOIGT)
@fill_doc
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
    >>> law = pounding.KelvinVoigt(stiffness=1.46e6, damping=5.0)
    >>> f"{law.relaxation_time_s:.2e} s"
    '3.42e-06 s'
    {pushed_run}
    >>> run.impacts["restitution"].round(2).tolist()
    [0.95, 0.95, 0.93, 0.93]
    """

    stiffness: float
    damping: float = 0.0


    def __post_init__(self) -> None:
        object.__setattr__(self, "stiffness", coefficient("law.stiffness", self.stiffness, "N/m", True))
        object.__setattr__(self, "damping", coefficient("law.damping", self.damping, "N s/m", False))

    def params(self) -> np.ndarray:
        """Parameters as the compiled kernels take them, shape (N_LAW_PARAMS,)."""
        return padded([self.stiffness, self.damping])

    @property
    def relaxation_time_s(self) -> float:
        """Time constant ``C_b / K_b`` of the free recovery, s."""
        return self.damping / self.stiffness
