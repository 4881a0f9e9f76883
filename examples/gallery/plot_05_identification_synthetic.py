"""
Identification on synthetic data
================================

Model updating checked where the answer is known: "measurements" are made by sweeping a known system
(``paper_damped``: isolator damping 1000 N s/m, bumper stiffness 1.46 MN/m), and
:func:`pounding.identify` is asked to find those two numbers again from the measured peaks, excursions and
contact times, within bounds a factor of three either side. The search is kept small so that it runs in
seconds (a real fit uses the defaults, ``popsize=10, maxiter=30``).
"""

import matplotlib.pyplot as plt
import numpy as np

import pounding

truth = pounding.presets.paper_damped()
freqs = np.round(np.arange(1.0, 3.01, 0.1), 2)
sweep = pounding.sweep(truth, 0.05, direction="up", freqs_hz=freqs, steady="fixed", cycles=30,
                       measure_cycles=5)
df = sweep.to_dataframe()
peak = df.loc[df["alpha"].idxmax()]
measured = {"nu_r": sweep.nu_r, "alpha": peak["alpha"], "eta": df["eta"].max(),
            "contact_time_ms": peak["contact_time_s"] * 1e3}
print({name: round(float(value), 3) for name, value in measured.items()})

targets = pounding.Targets.from_records(
    [{"configuration": "YBs", "a_g": 0.05, "quantity": name, "value": float(value), "direction": "up"}
     for name, value in measured.items()])

# %%
# The family fixes everything but the two numbers sought.
family = pounding.ModelFamily(500.0, branches=3, law="kelvin_voigt",
                              fixed={"slope_1": 38e3, "slope_2": 18e3, "slope_3": 2e3,
                                     "breakpoint_1": 0.015, "breakpoint_2": 0.04, "gap": 0.015,
                                     "bumper_damping": 5.0})
bounds = {"isolator_damping": (330.0, 3000.0), "bumper_stiffness": (0.5e6, 4.4e6)}
fit = pounding.identify(targets, family, bounds, seed=1, popsize=4, maxiter=4, freqs_hz=freqs, workers=1)
print(fit.message)
print({name: round(value, 1) for name, value in fit.parameters.items()}, "(truth: 1000.0, 1460000.0)")

# %%
# Each target, measured and modelled, in tolerances: within the band is met.
fit.plot()
plt.gcf().tight_layout()
