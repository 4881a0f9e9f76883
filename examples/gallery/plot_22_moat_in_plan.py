"""
A moat's gap in plan: seven pairs, every orientation, and the code's torsion
============================================================================

The two-storey building of the previous example, its masses 3 m off centre, at an ASCE 7-16 site with S_DS =
1.0 g and S_D1 = 0.6 g. Seven pairs of the FEMA P695 far-field set are scaled together so that their mean
maximum-direction spectrum (RotD100) is nowhere below the MCE_R spectrum from 0.75 to 1.25 times the isolated
period (ASCE 7-16 17.3.3): the bearings' effective period at the code's maximum displacement D_M, which their
effective stiffness and damping there give (found by iteration). Each pair is turned to every orientation from
0 to 165 degrees in the building's axes, the moat taken away; its most critical orientation gives its largest
bearing displacement in plan, and the mean of the seven is the design displacement (17.6.3.3), with the moat's
demand beside it (its corners' largest displacement towards a wall). Beside it, the code's total maximum
displacement with torsion, D_TM, from D_M and the building's actual and 5 % accidental eccentricity (17.5-3).
"""

import matplotlib.pyplot as plt
import numpy as np

import pounding
from pounding import Bearing, Floor, Frame, PlanBuilding, RectangularMoat, design

lrb = pounding.Isolator(slopes_n_m=[1.2e7, 1.2e6], breakpoints_m=[0.01], damping_n_s_m=3.0e4)
bearings = [Bearing((sx * 14.0, sy * 5.0), lrb) for sx in (-1, 1) for sy in (-1, 1)]
frames = [Frame(s, "x", y, 4.0e8, 1.0e5) for s in (1, 2) for y in (-6.0, 6.0)]
frames += [Frame(s, "y", x, k, 1.0e5) for s in (1, 2) for x, k in ((-15.0, 9.0e8), (15.0, 3.0e8))]
moat = RectangularMoat(gap_m=0.3, law=pounding.KelvinVoigt(stiffness=5.0e8, damping=1.0e6))
building = PlanBuilding([Floor(4.0e5, (30.0, 12.0), centre_m=(3.0, 0.0))] * 3, bearings, frames, moat)

code = design.asce7_bearings_displacement(building, s_m1_g=1.5 * 0.6)  # D_M, T_M, beta_M
t_m, d_m = code["t_m_x_s"], code["d_m_m"]
print(f"T_M {t_m:.2f} s, beta_M {code['beta_m_x']:.3f}, D_M {d_m:.3f} m")
mce = design.asce7_spectrum(1.0, 0.6, level="mce")
pairs = pounding.records.fema_p695_pairs("far_field")[:7]
suite = design.scale_suite(pairs, mce, period_range_s=(0.75 * t_m, 1.25 * t_m))
print(suite)
found = design.moat_design(building, list(suite.records), duration_s=20.0, d_m_m=d_m)
print(found.critical.round(3))
print(f"design displacement {found.design_displacement_m:.3f} m ({found.attrs['rule']} of 7 pairs), the "
      f"moat's demand {found.moat_demand_m:.3f} m; code D_M {d_m:.3f} m, D_TM {found.code['d_tm_m']:.3f} m "
      f"(P_T {found.code['p_t']:.2f})")

# %%
# Each pair's critical bearing displacement in plan, the design value and the code's.
found.plot()

# %%
# How the orientation changes each pair's largest bearing displacement in plan.
fig, ax = plt.subplots(figsize=(6, 3.4), constrained_layout=True)
for name, group in found.data.groupby(level="pair"):
    angles = group.index.get_level_values("angle_deg")
    ax.plot(angles, group["disp_max_m"] * 1e3, marker=".", lw=1, label=str(name)[:24])
ax.axhline(found.design_displacement_m * 1e3, color="k", lw=1.2, ls="--", label="design (mean)")
ax.set_xticks(np.arange(0, 180, 30))
ax.set_xlabel("orientation of the pair, degrees from the building's x axis")
ax.set_ylabel("largest bearing displacement in plan (mm)")
ax.legend(fontsize=6, ncol=2)
plt.show()
