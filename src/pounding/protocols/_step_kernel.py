"""One frequency step of a stepped-sine sweep, run by the compiled core (``pounding._core.step``): cycles
until steady, then measure.

The step is run one forcing cycle at a time by the event-exact engine (the state carried over is exact, so
cutting at cycle ends changes nothing).  After each cycle the state at the cycle end (the stroboscopic
sample, table phase 0) is kept; the response is steady with period multiple ``k`` when the last ``m``
strobes repeat those ``k`` cycles earlier to within ``steady_rtol`` of the response amplitude, after
allowing for how slowly the strobes still converge.  Here: the columns of what it returns.
"""

from __future__ import annotations

from .._core import LAYOUT, periodicity, step as step_kernel  # noqa: F401  (the core's, for the protocols)
from ..metrics._impacts import SIDE_SUMS

# per-cycle record: exact extrema, then the impact sums of both sides
CY_DMAX, CY_DMIN, CY_AMAX = 0, 1, 2
CY_SUMS = 3
CYCLE_COLS = CY_SUMS + 2 * SIDE_SUMS
# the measurement window: extrema, number of cycles, impact sums (left then right)
W_DMAX, W_DMIN, W_AMAX, W_CYCLES = 0, 1, 2, 3
W_SUMS = 4
WINDOW_COLS = W_SUMS + 2 * SIDE_SUMS
assert (CYCLE_COLS, WINDOW_COLS) == (LAYOUT["CYCLE_COLS"], LAYOUT["WINDOW_COLS"])
