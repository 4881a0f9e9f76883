"""What the core takes: the system (``kernel_system`` packs an ``Oscillator`` into the core's
:class:`pounding._core.System`, picklable) and the forcing (``Harmonic.kernel_arrays`` /
``Record.kernel_arrays``: its kind, its parameters and, for a record, its times and accelerations)."""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from .._core import System  # noqa: F401  (the core's; re-exported for the engine's callers)


class Forcing(NamedTuple):
    """The excitation as the core takes it: its kind (``EXC_HARMONIC`` or a record), its parameters
    (harmonic: amplitude m/s^2, omega rad/s, phase rad; a record: its uniform step or 0) and, for a record,
    its times (s) and accelerations (m/s^2) (one-element zeros otherwise)."""

    kind: int
    p: np.ndarray
    rec_t: np.ndarray
    rec_a: np.ndarray


EXC_HARMONIC = 0
