"""
Rigid moat walls in plan: impulses at the corners, corners held on a wall
==========================================================================

The two-storey building of the earlier examples, its masses 3 m off centre, in a moat 8 cm wide whose walls
are rigid stops: a corner that reaches a wall is struck by an impulse along its line, ``x - y_c theta``, which
turns the floor as it stops the corner (Newton's law with the restitution ``e``); two corners meeting a wall
flat are struck at one instant (Moreau's law); a corner met at rest and pushed on is held on the wall, the
floor turning about it, until the wall's force comes back to zero. Beside them, the same building against
concrete walls behind a stiff pad (a Kelvin-Voigt law), each contact followed through its few milliseconds:
after the first contacts the three motions part ways, each wall sending the building off differently.
"""

import matplotlib.pyplot as plt
import numpy as np

import pounding
from pounding import Bearing, Floor, Frame, PlanBuilding, RectangularMoat

lrb = pounding.Isolator(slopes_n_m=[1.2e7, 1.2e6], breakpoints_m=[0.01], damping_n_s_m=3.0e4)
bearings = [Bearing((sx * 14.0, sy * 5.0), lrb) for sx in (-1, 1) for sy in (-1, 1)]
frames = [Frame(s, "x", y, 4.0e8, 1.0e5) for s in (1, 2) for y in (-6.0, 6.0)]
frames += [Frame(s, "y", x, k, 1.0e5) for s in (1, 2) for x, k in ((-15.0, 9.0e8), (15.0, 3.0e8))]
floors = [Floor(4.0e5, (30.0, 12.0), centre_m=(3.0, 0.0))] * 3


def building(law):
    return PlanBuilding(floors, bearings, frames, RectangularMoat(gap_m=0.08, law=law))


quake = pounding.RecordPair.of_direction(pounding.records.el_centro().scaled(pga_g=0.5), 60.0)
walls = {"rigid, e = 0.6": pounding.RigidStop(0.6), "rigid, e = 0 (plastic)": pounding.RigidStop(0.0),
         "concrete behind a pad": pounding.KelvinVoigt(stiffness=5.0e9, damping=2.0e6)}
runs = {name: pounding.simulate(building(law), quake, duration=15.0) for name, law in walls.items()}
for name, run in runs.items():
    print(f"{name}: {run.message} {len(run.contacts)} contacts, the largest bearing displacement "
          f"{run.bearing_displacement_max_m.max() * 1e3:.1f} mm")

# %%
# Where and when each corner struck (the plastic walls' first contacts): the wall, the corner, the place
# along the wall, the impulse (a hold's row: from its start to its release, its impulse over that time).
columns = ["wall", "corner", "at_m", "t_start_s", "t_end_s", "impulse_n_s"]
print(runs["rigid, e = 0 (plastic)"].contacts[columns].head(8).round(4).to_string())

# %%
# The corners' orbits inside the plastic walls' moat (crosses: where contacts began; a held corner runs
# along its wall).
runs["rigid, e = 0 (plastic)"].plot()

# %%
# The contacts' instants against the moat: the rigid walls' impacts among the pad's contacts.
fig, ax = plt.subplots(figsize=(7, 2.6), constrained_layout=True)
for row, (name, run) in enumerate(runs.items()):
    t = run.contacts.t_start_s.to_numpy()
    ax.plot(t, np.full(t.size, row), "|", ms=14, label=name)
ax.set_yticks(range(len(runs)), list(runs))
ax.set_xlabel("time (s)")
ax.set_ylim(-0.7, len(runs) - 0.3)
plt.show()
