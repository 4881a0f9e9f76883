"""The harmonic table acceleration of a shaking table (and the limits every excitation shares)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .._checks import at_most, plausible, positive, real
from .._core import EXCITATION
from .._units import GRAVITY_M_S2  # (re-exported: pounding.excitation.GRAVITY_M_S2)

HARMONIC, RECORD = EXCITATION["harmonic"], EXCITATION["record"]  # (the core's kinds)
# refused beyond: no shaking table or earthquake comes near (a unit error, or overflow ahead)
MAX_A_G = 1e3
MAX_ACCEL_M_S2 = MAX_A_G * GRAVITY_M_S2
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

    Examples
    --------
    A shaking table at 10 % of g and 2 Hz, shaking the paper's YBs system for 5 s:

    >>> import pounding
    >>> table = pounding.Harmonic(a_g=0.1, freq_hz=2.0)
    >>> round(table.peak_m_s2, 3), table.period_s  # m/s^2, s
    (0.981, 0.5)
    >>> # m/s^2 at 0, T/4, 3T/4
    >>> table.acceleration([0.0, 0.125, 0.375]).round(3).tolist()
    [0.0, 0.981, -0.981]
    >>> run = pounding.simulate(pounding.presets.paper_damped(), table,
    ...                         duration=5.0)
    >>> run.status.name, len(run.contacts)
    ('SUCCESS', 19)
    """

    a_g: float
    freq_hz: float
    phase: float = 0.0
    g: float = GRAVITY_M_S2

    def __post_init__(self) -> None:
        a_g = at_most("a_g", real("a_g", self.a_g), MAX_A_G, " g", "a_g is in g: 0.05 is 5 % of g")
        freq = at_most("freq_hz", positive("freq_hz", self.freq_hz, "Hz"), MAX_FREQ_HZ, " Hz",
                       "give it in Hz")
        plausible("freq_hz", freq, 0.0, 1e3, "the frequency is in Hz, not rad/s")
        phase = real("phase", self.phase)
        g = at_most("g", positive("g", self.g, "m/s^2"), MAX_A_G, " m/s^2", "give g in m/s^2 (9.81)")
        plausible("g", g, 1.0, 30.0, "g is gravity's acceleration in m/s^2 (9.81 on Earth)")
        # (the peak against Earth's gravity: a_g given with g = 1 is in m/s^2)
        plausible("a_g", abs(a_g) * g / GRAVITY_M_S2, 0.0, 5.0,
                  "a_g is the peak table acceleration in g (0.05 is 5 % of g)")
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
        """``1 / f`` in s."""
        return 1.0 / self.freq_hz

    def negated(self) -> "Harmonic":
        """The same forcing with the opposite sign."""
        return Harmonic(-self.a_g, self.freq_hz, self.phase, self.g)

    def acceleration(self, t: np.ndarray) -> np.ndarray:
        """Table acceleration (m/s^2) at times ``t`` (s)."""
        return self.peak_m_s2 * np.sin(self.omega_rad_s * np.asarray(t, dtype=float) + self.phase)

    def kernel_arrays(self) -> tuple[int, np.ndarray, np.ndarray, np.ndarray]:
        """The excitation as the compiled engine takes it: a kind code and three float arrays (internal)."""
        return HARMONIC, np.array([self.peak_m_s2, self.omega_rad_s, self.phase]), np.zeros(1), np.zeros(1)
