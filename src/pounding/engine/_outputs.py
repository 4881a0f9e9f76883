"""What the kernel records at an instant: the forces and the absolute acceleration, and the energies
stored (the ledger's kinetic, isolator and bumper terms)."""

from __future__ import annotations

from .._jit import jit
from ..model.contact_laws import AT_START, law_energy, law_force
from ._isolator import iso_energy, iso_linear
from ._layout import (DEF_L, DEF_R, IN_L, IN_R, P_BW, P_CD, P_INL, P_INR, P_KISO, P_RISO, SIDE_L, SIDE_R,
                      ZETA, ZL_AT, ZR_AT, D, V)
from ._trajectory import contact_force, phase_zeta, table_acceleration


@jit
def outputs(st, d, v, sy):
    """``(abs_acceleration, isolator_force, left bumper force, right bumper force)`` at (d, v) of
    the system ``sy`` (``_system.System``)."""
    k, r0 = iso_linear(sy.slopes, sy.breaks, sy.rule, st)
    f_iso = k * d + r0 + sy.c_d * v + sy.bw[0] * st[ZETA]
    f_l = 0.0
    f_r = 0.0
    if st[IN_L] != 0.0:
        f_l = law_force(sy.law_l, sy.p_l, AT_START, -d - sy.gap_l, -v, st, ZL_AT)[0]
    if st[IN_R] != 0.0:
        f_r = law_force(sy.law_r, sy.p_r, AT_START, d - sy.gap_r, v, st, ZR_AT)[0]
    return -(f_iso + f_r - f_l) / sy.mass, f_iso, f_l, f_r


@jit
def outputs_in_phase(ph, tau, d, v, a):
    """``outputs`` inside a sub-interval, from its phase descriptor (no isolator loop)."""
    f_iso = ph[P_KISO] * d + ph[P_RISO] + ph[P_CD] * v
    if ph[P_BW] != 0.0:
        f_iso += ph[P_BW] * phase_zeta(ph, tau)
    f_l = contact_force(ph, SIDE_L, d, v, a)[0] if ph[P_INL] != 0.0 else 0.0
    f_r = contact_force(ph, SIDE_R, d, v, a)[0] if ph[P_INR] != 0.0 else 0.0
    return a + table_acceleration(ph, tau), f_iso, f_l, f_r


@jit
def energies(st, sy):
    """The energies stored in the state: ``(kinetic, isolator, bumpers)``, J."""
    bw = sy.bw
    # (subinterval.bouc_wen_energy)
    e_bw = 0.5 * bw[0] * bw[1] * st[ZETA] ** 2 / bw[2] if bw[0] != 0.0 else 0.0
    return (0.5 * sy.mass * st[V] ** 2, iso_energy(sy.slopes, sy.breaks, sy.rule, st, st[D]) + e_bw,
            law_energy(sy.law_l, sy.p_l, st[DEF_L], st, ZL_AT) + law_energy(sy.law_r, sy.p_r, st[DEF_R], st,
                                                                            ZR_AT))
