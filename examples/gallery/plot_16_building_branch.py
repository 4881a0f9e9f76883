"""
A building's periodic response: its branch, its folds and the shaking table's jumps
===================================================================================

A two-level building (a 2 t base on a linear isolator, a 1 t storey above it) in a moat 2 cm wide whose
soft wall is a Kelvin-Voigt law. At a_G = 0.05 g its periodic response is followed from 1 to 2.5 Hz by
continuation: every orbit found by Newton shooting, its Floquet multipliers from the exact monodromy of the
two-mass system (a saltation matrix at each contact with the wall), the branch's folds and its grazings
(the base just touching the wall) located. Over it, the shaking table's view: a stepped sine up and down,
the base's state at table phase 0 recorded after each frequency's transient. The sweeps jump at the folds,
and between them two responses coexist: pounding the wall, or free.
"""

import matplotlib.pyplot as plt
import numpy as np

import pounding

isolator = pounding.Isolator(slopes_n_m=[2.0e5], breakpoints_m=[], damping_n_s_m=4.0e3)
wall = pounding.Wall(level=0, gap_left_m=0.02, gap_right_m=0.02,
                     law=pounding.KelvinVoigt(stiffness=2.0e6, damping=2.0e3))
storey = pounding.Storey(mass_kg=1.0e3, stiffness_n_m=2.0e6, damping_n_s_m=2.0e3)
building = pounding.Structure(base_mass_kg=2.0e3, isolator=isolator, storeys=[storey], walls=[wall])
branch = pounding.continuation(building, 0.05, (1.0, 2.5))
print(branch.message)
print(branch.bifurcation_table()[["kind", "side", "freq_hz", "alpha"]].round(4).to_string(index=False))

diagram = pounding.bifurcation_diagram(building, 0.05, np.arange(1.0, 2.51, 0.05), transient_cycles=60,
                                       record_cycles=10)
fig, (top, bottom) = plt.subplots(2, 1, figsize=(7.0, 7.0), constrained_layout=True)
diagram.plot(ax=top, branches=branch, level=0)
top.set_title("the base at table phase 0: sweeps (markers) on the branch (lines)", fontsize="medium")
branch.plot(ax=bottom, y="alpha")
bottom.set_title("the largest alpha over both levels along the branch; unstable dashed", fontsize="medium")

# %%
# Between the folds both responses exist. From rest the building settles on the free one; the branch holds
# the pounding one too: its stable orbit nearest the middle, every level in its phase plane.
folds = sorted(b.freq_hz for b in branch.folds())
middle = 0.5 * (folds[0] + folds[1])
free = pounding.periodic_orbit(building, pounding.Harmonic(0.05, middle))
print(f"from rest at {middle:.3f} Hz: {free.contacts_per_period} contacts, alpha over the levels "
      f"{free.run.abs_acceleration_max.max() / free.run.excitation.peak_m_s2:.2f}")
rows = branch.to_dataframe()
pounding_rows = rows[rows["stable"] & (rows["contacts_per_period"] > 0)]
i = int((pounding_rows["freq_hz"] - middle).abs().idxmin())
orbit = branch.orbit(i)
print(orbit.message, f"at {rows['freq_hz'][i]:.3f} Hz: max |mu| = {orbit.max_abs_multiplier:.3f}, "
      f"{orbit.contacts_per_period} contacts per period")
orbit.plot()
plt.show()
