"""The measurement chain's cutoff as one more free number of a fit: the hypothesis that the lab's
filtering explains its accelerations, fitted together with the physics.

``identify(..., bounds={..., CUTOFF: (5.0, 100.0)})`` frees the low-pass corner of the chain's
accelerometers (table and mass): every candidate's metrics are measured through
``measurement.with_cutoff(value)`` (``measurement`` the chain given to ``identify``, or a 4th-order
zero-phase low-pass at 1 kHz). The bounds are what shaking-table data acquisition plausibly uses:
refused below 1 Hz or at half the recording's rate and above, warned outside 5-100 Hz.
"""

from __future__ import annotations

import warnings
from typing import Any

from .._checks import instance_of, real
from .._errors import InputError, PoundingWarning, Problem
from ..model import MeasurementChain

CUTOFF = "measurement_cutoff_hz"  # the free number's name in identify's bounds
PLAUSIBLE_CUTOFF_HZ = (5.0, 100.0)  # what data acquisition plausibly uses for shaking-table accelerations


def split_cutoff(bounds: Any, options: dict) -> tuple[Any, tuple[float, float] | None, dict]:
    """``bounds`` without :data:`CUTOFF`, the cutoff's bounds (None when not free) and the sweep
    options with the chain the candidates' cutoffs go into."""
    if not isinstance(bounds, dict) or CUTOFF not in bounds:
        return bounds, None, options
    rest = {k: v for k, v in bounds.items() if k != CUTOFF}
    pair = bounds[CUTOFF]
    if not isinstance(pair, (list, tuple)) or len(pair) != 2:
        raise InputError(Problem.WRONG_TYPE, f"bounds.{CUTOFF}", pair, got=type(pair).__name__,
                         expected="pair [low, high] in Hz, e.g. (5.0, 100.0)")
    low, high = real(f"bounds.{CUTOFF}[0]", pair[0]), real(f"bounds.{CUTOFF}[1]", pair[1])
    if not low < high:
        raise InputError(Problem.NOT_INCREASING, f"bounds.{CUTOFF}", list(pair))
    chain = options.get("measurement")
    if chain is None:
        chain = MeasurementChain.lowpass(high if high < 500.0 else 100.0)
    instance_of("measurement", chain, MeasurementChain,
                "pounding.MeasurementChain (its accelerometers' cutoff is fitted)")
    nyquist = 0.5 * (chain.sample_rate_hz if chain.mass.zero_phase else chain.internal_rate_hz)
    if low < 1.0 or high >= nyquist:
        raise InputError(Problem.OUT_OF_RANGE, f"bounds.{CUTOFF}", [low, high],
                         range=f"[1, {nyquist:g}) Hz, below half the rate the filter runs at",
                         hint=" (a cutoff is in Hz)")
    if low < PLAUSIBLE_CUTOFF_HZ[0] or high > PLAUSIBLE_CUTOFF_HZ[1]:
        warnings.warn(f"bounds.{CUTOFF} = [{low:g}, {high:g}] Hz reaches beyond what shaking-table data "
                      f"acquisition plausibly uses for accelerations ({PLAUSIBLE_CUTOFF_HZ[0]:g}-"
                      f"{PLAUSIBLE_CUTOFF_HZ[1]:g} Hz)", PoundingWarning, stacklevel=3)
    return rest, (low, high), {**options, "measurement": chain}


def apply_cutoff(values: dict[str, float], options: dict) -> tuple[dict[str, float], dict]:
    """A candidate's family numbers and sweep options: its :data:`CUTOFF` moved into the chain."""
    if CUTOFF not in values:
        return values, options
    rest = {k: v for k, v in values.items() if k != CUTOFF}
    return rest, {**options, "measurement": options["measurement"].with_cutoff(values[CUTOFF])}
