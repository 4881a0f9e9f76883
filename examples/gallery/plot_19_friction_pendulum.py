"""
A friction pendulum against bumpers: exact stick and slip
=========================================================

A 500 kg mass on a friction pendulum (radius 1.5 m, friction coefficient 0.1:
:class:`pounding.FrictionIsolator`) between compliant bumpers 30 mm away, shaken at 0.2 g. The bearing
sticks while the force needed to hold it stays within mu W and slips at mu W against its velocity; each
switch is an event located on the exact trajectory, so each steady cycle has the same few events, and no
stick is cut into slips of zero length (what a stepping code's stiff initial branch would ring through).
"""

import matplotlib.pyplot as plt
import numpy as np

import pounding

fps = pounding.FrictionIsolator(mu=0.1, radius_m=1.5)
bumpers = pounding.Bumpers(0.03, 0.03, pounding.KelvinVoigt(2.0e6, 500.0))
osc = pounding.Oscillator(500.0, fps, bumpers)
print(f"mu W = {osc.isolator.friction_force_n:.0f} N, W / R = {osc.isolator.restoring_stiffness_n_m:.0f} N/m,"
      f" period {osc.isolator.period_s:.2f} s")

# %%
# A sweep over the table's frequency: the peak acceleration and the contacts per cycle of each step's
# steady window.
sweep = pounding.sweep(osc, 0.2, np.arange(0.3, 1.61, 0.05))
fig, (ax_a, ax_c) = plt.subplots(2, 1, figsize=(6, 5), sharex=True)
frame = sweep.to_dataframe()
ax_a.plot(frame.freq_hz, frame.alpha, "o-", ms=3)
ax_a.set_ylabel("alpha = max|a_abs| / A_t [-]")
ax_c.plot(frame.freq_hz, frame.contacts_per_cycle, "o-", ms=3, color="C1")
ax_c.set_ylabel("contacts per cycle")
ax_c.set_xlabel("f [Hz]")
fig.tight_layout()

# %%
# One step, 0.6 Hz, in its steady state (its last four cycles): the base's displacement with its sticks
# shaded (above), and the isolator's force against its displacement (below): slips along the pendulum's
# slope offset by +-mu W, vertical sticks, and the bumpers beyond +-30 mm. The events of each cycle are
# counted: the same in every cycle.
freq_hz, cycles = 0.6, 40
run = pounding.simulate(osc, pounding.Harmonic(0.2, freq_hz), duration=cycles / freq_hz,
                        sample_rate_hz=2000)
t_steady = (cycles - 4) / freq_hz
steady = run.events[run.events["t_s"] >= t_steady]
cycle = np.floor((steady["t_s"].to_numpy() - t_steady) * freq_hz).astype(int)
print("events in each of the last four cycles:", np.bincount(cycle, minlength=4)[:4].tolist())
print(steady.groupby("kind", observed=True).size().div(4).rename("per cycle").to_string())

frame = run.to_dataframe()
window = frame[frame.t_s >= t_steady]
fig, (ax, af) = plt.subplots(2, 1, figsize=(6, 7))
ax.plot(window.t_s, window.displacement_m * 1e3, lw=0.9)
starts, kinds = run.events["t_s"].to_numpy(), run.events["kind"].to_numpy()
for t0, t1, k0 in zip(starts, np.append(starts[1:], run.t[-1]), kinds):
    if k0 == "stick" and t1 > t_steady:
        ax.axvspan(max(t0, t_steady), t1, color="0.85")
for gap in (-30.0, 30.0):
    ax.axhline(gap, color="k", lw=1.2)
ax.set_xlabel("t [s]")
ax.set_ylabel("base displacement [mm] (sticks shaded)")
run.plot_isolator_loop(ax=af, t_start_s=t_steady)
fig.tight_layout()
plt.show()
