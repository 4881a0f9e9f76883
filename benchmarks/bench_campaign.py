"""Speed of the paper's whole campaign in fixed mode (issue 3): 14 sweeps x 46 steps x 30 cycles.

Prints the warm wall time (best of repeats) with 1 worker and with every core, the
simulated seconds per wall second, and the scipy ``solve_ivp`` reference of the tests
running the same protocol on a slice of the campaign (extrapolated per simulated second),
all measured in this run.  Target: the whole campaign at most 1 s warm on the 2-core
development machine.

    python benchmarks/bench_campaign.py
"""

from __future__ import annotations

import os
import platform
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))

import pounding as pd_  # noqa: E402
from reference_sweep import reference_sweep  # noqa: E402

CYCLES, MEASURED = 30, 5


def best_time(fn, repeats=5):
    best = float("inf")
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def main() -> None:
    ybs = pd_.presets.paper_printed()
    nbs = ybs.without_bumpers()
    kw = dict(steady="fixed", cycles=CYCLES, measure_cycles=MEASURED)
    freqs = pd_.paper_frequencies_hz()
    simulated_s = sum(CYCLES / f for f in freqs) * (3 + 4) * 2
    t0 = time.perf_counter()
    result = pd_.campaign(nbs, ybs, **kw)
    first = time.perf_counter() - t0
    cores = os.cpu_count() or 1
    print(f"machine: {platform.processor() or platform.machine()}, {cores} cores, "
          f"Python {platform.python_version()}")
    n_contacts = float((result.dataset["contacts_per_cycle"] * MEASURED).sum())
    print(f"campaign: paper_printed NBs (3 a_G) and YBs (4 a_G), up and down, {freqs.size} steps, "
          f"{CYCLES} cycles per step ({MEASURED} measured): {simulated_s:,.0f} simulated s, "
          f"{n_contacts:,.0f} contacts in the measured windows")
    print(f"first call in this process (Numba cache as found): {first:.2f} s")
    rows = []
    for workers in sorted({1, cores}):
        wall = best_time(lambda: pd_.campaign(nbs, ybs, workers=workers, **kw))
        rows.append((f"pounding.campaign, {workers} worker(s)", wall, simulated_s / wall))
    # the reference on a slice: YBs a_G = 0.05, up, three steps around the resonance
    slice_freqs = [1.4, 1.5, 1.6]
    t0 = time.perf_counter()
    reference_sweep(ybs, 0.05, slice_freqs, CYCLES, MEASURED, rtol=1e-10, atol=1e-13)
    ref_wall = time.perf_counter() - t0
    ref_rate = sum(CYCLES / f for f in slice_freqs) / ref_wall
    rows.append(("scipy solve_ivp reference (rtol 1e-10), extrapolated", simulated_s / ref_rate, ref_rate))
    print(f"\n{'tool':54s} {'wall s':>9s} {'sim s / wall s':>15s} {'ratio to scipy':>15s}")
    for label, wall, rate in rows:
        print(f"{label:54s} {wall:9.3f} {rate:15,.0f} {rate / ref_rate:15,.0f}")
    print(f"\ntarget: whole campaign <= 1 s warm; best {min(r[1] for r in rows[:-1]):.3f} s")


if __name__ == "__main__":
    main()
