"""
Basins of attraction: which initial states end in contact with the bumpers
==========================================================================

At 1.8 Hz and a_G = 0.05 g the damped paper system has two stable responses: one pounding the bumpers
(alpha above 11) and one free of them (alpha 1.4). :func:`pounding.basins` runs every initial state of a
grid at table phase 0 until it settles, finds the two responses, and colours each state by the one it
ends on: the share of the grid in the impacting basin is the chance that equipment starting anywhere in
the box pounds.
"""

import matplotlib.pyplot as plt

import pounding

osc = pounding.presets.paper_damped()
b = pounding.basins(osc, pounding.Harmonic(0.05, 1.8), n=(40, 40))
print(b.attractors[["period", "alpha", "impacts", "fraction", "standard_error"]].round(3).to_string())

fig, ax = plt.subplots(figsize=(6.5, 4.5))
b.plot(ax=ax)
fig.tight_layout()
