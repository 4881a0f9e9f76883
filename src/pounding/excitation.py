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

from ._checks import at_most, float_array, plausible, positive, real
from ._errors import InputError, Problem

STANDARD_GRAVITY = 9.81  # m/s^2, the value the paper uses

HARMONIC = 0
RECORD = 1
# refused beyond: no shaking table or earthquake comes near (a unit error, or overflow ahead)
MAX_A_G = 1e3
MAX_ACCEL_M_S2 = MAX_A_G * STANDARD_GRAVITY
MAX_FREQ_HZ = 1e6
MAX_TIME_S = 1e9


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
        a_g = at_most("a_g", real("a_g", self.a_g), MAX_A_G, " g", "a_g is in g: 0.05 is 5 % of g")
        plausible("a_g", abs(a_g), 0.0, 5.0, "a_g is the peak table acceleration in g (0.05 is 5 % of g)")
        freq = at_most("freq_hz", positive("freq_hz", self.freq_hz, "Hz"), MAX_FREQ_HZ, " Hz",
                       "give it in Hz")
        plausible("freq_hz", freq, 0.0, 1e3, "the frequency is in Hz, not rad/s")
        phase = real("phase", self.phase)
        g = at_most("g", positive("g", self.g, "m/s^2"), MAX_A_G, " m/s^2", "give g in m/s^2 (9.81)")
        plausible("g", g, 1.0, 30.0, "g is gravity's acceleration in m/s^2 (9.81 on Earth)")
        for name, value in (("a_g", a_g), ("freq_hz", freq), ("phase", phase), ("g", g)):
            object.__setattr__(self, name, value)

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
                             got=accel.size, expected=t.size, hint=" (one acceleration per time in record.t)")
        steps = np.diff(t)
        if np.any(steps <= 0.0):
            i = int(np.flatnonzero(steps <= 0.0)[0])
            raise InputError(Problem.NOT_INCREASING, f"record.t[{i}:{i + 2}]", t[i:i + 2].tolist())
        i = int(np.argmax(np.abs(t)))
        at_most(f"record.t[{i}]", float(t[i]), MAX_TIME_S, " s", "give the times in s")
        i = int(np.argmax(np.abs(accel)))
        at_most(f"record.accel[{i}]", float(accel[i]), MAX_ACCEL_M_S2, " m/s^2 (1000 g)",
                "give the acceleration in m/s^2 (Record.from_g takes units of g)")
        plausible(f"record.accel[{i}]", abs(float(accel[i])), 0.0, 5.0 * STANDARD_GRAVITY,
                  "the acceleration is in m/s^2 (use Record.from_g for units of g)")
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
