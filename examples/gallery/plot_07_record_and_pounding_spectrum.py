"""
An earthquake record and its pounding spectrum
==============================================

El Centro 1940 N-S (shipped with pounding) scaled to a peak of 0.3 g shakes the damped paper system: the
engine is exact for a record as for a sine, every contact located and every peak found between the
samples. Then its pounding spectrum: for isolation periods from 0.5 to 3 s and two gaps, a 500 kg mass on
a linear isolator with 5 % damping, with the paper's Kelvin-Voigt bumpers (1.46 MN/m, 5 N s/m: nearly
elastic) and without, and the amplification of the peak
acceleration by pounding.
"""

import matplotlib.pyplot as plt

import pounding
from pounding.records import el_centro

quake = el_centro().scaled(pga_g=0.3)
run = pounding.simulate(pounding.presets.paper_damped(), quake, quake.duration_s)
print(f"{quake.duration_s:.1f} s of record, {len(run.contacts)} impacts, "
      f"peak acceleration {run.abs_acceleration_max / 9.81:.2f} g, "
      f"peak displacement {max(run.displacement_max, -run.displacement_min) * 1e3:.1f} mm")

# %%
# The record and the response.
fig, (ax_r, ax_d) = plt.subplots(2, 1, figsize=(6.5, 4.5), sharex=True)
pounding.plots.plot_record(quake, ax=ax_r)
ax_d.plot(run.t, run.displacement * 1e3, lw=0.7)
for gap in (0.015, -0.015):
    ax_d.axhline(gap * 1e3, color="k", ls="--", lw=0.6)
ax_d.set_ylabel("D (mm)")
ax_d.set_xlabel("time (s)")
fig.tight_layout()

# %%
# The pounding spectrum: peak acceleration with bumpers over without, against the isolation period.
spectrum = pounding.pounding_spectrum([quake], [0.5, 0.75, 1.0, 1.5, 2.0, 2.5, 3.0], gaps_m=[0.01, 0.03],
                                      damping_ratio=0.05)
print(spectrum.summary()["amplification"].sel(percentile=50.0).to_pandas().round(2))
spectrum.plot()
