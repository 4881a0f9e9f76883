"""Structures of several masses (issue 50): what an event costs as the structure grows, and a building under
a whole record set.

    pip install -e ".[records]"      # the FEMA P695 far-field set
    python benchmarks/structures.py  # about a minute; --no-write to leave RESULTS.md alone

Work:
  1. cost against N: a shear building of N = 1, 2, 4, 8 levels (the base on a bilinear isolator, N - 1
     storeys) in a moat 6 cm wide, under El Centro 1940 N-S scaled to PGA 0.5 g (microseconds per
     record sample: each is a phase) and under a sine that makes it pound every cycle (microseconds per
     event), events only (no history), CPU time, best of 5;
  2. an N = 4 building under the FEMA P695 far-field set (44 components, each scaled to PGA 0.5 g), at
     each record's own step, on 2 worker processes: wall time against the issue's 5 s.
The tables go to benchmarks/RESULTS.md between its ``structures.py`` markers.
"""

from __future__ import annotations

import argparse
import time
from concurrent.futures import ProcessPoolExecutor
from datetime import date

import numpy as np

import pounding as pd_
from run import machine, write_section

BEGIN, END = "<!-- structures.py: begin -->", "<!-- structures.py: end -->"
PGA_G = 0.5
HARMONIC = (0.4, 1.0, 60.0)  # a_G (g), Hz, s: the base pounds its moat wall every cycle
TARGET_SET_S = 5.0


def building(levels: int) -> pd_.Structure:
    """A base of 30 t on a bilinear isolator, ``levels - 1`` storeys of 20 t and 40 MN/m (2 % damping),
    a moat wall 6 cm from the base."""
    iso = pd_.Isolator(slopes_n_m=[4.0e6, 1.0e6], breakpoints_m=[0.02], damping_n_s_m=2.0e4)
    storeys = [pd_.Storey(2.0e4, 4.0e7, 4.0e4)] * (levels - 1)
    moat = pd_.Wall(0, 0.06, 0.06, pd_.KelvinVoigt(stiffness=2.0e8, damping=1.0e5))
    return pd_.Structure(3.0e4, iso, storeys, [moat])


def cpu_best(fn, repeat: int) -> tuple[float, object]:
    best, out = np.inf, None
    for _ in range(repeat):
        t = time.process_time()
        out = fn()
        best = min(best, time.process_time() - t)
    return best, out


def one_record(args: tuple) -> tuple[int, int, float]:
    structure, record = args
    run = pd_.simulate(structure, record, record.duration_s, sample_rate_hz=0)
    return len(run.event_table), len(run.contacts), float(run.abs_acceleration_max.max())


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--no-write", action="store_true")
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    quake = pd_.records.el_centro().scaled(pga_g=PGA_G)
    title = (f"**Cost against N** (El Centro 1940 N-S at PGA {PGA_G:g} g, {quake.duration_s:.1f} s at "
             f"{quake.dt_s:g} s, and a sine of {HARMONIC[0]:g} g at {HARMONIC[1]:g} Hz for "
             f"{HARMONIC[2]:g} s; a moat 6 cm from the base; events only, CPU time, best of {args.repeat})")
    lines = [BEGIN, f"## `python benchmarks/structures.py` ({date.today().isoformat()})", "",
             f"Machine: {machine()}.", "", title, "",
             "| levels N | record: events | impacts | CPU ms | us per sample | vs N = 1 "
             "| sine: events | us per event | vs N = 1 |",
             "| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
    first = None
    for n in (1, 2, 4, 8):
        b = building(n)
        pd_.simulate(b, quake, 2.0, sample_rate_hz=0)  # (warm)
        cpu, run = cpu_best(lambda: pd_.simulate(b, quake, quake.duration_s, sample_rate_hz=0), args.repeat)
        sine = pd_.Harmonic(HARMONIC[0], HARMONIC[1])
        cpu_h, run_h = cpu_best(lambda: pd_.simulate(b, sine, HARMONIC[2], sample_rate_hz=0), args.repeat)
        per_sample = cpu / len(quake.t) * 1e6
        per_event = cpu_h / max(len(run_h.event_table), 1) * 1e6
        first = first or (per_sample, per_event)
        lines.append(f"| {n} | {len(run.event_table)} | {len(run.contacts)} | {cpu * 1e3:.2f} "
                     f"| {per_sample:.3f} | {per_sample / first[0]:.2f} | {len(run_h.event_table)} "
                     f"| {per_event:.2f} | {per_event / first[1]:.2f} |")
        print(lines[-1])
    suite = [r.scaled(pga_g=PGA_G) for r in pd_.records.fema_p695("far_field")]
    b4 = building(4)
    with ProcessPoolExecutor(2) as pool:
        list(pool.map(one_record, [(b4, suite[0])] * 2))  # (the workers started and warm)
        t = time.perf_counter()
        out = list(pool.map(one_record, [(b4, r) for r in suite]))
        wall = time.perf_counter() - t
    samples = sum(len(r.t) for r in suite)
    hit = sum(1 for _, impacts, _ in out if impacts)
    verdict = "met" if wall <= TARGET_SET_S else "missed"
    lines += ["", f"**An N = 4 building under the FEMA P695 far-field set** ({len(suite)} components, each "
              f"scaled to PGA {PGA_G:g} g, {samples:,} record samples in all, each at its own step), 2 "
              "worker processes, warm:", "",
              f"- wall time {wall:.2f} s (target {TARGET_SET_S:g} s: {verdict}); "
              f"{sum(e for e, _, _ in out):,} events; {hit} of {len(suite)} records pound the moat wall.",
              END]
    print("\n".join(lines[-4:]))
    if not args.no_write:
        write_section("\n".join(lines), BEGIN, END)


if __name__ == "__main__":
    main()
