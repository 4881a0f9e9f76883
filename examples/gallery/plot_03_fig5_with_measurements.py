"""
The paper's Fig. 5, with the measurements
=========================================

The paper's Fig. 5 draws the peak absolute acceleration alpha against nu for each table acceleration, with
bumpers. Here two fitted presets are swept up at three levels, and the paper's measured peaks (nu_R and
alpha, its Table 2) are drawn over the curves. ``paper_calibrated`` (solid) meets the measured contact times
and restitutions and the resonance frequencies, but its peaks are 1.9 to 2.4 times the measured ones;
``paper_calibrated_v2`` (dashed) comes close to the measured peaks and misses the contacts. Why no model
here meets both, and how the lab's filtering may explain it: :doc:`/calibration`.
"""

import matplotlib.pyplot as plt
import numpy as np

import pounding

measured = pounding.data.measured("2")
ybs = measured[measured["configuration"] == "YBs"]
freqs = np.round(np.arange(0.6, 3.61, 0.15), 2)

fig, ax = plt.subplots(figsize=(6.5, 4.2))
for preset, style in [(pounding.presets.paper_calibrated, "-"), (pounding.presets.paper_calibrated_v2, "--")]:
    osc = preset()
    for a_g, colour in [(0.05, "C0"), (0.075, "C1"), (0.1, "C2")]:
        sweep = pounding.sweep(osc, a_g, direction="up", freqs_hz=freqs, steady="fixed", cycles=20,
                               measure_cycles=3)
        df = sweep.to_dataframe()
        label = f"a_G = {a_g}" if style == "-" else None
        ax.plot(df["nu"], df["alpha"], style, color=colour, label=label)
        print(f"{preset.__name__}, a_G {a_g}: nu_R {sweep.nu_r}, alpha {df['alpha'].max():.2f}")
for a_g, colour in [(0.05, "C0"), (0.075, "C1"), (0.1, "C2")]:
    row = ybs[np.isclose(ybs["a_g"], a_g)].iloc[0]
    ax.plot(row["nu_r"], row["alpha"], "o", color=colour, markeredgecolor="k", markersize=8)
    print(f"measured, a_G {a_g}: nu_R {row['nu_r']}, alpha {row['alpha']}")
ax.plot([], [], "k-", label="paper_calibrated")
ax.plot([], [], "k--", label="paper_calibrated_v2")
ax.plot([], [], "ko", label="measured peak (Table 2)")
ax.set_xlabel("nu = f / f_R")
ax.set_ylabel("alpha = max |a_abs| / A_t")
ax.legend(fontsize=7, ncol=2)
ax.set_title("YBs, up sweeps: two fitted models and the paper's peaks")
fig.tight_layout()
