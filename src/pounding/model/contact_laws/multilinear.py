"""The contact law :class:`MultilinearBumper`: its checks and what the engine asks of it (its C++ side:
``src/core/laws.cpp``)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from ..._docs import fill_doc
from ..._checks import backbone
from ..._errors import InputError, Problem
from . import law_states
from ._base import (MAX_BRANCHES, MAX_LAW_COEFFICIENT, MULTILINEAR, MULTILINEAR_KINEMATIC, coefficient,
                    engine_needs, padded)


@engine_needs("multilinear", law_states.multilinear, linear=False, piecewise=True)
@fill_doc
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
    {pushed_run}
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
        object.__setattr__(self, "damping", coefficient("law.damping", self.damping, "N s/m", False))
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

    @property
    def has_memory(self) -> bool:
        """Whether its state carries its springs' slips from one contact to the next (kinematic)."""
        return self.hysteresis == "kinematic"

    def monodromy_caveat(self) -> str | None:
        """Why the exact monodromy cannot follow this bumper (None: it can): without a dashpot, a kinematic
        one rests compressed at its set once a contact ends, a depth that moves with the state."""
        if self.hysteresis == "kinematic" and self.damping == 0.0:
            return "its kinematic multi-linear law has no damping (its set after a contact)"
        return None

    def params(self) -> np.ndarray:
        """Parameters as the compiled kernels take them, shape (N_LAW_PARAMS,): damping, the
        number of slopes, the slopes (4 places), the breakpoints (3 places)."""
        out = padded([self.damping, float(len(self.slopes))])
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
