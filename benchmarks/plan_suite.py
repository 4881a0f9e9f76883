"""A building in plan under the FEMA P695 far-field set's 22 pairs at 8 orientations, on 2 workers: the design
of its moat's gap (``pounding.design.moat_design``), timed.

    pip install -e ".[records]"
    python benchmarks/plan_suite.py                 # the 5-storey building of opensees_plan.py
    python benchmarks/plan_suite.py --storeys 3 --workers 4

Target (issue "isolated buildings in the plane"): the 22 pairs at 8 angles in under 30 s on 2 workers. Each
run is a whole record (its own length, 20 to 100 s).
"""

from __future__ import annotations

import argparse
import time

import numpy as np

import pounding as pd_
from opensees_plan import building

TARGET_S = 30.0


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--storeys", type=int, default=5, help="storeys above the base (default 5)")
    ap.add_argument("--workers", type=int, default=2, help="threads (default 2)")
    args = ap.parse_args()
    b = building(args.storeys)
    pairs = pd_.records.fema_p695_pairs("far_field")
    angles = np.arange(0.0, 180.0, 22.5)
    seconds = sum(p.duration_s for p in pairs) * angles.size
    pd_.simulate(b.without_bumpers(), pairs[0], 1.0, sample_rate_hz=0)  # (warm: the core loaded)
    t0, c0 = time.perf_counter(), time.process_time()
    found = pd_.design.moat_design(b, pairs, angles, workers=args.workers)
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    runs = len(found.data)
    print(f"pounding {pd_.__version__}: a building in plan of {args.storeys} storeys ({b.n_dofs} dofs), "
          f"the far-field set's {len(pairs)} pairs at {angles.size} angles: {runs} runs, {seconds:,.0f} "
          "simulated s")
    print(f"  {wall:.2f} s wall on {args.workers} workers ({cpu:.2f} CPU s, {cpu / runs * 1e3:.1f} ms a "
          f"run); target < {TARGET_S:g} s: {'met' if wall < TARGET_S else 'MISSED'}")
    print(f"  design displacement {found.design_displacement_m:.3f} m ({found.attrs['rule']} of the pairs' "
          f"critical), the largest pair's {found.critical['disp_max_m'].max():.3f} m")


if __name__ == "__main__":
    main()
