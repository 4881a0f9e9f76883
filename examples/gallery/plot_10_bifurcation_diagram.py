"""
A bifurcation diagram: which response the shaking table ends on
===============================================================

:func:`pounding.bifurcation_diagram` steps the frequency up, then down from where the up sweep ended,
holds each step for 100 cycles and records the state at table phase 0 over the next 20. One point per
frequency is a periodic response; up and down differ where an impacting and a free response coexist,
between the folds of the branch that :func:`pounding.continuation` follows (drawn under it at the same
section: stable solid, unstable dashed). The isolator here is elastic, so that each frequency has one
orbit per branch (a kinematic isolator's slips shift the orbit a sweep ends on).
"""

import matplotlib.pyplot as plt
import numpy as np

import pounding

osc = pounding.presets.paper_damped(hysteresis="elastic")
freqs = np.round(np.arange(1.0, 3.0001, 0.01), 2)
diagram = pounding.bifurcation_diagram(osc, 0.05, freqs)
print(diagram.message)
for sw in diagram.sweeps:
    jumps = sw.jumps()
    print(sw.direction, "sweep jumps:", ", ".join(f"{a:g} -> {b:g} Hz" for a, b in
                                                   zip(jumps["freq_from_hz"], jumps["freq_to_hz"])))

# %%
# The samples over the branch's crossings of the same section.
branch = pounding.continuation(osc, 0.05, (1.0, 3.0))
fig, ax = plt.subplots(figsize=(6.5, 4))
diagram.plot(ax=ax, branches=branch)
fig.tight_layout()
