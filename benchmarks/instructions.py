"""Instruction counts (callgrind) beside CPU times, for the work every benchmark script times (issue 66).

    python benchmarks/instructions.py            # about 35 minutes; --quick, --no-write, --only NAME
    (needs valgrind on the PATH: apt install valgrind; the FEMA P695 sets: pip install -e ".[records]")

The machines here are noisy: a CPU time moves by tens of per cent from one run to the next, an instruction
count does not. Each work below is built and run once (warm: its caches made, its modules imported), then run
once more in a fresh process under ``valgrind --tool=callgrind`` with collection switched on only inside that
one call (``--toggle-collect`` on ``operator.call``, through which it is made): its count is the whole call's,
Python and the core together, with Python's hashing seeded (``PYTHONHASHSEED=0``) and its garbage collector
held off during the call: the same count from run to run to a few parts in 1,000 (the orbit: 36.79 M and 36.89
M on two days, 151 instructions apart in two runs of a day). A work whose core runs in a thread of its own (a
sweep's steps, a spectrum's runs, a long run's) is also collected in every other thread from its start
(``--toggle-collect=thread_run``) and counted as the process with two calls less the process with one (the
same to 1e-4 from run to run). The CPU time is the best of a few runs of the same call, in this process,
collector on.

Work (each the call a benchmark script times, or one of the many it makes, or a part callgrind runs in a
minute): the long run, the up sweep and the campaign of ``run.py`` (and ``laws.py``'s campaign); the record
run, the elastic and the pounding spectrum of ``records.py`` (the latter for one record, 20 periods);
``structures.py``'s buildings of N = 1, 2, 4 and 8 levels; ``continuation.py``'s branch of the calibrated
preset, an orbit and a Lyapunov spectrum of it; ``diagram.py``'s diagram (by 0.1 Hz); a point of
``study.py``; ``rigid_stops.py``'s chatter; a run of ``design.py``'s stripes; ``rotd.py``'s spectra of one
pair (20 periods); the buildings of ``opensees_building.py``, ``opensees_friction.py``,
``opensees_triple_friction.py`` and ``opensees_plan.py`` (also ``plan_suite.py``'s and ``plan_rubber.py``'s)
under their records. The table goes to benchmarks/RESULTS.md between its ``instructions.py`` markers.
"""

from __future__ import annotations

import argparse
import gc
import operator
import os
import re
import shutil
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from datetime import date
from pathlib import Path
from typing import Callable

import numpy as np

import pounding as pd_
from run import machine, write_section
from structures import cpu_best

BEGIN, END = "<!-- instructions.py: begin -->", "<!-- instructions.py: end -->"
HERE = Path(__file__).resolve()


@dataclass(frozen=True)
class Work:
    """One call to count: ``call``, and what its figure is given per (``units`` of ``unit``)."""

    call: Callable[[], object]
    units: int
    unit: str
    threaded: bool = False  # (its core runs in a thread of its own: counted as a difference, below)


def _record():
    far = pd_.records.fema_p695("far_field")
    return next(r for r in far if r.duration_s >= 40.0).scaled(pga_g=0.3)


def long_run() -> Work:
    from pounding import _core
    from pounding._control import new_control
    from pounding.engine.simulate import kernel_forcing, kernel_system

    osc = pd_.presets.paper_printed()
    sy, fo = kernel_system(osc), kernel_forcing(pd_.Harmonic(0.05, 2.2))
    state0 = pd_.State.at_rest(osc, velocity_m_s=0.6).vector

    def call():
        return _core.run(sy, fo, state0.copy(), 200.0, 0.0, 1e-10, 10**9, False, new_control(10**12))

    return Work(call, int(call().events.shape[0]), "event")


def sweep_up() -> Work:
    osc = pd_.presets.paper_printed()
    freqs = np.round(np.arange(0.5, 5.0 + 1e-9, 0.1), 10)

    def call():
        return pd_.sweep(osc, 0.05, freqs, "up", steady="fixed", cycles=30, measure_cycles=5)

    return Work(call, freqs.size, "step", threaded=True)


def record_run() -> Work:
    osc, rec = pd_.presets.paper_printed(), _record()

    def call():
        return pd_.simulate(osc, rec, rec.duration_s, rtol=1e-10, sample_rate_hz=0)

    return Work(call, len(rec.t), "sample")


def elastic_spectrum() -> Work:
    rec, periods = _record(), np.linspace(0.05, 5.0, 100)
    return Work(lambda: pd_.response_spectrum(rec, periods), periods.size, "period", threaded=True)


def pounding_spectrum() -> Work:
    rec, periods, gaps = _record(), np.linspace(0.05, 5.0, 20), (0.01, 0.02, 0.05)
    return Work(lambda: pd_.pounding_spectrum([rec], periods, gaps_m=gaps, workers=1), periods.size * 4,
                "run", threaded=True)


def building(levels: int) -> Callable[[], Work]:
    def make() -> Work:
        from structures import PGA_G
        from structures import building as shear_building

        b, quake = shear_building(levels), pd_.records.el_centro().scaled(pga_g=PGA_G)
        # (threaded: a run whose sub-intervals may pass simulate's direct call's bound runs in a helper
        # thread, the 8-level building's among them; its count in the main thread alone was the waiting's)
        return Work(lambda: pd_.simulate(b, quake, quake.duration_s, sample_rate_hz=0), len(quake.t),
                    "sample", threaded=True)

    return make


def continuation() -> Work:
    osc = pd_.presets.paper_calibrated()

    def call():
        return pd_.continuation(osc, 0.05, (0.5, 5.0))

    return Work(call, len(call()), "orbit")


def orbit() -> Work:
    osc = pd_.presets.paper_calibrated()
    return Work(lambda: pd_.periodic_orbit(osc, pd_.Harmonic(0.1, 1.3), settle_cycles=20), 1, "orbit")


def lyapunov() -> Work:
    osc = pd_.presets.paper_calibrated()
    return Work(lambda: pd_.lyapunov(osc, pd_.Harmonic(0.05, 1.5), cycles=200), 200, "cycle")


def campaign() -> Work:
    ybs = pd_.presets.paper_printed()
    nbs = ybs.without_bumpers()
    return Work(lambda: pd_.campaign(nbs, ybs, steady="fixed", cycles=30, measure_cycles=5, workers=1), 14,
                "sweep", threaded=True)


def diagram() -> Work:
    osc, freqs = pd_.presets.paper_damped(), np.round(np.arange(0.5, 5.0 + 1e-9, 0.1), 10)
    return Work(lambda: pd_.bifurcation_diagram(osc, 0.05, freqs), 2 * freqs.size, "step", threaded=True)


def study_point() -> Work:
    osc = pd_.presets.paper_printed()
    return Work(lambda: pd_.simulate(osc, pd_.Harmonic(0.05, 2.0), 2600.0, sample_rate_hz=0), 2600,
                "simulated second", threaded=True)


def rigid_stops() -> Work:
    import rigid_stops as rs

    osc, tab = rs.system(), rs.table()

    def call():
        return pd_.simulate(osc, tab, 200.0, sample_rate_hz=0)

    return Work(call, len(call().contacts), "impact", threaded=True)


def design_run() -> Work:
    import design as ds

    osc, rec = ds.system(), _record()
    return Work(lambda: pd_.simulate(osc, rec, rec.duration_s, sample_rate_hz=0), len(rec.t), "sample")


def rotd() -> Work:
    pair, periods = pd_.records.fema_p695_pairs("far_field")[0], np.linspace(0.05, 5.0, 20)
    return Work(lambda: pd_.rotd_spectrum(pair, periods), periods.size, "period", threaded=True)


def record_building(make: Callable[[], tuple[object, object]]) -> Callable[[], Work]:
    def work() -> Work:
        building, rec = make()
        return Work(lambda: pd_.simulate(building, rec, rec.duration_s, sample_rate_hz=0), len(rec.t),
                    "sample", threaded=True)

    return work


def _moat_building():
    import opensees_building as ob

    building = ob.elastic_walls(pd_.Structure.from_toml(ob.toml_path()))
    return building, pd_.records.el_centro().scaled(pga_g=ob.PGA_G)


def _friction_building():
    import opensees_friction as of

    return of.the_building(None)[0], pd_.records.el_centro().scaled(pga_g=of.PGA_G)


def _triple_friction_building():
    import opensees_triple_friction as ot

    return ot.the_building(), pd_.records.el_centro().scaled(pga_g=1.0)


def _plan_building():
    import opensees_plan as op

    return op.building(5), pd_.records.fema_p695_pairs("far_field")[0].scaled(op.SCALE)


WORKS: dict[str, tuple[str, Callable[[], Work]]] = {
    "long": ("long run, printed YBs, 200 s at 2.2 Hz, the core alone", long_run),
    "sweep": ("up sweep, printed YBs, 46 steps of 30 cycles", sweep_up),
    "record": ("one record, printed YBs, at the record's step", record_run),
    "spectrum": ("elastic response spectrum of that record, 100 periods", elastic_spectrum),
    "pounding": ("pounding spectrum of that record, 20 periods x 3 gaps and none, one worker",
                 pounding_spectrum),
    **{f"building{n}": (f"building of N = {n} under El Centro, PGA 0.5 g", building(n))
       for n in (1, 2, 4, 8)},
    "continuation": ("continuation, calibrated preset, a_G 0.05, 0.5-5 Hz", continuation),
    "orbit": ("periodic orbit, calibrated preset, a_G 0.1, 1.3 Hz", orbit),
    "lyapunov": ("Lyapunov spectrum, calibrated preset, a_G 0.05, 1.5 Hz, 200 cycles", lyapunov),
    "campaign": ("campaign (`run.py`, `laws.py`), printed YBs and NBs, 14 sweeps, one worker", campaign),
    "diagram": ("bifurcation diagram (`diagram.py`), paper_damped, 0.5-5 Hz by 0.1, up and down", diagram),
    "study": ("a study's point (`study.py`), printed YBs, 2 Hz, 2600 s", study_point),
    "rigid": ("rigid stops' chatter (`rigid_stops.py`), 200 s", rigid_stops),
    "design": ("a stripe's run (`design.py`), calibrated isolator, Kelvin-Voigt bumpers", design_run),
    "rotd": ("RotD spectra (`rotd.py`), a far-field pair, 20 periods, 180 angles", rotd),
    "moat": ("building pounding its moat (`opensees_building.py`), El Centro 0.6 g",
             record_building(_moat_building)),
    "friction": ("building on friction pendulums (`opensees_friction.py`), El Centro 0.6 g",
                 record_building(_friction_building)),
    "triple": ("building on triple friction pendulums (`opensees_triple_friction.py`), El Centro 1 g",
               record_building(_triple_friction_building)),
    "plan": ("building in plan, 5 storeys (`opensees_plan.py`, `plan_suite.py`), a far-field pair x2",
             record_building(_plan_building)),
}
QUICK = ("long", "orbit", "building4")


def count_one(name: str, calls: int) -> None:
    """(In the process callgrind runs.) Build ``name``'s work, run it once warm, then ``calls`` times
    through ``operator.call`` (where callgrind collects in this thread: :func:`_callgrind`)."""
    work = WORKS[name][1]()
    work.call()
    gc.collect()
    gc.freeze()  # (what the warm call left: out of every later collection)
    gc.disable()  # (no collection inside a counted call: when one falls is not the call's own work)
    for _ in range(calls):
        operator.call(work.call)


def _callgrind(name: str, calls: int) -> int:
    """What callgrind collects in a fresh process that runs ``name``'s work warm, then ``calls`` times:
    inside ``operator.call`` in this thread, and in every other thread from its start (``thread_run``, where
    a Python thread begins: a worker's every call, the warm one's too where the thread lives on)."""
    with tempfile.TemporaryDirectory() as tmp:
        out = subprocess.run(
            ["valgrind", "--tool=callgrind", "--collect-atstart=no", "--toggle-collect=_operator_call*",
             "--toggle-collect=thread_run", f"--callgrind-out-file={Path(tmp) / 'callgrind.out'}",
             sys.executable, str(HERE), "--count", name, "--calls", str(calls)],
            capture_output=True, text=True, cwd=HERE.parent,
            env={**os.environ, "PYTHONHASHSEED": "0"})  # (the same imports' work in every process)
    found = re.search(r"Collected : (\d+)", out.stderr)
    if out.returncode != 0 or found is None:
        raise RuntimeError(f"callgrind on {name!r} failed (exit {out.returncode}):\n{out.stderr[-2000:]}")
    return int(found.group(1))


def instructions(name: str, threaded: bool) -> int:
    """The instructions of one warm call of ``name``'s work: what callgrind collects in it; for a work whose
    core runs in a thread of its own, the count with two calls less the count with one (a worker thread
    collected from its start may hold the warm call's work too)."""
    if not threaded:
        return _callgrind(name, 1)
    return _callgrind(name, 2) - _callgrind(name, 1)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help=f"a smoke run: {', '.join(QUICK)} only")
    parser.add_argument("--no-write", action="store_true", help="print only; leave RESULTS.md alone")
    parser.add_argument("--only", action="append", choices=sorted(WORKS), help="this work alone (repeatable)")
    parser.add_argument("--repeat", type=int, default=5, help="CPU-time runs of each work (the best is kept)")
    parser.add_argument("--count", choices=sorted(WORKS), help=argparse.SUPPRESS)  # (callgrind's process)
    parser.add_argument("--calls", type=int, default=1, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.repeat < 1 or args.calls < 1:
        parser.error("--repeat (and --calls) take a whole number of runs, 1 or more")
    if args.count:
        count_one(args.count, args.calls)
        return
    if shutil.which("valgrind") is None:
        sys.exit("instructions.py needs valgrind's callgrind on the PATH: apt install valgrind")
    names = args.only or (list(QUICK) if args.quick else list(WORKS))
    lines = [BEGIN, f"## `python benchmarks/instructions.py` ({date.today().isoformat()})", "",
             f"Machine: {machine()}.", "",
             "Instructions of one warm call (callgrind, Python and the core together) beside its CPU time "
             f"(best of {args.repeat}); per unit, the call's figure over its units.", "",
             "| work | CPU ms | instructions (M) | units | CPU us per unit | instructions per unit |",
             "| --- | ---: | ---: | ---: | ---: | ---: |"]
    for name in names:
        title, make = WORKS[name]
        try:
            work = make()
        except ImportError as exc:  # (the FEMA set's extra)
            print(f"{name}: skipped: {exc}", file=sys.stderr)
            continue
        work.call()  # (warm, as the counted call is)
        cpu = cpu_best(work.call, args.repeat)[0]
        count = instructions(name, work.threaded)
        if count < 2e8 * cpu:  # (far fewer than its CPU time takes: its core ran in a thread left out)
            raise RuntimeError(f"{name}: {count:,} instructions in {cpu * 1e3:.1f} ms of CPU: its core "
                               "runs in a thread of its own; mark its Work threaded=True")
        unit = work.unit if work.units == 1 else f"{work.unit}s"
        lines.append(f"| {title} | {cpu * 1e3:.2f} | {count / 1e6:,.1f} | {work.units:,} {unit} "
                     f"| {cpu / work.units * 1e6:,.2f} | {count / work.units:,.0f} |")
        print(lines[-1], flush=True)
    lines.append(END)
    if not args.no_write:
        write_section("\n".join(lines), BEGIN, END)


if __name__ == "__main__":
    main()
