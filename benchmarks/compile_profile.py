"""Where the cold start goes: the engine's compile time, function by function, from an empty cache.

    python benchmarks/compile_profile.py             # about a minute on a 2-core machine
    python benchmarks/compile_profile.py --top 40    # more rows
    python benchmarks/compile_profile.py --no-write  # print only; leave benchmarks/RESULTS.md alone

In a fresh process with ``NUMBA_CACHE_DIR`` a new, empty folder, the first ``simulate`` of the
printed preset compiles ``run_kernel`` and every function it calls. Numba announces each
function's compilation (``numba:compile`` events); this script records their nesting and prints,
per function, the seconds its own compilation took (``own``: its type inference, lowering and
LLVM, its callees' compilations subtracted) and with its callees (``with callees``), and over all
of them the split between Numba's passes (type inference without the callees it compiles, native
lowering with LLVM's optimisation and code generation of the function's library) from Numba's own
pass timings.

Numba gives every compiled function a library of its own and, when a function's library is
finalised, links its callees' libraries in and optimises and generates machine code for the
whole: a function five calls deep is optimised five times. The table shows how much of the
cold start that is.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from datetime import date
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from run import machine, write_section  # noqa: E402  (the shared helpers of the benchmarks)

BEGIN, END = "<!-- compile_profile.py: begin -->", "<!-- compile_profile.py: end -->"

PROFILE = r"""
import gc, json, time
from numba.core import event
from numba.core.registry import CPUDispatcher

rows, stack = [], []

class Listener(event.Listener):
    def on_start(self, ev):
        f = ev.data["dispatcher"].py_func
        stack.append([f.__module__.rsplit(".", 1)[-1] + "." + f.__qualname__, time.perf_counter(), 0.0])

    def on_end(self, ev):
        name, t0, inner = stack.pop()
        total = time.perf_counter() - t0
        if stack:
            stack[-1][2] += total
        rows.append((name, total, total - inner))

event.register("numba:compile", Listener())
import pounding as p
osc = p.presets.paper_printed()
t0 = time.perf_counter()
p.simulate(osc, p.Harmonic(0.05, 2.2), 1.0)
first = time.perf_counter() - t0
passes = {}
for obj in gc.get_objects():
    if isinstance(obj, CPUDispatcher) and obj.py_func.__module__.startswith("pounding"):
        for cres in obj.overloads.values():
            for timings in cres.metadata.get("pipeline_times", {}).values():
                for name, t in timings.items():
                    key = name.split("_", 1)[1]
                    passes[key] = passes.get(key, 0.0) + t.init + t.run + t.finalize
print(json.dumps({"first": first, "rows": rows, "passes": passes}))
"""


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--top", type=int, default=20, help="how many functions to list (default 20)")
    ap.add_argument("--no-write", action="store_true", help="print only; leave RESULTS.md alone")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        env = dict(os.environ, NUMBA_CACHE_DIR=tmp)
        out = subprocess.run([sys.executable, "-c", PROFILE], env=env, capture_output=True, text=True,
                             check=True).stdout
    data = json.loads(out.strip().splitlines()[-1])
    rows = sorted(data["rows"], key=lambda r: -r[2])
    passes = data["passes"]
    own_total = sum(r[2] for r in rows)
    # type inference's pass time holds the compilations of the callees it types: take them out
    lowering = passes.get("native_lowering", 0.0)
    typing = own_total - lowering - sum(v for k, v in passes.items()
                                        if k not in ("native_lowering", "nopython_type_inference"))
    lines = [BEGIN, f"## `python benchmarks/compile_profile.py` ({date.today().isoformat()})", "",
             f"Machine: {machine()}.", "",
             f"The first `simulate` of the printed preset from an empty cache: {data['first']:.1f} s, "
             f"{len(rows)} compilations. Over all of them: type inference {typing:.1f} s, native "
             f"lowering with LLVM (optimisation and machine code of each function's library, its callees "
             f"linked in) {lowering:.1f} s, the other passes {own_total - typing - lowering:.1f} s.", "",
             "| function | own s | with callees s |", "| --- | ---: | ---: |"]
    lines += [f"| `{name}` | {own:.2f} | {total:.2f} |" for name, total, own in rows[:args.top]]
    lines += ["", f"The other {max(0, len(rows) - args.top)} functions: "
              f"{sum(r[2] for r in rows[args.top:]):.1f} s together.", END]
    print("\n".join(lines[1:-1]))
    if not args.no_write:
        write_section("\n".join(lines), BEGIN, END)


if __name__ == "__main__":
    main()
