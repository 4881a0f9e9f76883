"""
A building in plan: torsion, a corner against the moat
=======================================================

A two-storey building 30 m by 12 m on four lead-rubber bearings, inside a moat 15 cm wide, shaken by El
Centro 1940 at 0.5 g along 60 degrees from its long side. Its floors' centres of mass lie 3 m off the centre
of its plan: it twists as it sways, and its corners strike the moat where the twist carries them. Each
corner's path in plan is drawn inside the moat's clearance, and each bearing's largest displacement in plan
(the vector sum of its two directions at each instant, located exactly) is what the gap must exceed. The
same building with its masses centred stays clear of the moat, and its corner bearings move less.
"""

import matplotlib.pyplot as plt
import numpy as np

import pounding
from pounding import Bearing, Floor, Frame, PlanBuilding, RectangularMoat

lrb = pounding.Isolator(slopes_n_m=[1.2e7, 1.2e6], breakpoints_m=[0.01], damping_n_s_m=3.0e4)
bearings = [Bearing((sx * 14.0, sy * 5.0), lrb) for sx in (-1, 1) for sy in (-1, 1)]
frames = [Frame(s, "x", y, 4.0e8, 1.0e5) for s in (1, 2) for y in (-6.0, 6.0)]
frames += [Frame(s, "y", x, k, 1.0e5) for s in (1, 2) for x, k in ((-15.0, 9.0e8), (15.0, 3.0e8))]
moat = RectangularMoat(gap_m=0.15, law=pounding.KelvinVoigt(stiffness=5.0e8, damping=1.0e6))


def building(centre_m):
    return PlanBuilding([Floor(4.0e5, (30.0, 12.0), centre_m=centre_m)] * 3, bearings, frames, moat)


quake = pounding.RecordPair.of_direction(pounding.records.el_centro().scaled(pga_g=0.5), 60.0)
eccentric = building((3.0, 0.0))
print("eccentricities [m]:", eccentric.eccentricities_m().round(2).tolist())
run = pounding.simulate(eccentric, quake, duration=20.0)
print(run.message, f"{len(run.contacts)} contacts with the moat")
print(run.bearings()[["at_x_m", "at_y_m", "displacement_max_m", "displacement_max_time_s"]].round(3))

# %%
# The corners' orbits inside the moat's clearance (crosses: where contacts began).
run.plot()

# %%
# Each bearing's largest displacement in plan, the masses 3 m off centre and centred.
centred = pounding.simulate(building((0.0, 0.0)), quake, duration=20.0)
print(f"centred: {len(centred.contacts)} contacts")
fig, ax = plt.subplots(figsize=(6, 3.2), constrained_layout=True)
x = np.arange(len(bearings))
ax.bar(x - 0.2, run.bearing_displacement_max_m * 1e3, 0.4, label="masses 3 m off centre")
ax.bar(x + 0.2, centred.bearing_displacement_max_m * 1e3, 0.4, label="masses centred")
ax.axhline(150.0, color="k", lw=1, ls="--", label="moat gap")
ax.set_xticks(x, [f"({b.at_m[0]:g}, {b.at_m[1]:g})" for b in bearings])
ax.set_xlabel("bearing at (x, y), m")
ax.set_ylabel("largest displacement in plan (mm)")
ax.legend(fontsize=8, loc="lower right")
plt.show()
