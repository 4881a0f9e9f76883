"""Cold start: how long a user waits before the first result, in a fresh process after installing.

    python benchmarks/cold_start.py             # about a minute on a 2-core machine
    python benchmarks/cold_start.py --build     # and the build of the wheel itself (a few minutes)
    python benchmarks/cold_start.py --no-write  # print only; leave benchmarks/RESULTS.md alone

The engine's core is compiled when the package is built, so nothing is compiled at run time; each
measure runs in a fresh Python process (nothing imported or loaded before) and prints wall seconds:

- the first ``simulate`` of the printed preset (import apart), then in the same process the first
  ``sweep`` and the first ``campaign`` (what each adds);
- the first ``simulate`` and ``sweep`` of the printed and the calibrated presets, import included
  (the first use of the paper's systems; target 2 s);
- ``pounding --help`` and the README's one-run command;
- the first ``pounding reproduce`` against the second (no cache between them any more: equal);
- with ``--build``: ``pip wheel .`` (the core compiled in a build environment of its own).

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
TARGET_S = 2.0
TARGET_REPRODUCE_RATIO = 1.2

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


def _fresh(code: str | None, argv: list[str] | None = None, cwd: str | None = None) -> tuple[float, str]:
    """Run ``code`` (or the command ``argv``) in a new process; (wall seconds, its stdout)."""
    cmd = argv if argv is not None else [sys.executable, "-c", code]
    t = time.perf_counter()
    out = subprocess.run(cmd, capture_output=True, text=True, check=True, cwd=cwd)
    return time.perf_counter() - t, out.stdout


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--no-write", action="store_true", help="print only; leave RESULTS.md alone")
    ap.add_argument("--build", action="store_true", help="also time pip wheel . (the core's build)")
    args = ap.parse_args()
    cli = [sys.executable, "-m", "pounding.cli"]
    with tempfile.TemporaryDirectory() as tmp:
        _, out = _fresh(FIRST_CALLS)
        imp, sim, swp, camp = (float(x) for x in out.split()[-4:])
        print(f"import {imp:.2f} s; first simulate {sim:.2f} s, then sweep +{swp:.2f} s, "
              f"campaign +{camp:.2f} s")
        _, out = _fresh(PAPER_SYSTEMS)
        paper = float(out.split()[-1])
        print("first simulate + sweep of the printed and the calibrated presets, import included: "
              f"{paper:.2f} s")
        helped, _ = _fresh(None, [*cli, "--help"])
        one_run, _ = _fresh(None, [*cli, "simulate", str(HERE.parent / "examples" / "paper_printed_ybs.toml"),
                                   "--a-g", "0.05", "--freq", "2.2", "--duration", "20", "--velocity", "0.6",
                                   "--contacts", os.path.join(tmp, "c.csv")])
        print(f"pounding --help {helped:.2f} s; the README's one run {one_run:.2f} s")
        first, _ = _fresh(None, [*cli, "reproduce", "--out", os.path.join(tmp, "r1")])
        second, _ = _fresh(None, [*cli, "reproduce", "--out", os.path.join(tmp, "r2")])
        print(f"pounding reproduce: first {first:.1f} s, second {second:.1f} s ({first / second:.2f} x)")
        build = None
        if args.build:
            build, _ = _fresh(None, [sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", "-w",
                                     os.path.join(tmp, "w"), str(HERE.parent)])
            print(f"pip wheel . (the core compiled, in a build environment of its own): {build:.0f} s")
    verdict = lambda ok: "met" if ok else "**missed**"  # noqa: E731
    lines = [BEGIN, f"## `python benchmarks/cold_start.py` ({date.today().isoformat()})", "",
             f"Machine: {machine()}.", "",
             "Each row a fresh process; the core was compiled when the package was built.", "",
             "| measure | wall s | target |", "| --- | ---: | ---: |",
             f"| import pounding | {imp:.2f} | |",
             f"| first `simulate` of the printed preset (1 s simulated) | {sim:.2f} | |",
             f"| then the first `sweep` (what it adds) | {swp:.2f} | |",
             f"| then the first `campaign` (what it adds) | {camp:.2f} | |",
             "| first `simulate` + `sweep` of the printed and calibrated presets, import included "
             f"| {paper:.2f} | {TARGET_S:g} |",
             f"| `pounding --help` | {helped:.2f} | |",
             f"| the README's one run (`pounding simulate ... --duration 20`) | {one_run:.2f} | |",
             f"| first `pounding reproduce` | {first:.1f} | {TARGET_REPRODUCE_RATIO:g} x the second |",
             f"| second `pounding reproduce` | {second:.1f} | |",
             *([f"| `pip wheel .` (the core's build, in its own build environment) | {build:.0f} | |"]
               if build is not None else []), "",
             f"Targets: first use of the paper's systems {paper:.2f} s (target {TARGET_S:g} s): "
             f"{verdict(paper <= TARGET_S)}; the first reproduce {first / second:.2f} x the second (target "
             f"{TARGET_REPRODUCE_RATIO:g}): {verdict(first / second <= TARGET_REPRODUCE_RATIO)}.", END]
    print("\n".join(lines[1:-1]))
    if not args.no_write:
        write_section("\n".join(lines), BEGIN, END)


if __name__ == "__main__":
    main()
