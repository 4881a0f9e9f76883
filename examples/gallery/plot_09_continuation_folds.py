"""
A continued branch and its folds: why the response jumps
========================================================

A sweep shows where the response jumped, not why. :func:`pounding.continuation` follows the periodic
response over frequency through its folds (pseudo-arclength), with its exact Floquet multipliers, and
locates the folds: on ``paper_damped`` at a_G = 0.05 the impacting branch folds back near 2.01 Hz (where the
up sweep drops) and again near 1.6 Hz (where the down sweep climbs). Between the folds an impacting and a
non-impacting response coexist, and the unstable branch between them, which no sweep can settle on,
separates their basins.
"""

import matplotlib.pyplot as plt
import numpy as np

import pounding

osc = pounding.presets.paper_damped()
branch = pounding.continuation(osc, 0.05, (1.4, 2.6))
print(branch.message)
for bif in branch.bifurcations:
    side = f" ({bif.side})" if bif.kind == "grazing" else ""
    print(f"{bif.kind}{side} at {bif.freq_hz:.4f} Hz, alpha {bif.alpha:.2f}")

# %%
# The branch (stable solid, unstable dashed, the folds marked) with the up and down sweeps over it.
freqs = np.round(np.arange(1.4, 2.61, 0.1), 2)
sweeps = [pounding.sweep(osc, 0.05, direction=d, freqs_hz=freqs, steady="fixed", cycles=30, measure_cycles=5)
          for d in ("up", "down")]
fig, ax = plt.subplots(figsize=(6.5, 4))
branch.plot(ax=ax, sweeps=sweeps)
ax.set_title("paper_damped, a_G = 0.05: branch, folds and sweeps")
fig.tight_layout()

# %%
# The largest Floquet multiplier along the branch: it crosses 1 at each fold.
df = branch.to_dataframe()
fig, ax = plt.subplots(figsize=(6.5, 3))
ax.plot(df["freq_hz"], df["max_abs_multiplier"], lw=1)
ax.axhline(1.0, color="k", lw=0.6, ls="--")
ax.set_yscale("log")
ax.set_xlabel("f (Hz)")
ax.set_ylabel("max |mu|")
fig.tight_layout()
