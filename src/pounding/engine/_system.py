"""The records the compiled kernels take: the system (what ``kernel_system`` packs from an
``Oscillator``) and the forcing (what ``Harmonic.kernel_arrays`` / ``Record.kernel_arrays`` give).

Named tuples of arrays and scalars: Numba types them field by field, so a kernel reads
``sy.mass`` as it read a ``mass`` argument, and they travel to worker processes as plain tuples.
Each field keeps one type (floats as float, flags as bool, law ids as int, arrays float64 and
writable): a second type would compile a second copy of every kernel (``tests/test_compile.py``).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np


class System(NamedTuple):
    """The oscillator as the kernels take it.

    ``slopes`` (N/m), ``breaks`` (m) and ``rule`` are the isolator's backbone and hysteresis
    (``Isolator.kernel_arrays``), ``bw`` its Bouc-Wen spring (zeros without one); ``has_b``
    whether there are bumpers; ``law_l``/``law_r`` the bumpers' ``LAW_ID`` and ``p_l``/``p_r``
    their ``params()`` (a stand-in law never touched when there are none).
    """

    mass: float
    c_d: float
    slopes: np.ndarray
    breaks: np.ndarray
    rule: np.ndarray
    bw: np.ndarray
    has_b: bool
    gap_l: float
    gap_r: float
    law_l: int
    p_l: np.ndarray
    law_r: int
    p_r: np.ndarray


class Forcing(NamedTuple):
    """The excitation as the kernels take it: its kind (``_forcing.EXC_*``), its parameters
    and, for a record, its times (s) and accelerations (m/s^2) (one-element zeros otherwise)."""

    kind: int
    p: np.ndarray
    rec_t: np.ndarray
    rec_a: np.ndarray
