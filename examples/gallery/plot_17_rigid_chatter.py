"""
Rigid stops: chatter and sticking
=================================

A 1 kg mass on a spring of 100 N/m (10 rad/s, 2 % damping) between rigid stops 5 mm away, restitution 0.8
(:class:`pounding.RigidStop`), shaken slowly and hard (0.5 Hz, 40 m/s^2). Each half cycle the table throws
it against a stop, where its rebounds shrink by 0.8 each time while the table keeps pressing: infinitely
many impacts in finite time (complete chatter). The engine follows them one by one, sums the rest of the
sequence in closed form where it accumulates, then holds the mass on the stop until the stop's force, from
the equations of motion, would pull: the table turns, and the mass flies to the other stop.
"""

import matplotlib.pyplot as plt
import numpy as np

import pounding

iso = pounding.Isolator(slopes_n_m=[100.0], damping_n_s_m=0.4)
osc = pounding.Oscillator(1.0, iso, pounding.Bumpers(0.005, 0.005, pounding.RigidStop(0.8)))
table = pounding.Harmonic(a_g=40.0 / 9.81, freq_hz=0.5)  # (a_g in g: 40 m/s^2)
run = pounding.simulate(osc, table, duration=2.5, sample_rate_hz=4000)

c = run.contacts
impacts = c[c.t_end_s == c.t_start_s]
holds = c[(c.t_end_s != c.t_start_s) & (c.peak_force_n.notna() | c.t_end_s.isna())]
print(f"{len(impacts)} impacts followed one by one, {len(run.chatters)} chatter sequences:")
print(run.chatters.to_string(index=False))
print(f"energy ledger residual: {run.energy.residual:.1e} J of {run.energy.input_work:.3f} J put in")

# %%
# The mass against the stops (above) and the holding force (below). Each chatter ends where its impacts
# accumulate (dotted); the stop then holds the mass (shaded) until its force falls to zero.
fig, (ax, af) = plt.subplots(2, 1, figsize=(7, 5), sharex=True)
ax.plot(run.t, run.displacement * 1e3, lw=0.8)
for gap in (-5.0, 5.0):
    ax.axhline(gap, color="k", lw=1.5)
ax.plot(impacts.t_start_s, np.where(impacts.side == "right", 5.0, -5.0), "|", color="C3", ms=8,
        label="impacts")
end = run.t[-1]
for h in holds.itertuples():
    t1 = end if np.isnan(h.t_end_s) else h.t_end_s
    for a in (ax, af):
        a.axvspan(h.t_start_s, t1, color="0.9")
for t in run.chatters.t_end_s[run.chatters.accumulated]:
    ax.axvline(t, color="C2", ls=":", lw=1)
ax.set_ylabel("displacement [mm]")
ax.legend(loc="upper left", fontsize=8)
af.plot(run.t, run.bumper_force_right, label="right stop")
af.plot(run.t, run.bumper_force_left, label="left stop")
af.set_xlabel("time [s]")
af.set_ylabel("holding force [N]")
af.legend(fontsize=8)
fig.tight_layout()
