"""The contact law :class:`ElasticPlastic`: its checks and what the engine asks of it (its C++ side:
``src/core/laws.cpp``)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..._checks import at_most, positive
from ..._errors import InputError, Problem
from . import law_states
from ._base import ELASTIC_PLASTIC, coefficient, engine_needs, padded


@engine_needs("elastic_plastic", law_states.elastic_plastic, linear=False, law_id=ELASTIC_PLASTIC,
              piecewise=True)
@dataclass(frozen=True)
class ElasticPlastic:
    """An elastic-plastic impact law: yield in compression, stiffer elastic unloading
    (the bilinear law of OpenSees' ``ImpactMaterial``, Muthukumar and DesRoches 2006).

    The force starts along ``stiffness * d``; past ``yield_compression`` it follows the yield
    line ``stiffness * dy + post_yield_stiffness * (d - dy)``; it unloads with ``stiffness``
    down to the line ``post_yield_stiffness * d`` and along that back to zero.  Between the two
    lines it moves elastically, ``stiffness * (d - z)`` with ``z`` the plastic offset.  So an
    impact below the yield velocity ``dy sqrt(stiffness / M)`` is elastic (restitution 1); one
    above it lasts the longer the faster it comes, and its restitution falls to a least value
    and then rises slowly back towards 1 (the yield line dissipates ``(K1 - K2) dy`` per metre
    of compression, while the energy brought grows as the square of the velocity: for
    ``K2 = K1 / 20``, 0.48 at 3 yield velocities, 0.67 at 10, 0.92 at 50; :meth:`restitution`).  No dashpot:
    the force is rate-independent, never pulls, and the
    contact ends when the compression is back to zero; out of contact the bumper is unloaded
    (the next contact starts from ``z = 0``).  Piecewise linear, so every phase of motion stays
    closed-form.

    Parameters
    ----------
    stiffness : float
        ``K1``, the elastic (initial and unloading) stiffness, N/m, > 0.
    post_yield_stiffness : float
        ``K2``, N/m, with 0 < ``K2`` < ``K1``.
    yield_compression : float
        ``delta_y``, the compression where it first yields, m, > 0.

    Examples
    --------
    A bumper that yields at 2 mm, ``K2 = K1 / 20``: the restitution of the 500 kg mass hitting it
    at 0.05 (below the yield velocity), 0.3 and 1.0 m/s:

    >>> import pounding
    >>> law = pounding.ElasticPlastic(stiffness=2.0e6, post_yield_stiffness=1.0e5,
    ...                               yield_compression=0.002)
    >>> round(law.yield_velocity_m_s(500.0), 3)  # m/s
    0.126
    >>> law.restitution(500.0, [0.05, 0.3, 1.0]).round(2).tolist()
    [1.0, 0.51, 0.62]
    """

    stiffness: float
    post_yield_stiffness: float
    yield_compression: float


    def __post_init__(self) -> None:
        k1 = coefficient("law.stiffness", self.stiffness, "N/m", True)
        k2 = coefficient("law.post_yield_stiffness", self.post_yield_stiffness, "N/m", True)
        if not k2 < k1:
            raise InputError(Problem.OUT_OF_RANGE, "law.post_yield_stiffness", self.post_yield_stiffness,
                             range=f"(0, {k1:g}) N/m",
                             hint=" (below the elastic stiffness: the yield line is the softer one)")
        dy = positive("law.yield_compression", self.yield_compression, "m")
        dy = at_most("law.yield_compression", dy, 10.0, " m", "give it in m (2 mm is 0.002)")
        object.__setattr__(self, "stiffness", k1)
        object.__setattr__(self, "post_yield_stiffness", k2)
        object.__setattr__(self, "yield_compression", dy)

    def params(self) -> np.ndarray:
        """Parameters as the compiled kernels take them, shape (N_LAW_PARAMS,): K1, K2, delta_y."""
        return padded([self.stiffness, self.post_yield_stiffness, self.yield_compression])

    def yield_velocity_m_s(self, mass_kg: float) -> float:
        """Impact velocity (m/s) of a free mass ``mass_kg`` below which the contact is elastic."""
        return self.yield_compression * math.sqrt(self.stiffness / positive("mass_kg", mass_kg, "kg"))

    def restitution(self, mass_kg: float, velocity_m_s: Any) -> np.ndarray:
        """Coefficient of restitution of a free mass hitting the bumper at ``velocity_m_s``
        (m/s, >= 0, any shape): 1 below the yield velocity, then
        ``sqrt(E_back / (M v^2 / 2))`` with ``E_back`` the elastic energy at the deepest compression."""
        m = positive("mass_kg", mass_kg, "kg")
        try:
            v = np.asarray(velocity_m_s, dtype=float)
        except (TypeError, ValueError):
            raise InputError(Problem.NOT_A_NUMBER, "velocity_m_s", velocity_m_s) from None
        bad = ~np.isfinite(v) | (v < 0.0)
        if bad.any():
            first = float(v[bad][0]) if v.ndim else float(v)
            if not np.isfinite(first):
                raise InputError(Problem.NOT_FINITE, "velocity_m_s", first)
            raise InputError(Problem.NEGATIVE, "velocity_m_s", first, unit="m/s (an impact speed)")
        k1, k2, dy = self.stiffness, self.post_yield_stiffness, self.yield_compression
        energy = 0.5 * m * v * v
        # deepest compression: 1/2 k1 dy^2 + k1 dy s + 1/2 k2 s^2 = energy, s = d_max - dy >= 0
        e_y = 0.5 * k1 * dy * dy
        s = np.where(energy > e_y, (-k1 * dy + np.sqrt((k1 * dy) ** 2 + 2.0 * k2 * np.maximum(energy - e_y,
                                                                                              0.0)))
                     / k2, 0.0)
        f = k1 * dy + k2 * s
        dp = (k1 - k2) * s / k1
        back = 0.5 * f * f / k1 + 0.5 * k1 * k2 * dp * dp / (k1 - k2)
        with np.errstate(invalid="ignore", divide="ignore"):
            return np.where(energy > e_y, np.sqrt(back / np.where(energy > 0, energy, 1.0)), 1.0)
