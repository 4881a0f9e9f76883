"""Numerical propagation of a phase whose contact law is nonlinear (Dormand-Prince 5(4)).

The phase descriptor holds the linear part (isolator, linear bumpers, forcing) exactly as
for a closed-form phase; the nonlinear bumper forces and the isolator's Bouc-Wen spring (whose
variable z is integrated with the motion) are added in :func:`phase_rhs`.  A step
of any length ``tau`` from the phase start is one Dormand-Prince step, so the event
locator can evaluate the trajectory anywhere inside an accepted step.
"""

from __future__ import annotations

import math

from ..model.contact_laws import law_force
from .._jit import jit
from ._layout import (P_BW, P_C, P_D0, P_DP5, P_DP5_H, P_GAPL, P_GAPR, P_H, P_K, P_LAWL, P_LAWR, P_M, P_NLL,
                      P_NLR, P_P0, P_P1, P_PHI, P_V0, P_W, P_ZETA0, PL_AT, PR_AT, PZL_AT, PZR_AT)

# Dormand-Prince 5(4) tableau
C2, C3, C4, C5 = 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0
A21 = 1.0 / 5.0
A31, A32 = 3.0 / 40.0, 9.0 / 40.0
A41, A42, A43 = 44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0
A51, A52, A53, A54 = 19372.0 / 6561.0, -25360.0 / 2187.0, 64448.0 / 6561.0, -212.0 / 729.0
A61, A62, A63, A64, A65 = 9017.0 / 3168.0, -355.0 / 33.0, 46732.0 / 5247.0, 49.0 / 176.0, -5103.0 / 18656.0
B1, B3, B4, B5, B6 = 35.0 / 384.0, 500.0 / 1113.0, 125.0 / 192.0, -2187.0 / 6784.0, 11.0 / 84.0
E1, E3, E4, E5, E6, E7 = (71.0 / 57600.0, -71.0 / 16695.0, 71.0 / 1920.0, -17253.0 / 339200.0,
                          22.0 / 525.0, -1.0 / 40.0)


@jit
def bumper_forces(ph, d, v):
    """Forces (N, >= 0 in contact) of the nonlinear bumpers in contact: (left, right)."""
    fl = 0.0
    fr = 0.0
    if ph[P_NLL] != 0.0:
        fl = law_force(int(ph[P_LAWL]), ph, PL_AT, -d - ph[P_GAPL], -v, ph, PZL_AT)[0]
    if ph[P_NLR] != 0.0:
        fr = law_force(int(ph[P_LAWR]), ph, PR_AT, d - ph[P_GAPR], v, ph, PZR_AT)[0]
    return fl, fr


@jit
def zeta_rate(ph, v, z):
    """``dz/dt`` of the Bouc-Wen spring at velocity ``v`` (m/s) and ``z`` (0 without one)."""
    if ph[P_BW] == 0.0:
        return 0.0
    a, beta, gamma, n = ph[P_BW + 2], ph[P_BW + 3], ph[P_BW + 4], ph[P_BW + 5]
    az = abs(z)
    zn = az if n == 1.0 else az**n
    s = beta if v * z > 0.0 else -beta
    return v / ph[P_BW + 1] * (a - zn * (s + gamma))


@jit
def phase_rhs(ph, tau, d, v, z):
    """Relative acceleration (m/s^2) of a numerically integrated phase, Bouc-Wen ``z``."""
    fl, fr = bumper_forces(ph, d, v)
    force = ph[P_P0] + ph[P_P1] * tau + ph[P_H] * math.sin(ph[P_W] * tau + ph[P_PHI])
    return (force - ph[P_C] * v - ph[P_K] * d - ph[P_BW] * z - fr + fl) / ph[P_M]


@jit
def dp5_step(ph, h):
    """One Dormand-Prince step of length ``h`` from the phase start.

    Returns ``(D, V, A, error_D, error_V, z, error_z)``: the 5th-order solution, the
    acceleration there, the embedded error estimate, and the Bouc-Wen variable (the phase
    start's without one).
    """
    if ph[P_DP5_H] == h:  # the step just taken (its phase unchanged: _set_phase resets this)
        return (ph[P_DP5], ph[P_DP5 + 1], ph[P_DP5 + 2], ph[P_DP5 + 3], ph[P_DP5 + 4], ph[P_DP5 + 5],
                ph[P_DP5 + 6])
    d0 = ph[P_D0]
    v0 = ph[P_V0]
    z0 = ph[P_ZETA0]
    k1d = v0
    k1v = phase_rhs(ph, 0.0, d0, v0, z0)
    k1z = zeta_rate(ph, v0, z0)
    d = d0 + h * A21 * k1d
    v = v0 + h * A21 * k1v
    z = z0 + h * A21 * k1z
    k2d, k2v, k2z = v, phase_rhs(ph, C2 * h, d, v, z), zeta_rate(ph, v, z)
    d = d0 + h * (A31 * k1d + A32 * k2d)
    v = v0 + h * (A31 * k1v + A32 * k2v)
    z = z0 + h * (A31 * k1z + A32 * k2z)
    k3d, k3v, k3z = v, phase_rhs(ph, C3 * h, d, v, z), zeta_rate(ph, v, z)
    d = d0 + h * (A41 * k1d + A42 * k2d + A43 * k3d)
    v = v0 + h * (A41 * k1v + A42 * k2v + A43 * k3v)
    z = z0 + h * (A41 * k1z + A42 * k2z + A43 * k3z)
    k4d, k4v, k4z = v, phase_rhs(ph, C4 * h, d, v, z), zeta_rate(ph, v, z)
    d = d0 + h * (A51 * k1d + A52 * k2d + A53 * k3d + A54 * k4d)
    v = v0 + h * (A51 * k1v + A52 * k2v + A53 * k3v + A54 * k4v)
    z = z0 + h * (A51 * k1z + A52 * k2z + A53 * k3z + A54 * k4z)
    k5d, k5v, k5z = v, phase_rhs(ph, C5 * h, d, v, z), zeta_rate(ph, v, z)
    d = d0 + h * (A61 * k1d + A62 * k2d + A63 * k3d + A64 * k4d + A65 * k5d)
    v = v0 + h * (A61 * k1v + A62 * k2v + A63 * k3v + A64 * k4v + A65 * k5v)
    z = z0 + h * (A61 * k1z + A62 * k2z + A63 * k3z + A64 * k4z + A65 * k5z)
    k6d, k6v, k6z = v, phase_rhs(ph, h, d, v, z), zeta_rate(ph, v, z)
    d = d0 + h * (B1 * k1d + B3 * k3d + B4 * k4d + B5 * k5d + B6 * k6d)
    v = v0 + h * (B1 * k1v + B3 * k3v + B4 * k4v + B5 * k5v + B6 * k6v)
    z = z0 + h * (B1 * k1z + B3 * k3z + B4 * k4z + B5 * k5z + B6 * k6z)
    k7v, k7z = phase_rhs(ph, h, d, v, z), zeta_rate(ph, v, z)
    k7d = v
    ed = h * (E1 * k1d + E3 * k3d + E4 * k4d + E5 * k5d + E6 * k6d + E7 * k7d)
    ev = h * (E1 * k1v + E3 * k3v + E4 * k4v + E5 * k5v + E6 * k6v + E7 * k7v)
    ez = h * (E1 * k1z + E3 * k3z + E4 * k4z + E5 * k5z + E6 * k6z + E7 * k7z)
    ph[P_DP5_H] = h
    ph[P_DP5], ph[P_DP5 + 1], ph[P_DP5 + 2], ph[P_DP5 + 3] = d, v, k7v, ed
    ph[P_DP5 + 4], ph[P_DP5 + 5], ph[P_DP5 + 6] = ev, z, ez
    return d, v, k7v, ed, ev, z, ez
