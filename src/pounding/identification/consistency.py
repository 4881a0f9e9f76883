"""Are the measurements consistent?  Bounds that any mass obeying Newton's law must satisfy.

Each check combines measured numbers of one case (configuration, a_G, direction) and
compares one of them with a bound the others imply.  The bounds use kinematics only
(``a_abs = D'' + A``, ``A = A_t sin(2 pi f t)``), nothing of the isolator or the bumpers, so
a measured set that violates one cannot come from any model: calibrating to it trades one
number against another.  Measured values are given the benefit of their tolerances (the
targets' ``allowed``): a case is flagged only when it misses the bound by more.

The checks (one row each where the case has the quantities they need):

``alpha_vs_excursion``
    At resonance (frequency ``f = nu_R f_ref``) the steady response, periodic with the
    table's period ``T = 1/f``, covers the excursion ``E`` between two velocity zeros in at
    most half a period: somewhere ``|D''| >= 16 E f^2`` (accelerating for half of that time
    and braking for the other half is the least it takes), and ``|a_abs| >= |D''| - A_t``:
    ``alpha >= 16 E f^2 / A_t - 1``.  ``E`` is ``eta * gap_total`` (YBs) or ``e * D_tmax``
    (NBs, ``D_tmax = A_t / omega_min^2``), or the measured ``excursion_max_m`` where given.
``alpha_vs_excursion_sinusoidal``
    The same for a sinusoidal response of amplitude ``E / 2`` (a linear or mildly nonlinear
    isolator near resonance, no impacts): ``|D''|`` reaches ``2 pi^2 f^2 E``, so
    ``alpha >= 2 pi^2 f^2 E / A_t - 1`` whatever the phase.  An impact only adds to
    ``alpha``, so a measured alpha below it means the response was far from sinusoidal or
    the numbers do not belong together.  ``consistent`` is then the plausibility of the
    near-sinusoidal response, not a law: the column ``kind`` says which.
``alpha_vs_impact``
    Over one contact the relative velocity turns from ``v_i`` to ``-s v_i`` in ``dt_c``, so
    the mean of ``D''`` over the contact is ``v_i (1 + s) / dt_c`` and
    ``alpha >= v_i (1 + s) / (dt_c A_t) - 1``, with ``v_i`` from the dissipated energy and
    the restitution: ``E_d / M = v_i^2 (1 - s^2) / 2``.  Needs ``restitution``,
    ``contact_time_ms`` and ``dissipated_energy_per_mass``, and ``s < 1``.
``energy_vs_restitution``
    ``E_d / M = v_i^2 (1 - s^2) / 2``: with ``s < 1`` the dissipated energy is positive.
``contact_time_vs_compression``
    YBs: the bumpers' deepest compressions in a cycle add up to ``S = E - Delta``, so the
    deepest reaches ``delta >= S / 2``.  From the bumper's surface to that depth the
    velocity falls to zero with ``|D''| <= (alpha + 1) A_t``, which takes at least
    ``sqrt(2 delta / ((alpha + 1) A_t))``: ``dt_c >= sqrt(S / ((alpha + 1) A_t))``.  It
    assumes that each contact starts at the bumper's recovered surface at the nominal gap
    (a larger effective gap, or a bumper that has not recovered, shortens ``S``), that the
    measured contact time is that of the deepest contact, and that the largest excursion
    ``E`` is reached at the resonance, where the contact times were measured: the column
    ``kind`` says "contact".  The explanation gives the effective gap the measured contact
    time would need.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np
import pandas as pd

from .._checks import at_most, gap_total, positive
from .._errors import InputError, Problem
from ..data import PAPER_F_REF_HZ, PAPER_OMEGA_MIN_RAD_S
from .._units import GRAVITY_M_S2

if TYPE_CHECKING:
    from .targets import Targets

COLUMNS = ("configuration", "a_g", "direction", "check", "kind", "quantity", "measured", "allowed", "bound",
           "consistent", "margin", "explanation")
LAW = "law"                # a bound no system can violate
SINUSOIDAL = "sinusoidal"  # a bound for a near-sinusoidal response: plausibility
CONTACT = "contact"        # a bound for contacts from the recovered surface at the nominal gap


def check_consistency(targets: Targets, mass_kg: float, gap_total_m: float | None = None, *,
                      g: float = GRAVITY_M_S2,
                      f_ref_hz: float = PAPER_F_REF_HZ,
                      omega_min_rad_s: float = PAPER_OMEGA_MIN_RAD_S) -> pd.DataFrame:
    """Check measured targets against bounds any mass obeying Newton's law satisfies.

    Parameters
    ----------
    targets : Targets
        The measurements (e.g. :func:`pounding.paper_targets` with
        ``quantities=CONSISTENCY_QUANTITIES`` for the dissipated energies too).
    mass_kg : float
        The mass ``M``, kg (the bounds are per unit mass: it enters only through the energies).
    gap_total_m : float, optional
        ``Delta = g_L + g_R``, m: YBs excursions are ``eta * Delta``.  Default: the targets'
        ``eta_gap_total_m`` (required when they have none).
    g, f_ref_hz, omega_min_rad_s : float
        Gravity (m/s^2), the reference frequency of ``nu`` (Hz) and ``Omega_min`` of NBs
        ``e = E / D_tmax`` (rad/s), as the sweeps use them.

    Returns
    -------
    DataFrame
        One row per check and case (see the module docstring): ``configuration``, ``a_g``,
        ``direction``, ``check``, ``kind`` ("law": no system can violate it;
        "sinusoidal": a near-sinusoidal response cannot), ``quantity`` (the one compared),
        ``measured``, ``allowed`` (its tolerance), ``bound`` (the least value the case's other
        numbers allow), ``consistent`` (``measured + allowed >= bound``), ``margin``
        (``(measured - bound) / allowed``: below -1 flags it) and ``explanation``.
    """
    mass_kg = at_most("mass_kg", positive("mass_kg", mass_kg, "kg"), 1e12, " kg", "give the mass in kg")
    if gap_total_m is None:
        if targets.eta_gap_total_m is None:
            raise InputError(Problem.MISSING_INPUT, "gap_total_m", None,
                             what="the total gap Delta in m (the targets have no eta_gap_total_m)")
        gap_total_m = targets.eta_gap_total_m
    gap_total_m = gap_total("gap_total_m", gap_total_m)
    g = at_most("g", positive("g", g, "m/s^2"), 1000.0, " m/s^2", "give g in m/s^2 (9.81)")
    f_ref_hz = at_most("f_ref_hz", positive("f_ref_hz", f_ref_hz, "Hz"), 1e4, " Hz",
                       "give it in Hz (the paper's 1.0)")
    omega_min_rad_s = at_most("omega_min_rad_s", positive("omega_min_rad_s", omega_min_rad_s, "rad/s"), 1e5,
                              " rad/s", "give it in rad/s (the paper's 2 pi 0.6 = 3.77)")
    table = targets.data.assign(allowed=targets.allowed)
    rows: list[dict] = []
    for (conf, a_g, direction), case in table.groupby(["configuration", "a_g", "direction"], sort=True):
        q = {r.quantity: (float(r.value), float(r.allowed)) for r in case.itertuples(index=False)}
        a_t = a_g * g
        key = {"configuration": conf, "a_g": a_g, "direction": direction}
        excursion = _excursion(conf, q, a_t, gap_total_m, omega_min_rad_s)
        if "alpha" in q and "nu_r" in q and excursion is not None:
            f = q["nu_r"][0] * f_ref_hz
            e_low = excursion[0] - excursion[1]  # the excursion at the low end of its tolerance
            name = ("the measured E" if "excursion_max_m" in q else
                    "eta * Delta" if conf == "YBs" else "e * D_tmax")
            rows.append(_row(key, "alpha_vs_excursion", LAW, "alpha", q["alpha"],
                             16.0 * e_low * f * f / a_t - 1.0,
                             f"a periodic response of excursion E = {name} = {excursion[0]:.4g} m at "
                             f"f = {f:.3g} Hz needs |D''| >= 16 E f^2 somewhere: "
                             "alpha >= 16 E f^2 / A_t - 1"))
            rows.append(_row(key, "alpha_vs_excursion_sinusoidal", SINUSOIDAL, "alpha", q["alpha"],
                             2.0 * math.pi ** 2 * e_low * f * f / a_t - 1.0,
                             f"a sinusoidal response of excursion E = {excursion[0]:.4g} m at f = {f:.3g} Hz "
                             "has |D''| = 2 pi^2 f^2 E: alpha >= 2 pi^2 f^2 E / A_t - 1 (impacts only add)"))
        if conf == "YBs" and "alpha" in q and "contact_time_ms" in q and excursion is not None:
            s_low = excursion[0] - excursion[1] - gap_total_m  # the compressions' sum, at its low end
            a_max = (q["alpha"][0] + q["alpha"][1] + 1.0) * a_t  # |D''| at the high end of alpha
            if s_low > 0.0:
                dt_high_s = (q["contact_time_ms"][0] + q["contact_time_ms"][1]) * 1e-3
                gap_needed = max(0.5 * (excursion[0] - excursion[1] - a_max * dt_high_s ** 2), 0.0)
                rows.append(_row(key, "contact_time_vs_compression", CONTACT, "contact_time_ms",
                                 q["contact_time_ms"], 1e3 * math.sqrt(s_low / a_max),
                                 f"the bumpers are compressed by S = E - Delta = {1e3 * s_low:.3g} mm in "
                                 "all, the deepest by S / 2, brought to rest there at |D''| <= (alpha + 1) "
                                 f"A_t = {a_max:.3g} m/s^2: dt_c >= sqrt(S / ((alpha + 1) A_t)) for contacts "
                                 "from the recovered surface at the nominal gap; the measured dt_c is "
                                 f"possible with a gap of {1e3 * gap_needed:.3g} mm a side or more"))
        needed = ("alpha", "restitution", "contact_time_ms", "dissipated_energy_per_mass")
        if all(k in q for k in needed):
            s, s_allowed = q["restitution"]
            ed, ed_allowed = q["dissipated_energy_per_mass"]
            dt_s = (q["contact_time_ms"][0] + q["contact_time_ms"][1]) * 1e-3  # the longest allowed
            s_high = s + s_allowed
            ed_low = max(ed - ed_allowed, 0.0)
            if s_high < 1.0 and dt_s > 0.0:
                v_in = math.sqrt(2.0 * ed_low / (1.0 - s_high * s_high))
                rows.append(_row(key, "alpha_vs_impact", LAW, "alpha", q["alpha"],
                                 v_in * (1.0 + s - s_allowed) / (dt_s * a_t) - 1.0,
                                 f"an impact at v_i = {v_in:.3g} m/s (from E_d / M and s) reversed to s v_i "
                                 f"within dt_c = {dt_s * 1e3:.3g} ms: alpha >= v_i (1 + s) / (dt_c A_t) - 1"))
        if "restitution" in q and "dissipated_energy_per_mass" in q:
            s, s_allowed = q["restitution"]
            if s + s_allowed < 1.0:  # E_d / M = v_i^2 (1 - s^2) / 2 > 0
                rows.append(_row(key, "energy_vs_restitution", LAW, "dissipated_energy_per_mass",
                                 q["dissipated_energy_per_mass"], 0.0,
                                 f"s = {s:g} < 1: the contact took energy, "
                                 "E_d / M = v_i^2 (1 - s^2) / 2 > 0"))
    return pd.DataFrame(rows, columns=list(COLUMNS))


# what paper_targets(quantities=...) needs for every check: Table 2, the NBs excursions of
# Sect. 3.2, Tables 3 and 4
CONSISTENCY_QUANTITIES = ("nu_r", "alpha", "eta", "e", "excursion_max_m", "contact_time_ms", "restitution",
                          "dissipated_energy_per_mass")


def _excursion(conf: str, q: dict, a_t: float, gap_total_m: float,
               omega_min_rad_s: float) -> tuple[float, float] | None:
    """``(E, allowed)`` in m: ``excursion_max_m``, or from ``eta`` (YBs) or ``e`` (NBs); or None."""
    if "excursion_max_m" in q:
        return q["excursion_max_m"]
    if conf == "YBs" and "eta" in q:
        return q["eta"][0] * gap_total_m, q["eta"][1] * gap_total_m
    if conf == "NBs" and "e" in q:
        d_tmax = a_t / omega_min_rad_s ** 2
        return q["e"][0] * d_tmax, q["e"][1] * d_tmax
    return None


def _row(key: dict, check: str, kind: str, quantity: str, measured: tuple[float, float], bound: float,
         explanation: str) -> dict:
    value, allowed = measured
    margin = (value - bound) / allowed if allowed > 0 else (np.inf if value >= bound else -np.inf)
    return {**key, "check": check, "kind": kind, "quantity": quantity, "measured": value, "allowed": allowed,
            "bound": bound, "consistent": bool(value + allowed >= bound), "margin": margin,
            "explanation": explanation}
