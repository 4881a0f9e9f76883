"""Index constants shared by the compiled kernels and their Python wrapper.

Numba freezes module-level integers as compile-time constants, so these are safe to use
inside ``@jit`` functions and cost nothing.
"""

import numpy as np

from ..model.contact_laws import N_LAW_PARAMS, N_LAW_STATE
from ..model.isolator import BW_PARAMS

# ---- state vector (float64), length STATE_BASE + 2 * (n_branches - 1)
T = 0            # time, s
D = 1            # displacement relative to the table, m
V = 2            # velocity relative to the table, m/s
DEF_L = 3        # compression of the left bumper, m (>= 0)
DEF_R = 4        # compression of the right bumper, m
IN_L = 5         # 1.0 while in contact with the left bumper
IN_R = 6         # 1.0 while in contact with the right bumper
REGION = 7       # backbone branch of the elastic rule: 0 centre, +-j the j-th outer branch
ACC_L = 8        # contact accumulators of the left bumper (N_ACC values)
ACC_R = 15       # ... of the right bumper
N_ACC = 7
A_TSTART, A_VIN, A_DSTART, A_IMPULSE, A_PEAK, A_MAXCOMP, A_WORK = 0, 1, 2, 3, 4, 5, 6
Z_L = 22         # the left bumper's law state, N_LAW_STATE values (contact_laws; 0 for a stateless law)
Z_R = Z_L + N_LAW_STATE  # ... the right one's
ZETA = Z_R + N_LAW_STATE  # the isolator's Bouc-Wen variable z (0 without one)
STATE_BASE = ZETA + 1  # then u_i (n-1 plastic slips, m), then s_i (n-1 slip directions, -1/0/+1)
ZL_AT, ZR_AT = np.int64(Z_L), np.int64(Z_R)  # as offsets for the law_* functions (typed)

# ---- phase descriptor (float64), see _linear.py and _numeric.py
P_M, P_C, P_K, P_P0, P_P1, P_H, P_W, P_PHI = 0, 1, 2, 3, 4, 5, 6, 7
P_S, P_Q2, P_ROOT, P_B0, P_B1, P_B2, P_B3, P_ZR, P_ZI, P_Y0, P_Y1 = 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18
P_D0, P_V0, P_MODE, P_NLL, P_NLR, P_GAPL, P_GAPR = 19, 20, 21, 22, 23, 24, 25
P_LAWL = 26                                   # left law id, then its N_LAW_PARAMS parameters
P_PL = P_LAWL + 1
P_LAWR = P_PL + N_LAW_PARAMS                  # right law id and parameters
P_PR = P_LAWR + 1
PL_AT, PR_AT = np.int64(P_PL), np.int64(P_PR)  # as offsets for the law_* functions (typed)
P_DL0 = P_PR + N_LAW_PARAMS
P_DR0, P_CD, P_AX0, P_AX1, P_AXH = P_DL0 + 1, P_DL0 + 2, P_DL0 + 3, P_DL0 + 4, P_DL0 + 5
P_INL, P_INR, P_KISO, P_RISO = P_DL0 + 6, P_DL0 + 7, P_DL0 + 8, P_DL0 + 9
P_SPHI, P_CPHI = P_DL0 + 10, P_DL0 + 11       # sin and cos of the forcing phase
# a linear law's branch in this phase, per side: F = k x + r + c x' (law_linear_branch)
P_KBL, P_CBL, P_RBL, P_JBL = P_DL0 + 12, P_DL0 + 13, P_DL0 + 14, P_DL0 + 15
P_KBR, P_CBR, P_RBR, P_JBR = P_DL0 + 16, P_DL0 + 17, P_DL0 + 18, P_DL0 + 19
# the transcendental values at the end tau = h of a full sub-interval, reused while the
# phase's (h, w, s, q2) stay the same: see _linear.py
P_NKEY = P_DL0 + 20  # h, w, s, q2 the end values were computed for (4 values)
P_NODE = P_NKEY + 4  # sin(w h), cos(w h), and the free response's two terms at h
# ... and those of the last phases met (a steady motion cycles through a few), 8 values each
P_ENDS = P_NODE + 4
N_ENDS = 8
P_ENDS_NEXT = P_ENDS + 8 * N_ENDS   # the slot the next new phase takes
# the run's length (m) and velocity (m/s) scales, set once per run (_kernel.run_scales), and
# the phase's: the larger of those and the sizes of the terms its closed form adds (a nearly
# resonant particular solution of 50 m cancelled by the free response to 1e-8 m).  What the
# bumpers' event values are rounded against, not the displacement itself
P_XRUN = P_ENDS_NEXT + 1
P_VRUN = P_ENDS_NEXT + 2
P_XROUND = P_ENDS_NEXT + 3
P_VROUND = P_ENDS_NEXT + 4
P_LZL = P_ENDS_NEXT + 5  # the bumpers' law states (Z_L, Z_R: N_LAW_STATE values each) for this phase
P_LZR = P_LZL + N_LAW_STATE
PZL_AT, PZR_AT = np.int64(P_LZL), np.int64(P_LZR)
P_BW = P_LZR + N_LAW_STATE  # the isolator's Bouc-Wen spring (BW_PARAMS values: force scale 0 for none)
P_ZETA0 = P_BW + BW_PARAMS  # its z at the phase start
# the last Dormand-Prince step of a numerical phase: its length (-1: none yet) and its 7 results
# (the kernel, the event rows and the rates ask for the step at the sub-interval's end again and again)
P_DP5_H = P_ZETA0 + 1
P_DP5 = P_DP5_H + 1
# the phase's restoring force at D = 0 (isolator branch and linear bumper branches, N): with
# M, c, k it is all a record's next piece needs to continue the phase (_kernel.run_kernel)
P_R0 = P_DP5 + 7
PH_LEN = P_R0 + 1
MODE_LINEAR = 0.0
MODE_NUMERIC = 1.0

# ---- events: rows of (kind, alpha, beta, gamma, relax_side, action, index, direction)
E_KIND, E_ALPHA, E_BETA, E_GAMMA, E_SIDE, E_ACTION, E_INDEX, E_DIR = 0, 1, 2, 3, 4, 5, 6, 7
EV_COLS = 8
KIND_LINEAR = 0   # g = alpha + beta D + gamma V (+ compression of the relaxing bumper E_SIDE)
KIND_RELEASE = 1  # the contact law's release function on side E_SIDE
KIND_ZETA = 2     # the isolator's Bouc-Wen z times alpha (its sign at the phase start): where z crosses 0
# Codes that compiled functions pass to each other as arguments are typed integers
# (np.int64), not Python ints: Numba gives a Python-int constant argument a literal type
# and compiles the callee once more for each literal value (see _jit.py).
SIDE_NONE, SIDE_L, SIDE_R = np.int64(-1), np.int64(0), np.int64(1)
ACT_YIELD, ACT_REVERSAL, ACT_REGION, ACT_CONTACT, ACT_RELEASE, ACT_LAW_BRANCH, ACT_BOUC_WEN = (
    np.int64(k) for k in range(7))
EVENT_NAMES = ("yield", "reversal", "branch", "contact_start", "contact_end", "bumper_branch",
               "bouc_wen_zero")

# ---- outputs
SAMPLE_COLS = 7   # t, D, V, abs_acceleration, isolator_force, bumper_force_left, bumper_force_right
CONTACT_COLS = 9  # side, t_start, t_end, v_in, v_out, impulse, peak_force, max_compression, work
EVENT_COLS = 3    # t, action, index
# the energy ledger's slots, J: work of the input, dissipated by the dashpot, the isolator's hysteresis
# and the bumpers, and the changes of the kinetic, the isolator's and the bumpers' elastic energies
L_INPUT, L_VISCOUS, L_HYSTERETIC, L_BUMPER_LOSS, L_KINETIC, L_ISOLATOR, L_BUMPER = range(7)
LEDGER_LEN = 7

# ---- run control (int64 array shared between Python and the kernels, see _control.py)
from .._control import CTL_BUDGET, CTL_HELD, CTL_LEN, CTL_STOP, CTL_WORK  # noqa: E402,F401  (pounding._control's)
