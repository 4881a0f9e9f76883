"""What shakes the system: base (table) accelerations.

The engine sees every excitation the same way: a base acceleration that is, piece by
piece, a polynomial of degree <= 1 plus one sinusoid.  :class:`Harmonic` is one sinusoid
forever; :class:`Record` is linear between samples.  Nothing downstream assumes either.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Union

import numpy as np

from ._checks import float_array, positive, real
from ._errors import InputError, Problem

STANDARD_GRAVITY = 9.81  # m/s^2, the value the paper uses

HARMONIC = 0
RECORD = 1


@dataclass(frozen=True)
class Harmonic:
    """Harmonic table acceleration ``A(t) = a_g * g * sin(2 pi freq_hz t + phase)``.

    Parameters
    ----------
    a_g : float
        Peak table acceleration in units of ``g`` (the paper's ``a_G``); a negative value
        flips the sign of the forcing.
    freq_hz : float
        Frequency ``f`` in Hz, > 0.
    phase : float
        Phase in rad at ``t = 0``.
    g : float
        Gravity's acceleration in m/s^2 (default 9.81, the paper's).
    """

    a_g: float
    freq_hz: float
    phase: float = 0.0
    g: float = STANDARD_GRAVITY

    def __post_init__(self) -> None:
        object.__setattr__(self, "a_g", real("a_g", self.a_g))
        object.__setattr__(self, "freq_hz", positive("freq_hz", self.freq_hz, "Hz"))
        object.__setattr__(self, "phase", real("phase", self.phase))
        object.__setattr__(self, "g", positive("g", self.g, "m/s^2"))

    @property
    def peak_m_s2(self) -> float:
        """``A_t = a_g g`` in m/s^2."""
        return self.a_g * self.g

    @property
    def omega_rad_s(self) -> float:
        """``Omega = 2 pi f`` in rad/s."""
        return 2.0 * math.pi * self.freq_hz

    @property
    def period_s(self) -> float:
        return 1.0 / self.freq_hz

    def negated(self) -> "Harmonic":
        """The same forcing with the opposite sign."""
        return Harmonic(-self.a_g, self.freq_hz, self.phase, self.g)

    def acceleration(self, t: np.ndarray) -> np.ndarray:
        """Table acceleration (m/s^2) at times ``t`` (s)."""
        return self.peak_m_s2 * np.sin(self.omega_rad_s * np.asarray(t, dtype=float) + self.phase)

    def kernel_arrays(self) -> tuple[int, np.ndarray, np.ndarray, np.ndarray]:
        return HARMONIC, np.array([self.peak_m_s2, self.omega_rad_s, self.phase]), np.zeros(1), np.zeros(1)


@dataclass(frozen=True, eq=False)
class Record:
    """Sampled table acceleration, linear between samples and zero outside ``[t[0], t[-1]]``.

    Parameters
    ----------
    t : array_like, shape (n,)
        Sample times in s, strictly increasing, n >= 2.
    accel : array_like, shape (n,)
        Table acceleration in m/s^2 at those times (use :meth:`from_g` for units of g).
    """

    t: np.ndarray = field(repr=False)
    accel: np.ndarray = field(repr=False)

    def __post_init__(self) -> None:
        t = float_array("record.t", self.t, min_len=2)
        accel = float_array("record.accel", self.accel, min_len=2)
        if accel.size != t.size:
            raise InputError(Problem.LENGTH_MISMATCH, "record.accel", f"array of {accel.size}",
                             got=accel.size, expected=t.size)
        steps = np.diff(t)
        if np.any(steps <= 0.0):
            i = int(np.flatnonzero(steps <= 0.0)[0])
            raise InputError(Problem.NOT_INCREASING, f"record.t[{i}:{i + 2}]", t[i:i + 2].tolist())
        t.setflags(write=False)
        accel.setflags(write=False)
        object.__setattr__(self, "t", t)
        object.__setattr__(self, "accel", accel)

    @classmethod
    def from_g(cls, t: np.ndarray, accel_g: np.ndarray, g: float = STANDARD_GRAVITY) -> "Record":
        """A record given in units of ``g``."""
        return cls(t, np.asarray(accel_g, dtype=float) * g)

    def negated(self) -> "Record":
        """The same record with the opposite sign."""
        return Record(self.t, -self.accel)

    def acceleration(self, t: np.ndarray) -> np.ndarray:
        """Table acceleration (m/s^2) at times ``t`` (s)."""
        return np.interp(np.asarray(t, dtype=float), self.t, self.accel, left=0.0, right=0.0)

    def __repr__(self) -> str:
        return f"Record(n={self.t.size}, t=[{self.t[0]:g}, {self.t[-1]:g}] s)"

    def kernel_arrays(self) -> tuple[int, np.ndarray, np.ndarray, np.ndarray]:
        # writable copies: a read-only array is another type to Numba, hence another compilation
        return RECORD, np.zeros(3), np.array(self.t, dtype=float), np.array(self.accel, dtype=float)


Excitation = Union[Harmonic, Record]
