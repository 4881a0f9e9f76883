"""Ready-made systems.

``paper_printed``: the values printed in Sect. 5 of the paper, exactly (MODEL.md §1).  Note
MODEL.md §5: with ``C_d = 1 N s/m`` the isolator has about 0.01 % of critical damping, so
these values do not reproduce the paper's measured curves; a calibrated preset comes with
model updating.
"""

from __future__ import annotations

from ._checks import one_of
from .model import Bumpers, Isolator, KelvinVoigt, Oscillator

PAPER_MASS_KG = 500.0
PAPER_SLOPES_N_M = (38_000.0, 18_000.0, 2_000.0)
PAPER_BREAKPOINTS_M = (0.015, 0.040)
PAPER_ISOLATOR_DAMPING_N_S_M = 1.0
PAPER_BUMPER_STIFFNESS_N_M = 1_460_000.0
PAPER_BUMPER_DAMPING_N_S_M = 5.0
PAPER_TOTAL_GAP_M = 0.03


def paper_printed(bumpers: bool = True, hysteresis: str = "kinematic") -> Oscillator:
    """The paper's printed parameters (Sect. 5): YBs with ``bumpers=True``, else NBs.

    Parameters
    ----------
    bumpers : bool
        True: the YBs configuration, Kelvin-Voigt bumpers 0.015 m away on each side.
    hysteresis : {"kinematic", "elastic"}
        Rule of the tri-linear isolator (SAP2000's multi-linear plastic link is kinematic).
    """
    isolator = Isolator(PAPER_SLOPES_N_M, PAPER_BREAKPOINTS_M, hysteresis, PAPER_ISOLATOR_DAMPING_N_S_M)
    b = None
    if bumpers:
        half = PAPER_TOTAL_GAP_M / 2
        b = Bumpers(half, half, KelvinVoigt(PAPER_BUMPER_STIFFNESS_N_M, PAPER_BUMPER_DAMPING_N_S_M))
    return Oscillator(PAPER_MASS_KG, isolator, b)


PRESETS = {"paper-printed": paper_printed}


def by_name(name: str, bumpers: bool = True) -> Oscillator:
    """A preset by its CLI name (see :data:`PRESETS`)."""
    one_of("preset", name, PRESETS)
    return PRESETS[name](bumpers=bumpers)
