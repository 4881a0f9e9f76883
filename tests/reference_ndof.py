"""A slow, obviously-correct reference for structures of several masses: scipy's solve_ivp (DOP853) with
events, restarted at each of them.

The structure restated directly, sharing no code with the engine: n masses with displacements x relative to
the ground, M x'' + C x' + K x + f_iso + f_contacts = -M 1 a_g(t); a linear isolator (spring k_iso, dashpot
c_iso) between the first mass and the ground; Kelvin-Voigt bumpers on both sides of one mass (``level``: the
first by default) behind a gap, each fixed to the ground or to another mass (``partners``): in contact the
force K d + C d' (d = sign (x_level - x_partner) - gap, the compression) until it would pull; out of contact
the bumper's compression relaxes as d_r exp(-K (t - t_r) / C) from where it was released, and contact starts
when the mass meets that surface. Another law (``law``: a multi-linear bumper with elastic hysteresis, Hunt-
Crossley, ...) is restated by tests/reference.py's laws: its force, the way its surface relaxes and when it
would pull; a contact also ends where the compression returns to 0. Each level's displacement extrema are
located as events of its velocity (not ending the integration). The table's acceleration is a sine, or a
record (linear between its samples; the integration restarted at each). A storey may add an elastic-
perfectly-plastic spring (``plastic``): stuck, it pulls the drift back by k_p (drift - slip); it slips when
its strain reaches +-D and sticks again when the drift's rate turns back (a bilinear storey with Masing's
rule, k0 holding its second slope).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq


@dataclass
class Structure:
    mass: np.ndarray          # kg, (n,)
    k0: np.ndarray            # N/m, (n, n): the storeys' springs
    c0: np.ndarray            # N s/m, (n, n): their dashpots
    k_iso: float              # N/m, the first mass to the ground
    c_iso: float
    gaps: tuple[float, float]  # m, left and right
    k_b: float                # the bumpers' Kelvin-Voigt law
    c_b: float
    a_g: float                # m/s^2, amplitude of a_g(t) = a_g sin(w t)
    omega: float              # rad/s
    level: int = 0            # the mass the bumpers stop
    # what each bumper (left, right) stands on: -1 the ground, or a mass (a bumper between two masses)
    partners: tuple = (-1, -1)
    # storeys with an elastic-perfectly-plastic spring besides k0 (a bilinear storey with Masing's rule):
    # (storey i, between masses i and i + 1; its stiffness N/m; its yield drift D, m)
    plastic: list = field(default_factory=list)
    # a record instead of the sine: (times s, accelerations m/s^2), linear between its samples, zero outside
    record: tuple | None = None
    # the bumpers' law, a pounding contact law (stateless: Kelvin-Voigt, an elastic multi-linear bumper,
    # Hunt-Crossley); None: Kelvin-Voigt with k_b, c_b
    law: object | None = None


@dataclass
class NdofResult:
    yields: list = field(default_factory=list)           # (storey, t): a plastic spring began to slip
    contact_starts: list = field(default_factory=list)  # (contact, t): 0 left (sign -1), 1 right
    contact_ends: list = field(default_factory=list)
    depths: list = field(default_factory=list)          # each finished contact's deepest compression, m
    speeds: list = field(default_factory=list)          # each start's approach speed, m/s
    y: np.ndarray | None = None                         # the final (x, v)
    x_max: np.ndarray | None = None                     # each mass's largest and smallest displacement, m
    x_min: np.ndarray | None = None


SIGNS = (-1.0, 1.0)


class TouchAtRest(RuntimeError):
    """An event fired again at its own instant: a contact met or left at (nearly) zero speed, which this
    reference cannot step past."""


def reference(s: Structure, t_end: float, y0: np.ndarray, rtol: float = 1e-12, atol: float = 1e-15,
              max_step: float | None = None, steps_per_period: float = 100.0) -> NdofResult:
    n = s.mass.size
    inv_m = 1.0 / s.mass
    # the longest step: a hundredth (1 / steps_per_period) of the fastest period of the phase, so that a dip
    # of an event function shorter than a step does not fall between two steps' signs: during a contact,
    # with both bumpers' stiffness (as if both sides were engaged: shorter steps, safe); outside
    # every contact, without them (their stiffness is not in the motion then; with them throughout, as
    # before, test_a_wall_at_any_level_matches_the_reference ran 1.4 times as long). The steps bound the
    # accuracy here, not rtol: on one of that test's draws, steps 3 times longer moved the final velocity by
    # 1.3e-8 of the motion's scale whatever rtol, against 4e-10 at these.
    k = s.k0.copy()
    k[0, 0] += s.k_iso
    for i, k_p, _ in s.plastic:
        k[i:i + 2, i:i + 2] += k_p * np.array([[1.0, -1.0], [-1.0, 1.0]])
    k_in = k.copy()
    for c in range(2):
        j = s.partners[c]
        k_in[s.level, s.level] += s.k_b
        if j >= 0:
            k_in[j, j] += s.k_b
            k_in[s.level, j] -= s.k_b
            k_in[j, s.level] -= s.k_b

    def longest_step(kk):  # (no stiffness at all: no bound)
        w_max = math.sqrt(max(float(np.max(np.linalg.eigvals(kk * inv_m[:, None]).real)), 0.0))
        return 2.0 * math.pi / w_max / steps_per_period if w_max > 0.0 else np.inf

    step_in, step_out = ((max_step, max_step) if max_step is not None
                         else (longest_step(k_in), longest_step(k)))
    inside = [False, False]
    relax = [(0.0, 0.0), (0.0, 0.0)]  # (compression at release, release time)
    laws = [_restated(s) for _ in range(2)]  # (force(d, d'), relax(d_r, tau), release(d, d')) each
    out = NdofResult()
    deepest = [0.0, 0.0]

    def rel(y, c):  # the bumper's mass against what it stands on: displacement, velocity
        j = s.partners[c]
        return (y[s.level] - (y[j] if j >= 0 else 0.0), y[n + s.level] - (y[n + j] if j >= 0 else 0.0))

    def surface(c, t):  # the relaxing compression of bumper c at t
        d_r, t_r = relax[c]
        if d_r == 0.0:
            return 0.0
        return laws[c][1](d_r, t - t_r)

    # each plastic spring: its slip u_p and its mode (0 stuck, +-1 slipping that way)
    slip = [0.0] * len(s.plastic)
    mode = [0] * len(s.plastic)
    # a spring just stuck from slipping that way (+-1; 0 none): its strain leaves that yield by less than the
    # rounding at first, so that yield is looked for only once the strain turns back towards it
    left = [0] * len(s.plastic)

    def drift(y, i):
        return y[i + 1] - y[i]

    def plastic_force(q, y):  # on mass i + 1 (and the opposite on mass i), pulling the drift back
        i, k_p, d_y = s.plastic[q]
        return k_p * (drift(y, i) - slip[q]) if mode[q] == 0 else mode[q] * k_p * d_y

    # the linear springs and dashpots in one matrix: the storeys' and the isolator's (K x + C v = [K C] y)
    kc = np.hstack([s.k0, s.c0])
    kc[0, 0] += s.k_iso
    kc[0, n] += s.c_iso

    def nonlinear_forces(y):  # the plastic springs' and the bumpers' (the linear ones: kc @ y)
        f = np.zeros(n)
        for q, (i, _, _) in enumerate(s.plastic):
            fp = plastic_force(q, y)
            f[i + 1] += fp
            f[i] -= fp
        for c in range(2):
            if inside[c]:
                sg = SIGNS[c]
                dx, dv = rel(y, c)
                f_c = laws[c][0](sg * dx - s.gaps[c], sg * dv)
                f[s.level] += sg * f_c
                if s.partners[c] >= 0:
                    f[s.partners[c]] -= sg * f_c
        return f

    # the linear part of the motion in one matrix: y' = A y + (the nonlinear forces and the table)
    a_lin = np.zeros((2 * n, 2 * n))
    a_lin[:n, n:] = np.eye(n)
    a_lin[n:] = -inv_m[:, None] * kc

    def rhs(t, y):
        a_g = (float(np.interp(t, s.record[0], s.record[1], left=0.0, right=0.0)) if s.record is not None
               else s.a_g * math.sin(s.omega * t))
        out = a_lin @ y
        out[n:] -= a_g
        if s.plastic or inside[0] or inside[1]:  # (otherwise those forces are all 0)
            out[n:] -= inv_m * nonlinear_forces(y)
        return out

    def make_events(quiet_contact=None):
        evs = []
        for c in range(2):
            sg = SIGNS[c]
            if c == quiet_contact:
                continue
            if inside[c]:
                def release(t, y, c=c, sg=sg):
                    dx, dv = rel(y, c)
                    return laws[c][2](sg * dx - s.gaps[c], sg * dv)

                def emptied(t, y, c=c, sg=sg):  # (the compression back to 0: the contact ends too)
                    return sg * rel(y, c)[0] - s.gaps[c]
                emptied.terminal = True
                emptied.direction = -1.0
                emptied.contact = c
                evs.append(emptied)
            else:
                def release(t, y, c=c, sg=sg):
                    return s.gaps[c] + surface(c, t) - sg * rel(y, c)[0]
            release.terminal = True
            release.direction = -1.0
            release.contact = c
            evs.append(release)
        for q, (i, _, d_y) in enumerate(s.plastic):
            for sg in (1.0, -1.0):
                if mode[q] == 0 and left[q] == sg:  # just stuck from this side: the drift turns back
                    def change(t, y, i=i, sg=sg):
                        return -sg * (y[n + i + 1] - y[n + i])
                    change.turn = True
                elif mode[q] == 0:  # stuck: the spring's strain reaches +-D
                    def change(t, y, q=q, i=i, sg=sg, d_y=d_y):
                        return d_y - sg * (drift(y, i) - slip[q])

                    def rate(t, y, i=i, sg=sg):  # (change's derivative: its minima are the drift's turns)
                        return -sg * (y[n + i + 1] - y[n + i])
                    change.rate = rate
                elif mode[q] == sg:  # slipping: the drift's rate turns back
                    def change(t, y, i=i, sg=sg):
                        return sg * (y[n + i + 1] - y[n + i])
                else:
                    continue
                change.terminal = True
                change.direction = -1.0
                change.plastic = (q, sg)
                evs.append(change)
        return evs

    t, y = 0.0, np.array(y0, dtype=float)
    quiet = None  # (a contact just released, until when its start is not looked for)
    x_max, x_min = y[:n].copy(), y[:n].copy()
    knots = np.asarray(s.record[0]) if s.record is not None else np.zeros(0)
    while t < t_end:
        quiet_now = quiet is not None and t < quiet[1]
        evs = make_events(quiet[0] if quiet_now else None)
        after = knots[knots > t * (1.0 + 1e-15) + 1e-15]  # (a record's kink: a stretch ends at the next)
        t_next = min(t_end, float(after[0])) if after.size else t_end
        if quiet_now:
            t_next = min(t_next, quiet[1])
        turns = [_turn(i, n) for i in range(n)]  # (each mass's velocity's zeros: its extrema)
        sol = solve_ivp(rhs, (t, t_next), y, method="DOP853", rtol=rtol, atol=atol, events=evs + turns,
                        dense_output=True, max_step=step_in if any(inside) else step_out)
        if sol.status == -1:
            raise RuntimeError(sol.message)
        # the deepest compression of the contacts this stretch was in
        for c in range(2):
            if inside[c]:
                ts = np.linspace(t, sol.t[-1], 200)
                ys = sol.sol(ts)
                depth = ys[s.level] - (ys[s.partners[c]] if s.partners[c] >= 0 else 0.0)
                deepest[c] = max(deepest[c], float(np.max(SIGNS[c] * depth - s.gaps[c])))
        hits = [(float(te[0]), c) for c, te in enumerate(sol.t_events[:len(evs)])
                if te.size and te[0] > t + 1e-13]
        dip = _stepped_over(evs, sol, t)
        if dip is not None:
            hits.append(dip)
        t_stop = min(hits)[0] if hits else float(sol.t[-1])
        for i in range(n):  # the extrema up to where this stretch stops
            turned = zip(sol.t_events[len(evs) + i], sol.y_events[len(evs) + i])
            xs = [y[i], float(sol.sol(t_stop)[i])] + [float(ye[i]) for te, ye in turned if te <= t_stop]
            x_max[i], x_min[i] = max(x_max[i], *xs), min(x_min[i], *xs)
        # (a stretch that slipped: the slip followed the drift)
        for q, (i, _, d_y) in enumerate(s.plastic):
            if mode[q] != 0:
                end = sol.sol(min(hits)[0]) if hits else sol.y[:, -1]
                slip[q] = drift(end, i) - mode[q] * d_y
        if not hits:
            if sol.status != 0:
                fired = [evs[k] for k, te in enumerate(sol.t_events[:len(evs)]) if te.size]
                just = [f.contact for f in fired if hasattr(f, "contact") and not inside[f.contact]
                        and relax[f.contact][1] == t]
                if just and (quiet is None or quiet[1] <= t):
                    # a contact released here, its function zero with a zero rate (a Kelvin-Voigt wall's
                    # surface relaxes at the mass's own speed as the force crosses zero): the sign of its
                    # first step is rounding; a nanosecond without its check, then on
                    quiet = (just[0], t + 1e-9)
                    continue
                raise TouchAtRest(f"an event fires again at its own instant, t = {t}")
            t, y = float(sol.t[-1]), sol.y[:, -1]
            if t_next < t_end:
                continue
            break
        t_hit, c = min(hits)
        y = sol.sol(t_hit)
        t = t_hit
        if hasattr(evs[c], "plastic"):
            q, sg = evs[c].plastic
            i = s.plastic[q][0]
            if hasattr(evs[c], "turn"):  # (its drift turned back: its yield is looked for again)
                left[q] = 0
            elif mode[q] == 0:
                mode[q], left[q] = int(sg), 0
                out.yields.append((i, t))
            else:
                mode[q] = 0
                # (it leaves the yield it stuck at where the drift's acceleration heads away from it)
                a = rhs(t, y)
                left[q] = int(sg) if -sg * (a[n + i + 1] - a[n + i]) > 0.0 else 0
            continue
        c = evs[c].contact
        sg = SIGNS[c]
        if inside[c]:
            inside[c] = False
            relax[c] = (max(sg * rel(y, c)[0] - s.gaps[c], 0.0), t)
            out.contact_ends.append((c, t))
            out.depths.append(deepest[c])
            deepest[c] = 0.0
        else:
            inside[c] = True
            out.contact_starts.append((c, t))
            out.speeds.append(abs(rel(y, c)[1]))
            deepest[c] = max(sg * rel(y, c)[0] - s.gaps[c], 0.0)
    out.y = y
    out.x_max, out.x_min = x_max, x_min
    return out


def _stepped_over(evs, sol, t0: float):
    """The earliest crossing of a contact's or a plastic spring's event function inside one solver step,
    ``(t, index)``, or None.

    ``solve_ivp`` checks an event's sign at step ends only: a wall's force that dips below zero and back
    within a step (the mass leaves the wall for half a millisecond, 1.5 um, and strikes it again: a draw
    of test_yielding_storeys_match_the_reference, the reference one contact short and every later yield
    off by up to 4.5e-7 s) is missed; so is a storey's drift that touches its yield drift and turns back
    within 6 us (another draw: one yield short, the later ones off by up to 1.1e-8 s).  Each such function
    is sampled at 8 points inside every step from the dense output; a sample at or below zero after one
    above it brackets the crossing.  A stuck plastic spring's function (it has a ``rate``: its derivative)
    may dip to zero and back between two samples: where its rate turns from negative to positive between
    them, its minimum is found, and a minimum at or below zero brackets a crossing before it."""
    if sol.t.size < 2:
        return None
    inner = (sol.t[:-1, None] + np.diff(sol.t)[:, None] * np.linspace(0.0, 1.0, 10)[1:-1]).ravel()
    grid = np.sort(np.concatenate([sol.t, inner]))
    ys = sol.sol(grid)
    best = None
    for k, f in enumerate(evs):
        if not (hasattr(f, "contact") or hasattr(f, "plastic")):
            continue
        g = _on_grid(f, grid, ys)
        down = np.flatnonzero((g[:-1] > 0.0) & (g[1:] <= 0.0))
        brackets = [(grid[down[0]], grid[down[0] + 1])] if down.size else []
        if hasattr(f, "rate"):  # (a minimum between two samples that dips to zero: a graze within 6 us)
            r = _on_grid(f.rate, grid, ys)
            for m in np.flatnonzero((r[:-1] < 0.0) & (r[1:] >= 0.0) & (g[:-1] > 0.0) & (g[1:] > 0.0)):
                if brackets and grid[m] >= brackets[0][0]:
                    break
                turn = brentq(lambda tt: f.rate(tt, sol.sol(tt)), grid[m], grid[m + 1], xtol=1e-16,
                              rtol=8.9e-16)
                if f(turn, sol.sol(turn)) <= 0.0:
                    brackets.insert(0, (grid[m], turn))  # (before the sampled crossing, if any)
                    break
        for lo, hi in brackets:  # (the earliest whose root is past the stretch's start)
            root = brentq(lambda tt: f(tt, sol.sol(tt)), lo, hi, xtol=1e-16, rtol=8.9e-16)
            for _ in range(64):  # (just past the crossing, as solve_ivp's own events: the function <= 0)
                if f(root, sol.sol(root)) <= 0.0 or root >= hi:
                    break
                root = np.nextafter(root, np.inf)
            if root > t0 + 1e-13:
                if best is None or root < best[0]:
                    best = (float(root), k)
                break
    return best


def _on_grid(f, grid: np.ndarray, ys: np.ndarray) -> np.ndarray:
    """An event function's values at the times ``grid`` (states ``ys``, one column each): in one call where
    the function takes arrays (the Kelvin-Voigt bumpers of ``k_b`` and ``c_b``), point by point where it
    does not (a ``law``'s, restated by tests/reference.py with branches and math functions) or where the one
    call disagrees with the point-by-point values at the ends."""
    try:
        g = np.broadcast_to(np.asarray(f(grid, ys), dtype=float), grid.shape)
        if g[0] == f(grid[0], ys[:, 0]) and g[-1] == f(grid[-1], ys[:, -1]):
            return g
    except (TypeError, ValueError):
        pass
    return np.array([f(tt, ys[:, m]) for m, tt in enumerate(grid)])


def _turn(i: int, n: int):
    def turn(t, y):
        return y[n + i]
    turn.terminal = False
    return turn


def _restated(s: Structure) -> tuple:
    """The bumpers' law as (force(d, d'), relax(d_r, tau), release(d, d'))."""
    if s.law is not None:
        from reference import _law

        force, relax, release, state = _law(s.law)
        assert state is None, "a law with a state of its own: not restated here"
        return force, relax, release
    k, c = s.k_b, s.c_b
    return (lambda d, dd: k * d + c * dd,
            lambda d_r, tau: 0.0 if c == 0.0 else d_r * np.exp(-k * tau / c),  # (tau: a time or an array)
            lambda d, dd: k * d + c * dd)
