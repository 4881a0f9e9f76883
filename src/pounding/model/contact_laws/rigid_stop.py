"""The rigid stop: an instantaneous impact with Newton's coefficient of restitution.

Its C++ side is the core's ``RIGID`` law (``src/core/laws.cpp``: no force at any compression;
``src/core/impact.cpp``: the impact, a chatter's accumulation; ``src/core/sticking.cpp``: the stop
held shut).  A rigid stop never compresses: at each impact the pair's relative normal velocity
``v`` becomes ``-e v`` by an impulse between the two sides, the kinetic energy
``(1 - e^2) mu v^2 / 2`` (``mu`` the pair's effective mass) is lost, and while the motion pushes the
stop shut after a chatter (or an impact with ``e = 0``) the pair moves as one until the stop's
force would pull.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ..._checks import real
from ..._core import LAW_IDS, LAYOUT
from ..._errors import InputError, Problem
from . import law_states
from ._base import engine_needs

RIGID_ID = LAW_IDS["rigid"]


@engine_needs("rigid", law_states.stateless, linear=False, law_id=RIGID_ID, rigid=True)  # (no stiffness)
@dataclass(frozen=True)
class RigidStop:
    """A rigid stop: impacts with a coefficient of restitution, chatter and sticking.

    Parameters
    ----------
    restitution : float
        Newton's coefficient of restitution ``e``, in [0, 1]: the relative normal velocity after
        an impact is ``-e`` times the one before (1: elastic, no loss; 0: plastic, the pair then
        moves as one while the motion pushes it shut).

    Notes
    -----
    Impacts are instantaneous, so a contact row has ``t_end_s == t_start_s``, no peak force
    (NaN) and no compression; its ``impulse_n_s`` is Newton's impulse and its
    ``bumper_dissipation_j`` the kinetic energy lost.  When impacts accumulate (complete
    chatter: the rebounds shrink by ``e`` each time while the motion pushes the stop shut),
    the engine sums the rest of the geometric sequence in closed form (its energy in the
    ledger's dissipation) and holds the stop shut: a row from the hold's start to its release,
    with the hold's impulse and peak force (``v_in_m_s`` 0: no restitution).  ``Run.chatters``
    lists each sequence: how many impacts it held and where it accumulated.

    Examples
    --------
    A mass on the paper's isolator between rigid stops 15 mm away, shaken at 0.1 g:

    >>> import pounding
    >>> stops = pounding.Bumpers(0.015, 0.015, pounding.RigidStop(0.7))
    >>> iso = pounding.presets.paper_damped().isolator
    >>> osc = pounding.Oscillator(500.0, iso, stops)
    >>> run = pounding.simulate(osc, pounding.Harmonic(a_g=0.1, freq_hz=1.0),
    ...                         duration=5.0)
    >>> len(run.contacts), round(float(run.impacts["restitution"].max()), 9)
    (10, 0.7)
    """

    restitution: float


    def __post_init__(self) -> None:
        e = real("law.restitution", self.restitution)
        if not 0.0 <= e <= 1.0:
            raise InputError(Problem.OUT_OF_RANGE, "law.restitution", self.restitution, range="[0, 1]",
                             hint=" (Newton's coefficient: 1 elastic, 0 plastic)")
        object.__setattr__(self, "restitution", e)

    def params(self) -> np.ndarray:
        """Parameters as the compiled kernels take them, shape (N_LAW_PARAMS,): the restitution."""
        out = np.zeros(LAYOUT["N_LAW_PARAMS"])
        out[0] = self.restitution
        return out


def is_rigid(law: Any) -> bool:
    """Whether ``law`` is a rigid stop (no stiffness: an impulse at each impact)."""
    return bool(getattr(law, "RIGID", False))


def refuse_clamp(field: str, gap_left: float, gap_right: float, left: Any, right: Any) -> None:
    """Refuse rigid stops on both sides with no gap between them (``field``: the left gap's name): the mass
    would be clamped, every impact at once against both (Newton's law has no answer there)."""
    if is_rigid(left) and is_rigid(right) and gap_left + gap_right == 0.0:
        raise InputError(Problem.BAD_STATE, field, gap_left,
                         why="and the other gap are 0 with rigid stops on both sides: the mass is clamped "
                             "between them",
                         fix="give one of the gaps a positive value, or a deformable law to one side")
