"""
A shaking-table recording analysed
==================================

:mod:`pounding.lab` measures a stepped-sine test as the paper's Sect. 3 does: it finds the steps in the
table's signal, measures the last cycles of each (alpha per accelerometer and of their mean, the excursion,
eta) and every contact (times, velocities, restitution, force). Here the recording is synthetic: the
simulator recorded through realistic sensors (1 kHz sampling, a 200 Hz anti-alias filter, two accelerometers
with 2 % gain errors, 1 % noise, a laser with 10 um resolution), which is also how a test is planned.
"""

import matplotlib.pyplot as plt

import pounding
from pounding.lab import analyse_stepped_sine, synthetic_test

freqs = [1.4, 1.6, 1.8, 2.0]
recording = synthetic_test(pounding.presets.paper_damped(), 0.05, freqs, cycles=20, sample_rate_hz=1000,
                           noise=0.01, anti_alias_hz=200, gains=(1.02, 0.98), laser_resolution_m=1e-5)
measured = analyse_stepped_sine(recording, mass_kg=500, gap_total_m=0.03, freqs_hz=freqs)
print(measured.to_dataframe()[["freq_hz", "alpha", "eta", "contact_time_s", "restitution"]].round(3))
print(f"{len(measured.impacts)} contacts measured")

# %%
# The raw signals of the last step: the table's and the mass's accelerations, and the laser.
rec = measured.record
last = rec.time_s > rec.time_s[-1] - 2.0
fig, (ax_a, ax_d) = plt.subplots(2, 1, figsize=(6, 4.5), sharex=True)
ax_a.plot(rec.time_s[last], rec.mass_acc_m_s2[last, 0] / 9.81, lw=0.8, label="mass, accelerometer 1")
ax_a.plot(rec.time_s[last], rec.table_acc_m_s2[last] / 9.81, lw=0.8, label="table")
ax_a.set_ylabel("acceleration (g)")
ax_a.legend(fontsize=7)
ax_d.plot(rec.time_s[last], rec.displacement_m[last] * 1e3, lw=0.8)
ax_d.set_ylabel("displacement (mm)")
ax_d.set_xlabel("time (s)")
fig.tight_layout()

# %%
# The measured sweep, as the paper's Fig. 5 and 6 draw it.
measured.plot()
