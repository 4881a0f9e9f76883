"""
A triple friction pendulum: its stages, and rigid or stiff rings
================================================================

A four-storey building on a triple friction pendulum (:class:`pounding.TripleFrictionPendulum`: four
sliding surfaces, each with its radius, friction coefficient and ring). Its stiffness and damping change
with the amplitude in five stages, which follow from the events where each surface slips and reaches its
ring; none of them is tabulated. The bearing's rings are rigid by default: a record strong enough to use up
the whole travel stops the run there (``Status.CAPACITY``). With ``ring_stiffness_n_m`` each ring gives,
and the bearing slides on past its travel, stiffer.
"""

import matplotlib.pyplot as plt
import numpy as np

import pounding

numbers = dict(radii_m=(2.1, 0.3, 0.3, 2.1), mu=(0.05, 0.02, 0.02, 0.08),
               capacities_m=(0.35, 0.05, 0.05, 0.35))
storeys = [pounding.Storey(30_000.0, 6.0e7, 1.0e5)] * 4
rigid = pounding.Structure(40_000.0, pounding.TripleFrictionPendulum(**numbers), storeys, [])
stiff = pounding.Structure(40_000.0, pounding.TripleFrictionPendulum(**numbers, ring_stiffness_n_m=2.0e7),
                           storeys, [])
print("stages' stiffnesses [kN/m]:", np.round(np.array(rigid.isolator.slopes_n_m) / 1e3, 1).tolist())
print("stage changes [m]:", np.round(rigid.isolator.breakpoints_m, 3).tolist(),
      f"(the travel: {rigid.isolator.travel_m:.2f} m)")

# %%
# The slide from rest, both ways: stages I to V with rigid rings, ending at the travel; with stiff rings
# the slide goes on past it.
u = np.linspace(-1.2, 1.2, 1201)
fig, ax = plt.subplots(figsize=(6, 4))
ax.plot(u * 1e3, stiff.isolator.backbone(u) / 1e3, color="C1", label="stiff rings (2e7 N/m)")
ax.plot(u * 1e3, rigid.isolator.backbone(u) / 1e3, color="C0", lw=2, label="rigid rings")
ax.set_xlabel("displacement [mm]")
ax.set_ylabel("force [kN]")
ax.legend()
fig.tight_layout()

# %%
# El Centro at 1.5 g: with rigid rings the bearing uses up its travel and the run stops there, saying so;
# with stiff rings it goes on. The events name each surface's slip (``surface_slip``), its ring's entry
# (``ring``) and its exit (``ring_off``).
record = pounding.records.el_centro().scaled(pga_g=1.5)
for name, building in (("rigid", rigid), ("stiff", stiff)):
    run = pounding.simulate(building, record, duration=record.duration_s)
    s = run.summary()
    print(f"{name} rings: {run.status.name} at t = {s['t_end_s']:.2f} s, base peak "
          f"{max(s['displacement_max_m'], -s['displacement_min_m']):.3f} m, {s['surface_slips']} surface "
          f"slips, {s['rings']} rings reached")
counts = run.events["kind"].value_counts()
print(counts[["slip", "stick", "surface_slip", "ring", "ring_off"]].to_string())

# %%
# The stiff-ringed bearing's loop, with its slide from rest both ways (dotted).
fig, ax = plt.subplots(figsize=(6, 4.5))
run.plot_isolator_loop(ax=ax)
fig.tight_layout()
plt.show()
