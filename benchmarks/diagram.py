"""Bifurcation diagram benchmark: the paper's damped system at a_G 0.05, 0.5 to 5 Hz by 0.01 Hz, up
and down, 100 + 20 cycles a step (the target: 3 s on the 2-core machine), against a plain stepped
sweep over the same frequencies and cycles in the same run (the ratio is what compares across
machines: the diagram adds only its bookkeeping to the sweeps it is made of).

Then the Lyapunov spectrum: 1,000 periods counted on the same system at a_G 0.05, 1.5 Hz (two
impacts a period, nine phases) and 2.2 Hz (free), no transient (the target: 0.5 s), against the
engine's own 1,000 periods from the same state (a simulate of that length, events only).

    python benchmarks/diagram.py [--repeat 3]
"""

from __future__ import annotations

import argparse
import platform
import time

import numpy as np

import pounding as pd_

TARGET_S = 3.0
TARGET_LYAPUNOV_S = 0.5


def best_of(fn, repeat: int) -> tuple[float, object]:
    out, best = None, np.inf
    for _ in range(repeat):
        t = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t)
    return best, out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    print(f"machine: {platform.processor() or platform.machine()}, Python {platform.python_version()}")
    osc = pd_.presets.paper_damped()
    freqs = np.round(np.arange(0.5, 5.0 + 1e-9, 0.01), 2)
    pd_.bifurcation_diagram(osc, 0.05, freqs[:10], transient_cycles=10, record_cycles=10)  # (warm)
    t_diagram, diagram = best_of(lambda: pd_.bifurcation_diagram(osc, 0.05, freqs), args.repeat)

    def sweeps() -> None:
        kw = dict(steady="fixed", cycles=120, measure_cycles=20)
        up = pd_.sweep(osc, 0.05, freqs, "up", **kw)
        pd_.sweep(osc, 0.05, freqs, "down", state=up.final_state, **kw)

    t_sweeps, _ = best_of(sweeps, args.repeat)
    cycles = 2 * freqs.size * 120
    print(f"paper_damped, a_G 0.05, {freqs.size} frequencies x up and down x 120 cycles ({cycles:,} cycles)")
    print(f"  {diagram.message}")
    print(f"  diagram       {t_diagram:7.3f} s   ({t_diagram / cycles * 1e6:.1f} us per cycle)")
    print(f"  the sweeps    {t_sweeps:7.3f} s   ratio diagram / sweeps = {t_diagram / t_sweeps:.2f}")
    print(f"  target {TARGET_S:g} s: {'met' if t_diagram <= TARGET_S else 'NOT met'} "
          f"(diagram / target = {t_diagram / TARGET_S:.2f})")
    for f in (1.5, 2.2):
        exc = pd_.Harmonic(0.05, f)
        pd_.lyapunov(osc, exc, cycles=5, transient_cycles=0)  # (compiled, not timed)
        t_lyap, spec = best_of(lambda: pd_.lyapunov(osc, exc, cycles=1000, transient_cycles=0,
                                                    align_cycles=0), args.repeat)
        t_run, _ = best_of(lambda: pd_.simulate(osc, exc, 1000 / f, sample_rate_hz=0), args.repeat)
        print(f"Lyapunov spectrum, {f:g} Hz, 1,000 periods: {t_lyap:6.3f} s ({t_lyap / t_run:.0f} x the "
              f"engine's {t_run:.3f} s for the periods alone); largest {spec.largest:.4f} 1/s; target "
              f"{TARGET_LYAPUNOV_S:g} s: {'met' if t_lyap <= TARGET_LYAPUNOV_S else 'NOT met'}")


if __name__ == "__main__":
    main()
