"""
A building on isolators against its moat wall
=============================================

A three-storey shear building on a bilinear isolator, in a moat 10 cm wide around its base, under El
Centro 1940 scaled to a PGA of 0.6 g. The base hits the moat wall a few times: each impact is located on
the exact trajectory, and the floors' accelerations jump with it (the same building is
``examples/building_moat.toml``). The envelopes on the right are the exact
peaks of each level (located on the trajectory, not read from the samples).
"""

import matplotlib.pyplot as plt

import pounding

isolator = pounding.Isolator(slopes_n_m=[4.0e6, 1.0e6], breakpoints_m=[0.02], damping_n_s_m=2.0e4)
storeys = [pounding.Storey(mass_kg=2.0e4, stiffness_n_m=4.0e7, damping_n_s_m=4.0e4)] * 3
moat = pounding.Wall(level=0, gap_left_m=0.10, gap_right_m=0.10,
                     law=pounding.KelvinVoigt(stiffness=2.0e8, damping=1.0e5))
building = pounding.Structure(base_mass_kg=3.0e4, isolator=isolator, storeys=storeys, walls=[moat])
print(f"isolated periods {building.modes().periods_s.round(3)} s, "
      f"fixed base {building.modes(fixed_base=True).periods_s.round(3)} s")
quake = pounding.records.el_centro().scaled(pga_g=0.6)
run = pounding.simulate(building, quake, duration=31.0)
print(run.message, f"{len(run.contacts)} contacts with the moat wall")
print(run.peaks().round(4))

# %%
# Each level against time (dotted: the contacts' starts), and the peak envelopes over the height.
run.plot()

# %%
# The same building in a moat twice as wide: no contact, and the floors' accelerations fall.
wide = pounding.Structure(building.base_mass_kg, building.isolator, building.storeys,
                          [pounding.Wall(0, 0.20, 0.20, building.walls[0].law)])
calm = pounding.simulate(wide, quake, duration=31.0)
fig, ax = plt.subplots(figsize=(6, 3.2), constrained_layout=True)
levels = range(building.n_levels)
ax.plot(run.abs_acceleration_max / 9.81, levels, "o-", label=f"moat 10 cm ({len(run.contacts)} contacts)")
ax.plot(calm.abs_acceleration_max / 9.81, levels, "s--", label=f"moat 20 cm ({len(calm.contacts)} contacts)")
ax.set_yticks(list(levels), ["base", "1", "2", "3"])
ax.set_xlabel("peak absolute acceleration (g)")
ax.set_ylabel("level")
ax.legend()
