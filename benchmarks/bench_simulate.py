"""Speed of `simulate` on the printed YBs system at a_G = 0.05, f = 2.2 Hz (issue 2).

Prints simulated seconds per wall second, warm (best of repeats), for pounding with and
without history sampling and for the plain scipy `solve_ivp` reference of the tests, all
measured in this run, and the ratio between them; then the first-call time in a fresh
process with an empty Numba cache (compilation) and with the cache filled.

    python benchmarks/bench_simulate.py
"""

from __future__ import annotations

import os
import platform
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))

import pounding as pd_  # noqa: E402
from reference import reference  # noqa: E402

DURATION_S = 20.0
V0 = 0.6  # starts on the impacting branch: about 2 contacts per cycle


def best_rate(fn, duration_s, repeats=7, min_time_s=0.5):
    best = float("inf")
    for _ in range(repeats):
        n, t0 = 0, time.perf_counter()
        while True:
            fn()
            n += 1
            el = time.perf_counter() - t0
            if el >= min_time_s:
                break
        best = min(best, el / n)
    return duration_s / best, best


COLD = """
import time; t0 = time.perf_counter()
import pounding as p
osc = p.presets.paper_printed()
p.simulate(osc, p.Harmonic(0.05, 2.2), 1.0)
print(time.perf_counter() - t0)
"""


def first_call_s(cache_dir: str) -> float:
    env = dict(os.environ, NUMBA_CACHE_DIR=cache_dir)
    out = subprocess.run([sys.executable, "-c", COLD], env=env, capture_output=True, text=True, check=True)
    return float(out.stdout.strip().splitlines()[-1])


def main() -> None:
    osc = pd_.presets.paper_printed()
    exc = pd_.Harmonic(0.05, 2.2)
    state = pd_.State.at_rest(osc, velocity_m_s=V0)
    run = pd_.simulate(osc, exc, DURATION_S, state, sample_rate_hz=0)
    print(f"machine: {platform.processor() or platform.machine()}, {os.cpu_count()} cores, "
          f"Python {platform.python_version()}")
    print(f"system: paper_printed YBs, a_G = 0.05, f = 2.2 Hz, {DURATION_S:g} s from v0 = {V0} m/s: "
          f"{len(run.contacts)} contacts, {len(run.events)} events")
    rows = []
    for label, rate in (("pounding, no history", 0.0), ("pounding, history at 1 kHz", 1000.0)):
        sps, _ = best_rate(lambda: pd_.simulate(osc, exc, DURATION_S, state, sample_rate_hz=rate), DURATION_S)
        rows.append((label, sps))
    ref_s = 4.0
    sps_ref, _ = best_rate(lambda: reference(osc, exc, ref_s, v0=V0), ref_s, repeats=3, min_time_s=0.1)
    rows.append(("scipy solve_ivp DOP853 + events (rtol 1e-10)", sps_ref))
    print(f"\n{'tool':48s} {'sim s / wall s':>15s} {'ratio to scipy':>15s}")
    for label, sps in rows:
        print(f"{label:48s} {sps:15.0f} {sps / sps_ref:15.1f}")
    with tempfile.TemporaryDirectory() as cache:
        cold = first_call_s(cache)
        cached = first_call_s(cache)
    print(f"\nfirst call in a fresh process: {cold:.1f} s with an empty Numba cache, {cached:.2f} s with it filled")


if __name__ == "__main__":
    main()
