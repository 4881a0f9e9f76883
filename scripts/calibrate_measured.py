"""The paper's calibration with its accelerations measured through a low-pass (issue 39): a profile.

The shipped preset (``presets.paper_calibrated()``) was fitted to the exact metrics.  Here its metrics
are measured through a 4th-order zero-phase Butterworth low-pass on the accelerometers (table and mass;
the laser as read), and the bumper's numbers that shape a contact pulse (the steep third slope and the
dashpot) are refitted by least squares (``identify``'s refinement from the preset, the "misses" loss) at
each fixed cutoff; with ``--free-cutoff`` the cutoff is fitted with them, within 5-100 Hz.  Each
evaluation measures 322 sweep steps through the chain (about 7 s on one core): a global search of the
preset's 15 numbers at that cost would take days, so this is a local profile, and says so.

    python scripts/calibrate_measured.py --cutoffs 10 15 20 30 50 100 --out profile.csv
    python scripts/calibrate_measured.py --free-cutoff --start-cutoff 15 --out free.csv --toml fitted.toml
    python scripts/calibrate_measured.py --from-measured --cutoffs 10 15 20 30 50 100 --out profile2.csv
"""

from __future__ import annotations

import argparse
import time
import warnings
from pathlib import Path

import pandas as pd

import pounding as pd_
from pounding.identification.measured import CUTOFF

FREE = {"bumper_slope_3": (5e5, 2e8), "bumper_damping": (10.0, 2e4)}  # (calibrate_paper.py's bounds)


def fit(cutoff_hz: float | None, free_cutoff: bool, workers: int,
        start_hz: float = 15.0, from_measured: bool = False) -> pd_.Identification:
    family = pd_.ModelFamily(500.0, branches=4, law="multilinear_kinematic")
    base = pd_.presets.paper_calibrated_measured()[0] if from_measured else pd_.presets.paper_calibrated()
    start = family.values_of(base)
    fixed = {k: v for k, v in start.items() if k not in FREE}
    bounds = dict(FREE)
    x0 = {k: start[k] for k in FREE}
    chain = pd_.MeasurementChain.lowpass(start_hz if cutoff_hz is None else cutoff_hz)
    if free_cutoff:
        bounds[CUTOFF] = (5.0, 100.0)
        x0[CUTOFF] = chain.mass.lowpass_hz
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", pd_.PoundingWarning)
        family = pd_.ModelFamily(500.0, branches=4, law="multilinear_kinematic", fixed=fixed)
        return pd_.identify(pd_.paper_targets(), family, bounds, maxiter=0, x0=x0, refine=True, loss="misses",
                            workers=workers, measurement=chain)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cutoffs", type=float, nargs="*", default=[])
    ap.add_argument("--free-cutoff", action="store_true")
    ap.add_argument("--workers", type=int, default=1)
    ap.add_argument("--start-cutoff", type=float, default=15.0, help="where the free cutoff starts (Hz)")
    ap.add_argument("--from-measured", action="store_true",
                    help="start from presets.paper_calibrated_measured() (else paper_calibrated())")
    ap.add_argument("--out", type=Path, required=True)
    ap.add_argument("--toml", type=Path, default=None, help="write the (last) fitted system here")
    args = ap.parse_args()
    rows = []
    runs = [(c, False) for c in args.cutoffs] + ([(None, True)] if args.free_cutoff else [])
    for cutoff, free in runs:
        t0 = time.perf_counter()
        result = fit(cutoff, free, args.workers, args.start_cutoff, args.from_measured)
        res = result.residuals
        row = {"cutoff_hz": result.measurement.mass.lowpass_hz, "cutoff_free": free, "met": result.n_within,
               "cost": result.cost, "evaluations": result.n_evaluations,
               "seconds": round(time.perf_counter() - t0, 1), **result.parameters,
               "missed": "; ".join(f"{r.configuration} {r.a_g:g} {r.quantity}"
                                   for r in res[~res["within"]].itertuples())}
        rows.append(row)
        print(row, flush=True)
        pd.DataFrame(rows).to_csv(args.out, index=False)
        if args.toml is not None:
            result.to_toml(args.toml)
            result.residuals.to_csv(args.toml.with_suffix(".residuals.csv"), index=False)


if __name__ == "__main__":
    main()
