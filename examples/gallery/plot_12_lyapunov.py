"""
Is it chaotic? Lyapunov exponents through every impact
======================================================

A soft impact oscillator (a linear oscillator with 2 % damping, a stop 30 times stiffer 5 mm away on
one side) driven at a_G = 0.1 g: at 2.6 Hz the bifurcation diagram shows a cloud. :func:`pounding.lyapunov`
follows the response with the exact tangent dynamics (state-transition matrices between the engine's
events, saltation matrices at the impacts) and finds a positive largest exponent: chaos. Over the
diagram, :func:`pounding.largest_exponents` labels every frequency: negative where the response is
periodic, positive where it is chaotic.
"""

import math

import matplotlib.pyplot as plt
import numpy as np

import pounding

m, k, zeta = 100.0, 4000.0, 0.02
stop = pounding.KelvinVoigt(stiffness=30 * k, damping=2 * zeta * math.sqrt(30 * k * m))
iso = pounding.Isolator(slopes_n_m=[k], damping_n_s_m=2 * zeta * math.sqrt(k * m))
soft = pounding.Oscillator(mass_kg=m, isolator=iso,
                           bumpers=pounding.Bumpers(gap_left_m=0.3, gap_right_m=0.005, law=stop))

spec = pounding.lyapunov(soft, pounding.Harmonic(0.1, 2.6), cycles=1000, transient_cycles=300)
print(spec)

freqs = np.round(np.arange(2.0, 3.01, 0.05), 2)
diagram = pounding.bifurcation_diagram(soft, 0.1, freqs, direction="up", transient_cycles=300,
                                       record_cycles=20)
diagram = pounding.largest_exponents(diagram, cycles=200)

fig, (ax1, ax2, ax3) = plt.subplots(3, 1, figsize=(7, 9), constrained_layout=True)
spec.plot(ax=ax1)
diagram.plot(ax=ax2)
lam = diagram.data["largest_exponent"].sel(direction="up")
ax3.plot(freqs, lam, "o-")
ax3.axhline(0.0, color="0.5", lw=0.8, ls=":")
ax3.set_xlabel("table frequency, Hz")
ax3.set_ylabel("largest exponent, 1/s")
