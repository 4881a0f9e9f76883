"""pounding against OpenSeesPy and scipy on the same work, in the same run (issue 5).

    pip install -e ".[bench]"      # the peers (openseespy; eqsig and sdof for records.py); scipy comes with
    pounding
    python benchmarks/run.py       # about 3 minutes; --quick for a smoke run, --no-write
                                   # to leave benchmarks/RESULTS.md alone

Work: the printed YBs system (``presets.paper_printed()``, kinematic isolator).
  1. a stepped sweep, a_G = 0.05, up, 0.5 to 5.0 Hz, 30 cycles per step, the last 5 measured;
  2. one long run, 60 s at 2.2 Hz from v0 = 0.6 m/s (the impacting branch), the last 5
     cycles measured.
Per tool: wall time, simulated seconds per wall second, and the largest relative error of
alpha and eta (over the steps) against a converged reference: pounding at rtol 1e-12,
cross-checked against OpenSeesPy at a 0.125 ms step.  Then pounding/peer speed ratios, the
whole campaign on one core and on all, the engine's own cost (one long run without a history:
simulated seconds per CPU second, CPU time per event, evaluations of the trajectory per event), and
the cold start (a fresh process: import and first
call; the core is compiled when the package is built, so nothing is compiled at run time).  The table goes to
benchmarks/RESULTS.md between its ``run.py`` markers, with the machine's description.
"""

from __future__ import annotations

import argparse
import os
import platform
import subprocess
import sys
import time
from datetime import date
from pathlib import Path

import numpy as np

import pounding as pd_
import peers

HERE = Path(__file__).resolve().parent
RESULTS = HERE / "RESULTS.md"
BEGIN, END = "<!-- run.py: begin -->", "<!-- run.py: end -->"
A_G, CYCLES, MEASURED = 0.05, 30, 5
LONG_F_HZ, LONG_S, LONG_V0 = 2.2, 60.0, 0.6
TARGET_SPEED, TARGET_ERROR = 1000.0, 100.0
TARGET_CAMPAIGN_S, TARGET_COLD_S = 0.5, 2.0
ENGINE_S, TARGET_ENGINE_RATE, TARGET_EVALS = 200.0, 150_000.0, 2.0


def machine() -> str:
    cpu = platform.processor() or platform.machine()
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    mem = ""
    try:
        kb = int(Path("/proc/meminfo").read_text().split()[1])
        mem = f", {kb / 2**20:.0f} GiB"
    except (OSError, ValueError, IndexError):
        pass
    import scipy
    return (f"{cpu}, {os.cpu_count()} cores{mem}, {platform.system()} {platform.release()}; "
            f"Python {platform.python_version()}, NumPy {np.__version__}, SciPy {scipy.__version__}, "
            f"pounding {pd_.__version__ if hasattr(pd_, '__version__') else 'dev'}")


# pounding's linear phases are closed forms, so its default rtol (which only steers the
# numeric contact laws) gives the reference's numbers to the last digit: its error is
# counted as this floor, the size of the rounding noise in alpha and eta
ERROR_FLOOR = 1e-12


def errors(outcome, ref, keep=None):
    """Largest relative error of alpha and of eta over the steps (those of ``keep`` only)."""
    keep = np.ones(ref.alpha.size, bool) if keep is None else keep
    return (float(np.max(np.abs(outcome.alpha[keep] / ref.alpha[keep] - 1.0))),
            float(np.max(np.abs(outcome.eta[keep] / ref.eta[keep] - 1.0))))


def fmt_error(e: float) -> str:
    return f"< {ERROR_FLOOR:.0e}" if e < ERROR_FLOOR else f"{e:.1e}"


def table(title, outcomes, ref, pounding_row, keep=None):
    lines = [f"**{title}**", "",
             "| tool | wall s | simulated s / wall s | alpha error | eta error | pounding speed / tool |",
             "| --- | ---: | ---: | ---: | ---: | ---: |"]
    for o in outcomes:
        ea, ee = errors(o, ref, keep)
        ratio = pounding_row.rate / o.rate
        lines.append(f"| {o.tool} | {o.wall_s:.4g} | {o.rate:,.0f} | {fmt_error(ea)} | {fmt_error(ee)} "
                     f"| {ratio:,.0f} |")
    return lines


def verdict(ok: bool) -> str:
    return "met" if ok else "**missed**"


COLD = """
import sys, time
t0 = time.perf_counter()
import pounding as p
t1 = time.perf_counter()
osc = p.presets.paper_printed()
if sys.argv[1] == "simulate":
    p.simulate(osc, p.Harmonic(0.05, 2.2), 1.0)
else:
    p.campaign(osc.without_bumpers(), osc, freqs_hz=[1.0, 2.0], steady="fixed", cycles=3, measure_cycles=1)
t2 = time.perf_counter()
print(t1 - t0, t2 - t1)
"""


def first_call(what: str) -> tuple[float, float]:
    """(import s, first call s) in a fresh process."""
    out = subprocess.run([sys.executable, "-c", COLD, what], capture_output=True, text=True, check=True)
    imp, call = out.stdout.split()[-2:]
    return float(imp), float(call)


def engine_cost(duration_s: float, repeats: int) -> dict:
    """The core alone on one long run of the printed YBs system (a_G 0.05, 2.2 Hz, v0 0.6 m/s), no
    history (events only) and no ledger: the best CPU time of ``repeats`` runs, its events, sub-intervals
    and the evaluations of the trajectory at an instant inside a sub-interval (the cost of finding events)."""
    from pounding import _core
    from pounding._control import CTL_EVALS, CTL_WORK, new_control
    from pounding.engine.simulate import kernel_forcing, kernel_system

    osc = pd_.presets.paper_printed()
    sy, fo = kernel_system(osc), kernel_forcing(pd_.Harmonic(A_G, LONG_F_HZ))
    state0 = pd_.State.at_rest(osc, velocity_m_s=LONG_V0).vector
    best, out, ctl = np.inf, None, None
    for _ in range(repeats):
        ctl = new_control(10**12)
        t0 = time.process_time()
        out = _core.run(sy, fo, state0.copy(), duration_s, 0.0, 1e-10, 10**9, False, ctl)
        best = min(best, time.process_time() - t0)
    n_events = max(int(out.events.shape[0]), 1)
    return {"duration_s": duration_s, "cpu_s": best, "rate": duration_s / best, "events": n_events,
            "subintervals": int(ctl[CTL_WORK]), "us_per_event": best / n_events * 1e6,
            "evals_per_event": int(ctl[CTL_EVALS]) / n_events}


def campaign_times(repeats: int) -> list[tuple[int, float, float]]:
    ybs = pd_.presets.paper_printed()
    nbs = ybs.without_bumpers()
    kw = dict(steady="fixed", cycles=CYCLES, measure_cycles=MEASURED)
    freqs = pd_.paper_frequencies_hz()
    simulated = float(np.sum(CYCLES / freqs)) * (3 + 4) * 2
    pd_.campaign(nbs, ybs, **kw)
    rows = []
    for workers in sorted({1, os.cpu_count() or 1}):
        best = min(_timed(lambda: pd_.campaign(nbs, ybs, workers=workers, **kw)) for _ in range(repeats))
        rows.append((workers, best, simulated / best))
    return rows


def _timed(fn) -> float:
    t0 = time.perf_counter()
    fn()
    return time.perf_counter() - t0


def pounding_and_opensees(pounding, opensees, ops, *work) -> list:
    """pounding's and OpenSeesPy's (1 ms step) outcomes on the same ``work`` (the tools'
    shared leading arguments), their timed rounds alternating (``peers.alternating``);
    OpenSeesPy's left out when it is not installed."""
    tools = [lambda s: pounding(*work, rounds=1, min_wall_s=s)]
    if ops is not None:
        tools.append(lambda s: opensees(ops, *work, 1e-3, rounds=1, min_wall_s=s))
    return peers.alternating(tools)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true", help="fewer frequencies, shorter runs: a smoke test")
    ap.add_argument("--no-write", action="store_true", help="print only; leave RESULTS.md alone")
    args = ap.parse_args()
    freqs = pd_.paper_frequencies_hz()
    long_s = LONG_S
    if args.quick:
        freqs, long_s = freqs[::9], 10.0
    osc = pd_.presets.paper_printed()
    exc = pd_.Harmonic(A_G, LONG_F_HZ)
    print(f"machine: {machine()}")
    ops, missing = peers.load_opensees()
    if missing:
        print(f"OpenSeesPy: not measured: {missing}")

    print("\n[1] stepped sweep (YBs, a_G = 0.05, up, 30 cycles per step, last 5 measured)")
    ref = peers.pounding_sweep(osc, A_G, freqs, CYCLES, MEASURED, rtol=1e-12, rounds=1)
    sweep_rows = pounding_and_opensees(peers.pounding_sweep, peers.opensees_sweep, ops,
                                       osc, A_G, freqs, CYCLES, MEASURED)
    cross = None
    if ops is not None:
        cross = peers.opensees_sweep(ops, osc, A_G, freqs, CYCLES, MEASURED, 0.125e-3, rounds=1)
        sweep_rows.append(cross)
    for rtol, atol in ((1e-6, 1e-9), (1e-10, 1e-13)):
        sweep_rows.append(peers.scipy_sweep(osc, A_G, freqs, CYCLES, MEASURED, rtol, atol))
    ill = peers.ill_conditioned_steps(osc, A_G, freqs, CYCLES, MEASURED, ref)
    print("\n".join(table("sweep, well-conditioned steps", sweep_rows, ref, sweep_rows[0], ~ill)))
    print(f"ill-conditioned steps (left out of the errors): {freqs[ill]} Hz")

    print(f"\n[2] one long run ({long_s:g} s at {LONG_F_HZ} Hz from v0 = {LONG_V0} m/s, last 5 cycles "
          "measured)")
    lref = peers.pounding_long(osc, exc, long_s, LONG_V0, MEASURED, rtol=1e-12, rounds=1)
    long_rows = pounding_and_opensees(peers.pounding_long, peers.opensees_long, ops,
                                      osc, exc, long_s, LONG_V0, MEASURED)
    if ops is not None:
        long_rows.append(peers.opensees_long(ops, osc, exc, long_s, LONG_V0, MEASURED, 0.125e-3, rounds=1))
    for rtol, atol in ((1e-6, 1e-9), (1e-10, 1e-13)):
        long_rows.append(peers.scipy_long(osc, exc, long_s, LONG_V0, MEASURED, rtol, atol))
    print("\n".join(table("long run", long_rows, lref, long_rows[0])))

    print("\n[3] the whole campaign (14 sweeps x 46 steps x 30 cycles, fixed mode), warm, best of 5")
    camp = campaign_times(2 if args.quick else 5)
    for workers, wall, rate in camp:
        print(f"  {workers} worker(s): {wall:.3f} s ({rate:,.0f} simulated s / wall s)")

    print(f"\n[4] the engine's cost: one run of {ENGINE_S:g} s at {LONG_F_HZ} Hz, no history, best of 5 "
          "(CPU time)")
    eng = engine_cost(20.0 if args.quick else ENGINE_S, 5)
    print(f"  {eng['rate']:,.0f} simulated s / CPU s; {eng['events']:,} events, {eng['subintervals']:,} "
          f"sub-intervals; {eng['us_per_event']:.2f} us and {eng['evals_per_event']:.2f} evaluations per "
          "event")

    print("\n[5] cold start: a fresh process, import and first call")
    cold = {}
    for what in ("simulate", "campaign"):
        cold[what] = min(first_call(what) for _ in range(3))
        imp, call = cold[what]
        print(f"  first {what}: {call:.2f} s (import {imp:.2f} s; best of 3)")

    lines = report(freqs, ill, sweep_rows, ref, cross, long_rows, lref, camp, eng, cold, ops is not None,
                   missing)
    print("\n" + "\n".join(lines[lines.index("Targets:"):]))
    if not args.no_write and not args.quick:
        write_results(lines)
        print(f"\nwritten to {RESULTS}")


def report(freqs, ill, sweep_rows, ref, cross, long_rows, lref, camp, eng, cold, have_ops, missing):
    lines = [BEGIN, f"## `python benchmarks/run.py` ({date.today().isoformat()})", "",
             f"Machine: {machine()}.", "",
             f"System: `presets.paper_printed()` (YBs, kinematic isolator). Reference: pounding at rtol "
             f"1e-12; errors are the largest relative error over the {int((~ill).sum())} well-conditioned "
             f"steps of {len(freqs)}.", "",
             f"Timing: pounding and OpenSeesPy at 1 ms, the best of {peers.ROUNDS} rounds taken in turn "
             f"(pounding, OpenSeesPy, pounding, ...), each round the mean wall time of runs repeated back "
             f"to back for at least {peers.ROUND_MIN_S:g} s (one run of a peer); the other peers, one run.",
             ""]
    lines += table(f"Stepped sweep: a_G = {A_G}, up, {freqs[0]:g}-{freqs[-1]:g} Hz, {CYCLES} cycles per step "
                   f"(last {MEASURED} measured), {sweep_rows[0].simulated_s:,.0f} simulated s",
                   sweep_rows, ref, sweep_rows[0], ~ill) + [""]
    worst = ", ".join(f"{o.tool.split(',')[0].split(' (')[0]}"
                      f"{o.tool[o.tool.find(' dt'):] if ' dt' in o.tool else ''}"
                      f"{' ' + o.tool[o.tool.find('(rtol'):] if '(rtol' in o.tool else ''} "
                      f"{errors(o, ref)[0]:.1e}"
                      for o in sweep_rows[1:])
    lines += [f"Ill-conditioned steps, left out above: {', '.join(f'{f:g}' for f in freqs[ill])} Hz (a 1e-9 "
              f"change of the mass moves alpha or eta by more than 1e-6 there: the sweep grazes the bumpers "
              f"and the barely damped transient decides what follows). Over all steps the largest alpha "
              f"errors are: {worst}.", ""]
    lines += table(f"Long run: {long_rows[0].simulated_s:g} s at {LONG_F_HZ} Hz from v0 = {LONG_V0} m/s "
                   f"(last {MEASURED} cycles measured)", long_rows, lref, long_rows[0]) + [""]
    if cross is not None:
        ea, ee = errors(cross, ref, ~ill)
        e1a, e1e = errors(sweep_rows[1], ref, ~ill)
        lines += [f"Cross-check of the reference: OpenSeesPy at 0.125 ms agrees with it to {ea:.1e} (alpha) "
                  f"and {ee:.1e} (eta); at 1 ms to {e1a:.1e} and {e1e:.1e}: it converges towards the "
                  f"reference.", ""]
    lines += ["| campaign, warm (best of 5) | wall s | simulated s / wall s |", "| --- | ---: | ---: |"]
    lines += [f"| {w} worker(s) | {wall:.3f} | {rate:,.0f} |" for w, wall, rate in camp] + [""]
    lines += [f"| the engine: {eng['duration_s']:g} s at {LONG_F_HZ} Hz, no history (best of 5, CPU time) "
              "| value |",
              "| --- | ---: |",
              f"| simulated s / CPU s | {eng['rate']:,.0f} |",
              f"| events | {eng['events']:,} |",
              f"| sub-intervals | {eng['subintervals']:,} |",
              f"| CPU us per event | {eng['us_per_event']:.2f} |",
              f"| evaluations of the trajectory per event | {eng['evals_per_event']:.2f} |", ""]
    lines += ["| cold start (a fresh process, best of 3) | import s | first call s |",
              "| --- | ---: | ---: |"]
    lines += [f"| first `{what}` | {c[0]:.2f} | {c[1]:.2f} |" for what, c in cold.items()] + [""]
    lines += ["Targets:"]
    if have_ops:
        for name, rows, r, keep in (("sweep", sweep_rows, ref, ~ill), ("long run", long_rows, lref, None)):
            speed = rows[0].rate / rows[1].rate
            err_ratio = min(e1 / max(e0, ERROR_FLOOR)
                            for e0, e1 in zip(errors(rows[0], r, keep), errors(rows[1], r, keep)))
            lines.append(f"- {name}: {speed:,.0f} x OpenSeesPy's speed at 1 ms (target {TARGET_SPEED:g}): "
                         f"{verdict(speed >= TARGET_SPEED)}; error {err_ratio:.1e} x smaller (target "
                         f"{TARGET_ERROR:g}; pounding's error counted as {ERROR_FLOOR:g}): "
                         f"{verdict(err_ratio >= TARGET_ERROR)}.")
    else:
        lines.append(f"- OpenSeesPy targets not measured: {missing}.")
    lines.append(f"- engine: {eng['rate']:,.0f} simulated s per CPU s (target {TARGET_ENGINE_RATE:,.0f}): "
                 f"{verdict(eng['rate'] >= TARGET_ENGINE_RATE)}; {eng['evals_per_event']:.2f} evaluations "
                 f"per event (target {TARGET_EVALS:g}): {verdict(eng['evals_per_event'] <= TARGET_EVALS)}.")
    best_camp = min(w for _, w, _ in camp)
    cold_s = max(c[0] + c[1] for c in cold.values())
    lines += [f"- campaign {best_camp:.3f} s warm (target {TARGET_CAMPAIGN_S} s): "
              f"{verdict(best_camp <= TARGET_CAMPAIGN_S)}.",
              f"- cold start {cold_s:.2f} s, import and first call (target {TARGET_COLD_S:g} s): "
              f"{verdict(cold_s <= TARGET_COLD_S)}.", END]
    return lines


def write_results(lines):
    text = RESULTS.read_text() if RESULTS.exists() else "# Benchmark results\n"
    block = "\n".join(lines)
    if BEGIN in text and END in text:
        head, rest = text.split(BEGIN, 1)
        text = head + block + rest.split(END, 1)[1]
    else:
        head, _, tail = text.partition("\n")
        text = f"{head}\n\n{block}\n{tail}"
    RESULTS.write_text(text)


def write_section(text: str, begin: str, end: str) -> None:
    """Put ``text`` (which starts with ``begin`` and ends with ``end``) in RESULTS.md in place of
    the section between those markers, or at its end the first time."""
    body = RESULTS.read_text()
    if begin in body and end in body:
        head, rest = body.split(begin, 1)
        body = head + text + rest.split(end, 1)[1]
    else:
        body = body.rstrip("\n") + "\n\n" + text + "\n"
    RESULTS.write_text(body)
    print(f"\nwritten to {RESULTS}")


if __name__ == "__main__":
    main()
