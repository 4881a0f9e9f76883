"""
The impact oscillator's bifurcation diagram
===========================================

The classic of vibro-impact dynamics (Shaw and Holmes 1983, Nordmark 1991, Budd and Dux 1994): a linear
oscillator, here of 1 Hz with 5 % damping, shaken harmonically (3 m/s^2) against a rigid stop at its
position of rest, restitution 0.8. As the forcing frequency grows past twice the natural one, the orbit with
one impact a period loses stability through a period doubling and the motion goes through a cascade of
them into chaos, with windows of periodic motion.

:func:`pounding.bifurcation_diagram` steps the frequency up, holds each step for 150 cycles and records the
state at table phase 0 over the next 40. Under it, the period-one orbit found by
:func:`pounding.periodic_orbit` at each frequency, solid where its Floquet multipliers (exact: the
saltation matrix of Newton's law at its impact) say it is stable, dashed where not: the diagram leaves it
where a multiplier crosses -1.
"""

import math
import warnings

import matplotlib.pyplot as plt
import numpy as np

import pounding

W0, ZETA, A, E = 2.0 * math.pi, 0.05, 3.0, 0.8
iso = pounding.Isolator(slopes_n_m=[W0 ** 2], damping_n_s_m=2.0 * ZETA * W0)  # (1 kg)
with warnings.catch_warnings():
    warnings.simplefilter("ignore")  # (a gap of 10 m on the left: no stop there)
    stops = pounding.Bumpers(10.0, 0.0, pounding.RigidStop(E))
osc = pounding.Oscillator(1.0, iso, stops)
a_g = A / 9.81  # (in g)
freqs = np.round(np.arange(2.0, 3.6001, 0.01), 3)
diagram = pounding.bifurcation_diagram(osc, a_g, freqs, direction="up", transient_cycles=150,
                                       record_cycles=40)
print(diagram.message)

# %%
# The period-one orbit: its state at table phase 0 and its largest multiplier.
rows = []
for f in freqs[::5]:
    orbit = pounding.periodic_orbit(osc, pounding.Harmonic(a_g, f))
    if orbit.converged:
        rows.append((f, orbit.state.displacement_m, orbit.max_abs_multiplier, orbit.method))
rows = np.array([r[:3] for r in rows])
boundary = rows[np.argmax(rows[:, 2] > 1.0), 0]
print(f"period-one orbit: stable up to {boundary:g} Hz (its largest |multiplier| crosses 1 there)")

fig, ax = plt.subplots(figsize=(7, 4))
diagram.plot(ax=ax, ms=1)
stable = rows[:, 2] < 1.0
ax.plot(rows[stable, 0], rows[stable, 1] * 1e3, "k-", lw=1, label="period one, stable")
ax.plot(rows[~stable, 0], rows[~stable, 1] * 1e3, "k--", lw=1, label="period one, unstable")
ax.set_xlabel("forcing frequency [Hz] (natural: 1 Hz)")
ax.legend(fontsize=8)
fig.tight_layout()
