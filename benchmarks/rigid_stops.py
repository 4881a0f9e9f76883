"""Rigid stops (issue 51): impacts per CPU second in a chatter-heavy run, against the scipy script users
write for an impact oscillator (solve_ivp with a terminal event, restarted at each impact with Newton's law),
on the same motion.

    python benchmarks/rigid_stops.py

The system: a linear oscillator (1 kg, 10 rad/s, 2 % damping) between rigid stops 5 mm away (restitution
0.9), shaken at 0.5 Hz and 40 m/s^2: every half cycle it is thrown against a stop, chatters (about 50
impacts), accumulates and sticks until the table pulls it off.  Target: >= 1 million impacts per second of
CPU.  The peer cannot accumulate a chatter (it steps each rebound until its event finder stalls), so it runs
the first 0.4 s only (its impacts per CPU second are what it manages there); the agreement of the impact
times is printed.
"""

from __future__ import annotations

import math
import os

# (idle BLAS threads spin: CPU time that is not the engine's)
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np
from scipy.integrate import solve_ivp

import pounding
from structures import cpu_best

GRAVITY = 9.81  # m/s^2
M, OMEGA, ZETA, GAP, E = 1.0, 10.0, 0.02, 0.005, 0.9
A, F_HZ = 40.0, 0.5


def system() -> pounding.Oscillator:
    iso = pounding.Isolator(slopes_n_m=[M * OMEGA ** 2], damping_n_s_m=2.0 * ZETA * OMEGA * M)
    return pounding.Oscillator(M, iso, pounding.Bumpers(GAP, GAP, pounding.RigidStop(E)))


def table() -> pounding.Harmonic:
    return pounding.Harmonic(a_g=A / GRAVITY, freq_hz=F_HZ, g=GRAVITY)  # (a_g in g)


def scipy_impacts(t_end: float, max_impacts: int = 10_000) -> list[float]:
    w = 2.0 * math.pi * F_HZ

    def rhs(t, y):
        return [y[1], -2.0 * ZETA * OMEGA * y[1] - OMEGA ** 2 * y[0] - A * math.sin(w * t)]

    def right(t, y):
        return y[0] - GAP

    def left(t, y):
        return y[0] + GAP

    right.terminal = left.terminal = True
    right.direction, left.direction = 1.0, -1.0
    t, y, times = 0.0, np.zeros(2), []
    while t < t_end and len(times) < max_impacts:
        sol = solve_ivp(rhs, (t, t_end), y, method="DOP853", rtol=1e-10, atol=1e-13, events=(right, left))
        if sol.status != 1:
            break
        hit = 0 if len(sol.t_events[0]) else 1
        t_new = float(sol.t_events[hit][0])
        y = np.array(sol.y_events[hit][0], dtype=float)
        y[1] = -E * y[1]
        if t_new - t < 1e-12:  # (the finder stalls on the chatter's vanishing flights)
            break
        t = t_new
        times.append(t)
    return times


def main() -> None:
    osc, tab = system(), table()
    duration = 2000.0
    secs, run = cpu_best(lambda: pounding.simulate(osc, tab, duration=duration, sample_rate_hz=0), 3)
    c = run.contacts
    impacts = int((c.t_end_s == c.t_start_s).sum())
    chatters = run.chatters
    rate = impacts / secs
    print(f"pounding: {duration:g} s simulated, {impacts:,} impacts, {len(chatters)} chatter sequences "
          f"({int(chatters.accumulated.sum())} accumulated, then held), {secs:.3f} CPU s")
    print(f"  impacts per CPU second: {rate:,.0f}  (target >= 1,000,000)")
    window = 0.4
    peer_secs, times = cpu_best(lambda: scipy_impacts(window), 1)
    ours = c.t_start_s.values[(c.t_end_s.values == c.t_start_s.values) & (c.t_start_s.values < window)]
    n = min(len(times), len(ours), 20)  # (further on the peer's flights shrink below its tolerances)
    agree = float(np.max(np.abs(np.asarray(times[:n]) - ours[:n]))) if n else math.nan
    peer_rate = len(times) / peer_secs
    print(f"scipy solve_ivp DOP853 + events (rtol 1e-10), restarted at each impact: {len(times)} impacts in "
          f"the first {window:g} s, {peer_secs:.3f} CPU s: {peer_rate:,.0f} impacts per CPU second")
    print(f"  impact times agree to {agree:.1e} s over its first {n} impacts; pounding / scipy: "
          f"{rate / peer_rate:,.0f}x impacts per CPU second")


if __name__ == "__main__":
    main()
