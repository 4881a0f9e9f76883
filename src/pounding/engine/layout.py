"""The state vector's offsets, the events' codes and the outputs' columns, as the compiled core writes them
(``pounding._core.LAYOUT``: the core defines them, Python reads them by these names).

The state vector (float64) of a one-mass system: ``T`` time, ``D`` displacement, ``V`` velocity, the two
contacts' (left, right) compressions ``DEF_L``, ``DEF_R`` and contact flags ``IN_L``, ``IN_R``, the elastic
isolator's branch ``REGION``, each contact's running totals (``ACC_L``, ``ACC_R``: ``N_ACC`` values at the
``A_*`` offsets) and law state (``Z_L``, ``Z_R``: ``N_LAW_STATE`` values), the Bouc-Wen ``ZETA``, then from
``STATE_BASE`` the kinematic isolator's slips and slip directions.
"""

from __future__ import annotations

import math

import numpy as np

from .._control import CTL_BUDGET, CTL_LEN, CTL_STOP, CTL_WORK  # noqa: F401  (pounding._control's)
from .._core import ACTIONS, CONTACT_COLUMNS, DOF_EXTREMA, EVENT_COLUMNS, LAYOUT, LEDGER, PAIR_EXTREMA  # noqa: F401

T, D, V = LAYOUT["T"], LAYOUT["D"], LAYOUT["V"]
DEF_L, DEF_R = LAYOUT["DEF"], LAYOUT["DEF"] + 1
IN_L, IN_R = LAYOUT["IN"], LAYOUT["IN"] + 1
REGION = LAYOUT["REGION"]
N_ACC = LAYOUT["N_ACC"]
ACC_L, ACC_R = LAYOUT["ACC"], LAYOUT["ACC"] + N_ACC
A_TSTART, A_VIN, A_DSTART, A_IMPULSE, A_PEAK, A_MAXCOMP, A_WORK = (
    LAYOUT[k] for k in ("A_TSTART", "A_VIN", "A_DSTART", "A_IMPULSE", "A_PEAK", "A_MAXCOMP", "A_WORK"))
N_LAW_STATE = LAYOUT["N_LAW_STATE"]
Z_L, Z_R = LAYOUT["Z"], LAYOUT["Z"] + N_LAW_STATE
ZETA = LAYOUT["ZETA"]
STATE_BASE = LAYOUT["STATE_BASE"]

# the events' actions: an event table's second column (the core's enum Action)
EVENT_NAMES = tuple(sorted(ACTIONS, key=ACTIONS.__getitem__))  # by code: EVENT_NAMES[code]
ACT_YIELD, ACT_REVERSAL, ACT_REGION, ACT_CONTACT, ACT_RELEASE, ACT_LAW_BRANCH, ACT_BOUC_WEN = (
    ACTIONS[k] for k in ("yield", "reversal", "branch", "contact_start", "contact_end", "bumper_branch",
                         "bouc_wen_zero"))
SIDE_L, SIDE_R = 0, 1  # a contact's index: the left and the right bumper

# outputs
SAMPLE_COLS = LAYOUT["SAMPLE_COLS"]    # t, D, V, abs_acceleration, isolator_force, bumper forces left, right
# a contact table's columns (CONTACT_COLUMNS: slot, t_start_s, t_end_s, v_in_m_s, v_out_m_s, impulse_n_s,
# peak_force_n, max_compression_m, bumper_dissipation_j), those read by name here
CONTACT_COLS = LAYOUT["CONTACT_COLS"]
C_SLOT, C_T_START, C_T_END, C_V_IN, C_MAX_COMPRESSION = (
    CONTACT_COLUMNS[k] for k in ("contact", "t_start_s", "t_end_s", "v_in_m_s", "max_compression_m"))
EVENT_COLS = LAYOUT["EVENT_COLS"]
E_T, E_ACTION, E_INDEX = (EVENT_COLUMNS[k] for k in ("t_s", "action", "index"))  # an event table's columns
# the energy ledger's slots, J: work of the input, dissipated by the dashpot, the isolator's hysteresis and
# the bumpers, and the changes of the kinetic, the isolator's and the bumpers' elastic energies
L_INPUT, L_VISCOUS, L_HYSTERETIC, L_BUMPER_LOSS, L_KINETIC, L_ISOLATOR, L_BUMPER = (
    LEDGER[k] for k in ("input", "viscous", "hysteretic", "bumper_loss", "kinetic", "isolator", "bumper"))
# a run's exact extrema (``RunOutput.per_dof``'s columns): a dof's displacement max and its time, min and its
# time, its absolute acceleration's largest magnitude and its time; a tracked pair's (``per_pair``) the same
X_D_MAX, X_D_MAX_T, X_D_MIN, X_D_MIN_T, X_A_MAX, X_A_MAX_T = (
    DOF_EXTREMA[k] for k in ("d_max", "d_max_t", "d_min", "d_min_t", "a_abs_max", "a_abs_max_t"))
P_MAX, P_MAX_T, P_MIN, P_MIN_T = (PAIR_EXTREMA[k] for k in ("max", "max_t", "min", "min_t"))
DOF_EXTREMA_LEN = LAYOUT["DOF_EXTREMA"]
LEDGER_LEN = LAYOUT["LEDGER_LEN"]


def impulses(table: np.ndarray) -> np.ndarray:
    """Which rows of a contact table are a rigid stop's impacts (instantaneous: an impulse, no force)."""
    return table[:, CONTACT_COLUMNS["t_end_s"]] == table[:, CONTACT_COLUMNS["t_start_s"]]


def force_max(table: np.ndarray) -> float:
    """A contact table's largest force, N: 0 without contact, inf where a rigid stop was struck (an impulse's
    force is unbounded; its impulse is in the table)."""
    if not len(table):
        return 0.0
    return math.inf if impulses(table).any() else float(table[:, CONTACT_COLUMNS["peak_force_n"]].max())
