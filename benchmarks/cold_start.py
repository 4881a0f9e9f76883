"""Cold start: how long a user waits for the engine's first compilation, measured from an empty cache.

    python benchmarks/cold_start.py             # about 5 minutes on a 2-core machine
    python benchmarks/cold_start.py --no-write  # print only; leave benchmarks/RESULTS.md alone

Each measure runs in a fresh Python process with ``NUMBA_CACHE_DIR`` pointing at a new, empty
folder (nothing compiled before), and prints wall seconds:

- the first ``simulate`` of the printed preset (import apart), then in the same process the first
  ``sweep`` and the first ``campaign`` (what each adds);
- the first ``simulate`` and ``sweep`` of the printed and the calibrated presets, import included
  (the first use of the paper's systems);
- ``pounding warm-up`` (every kernel);
- the first ``pounding reproduce`` after installing (an empty cache) against the second (the cache
  filled by the first).

It rewrites its block of ``benchmarks/RESULTS.md`` (between its markers) with the figures and the
machine. The machines here are noisy: run it on an otherwise idle machine.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from datetime import date
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from run import machine, write_section  # noqa: E402  (the shared helpers of the benchmarks)

BEGIN, END = "<!-- cold_start.py: begin -->", "<!-- cold_start.py: end -->"
TARGET_S = 10.0
TARGET_REPRODUCE_RATIO = 1.5

FIRST_CALLS = """
import time
t0 = time.perf_counter()
import pounding as p
t1 = time.perf_counter()
osc = p.presets.paper_printed()
p.simulate(osc, p.Harmonic(0.05, 2.2), 1.0)
t2 = time.perf_counter()
p.sweep(osc, 0.05, [1.0, 2.0], steady="fixed", cycles=5)
t3 = time.perf_counter()
p.campaign(osc.without_bumpers(), osc, nbs_a_g=[0.05], ybs_a_g=[0.05], freqs_hz=[1.0, 2.0],
           directions=["up"], steady="fixed", cycles=5)
t4 = time.perf_counter()
print(t1 - t0, t2 - t1, t3 - t2, t4 - t3)
"""

PAPER_SYSTEMS = """
import time
t0 = time.perf_counter()
import pounding as p
for osc in (p.presets.paper_printed(), p.presets.paper_calibrated()):
    p.simulate(osc, p.Harmonic(0.05, 2.2), 1.0)
    p.sweep(osc, 0.05, [1.0, 2.0], steady="fixed", cycles=5)
print(time.perf_counter() - t0)
"""


def _fresh(code: str | None, cache: str, argv: list[str] | None = None,
           cwd: str | None = None) -> tuple[float, str]:
    """Run ``code`` (or the command ``argv``) in a new process with ``cache`` as Numba's cache;
    (wall seconds, its stdout)."""
    env = dict(os.environ, NUMBA_CACHE_DIR=cache)
    cmd = argv if argv is not None else [sys.executable, "-c", code]
    t = time.perf_counter()
    out = subprocess.run(cmd, env=env, capture_output=True, text=True, check=True, cwd=cwd)
    return time.perf_counter() - t, out.stdout


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--no-write", action="store_true", help="print only; leave RESULTS.md alone")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        _, out = _fresh(FIRST_CALLS, os.path.join(tmp, "a"))
        imp, sim, swp, camp = (float(x) for x in out.split()[-4:])
        print(f"import {imp:.1f} s; first simulate {sim:.1f} s, then sweep +{swp:.1f} s, "
              f"campaign +{camp:.1f} s")
        _, out = _fresh(PAPER_SYSTEMS, os.path.join(tmp, "b"))
        paper = float(out.split()[-1])
        print("first simulate + sweep of the printed and the calibrated presets, import included: "
              f"{paper:.1f} s")
        warm, _ = _fresh(None, os.path.join(tmp, "c"), [sys.executable, "-m", "pounding.cli", "warm-up"])
        print(f"pounding warm-up from an empty cache: {warm:.1f} s")
        cache = os.path.join(tmp, "d")
        first, _ = _fresh(None, cache, [sys.executable, "-m", "pounding.cli", "reproduce", "--out",
                                        os.path.join(tmp, "r1")])
        second, _ = _fresh(None, cache, [sys.executable, "-m", "pounding.cli", "reproduce", "--out",
                                         os.path.join(tmp, "r2")])
        print(f"pounding reproduce: first {first:.1f} s, second {second:.1f} s ({first / second:.2f} x)")
    verdict = lambda ok: "met" if ok else "**missed**"  # noqa: E731
    lines = [BEGIN, f"## `python benchmarks/cold_start.py` ({date.today().isoformat()})", "",
             f"Machine: {machine()}.", "",
             "Each row a fresh process with an empty Numba cache (`NUMBA_CACHE_DIR` a new folder).", "",
             "| measure | wall s | target |", "| --- | ---: | ---: |",
             f"| import pounding | {imp:.1f} | |",
             f"| first `simulate` of the printed preset (1 s simulated) | {sim:.1f} | {TARGET_S:g} |",
             f"| then the first `sweep` (what it adds) | {swp:.1f} | |",
             f"| then the first `campaign` (what it adds) | {camp:.1f} | |",
             "| first `simulate` + `sweep` of the printed and calibrated presets, import included "
             f"| {paper:.1f} | {TARGET_S:g} |",
             f"| `pounding warm-up` | {warm:.1f} | {TARGET_S:g} |",
             f"| first `pounding reproduce` (empty cache) | {first:.1f} "
             f"| {TARGET_REPRODUCE_RATIO:g} x the second |",
             f"| second `pounding reproduce` (cache filled) | {second:.1f} | |", "",
             f"Targets: first use of the paper's systems {paper:.1f} s (target {TARGET_S:g} s): "
             f"{verdict(paper <= TARGET_S)}; warm-up {warm:.1f} s: {verdict(warm <= TARGET_S)}; the first "
             f"reproduce {first / second:.2f} x the second (target {TARGET_REPRODUCE_RATIO:g}): "
             f"{verdict(first / second <= TARGET_REPRODUCE_RATIO)}.", END]
    print("\n".join(lines[1:-1]))
    if not args.no_write:
        write_section("\n".join(lines), BEGIN, END)


if __name__ == "__main__":
    main()
