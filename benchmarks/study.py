"""Parameter studies (issue 19): the store's overhead, scaling from 1 to 2 workers, throughput.

    python benchmarks/study.py            # about 6 minutes; --quick for a smoke run, --no-write

Work:
  1. overhead: 120 simulate points of about 50 ms each (the paper's printed YBs system, 2 Hz,
     2600 s, over a grid of gaps and a_G), computed in a plain loop (``compute_point``, no store)
     and as a study on one thread (template, chunks, Zarr writes): the study's extra time;
  2. scaling: the same study on 1 and 2 workers, on threads, on processes (the first study of
     a fresh interpreter, which starts the forkserver its workers fork from, and later studies)
     and on Dask (a LocalCluster of 1 or 2 worker processes, started before: a cluster outlives
     its studies);
  3. throughput: a 10,000-point simulate study (20 s runs) on two threads, in points per second.
The tables go to benchmarks/RESULTS.md between its ``study.py`` markers.
"""

from __future__ import annotations

import argparse
import shutil
import subprocess
import sys
import tempfile
import time
from datetime import date
from pathlib import Path

import numpy as np

import pounding as pd_
from pounding.studies.points import compute_point
from run import machine, write_section

BEGIN, END = "<!-- study.py: begin -->", "<!-- study.py: end -->"
TARGET_OVERHEAD, TARGET_SCALING = 0.05, 1.8


def spec(n_gap: int, n_ag: int, duration_s: float) -> pd_.StudySpec:
    return pd_.StudySpec(pd_.presets.paper_printed(), {"kind": "simulate", "freq_hz": 2.0,
                                                       "duration_s": duration_s},
                         {"bumpers.gap_right_m": list(np.round(np.linspace(0.008, 0.03, n_gap), 6)),
                          "a_g": list(np.round(np.linspace(0.03, 0.3, n_ag), 6))})


def timed(fn) -> float:
    t0 = time.perf_counter()
    fn()
    return time.perf_counter() - t0


def run_study(sp: pd_.StudySpec, folder: Path, name: str, **kwargs) -> float:
    store = folder / f"{name}.zarr"
    shutil.rmtree(store, ignore_errors=True)
    wall = timed(lambda: pd_.study(sp, store, progress=False, **kwargs))
    assert bool(pd_.open_study(store).complete)
    return wall


def _first_study(quick: bool, workers: int, folder: Path) -> float:
    """Wall time of the scaling study on processes in a fresh interpreter (its first study)."""
    cmd = [sys.executable, __file__, "--first-study", str(workers), "--folder",
           str(folder)] + ["--quick"] * quick
    return float(subprocess.run(cmd, capture_output=True, text=True, check=True).stdout.split()[-1])


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="a smoke run: small studies")
    ap.add_argument("--no-write", action="store_true", help="print only; leave RESULTS.md alone")
    ap.add_argument("--first-study", type=int, metavar="WORKERS", help=argparse.SUPPRESS)
    ap.add_argument("--folder", type=Path, help=argparse.SUPPRESS)
    args = ap.parse_args()
    n_gap, n_ag = (4, 5) if args.quick else (12, 20)
    sp = spec(n_gap, n_ag, 2600.0)
    if args.first_study:  # (a fresh interpreter, for _first_study)
        print(run_study(sp, args.folder, f"first{args.first_study}", workers=args.first_study,
                        scheduler="processes"))
        return
    from distributed import Client, LocalCluster

    folder = Path(tempfile.mkdtemp(prefix="pounding-study-bench-"))
    lines = [BEGIN, f"## `python benchmarks/study.py` ({date.today()})", "", f"Machine: {machine()}.", ""]

    # 1. overhead against a plain loop, one thread
    def plain() -> None:
        for index in sp.indices():
            osc, options = sp.point(index)
            compute_point(osc, options)

    # interleaved, the best of each (this machine's noise is +-10 % from run to run)
    direct = one = float("inf")
    for _ in range(2 if args.quick else 4):
        direct = min(direct, timed(plain))
        one = min(one, run_study(sp, folder, "one", workers=1))
    per_point = direct / sp.size
    overhead = one / direct - 1.0
    lines += [f"**Overhead: {sp.size} simulate points of {per_point * 1e3:.0f} ms, one thread**", "",
              "| how | wall s | per point ms |", "| --- | ---: | ---: |",
              f"| plain loop (compute_point, no store) | {direct:.2f} | {per_point * 1e3:.1f} |",
              f"| pounding.study, workers=1 (template, chunks, Zarr writes) | {one:.2f} | "
              f"{one / sp.size * 1e3:.1f} |",
              "", f"Overhead {overhead * 100:+.1f} % (target at most {TARGET_OVERHEAD * 100:g} %).", ""]

    # 2. scaling from 1 to 2 workers
    rows = []
    t1, t2 = (min(run_study(sp, folder, f"threads{n}", workers=n, scheduler="threads") for _ in range(2))
              for n in (1, 2))
    rows.append(("threads", t1, t2))
    # processes: the first study of a session starts the forkserver (an interpreter importing pounding and
    # loading the compiled kernels), measured in a fresh interpreter; later studies fork from it at once
    t1, t2 = (min(_first_study(args.quick, n, folder) for _ in range(2)) for n in (1, 2))
    rows.append(("processes, first study of a session (forkserver start-up inside)", t1, t2))
    t1, t2 = (min(run_study(sp, folder, f"processes{n}", workers=n, scheduler="processes") for _ in range(2))
              for n in (1, 2))
    rows.append(("processes, later studies (forkserver running)", t1, t2))
    for n in (1, 2):
        with LocalCluster(n_workers=n, threads_per_worker=1, processes=True,
                          dashboard_address=None) as cluster, \
                Client(cluster) as client:
            # (each worker imports pounding once, as a long-lived cluster has)
            client.run(lambda: __import__("pounding").simulate)
            t = min(run_study(sp, folder, f"dask{n}", scheduler=client) for _ in range(2))
        if n == 1:
            t1 = t
        else:
            rows.append(("Dask LocalCluster (started before)", t1, t))
    lines += [f"**Scaling: the same {sp.size}-point study on 1 and 2 workers**", "",
              "| scheduler | 1 worker s | 2 workers s | speed-up |", "| --- | ---: | ---: | ---: |"]
    lines += [f"| {label} | {a:.2f} | {b:.2f} | {a / b:.2f} |" for label, a, b in rows]
    lines += ["",
              f"Target: at least {TARGET_SCALING:g}x with processes and with Dask. Worker processes are "
              "forked from a forkserver that imported pounding and loaded the compiled kernels once; it is "
              "started by the first study of a Python session (about 1.3 s, inside the first row's times) "
              "and serves the later ones.", ""]

    # 3. throughput of a 10,000-point simulate study
    big = spec(50, 20, 20.0) if args.quick else spec(100, 100, 20.0)
    wall = run_study(big, folder, "big", workers=2)
    lines += [f"**Throughput: a {big.size:,}-point simulate study (20 s runs at 2 Hz), two threads**", "",
              f"{wall:.1f} s wall: {big.size / wall:,.0f} points per second.", "", END]
    shutil.rmtree(folder, ignore_errors=True)
    text = "\n".join(lines)
    print(text)
    if not args.no_write:
        write_section(text, BEGIN, END)


if __name__ == "__main__":
    main()
