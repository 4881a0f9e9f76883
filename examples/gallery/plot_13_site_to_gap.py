"""
From a site to a gap: spectra, a scaled suite, fragility curves, risk
=====================================================================

A 500 kg UPS cabinet on the paper's isolator, at an ASCE 7-16 site with S_DS = 1.0 g and S_D1 = 0.6 g.
Which gap to the bumpers keeps pounding rare?

The intensity measure is the 5 %-damped pseudo-spectral acceleration at 1 s, Sa(1 s). The FEMA P695
far-field suite (44 records) is run at six stripes of it, on the isolator alone: a run without bumpers
reaches a gap exactly when its peak displacement does (until the first contact the motion with bumpers is
the same), so one run per record and stripe gives the probability of contact at every gap. A lognormal
fragility curve is fitted per gap by maximum likelihood, and with a hazard curve for Sa(1 s) it gives how
often each gap is reached in 50 years.
"""

import tempfile
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import pounding
from pounding import design

site = design.asce7_spectrum(1.0, 0.6)
mce = design.asce7_spectrum(1.0, 0.6, level="mce")
period_s = 1.0

# %%
# The suite scaled to the MCE_R spectrum around the isolated period (one factor for the suite, the
# mean not below the target from 0.75 to 1.25 s).
suite = design.scale_suite(pounding.records.fema_p695(), mce, period_range_s=(0.75, 1.25), n_periods=11)
print(suite)
suite.plot()

# %%
# Six stripes of Sa(1 s), each record scaled to each, on the isolator without bumpers: a stripe analysis
# (a parameter study into a resumable Zarr store; here a temporary one).
ups = pounding.presets.paper_calibrated()
isolated = pounding.Oscillator(ups.mass_kg, ups.isolator)
levels_g = [0.2, 0.4, 0.6, 0.8, 1.0, 1.2]
store = Path(tempfile.mkdtemp()) / "ups.zarr"
msa = design.stripe_analysis(isolated, "fema-p695:far_field", levels_g, period_s=period_s, store=store,
                             progress=False)
print(msa)
peak_m = msa.data["disp_max_m"].values  # (stripes, records)
print(f"median peak displacement per stripe (mm): {np.round(1e3 * np.median(peak_m, axis=1), 1)}")

# %%
# The probability of contact against Sa(1 s), one curve per gap, with 90 % bootstrap bands.
gaps_m = [0.05, 0.1, 0.15, 0.2]
curves = {}
fig, ax = plt.subplots(figsize=(6.5, 4))
for gap in gaps_m:
    curves[gap] = msa.fragility("contact", limit=gap)  # without bumpers: the peak reaching the gap
    curves[gap].plot(ax=ax)
ax.axvline(site.sa_g(period_s), color="k", ls=":", lw=1)
ax.axvline(mce.sa_g(period_s), color="k", ls="--", lw=1)
ax.set_xlabel("Sa(1 s) (g); dotted: design level, dashed: MCE_R")

# %%
# An illustrative hazard curve for Sa(1 s), with the MCE_R value at a 2,475-year return period, and
# the probability of contact in 50 years against the gap.
hazard = design.HazardCurve.from_return_periods([0.1, 0.3, mce.sa_g(period_s), 2.0],
                                                [30.0, 300.0, 2475.0, 20000.0], period_s)
for gap, curve in curves.items():
    r = design.risk(curve, hazard, years=50.0)
    print(f"gap {1e3 * gap:5.0f} mm: P(contact | design) {curve.probability(site.sa_g(period_s)):.2f}, "
          f"P(contact | MCE_R) {curve.probability(mce.sa_g(period_s)):.2f}, "
          f"in 50 years {r['probability']:.3f}")

# %%
# With bumpers, the same chain decides the gap and shows what the bumper costs once hit (peak
# acceleration, impact force), from one file: ``pounding design examples/design_ups.toml`` runs the suite
# at ten stripes over five gaps and three bumper stiffnesses and writes a report with the verdict first.
