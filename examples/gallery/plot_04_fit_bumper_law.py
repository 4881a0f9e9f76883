"""
Fitting a bumper law to a cyclic test
=====================================

A bumper's force-displacement test (two cycles each at 0.5 to 2 Hz, +-10 mm around 10 mm of compression,
as the paper's MTS tests) fitted by every contact law pounding can fit (all but Hertzdamp, whose damping
is chosen at each impact), ranked by their residual. The test
shipped with the package is synthetic (a Hunt-Crossley law with 1 % noise): the paper publishes its loops as
figures only.
"""

import pounding

test = pounding.data.bumper_cyclic_test()
ranked = pounding.rank_contact_laws(test["compression_m"], test["force_n"], time_s=test["time_s"],
                                    effective_mass_kg=500.0)
print(ranked[["law", "rms_n", "r_squared"]].to_string(index=False))

# %%
# The best law against the measured loops: force against compression, measured and fitted.
fit = pounding.fit_contact_law(test["compression_m"], test["force_n"], time_s=test["time_s"],
                               law="hunt_crossley")
print(fit.law)
fit.plot()
