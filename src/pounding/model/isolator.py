"""The isolator: a symmetric multi-linear backbone, a hysteresis rule and a linear dashpot."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, ClassVar, Literal

import numpy as np

from .._checks import at_most, backbone, non_negative, one_of, plausible

HYSTERESIS_RULES = ("kinematic", "elastic")
# magnitudes beyond any real isolator (refused: the engine's numbers would overflow)
MAX_STIFFNESS_N_M = 1e15
MAX_DAMPING_N_S_M = 1e15
MAX_BREAKPOINT_M = 1e3


@dataclass(frozen=True)
class Isolator:
    """Isolator ("damper") of the paper: rate-independent force ``R_d`` plus ``C_d * dD/dt``.

    The backbone of ``R_d`` is symmetric and multi-linear: slope ``slopes[j]`` between
    breakpoints ``breakpoints[j-1]`` and ``breakpoints[j]`` (with ``breakpoints[-1] = 0`` and
    the last slope running to infinity).  Any number of branches; softening (decreasing
    slopes, the paper's case) or hardening (real rubber bearings at large drift).

    Parameters
    ----------
    slopes : sequence of float, shape (n,)
        Branch stiffnesses ``K_1 ... K_n`` in N/m.  The first must be > 0, the others >= 0.
    breakpoints : sequence of float, shape (n - 1,)
        Displacements ``0 < D_1 < ... < D_{n-1}`` in m where the slope changes.
    hysteresis : {"kinematic", "elastic"}
        ``"kinematic"``: Masing / kinematic hardening, built exactly as a spring of slope
        ``K_n`` in parallel with ``n - 1`` elastic-perfectly-plastic springs (spring ``i`` of
        stiffness ``K_i - K_{i+1}`` slips at ``D_i``), as SAP2000's multi-linear plastic link.
        ``"elastic"``: the force follows the backbone both ways (no hysteresis).
    damping : float
        Linear dashpot ``C_d`` in N s/m, >= 0.

    Notes
    -----
    With a hardening backbone some of the parallel springs have negative stiffness; the
    construction stays exact (Masing loops) but such a spring returns energy while slipping,
    and strongly hardening backbones can give loops of negative area, as Masing's rule does.
    """

    slopes: tuple[float, ...]
    breakpoints: tuple[float, ...] = ()
    hysteresis: Literal["kinematic", "elastic"] = "kinematic"
    damping: float = 0.0

    FIELDS: ClassVar[tuple[str, ...]] = ("slopes", "breakpoints", "hysteresis", "damping")

    def __post_init__(self) -> None:
        slopes, breakpoints = backbone("isolator", self.slopes, self.breakpoints, MAX_STIFFNESS_N_M,
                                       " N/m, stiffer than any isolator",
                                       "give the slopes in N/m (38 kN/m is 38000.0)", MAX_BREAKPOINT_M,
                                       "give the breakpoints in m")
        for j, d in enumerate(breakpoints):
            plausible(f"isolator.breakpoints[{j}]", d, 0.0, 1.0,
                      "breakpoints are displacements in m (15 mm is 0.015)")
        one_of("isolator.hysteresis", self.hysteresis, HYSTERESIS_RULES)
        damping = non_negative("isolator.damping", self.damping, "N s/m")
        at_most("isolator.damping", damping, MAX_DAMPING_N_S_M, " N s/m", "give the damping in N s/m")
        object.__setattr__(self, "slopes", slopes)
        object.__setattr__(self, "breakpoints", breakpoints)
        object.__setattr__(self, "damping", damping)

    @property
    def n_branches(self) -> int:
        """Number of backbone branches ``n``."""
        return len(self.slopes)

    @property
    def yield_forces(self) -> np.ndarray:
        """Backbone force at each breakpoint, N, shape (n - 1,) (the paper's "yielding forces")."""
        return self.backbone(np.asarray(self.breakpoints))

    def backbone(self, displacement: Any) -> np.ndarray:
        """Backbone force (N) at displacement(s) in m, any shape; odd in the displacement."""
        d = np.asarray(displacement, dtype=float)
        a = np.abs(d)
        force = self.slopes[0] * np.minimum(a, self.breakpoints[0] if self.breakpoints else np.inf)
        edges = (*self.breakpoints, np.inf)
        for j in range(1, self.n_branches):
            force = force + self.slopes[j] * np.clip(a - edges[j - 1], 0.0, edges[j] - edges[j - 1])
        return np.sign(d) * force

    def to_dict(self) -> dict[str, Any]:
        return {"slopes": list(self.slopes), "breakpoints": list(self.breakpoints),
                "hysteresis": self.hysteresis, "damping": self.damping}

    def kernel_arrays(self) -> tuple[np.ndarray, np.ndarray, int]:
        """``(slopes, breakpoints, rule)`` as the compiled engine takes them."""
        return (np.array(self.slopes, dtype=float), np.array(self.breakpoints, dtype=float),
                HYSTERESIS_RULES.index(self.hysteresis))
