"""
Friction pendulums in plan: the friction circle
================================================

The two-storey building of the previous examples on four friction pendulums (R = 2.5 m, mu = 0.06, an
elastic pre-slip of 0.5 mm), shaken by El Centro 1940 at 0.5 g along 60 degrees. A sliding bearing sticks
while the force in the plane stays inside mu W and slips along its velocity once it reaches it: its friction
stays inside a circle of radius mu W (the friction circle), whatever the direction it slides in. By default
the circle is elastic-perfectly-plastic, each stick and slip located as an event; Constantinou, Mokha and
Reinhorn's smooth circle (a bidirectional Bouc-Wen spring, SAP2000's, ``friction_circle="bouc_wen"``)
rounds its corners. The same bearings with one friction along each axis (``bidirectional=False``), each
slipping under its own component, resist a diagonal slide with up to sqrt(2) mu W: their friction fills a
square, and the building slides less than it should.
"""

import matplotlib.pyplot as plt
import numpy as np

import pounding
from pounding import Bearing, Floor, Frame, PlanBuilding, RectangularMoat

fps = pounding.FrictionIsolator(mu=0.06, radius_m=2.5, preslip_m=0.0005)
frames = [Frame(s, "x", y, 4.0e8, 1.0e5) for s in (1, 2) for y in (-6.0, 6.0)]
frames += [Frame(s, "y", x, k, 1.0e5) for s in (1, 2) for x, k in ((-15.0, 9.0e8), (15.0, 3.0e8))]
moat = RectangularMoat(gap_m=0.2, law=pounding.KelvinVoigt(stiffness=5.0e8, damping=1.0e6))


def building(bidirectional, circle="plastic"):
    bearings = [Bearing((sx * 14.0, sy * 5.0), fps, bidirectional=bidirectional, friction_circle=circle)
                for sx in (-1, 1) for sy in (-1, 1)]
    return PlanBuilding([Floor(4.0e5, (30.0, 12.0), centre_m=(3.0, 0.0))] * 3, bearings, frames, moat)


quake = pounding.RecordPair.of_direction(pounding.records.el_centro().scaled(pga_g=0.5), 60.0)
runs = {name: pounding.simulate(building(*how), quake, duration=15.0, sample_rate_hz=200.0)
        for name, how in (("plastic circle", (True,)), ("Bouc-Wen circle", (True, "bouc_wen")),
                          ("one friction per axis", (False,)))}
weight = building(True).bearings[2].isolator.weight_n  # N: bearing 2's share, nearer the mass
for name, run in runs.items():
    print(f"{name}: largest bearing displacement {1e3 * run.bearing_displacement_max_m.max():.1f} mm, "
          f"{len(run.contacts)} contacts")

# %%
# Bearing 2's friction in the plane (its force less the pendulum's W / R u), over the circle mu W.
fig, axes = plt.subplots(1, 3, figsize=(11, 3.8), constrained_layout=True)
for ax, (name, run) in zip(axes, runs.items()):
    f = run.bearing_force[:, 2, :] - (weight / 2.5) * run.bearing_displacement[:, 2, :]
    ax.plot(f[:, 0] / 1e3, f[:, 1] / 1e3, lw=0.6)
    turn = np.linspace(0.0, 2.0 * np.pi, 200)
    ax.plot(0.06 * weight / 1e3 * np.cos(turn), 0.06 * weight / 1e3 * np.sin(turn), "k--", lw=1,
            label="mu W")
    ax.set_aspect("equal")
    ax.set_title(name, fontsize=9)
    ax.set_xlabel("friction along x (kN)")
axes[0].set_ylabel("friction along y (kN)")
axes[0].legend(fontsize=8, loc="lower right")
plt.show()

# %%
# The corners' orbits inside the moat's clearance, on the plastic friction circle.
runs["plastic circle"].plot()

# %%
# PTFE grips less at rest than when it slides fast (``mu_fast``, OpenSees' ``VelDependent``): the circle's
# radius then follows the slip's rate, mu W at a stick's start and end, up to mu_fast W in a fast slide.
# Bearing 2's friction in the plane against its speed, on the plastic circle: its slips on mu(v), its
# sticks below mu W (it moves there within its elastic pre-slip, and the building turns).
fast = pounding.FrictionIsolator(mu=0.06, radius_m=2.5, preslip_m=0.0005, mu_fast=0.1, rate_s_m=25.0)
vel = PlanBuilding([Floor(4.0e5, (30.0, 12.0), centre_m=(3.0, 0.0))] * 3,
                   [Bearing((sx * 14.0, sy * 5.0), fast) for sx in (-1, 1) for sy in (-1, 1)], frames, moat)
run = pounding.simulate(vel, quake, duration=15.0, sample_rate_hz=200.0)
print(f"velocity-dependent: largest bearing displacement {1e3 * run.bearing_displacement_max_m.max():.1f} mm")
u = run.bearing_displacement[:, 2, :]
speed = np.hypot(*np.gradient(u, run.t, axis=0).T)
friction = np.hypot(*(run.bearing_force[:, 2, :] - (weight / 2.5) * u).T)
v = np.linspace(0.0, speed.max(), 100)
fig, ax = plt.subplots(figsize=(5.5, 3.6), constrained_layout=True)
ax.plot(speed, friction / weight, ".", ms=2, label="bearing 2, every sample")
bearing = vel.bearings[2].isolator  # (it carries its share of the weight)
ax.plot(v, bearing.friction_at(v) / bearing.weight_n, "k--", lw=1, label="mu(v)")
ax.set_xlabel("bearing speed (m/s)")
ax.set_ylabel("friction / W")
ax.legend(fontsize=8)
plt.show()
