"""
How wide a moat: a building's sweep and its pounding spectrum
==============================================================

The three-storey building of ``examples/building_moat.toml`` on the shaking table: a stepped-sine sweep at
0.3 g with its moat wall 10 cm away, each step held until the whole building's motion repeats (or 500
cycles: where it pounds, two steps never settle, and their window is the last 5 cycles), each level's alpha
(its peak absolute acceleration over the table's) measured exactly over the window. Then its pounding
spectrum under El Centro at 0.6 g: the largest storey drift ratio against the superstructure's fixed-base
period, for moats of 5, 10 and 20 cm, and without a wall.
"""

import matplotlib.pyplot as plt
import numpy as np

import pounding

isolator = pounding.Isolator(slopes_n_m=[4.0e6, 1.0e6], breakpoints_m=[0.02], damping_n_s_m=2.0e4)
storeys = [pounding.Storey(mass_kg=2.0e4, stiffness_n_m=4.0e7, damping_n_s_m=4.0e4)] * 3
moat = pounding.Wall(level=0, gap_left_m=0.10, gap_right_m=0.10,
                     law=pounding.KelvinVoigt(stiffness=2.0e8, damping=1.0e5))
building = pounding.Structure(base_mass_kg=3.0e4, isolator=isolator, storeys=storeys, walls=[moat])
sweep = pounding.sweep(building, a_g=0.3, freqs_hz=np.arange(0.3, 1.61, 0.1))
print(sweep.message)
print(f"the roof's alpha peaks at {sweep.resonance_of(level=-1):g} Hz, the base's at "
      f"{sweep.resonance_of(level=0):g} Hz")
sweep.plot()

# %%
# The pounding spectrum: the superstructure stiffened or softened to each period (its storeys' damping
# ratios kept, the isolator as it is), the moat at each gap.
quake = pounding.records.el_centro().scaled(pga_g=0.6)
periods = np.arange(0.2, 1.01, 0.1)
spectrum = pounding.pounding_spectrum([quake], periods, gaps_m=[0.05, 0.10, 0.20], structure=building)
ds = spectrum.data.isel(record=0)
fig, ax = plt.subplots(figsize=(6.5, 3.6), constrained_layout=True)
for gap in ds["gap_m"].values:
    ax.plot(periods, 100 * ds["drift_ratio_max"].sel(gap_m=gap), "o-", label=f"moat {gap * 100:g} cm")
ax.plot(periods, 100 * ds["drift_ratio_max_free"], "k--", label="no wall")
ax.set_xlabel("superstructure's fixed-base period (s)")
ax.set_ylabel("largest storey drift ratio (%)")
ax.legend()
