"""Plan a shaking-table test on the virtual table: which sampling rate resolves the contacts?

Records the paper's calibrated YBs system at a_G = 0.05 through realistic sensors at several sampling rates,
measures each recording as a lab would (``analyse_stepped_sine``) and prints how far the measured contact
times, restitution and mean forces are from the simulator's exact values; then draws the lab's sweep over
the model's.  Run: ``python examples/plan_lab_test.py [OUT.png]`` (about a minute).
"""

from __future__ import annotations

import sys
import warnings

import numpy as np

import pounding as pd_
from pounding.lab import analyse_stepped_sine, synthetic_test

A_G = 0.05
FREQS = np.round(np.arange(1.0, 2.61, 0.2), 10)
SENSORS = dict(noise=0.01, gains=(1.02, 0.98), laser_resolution_m=1e-5, seed=1)


def main(out_png: str = "lab_vs_model.png") -> None:
    osc = pd_.presets.paper_calibrated()
    gap = osc.bumpers.total_gap  # (the fitted model's own gap: not the nominal 30 mm)
    model = pd_.sweep(osc, A_G, FREQS, "up", steady="fixed", cycles=30, measure_cycles=5)
    sim = model.to_dataframe()
    contact = sim["contact"].to_numpy()
    print(f"paper_calibrated YBs, a_G = {A_G} g, {contact.sum()} of {FREQS.size} steps in contact; "
          f"contacts last {1e3 * sim['contact_time_s'][contact].min():.0f}-"
          f"{1e3 * sim['contact_time_s'][contact].max():.0f} ms")
    print("rate (Hz)  worst |contact time error| (ms)  worst |restitution error|  worst mean force error")
    for rate in (250.0, 500.0, 1000.0, 2000.0):
        rec = synthetic_test(osc, A_G, FREQS, cycles=30, sample_rate_hz=rate, anti_alias_hz=rate / 5,
                             **SENSORS)
        with warnings.catch_warnings(record=True) as said:
            warnings.simplefilter("always")
            lab = analyse_stepped_sine(rec, mass_kg=500.0, gap_total_m=gap, freqs_hz=FREQS)
        df = lab.to_dataframe()
        dt = np.abs(df["contact_time_s"] - sim["contact_time_s"])[contact].max()
        ds = np.abs(df["restitution"] - sim["restitution"])[contact].max()
        df_ = np.abs(df["mean_force_n"] / sim["mean_force_n"] - 1.0)[contact].max()
        note = f"  (warned: {str(said[0].message).split(': ', 1)[1][:60]}...)" if said else ""
        print(f"{rate:9.0f}  {1e3 * dt:31.2f}  {ds:25.3f}  {100 * df_:21.1f} %{note}")
        if rate == 1000.0:
            best = lab
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(2, 1, sharex=True, figsize=(6.4, 6.0))
    model.plot(ax=ax)
    best.plot(ax=ax)
    ax[0].legend()
    fig.savefig(out_png, dpi=120)
    print(f"wrote {out_png}: the lab's measurements (1 kHz) over the model's sweep")


if __name__ == "__main__":
    main(*sys.argv[1:2])
