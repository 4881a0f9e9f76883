"""Make ``src/pounding/data/bumper_cyclic_test.csv``: a synthetic cyclic bumper test.

The paper's cyclic MTS tests (Sect. 2.2, Fig. 3: about +-10 mm around 10 mm of
precompression at 0.5 to 2 Hz) are shown as figures, not published as data.  This file
imitates their protocol with a Hunt-Crossley law (stiffness 1.46e7 N/m^1.5, exponent 1.5,
damping 2e7 N s/m^2.5: about 14.6 kN at 10 mm, as the paper's Kelvin-Voigt bumper) plus 1 %
Gaussian force noise, so that ``pounding.fit_contact_law``'s example runs on data shipped
with the package.  It is not a measurement.

Run: ``python scripts/make_bumper_test.py`` (deterministic: seed 0).
"""

from pathlib import Path

import numpy as np
import pandas as pd

from pounding import HuntCrossley
from pounding.identification.contact_law import _force

LAW = HuntCrossley(1.46e7, 1.5, 2.0e7)
PRECOMPRESSION_M, AMPLITUDE_M = 0.010, 0.010
FREQS_HZ = (0.5, 1.0, 1.5, 2.0)
CYCLES, SAMPLES_PER_CYCLE, NOISE = 2, 100, 0.01


def main() -> Path:
    rng = np.random.default_rng(0)
    parts, t0 = [], 0.0
    for f in FREQS_HZ:
        t = np.arange(CYCLES * SAMPLES_PER_CYCLE) / (SAMPLES_PER_CYCLE * f)
        d = PRECOMPRESSION_M - AMPLITUDE_M * np.cos(2 * np.pi * f * t)  # from 0 to 20 mm and back
        v = 2 * np.pi * f * AMPLITUDE_M * np.sin(2 * np.pi * f * t)
        force = _force(LAW, d, v)
        force = np.maximum(force + NOISE * np.abs(force).max() * rng.standard_normal(t.size), 0.0)
        parts.append(pd.DataFrame({"time_s": t0 + t, "freq_hz": f, "compression_m": d, "force_n": force}))
        t0 += CYCLES / f
    out = Path(__file__).parents[1] / "src" / "pounding" / "data" / "bumper_cyclic_test.csv"
    pd.concat(parts).round({"time_s": 6, "compression_m": 9, "force_n": 3}).to_csv(out, index=False)
    return out


if __name__ == "__main__":
    print(main())
