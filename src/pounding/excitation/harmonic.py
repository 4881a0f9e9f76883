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


@dataclass(frozen=True)
class HarmonicPair:
    """Two harmonic components at one frequency, applied together along the plan's x and y (a building in
    plan's shaking): ``a_x = x.a_g g sin(2 pi f t + x.phase)``, ``a_y = y.a_g g sin(2 pi f t + y.phase)``.

    Parameters
    ----------
    x, y : Harmonic
        The components along x and along y; their ``freq_hz`` and ``g`` must agree.

    Examples
    --------
    Circularly polarised shaking at 0.2 g and 0.8 Hz (the table's acceleration turns at a constant
    length), and the same motion along 30 degrees:

    >>> import numpy as np
    >>> import pounding
    >>> table = pounding.HarmonicPair.circular(a_g=0.2, freq_hz=0.8)
    >>> acc = table.acceleration([0.0, 0.3, 0.7])  # m/s^2, (x, y) at each time
    >>> np.hypot(acc[:, 0], acc[:, 1]).round(4).tolist()  # m/s^2: 0.2 g
    [1.962, 1.962, 1.962]
    >>> round(table.along(30.0).a_g, 6)  # the motion along any direction: 0.2 g too
    0.2
    """

    x: Harmonic
    y: Harmonic

    def __post_init__(self) -> None:
        from .._checks import instance_of
        from .._errors import InputError, Problem

        instance_of("pair.x", self.x, Harmonic, "pounding.Harmonic")
        instance_of("pair.y", self.y, Harmonic, "pounding.Harmonic")
        for name in ("freq_hz", "g"):
            if getattr(self.x, name) != getattr(self.y, name):
                raise InputError(Problem.BAD_STATE, f"pair.y.{name}", getattr(self.y, name),
                                 why=f"differs from pair.x.{name} = {getattr(self.x, name)!r}: the two "
                                     "components of a harmonic pair share one frequency and one g",
                                 fix=f"give both components the same {name}")

    @classmethod
    def circular(cls, a_g: float, freq_hz: float, g: float = GRAVITY_M_S2) -> "HarmonicPair":
        """Circularly polarised: ``a_x = A sin(w t)``, ``a_y = A cos(w t)`` (``A = a_g g``), turning from y
        towards x."""
        return cls(Harmonic(a_g, freq_hz, 0.0, g), Harmonic(a_g, freq_hz, 0.5 * math.pi, g))

    @property
    def freq_hz(self) -> float:
        """The frequency, Hz."""
        return self.x.freq_hz

    @property
    def omega_rad_s(self) -> float:
        """``2 pi f``, rad/s."""
        return self.x.omega_rad_s

    @property
    def g(self) -> float:
        """Gravity's acceleration, m/s^2."""
        return self.x.g

    @property
    def name(self) -> str:
        """What it is, in words."""
        return (f"harmonic pair {self.freq_hz:g} Hz, {self.x.a_g:g} g and {self.y.a_g:g} g "
                f"({math.degrees(self.y.phase - self.x.phase):g} deg apart)")

    def along(self, angle_deg: float) -> Harmonic:
        """The motion along the direction ``angle_deg`` (from x towards y, degrees): ``cos(a) a_x + sin(a)
        a_y``, one harmonic of the same frequency."""
        a = math.radians(real("angle_deg", angle_deg))
        # (phasors: A e^(i phase) of each component, summed)
        z = (math.cos(a) * self.x.a_g * complex(math.cos(self.x.phase), math.sin(self.x.phase))
             + math.sin(a) * self.y.a_g * complex(math.cos(self.y.phase), math.sin(self.y.phase)))
        return Harmonic(abs(z), self.freq_hz, math.atan2(z.imag, z.real), self.g)

    def rotated(self, angle_deg: float) -> "HarmonicPair":
        """The same motion in axes turned by ``angle_deg`` (from x towards y): the new x along
        ``angle_deg``, the new y along ``angle_deg + 90``."""
        return HarmonicPair(self.along(angle_deg), self.along(real("angle_deg", angle_deg) + 90.0))

    def acceleration(self, t: np.ndarray) -> np.ndarray:
        """The table's acceleration (m/s^2) at times ``t`` (s), shape (k, 2): x then y."""
        return np.column_stack([self.x.acceleration(t), self.y.acceleration(t)])

    def kernel_arrays(self) -> tuple[int, np.ndarray, np.ndarray, np.ndarray]:
        """The excitation as the compiled engine takes it: its x component's numbers, then its y's amplitude
        and phase (internal)."""
        return (HARMONIC, np.array([self.x.peak_m_s2, self.omega_rad_s, self.x.phase, self.y.peak_m_s2,
                                    self.y.phase]), np.zeros(1), np.zeros(1))
