"""
A circular moat: a ring struck at the corners
=============================================

The two-storey building of the previous examples (30 m by 12 m, its masses 3 m off the centre of its plan,
on four lead-rubber bearings) inside two moats of the same clearance at its corners, 20 cm: four walls, and
a ring around its base. Shaken by El Centro 1940 at 0.8 g along 60 degrees, its base moves 0.45 m in plan
and turns. A wall is struck where a corner's motion across it reaches its gap; the ring where a corner's
distance from its centre reaches its radius (the rectangle's half-diagonal plus the gap), along the ring's
normal. Each corner's clearance to the ring is drawn as that corner meets it: an arc 20 cm beyond where
the corner started, along its diagonal.
"""

import matplotlib.pyplot as plt

import pounding
from pounding import Bearing, CircularMoat, Floor, Frame, PlanBuilding, RectangularMoat

iso = pounding.Isolator(slopes_n_m=[1.2e7, 1.2e6], breakpoints_m=[0.01], hysteresis="kinematic",
                        damping_n_s_m=3.0e4)
bearings = [Bearing((sx * 14.0, sy * 5.0), iso) for sx in (-1, 1) for sy in (-1, 1)]
frames = [Frame(s, "x", y, 4.0e8, 1.0e5) for s in (1, 2) for y in (-6.0, 6.0)]
frames += [Frame(s, "y", x, k, 1.0e5) for s in (1, 2) for x, k in ((-15.0, 9.0e8), (15.0, 3.0e8))]
floors = [Floor(4.0e5, (30.0, 12.0), centre_m=(3.0, 0.0))] * 3
pad = pounding.KelvinVoigt(stiffness=5.0e8, damping=1.0e6)
building = PlanBuilding(floors, bearings, frames, CircularMoat(gap_m=0.2, law=pad))
walls = PlanBuilding(floors, bearings, frames, RectangularMoat(gap_m=0.2, law=pad))
print(f"the ring's radius: {building.moat.radius_m(floors[0]):.3f} m")
quake = pounding.RecordPair.of_direction(pounding.records.el_centro().scaled(pga_g=0.8), 60.0)
runs = {"four walls": pounding.simulate(walls, quake, duration=12.0, sample_rate_hz=200.0),
        "a ring": pounding.simulate(building, quake, duration=12.0, sample_rate_hz=200.0)}
for name, run in runs.items():
    print(f"{name}: {len(run.contacts)} contacts, smallest clearance {1e3 * run.clearance_m.min():.1f} mm, "
          f"largest bearing displacement {1e3 * run.bearing_displacement_max_m.max():.0f} mm")
print(runs["a ring"].contacts[["corner", "at_m", "t_start_s", "peak_force_n"]].round(3))

# %%
# The corners' orbits against each moat.
fig, axes = plt.subplots(1, 2, figsize=(11, 4.4), constrained_layout=True)
for ax, (name, run) in zip(axes, runs.items()):
    run.plot(ax=ax)
    ax.set_title(name, fontsize=9)
    ax.legend().remove()
plt.show()
