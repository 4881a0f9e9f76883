"""
One run with every impact
=========================

The paper's system with its printed values, at a_G = 0.05 g and 2.2 Hz, started with a push so that it
impacts from the first cycle. Every contact is located on the exact trajectory: the tables list each one
with its incoming and outgoing velocities, restitution and forces, and the extrema are exact whatever the
sampling rate. (A restitution slightly above 1 is no error: the table keeps shaking the mass during the
56 ms of a contact, and can send it off faster than it came.)
"""

import matplotlib.pyplot as plt

import pounding

osc = pounding.presets.paper_printed()
excitation = pounding.Harmonic(a_g=0.05, freq_hz=2.2)
run = pounding.simulate(osc, excitation, duration=6.0, state=pounding.State.at_rest(osc, velocity_m_s=0.6))
print(run.status.name, run.message)
print(f"peak displacement {run.displacement_max * 1e3:.2f} mm, "
      f"peak absolute acceleration {run.abs_acceleration_max / 9.81:.3f} g")
print(run.contacts[["side", "t_start_s", "v_in_m_s", "v_out_m_s"]].head())
print(run.impacts[["side", "restitution", "contact_time_s", "peak_force_n"]].head())

# %%
# The run's own figure: displacement and absolute acceleration against time, the gaps dashed.
run.plot()

# %%
# The same run, zoomed on one impact: the bumper's force against time, from the sampled history.
fig, ax = plt.subplots(figsize=(6, 3))
first = run.impacts.iloc[0]
window = (run.t > first.t_start_s - 0.02) & (run.t < first.t_start_s + first.contact_time_s + 0.02)
side = run.bumper_force_right if first.side == "right" else run.bumper_force_left
ax.plot(run.t[window] * 1e3, side[window] / 1e3)
ax.set_xlabel("time (ms)")
ax.set_ylabel(f"{first.side} bumper force (kN)")
ax.set_title(f"contact of {first.contact_time_s * 1e3:.1f} ms, restitution {first.restitution:.2f}")
fig.tight_layout()
