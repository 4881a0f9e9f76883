"""
Up and down sweeps: the jump
============================

A stepped-sine test as on the shaking table: the frequency steps up (then down) by 0.1 Hz, each step held
for a fixed number of cycles with the state carried over. With bumpers, the impacting response is followed
up to a fold where it jumps down to a small, non-impacting one; coming down, the response jumps up
elsewhere. Between the two jumps both responses exist, and which one you see depends on the history.
"""

import matplotlib.pyplot as plt
import numpy as np

import pounding

osc = pounding.presets.paper_damped()          # the printed values with C_d read as 1 kN s/m
freqs = np.round(np.arange(1.2, 2.61, 0.1), 2)
options = dict(freqs_hz=freqs, steady="fixed", cycles=30, measure_cycles=5)
up = pounding.sweep(osc, 0.05, direction="up", **options)
down = pounding.sweep(osc, 0.05, direction="down", **options)
columns = ["freq_from_hz", "freq_to_hz", "alpha_from", "alpha_to", "kind"]
print("up sweep's jump:\n", up.jumps()[columns].round(3).to_string(index=False))
print("down sweep's jump:\n", down.jumps()[columns].round(3).to_string(index=False))
print(f"pseudo-resonance nu_R: up {up.nu_r}, down {down.nu_r}")

# %%
# alpha (peak absolute acceleration over the table's) and eta (excursion over the total gap) against
# nu = f / 1 Hz, up solid, down dashed.
fig, axes = plt.subplots(2, 1, figsize=(6, 5.5), sharex=True)
up.plot(ax=axes)
down.plot(ax=axes)
axes[0].set_title("paper_damped, a_G = 0.05: the up sweep drops, the down sweep climbs")
fig.tight_layout()
