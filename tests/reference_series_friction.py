"""A slow, obviously-correct reference for a structure on friction surfaces in series (a triple friction
pendulum's series model): scipy's solve_ivp (DOP853) restarted at every stick, slip, surface slip and ring.

The model restated directly: n levels with displacements x relative to the ground, level 0 the base,
M x'' + C x' + K x = -M 1 a_g(t) - e_0 F, with K and C the storeys (and the bearing's dashpot) and F the
bearing's force.  The bearing is surfaces g = 0..3 one after another, each a spring k_g in parallel with a
friction f_g, of displacement u_g, sum u_g = x_0, all carrying F:
- a surface slips the way s only while F = k_g u_g + s f_g; it is held otherwise, and held at its ring once
  u_g = s d_g (until F comes back to its threshold the other way);
- a stiff ring (``ring`` > 0, N/m) instead adds ring (|u_g| - d_g) to the surface's spring beyond its travel:
  a slipping surface is then where its spring's force, which rises with u_g, is F - s f_g (found by inverting
  it, ``_inverse``), F is the force at which the slipping surfaces and the held ones add up to x_0 (on the
  piece between the surfaces' knees where it falls), and its rings' entries and exits are events for the
  record (``ring``, ``ring_off``);
- with the set S slipping, F = (x_0 - sum_{held} u_g + s sum_S f_g / k_g) / sum_S 1 / k_g;
- every surface held: the base is held (v_0 = 0) and F is what holding it needs, D = -m_0 a_g - (K x)_0 -
  (C x')_0; the bearing slips up where D reaches the lowest threshold up min_g (k_g u_g + f_g), down where it
  reaches the highest down, with the surfaces of that threshold.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from reference_friction import FrictionStructure, _phase

HELD, RING = 0, 2


class ReferenceCapacity(RuntimeError):
    """Every surface at its ring: the bearing's travel used up."""


@dataclass
class SeriesStructure:
    masses_kg: np.ndarray          # (n,), level 0 the base
    storey_k: np.ndarray           # (n - 1,), N/m
    storey_c: np.ndarray           # (n - 1,), N s/m
    k: np.ndarray                  # (4,) the surfaces' stiffnesses, N/m
    f: np.ndarray                  # (4,) their frictions, N
    cap: np.ndarray                # (4,) their travels to their rings, m
    accel: Callable[[float], float]
    c_r: float = 0.0               # the bearing's dashpot, N s/m
    ring: float = 0.0              # each ring's stiffness, N/m (0: rigid)

    def matrices(self) -> tuple[np.ndarray, np.ndarray]:
        """K and C, (n, n): the storeys' and the bearing's dashpot (its springs are the surfaces')."""
        return FrictionStructure(self.masses_kg, self.storey_k, self.storey_c, 0.0, self.c_r, 0.0,
                                 self.accel).matrices()


@dataclass
class SeriesResult:
    t: np.ndarray
    x: np.ndarray
    events: list = field(default_factory=list)   # (t, kind, surface or -1): stick, slip, surface_slip, ring
    # (t, the surfaces that started at once) at each surface slip: several of one threshold (to rounding)
    slip_groups: list = field(default_factory=list)
    friction_j: float = 0.0
    input_j: float = 0.0
    viscous_j: float = 0.0
    u_end: np.ndarray | None = None


def _spring(s: SeriesStructure, g: int, u: float) -> float:
    """Surface g's spring force at u, N: k_g u, and a stiff ring's past its travel."""
    beyond = max(abs(u) - s.cap[g], 0.0) if s.ring else 0.0
    return float(s.k[g] * u + math.copysign(s.ring * beyond, u))


def _inverse(s: SeriesStructure, g: int, y: float) -> float:
    """The u at which surface g's spring force is y (it rises with u)."""
    knee = s.k[g] * s.cap[g]
    if not s.ring or abs(y) <= knee:
        return float(y / s.k[g])
    return math.copysign(s.cap[g] + (abs(y) - knee) / (s.k[g] + s.ring), y)


def _force(s: SeriesStructure, x0: float, u: np.ndarray, state: np.ndarray, mode: int,
           law: tuple | None = None) -> float:
    """The bearing's force while the surfaces of ``state == mode`` slip, N (``law``: :func:`_law`'s, kept)."""
    on = state == mode
    if not s.ring:
        return (x0 - u[~on].sum() + mode * (s.f[on] / s.k[on]).sum()) / (1.0 / s.k[on]).sum()
    at, knees, k_end = law if law is not None else _law(s, u, state, mode)
    share = x0 - u[~on].sum()  # (the slipping surfaces' share of x0)
    if share <= at[0]:  # (past every knee below: each on its ring, the series' stiffness k_end)
        return float(knees[0] + (share - at[0]) * k_end)
    if share >= at[-1]:
        return float(knees[-1] + (share - at[-1]) * k_end)
    return float(np.interp(share, at, knees))


def _law(s: SeriesStructure, u: np.ndarray, state: np.ndarray, mode: int) -> tuple:
    """With stiff rings: the slipping surfaces' share of x_0 at each of their knees' forces, those forces
    (N), and the series' stiffness past the outermost knees (every slipping surface on its ring, N/m):
    linear between and beyond them, so that F follows by interpolation (from the nearest knee: from a far
    point, the force would lose its digits)."""
    slipping = np.flatnonzero(state == mode)

    def share(force: float) -> float:  # (rises with the force, linear between the surfaces' knees)
        return sum(_inverse(s, g, force - mode * s.f[g]) for g in slipping)

    knees = np.sort([mode * s.f[g] + side * s.k[g] * s.cap[g] for g in slipping for side in (-1, 1)])
    k_end = 1.0 / float(np.sum(1.0 / (s.k[slipping] + s.ring)))
    return np.array([share(f) for f in knees]), knees, k_end


def _threshold(s: SeriesStructure, u: np.ndarray, state: np.ndarray, g: int, way: int) -> float:
    return np.inf * way if state[g] == RING * way else _spring(s, g, u[g]) + way * s.f[g]


def _start(s: SeriesStructure, u: np.ndarray, state: np.ndarray, way: int, level: float) -> set:
    """The held surfaces whose threshold the way ``way`` is ``level`` (to rounding) slip: which."""
    scale = abs(level) + s.f.sum()
    started = set()
    for g in range(4):
        if abs(state[g]) != 1 and abs(_threshold(s, u, state, g, way) - level) <= 1e-9 * scale:
            state[g] = way
            started.add(g)
    return started


def reference(s: SeriesStructure, t_end: float, rtol: float = 1e-12, atol: float = 1e-15,
              knots: np.ndarray | None = None, max_phases: int = 100_000, start: tuple | None = None
              ) -> SeriesResult:
    """From rest, centred, at t = 0 to ``t_end``; or from ``start``, ``(x, v, u, state)`` (the levels'
    displacements and velocities, the surfaces' displacements and states, every surface held: 0 or +-2):
    moving, the bearing slips the way it moves from the lowest threshold that way (no event)."""
    m = np.asarray(s.masses_kg, float)
    n = m.size
    kk, cc = s.matrices()
    u, state = np.zeros(4), np.zeros(4)
    y = np.zeros(2 * n + 2)  # x, v, the input's work, the dashpots'
    if start is not None:
        y[:n], y[n:2 * n] = start[0], start[1]
        u, state = np.array(start[2], float), np.array(start[3], float)
    t, mode = 0.0, 0
    out = SeriesResult(t=np.array([0.0]), x=y[None, :n].copy())
    ts, xs = [np.array([0.0])], [y[None, :n].copy()]
    cuts = np.unique(np.append(np.asarray(knots if knots is not None else [], float), t_end))
    cuts = cuts[cuts <= t_end]

    def rest(tt: float, yy: np.ndarray) -> float:
        return float(-m[0] * s.accel(tt) - kk[0] @ yy[:n] - cc[0] @ yy[n:2 * n])

    def held_way(tt: float, yy: np.ndarray) -> int:
        d = rest(tt, yy)
        hi = min(_threshold(s, u, state, g, 1) for g in range(4))
        lo = max(_threshold(s, u, state, g, -1) for g in range(4))
        return 1 if d > hi else -1 if d < lo else 0

    def slip_from_rest(way: int) -> None:
        state[np.abs(state) == 1] = HELD
        _start(s, u, state, way, min(_threshold(s, u, state, g, way) * way for g in range(4)) * way)

    if y[n] != 0.0:  # (a moving start: a slip, no event)
        mode = 1 if y[n] > 0.0 else -1
        slip_from_rest(mode)
    mode = mode or held_way(0.0, y)
    if mode and y[n] == 0.0:
        slip_from_rest(mode)
        out.events.append((0.0, "slip", -1))
    for _ in range(max_phases):
        if t >= t_end:
            break
        t_stop = float(cuts[np.searchsorted(cuts, t, side="right")])
        frozen_u, frozen_state, frozen_mode = u.copy(), state.copy(), mode
        law = _law(s, u, state, mode) if s.ring and mode else None

        def rhs(tt: float, yy: np.ndarray) -> np.ndarray:
            x, v = yy[:n], yy[n:2 * n]
            ag = s.accel(tt)
            force = -m * ag - kk @ x - cc @ v
            if frozen_mode:
                force[0] -= _force(s, x[0], frozen_u, frozen_state, frozen_mode, law)
            else:
                force[0] = 0.0
            dy = np.zeros_like(yy)
            dy[:n] = v
            dy[n:2 * n] = force / m
            if not frozen_mode:
                dy[0] = dy[n] = 0.0
            dy[2 * n] = -ag * float(m @ v)
            dy[2 * n + 1] = float(v @ cc @ v)
            return dy

        events = []
        if mode == 0:
            hi = min(_threshold(s, u, state, g, 1) for g in range(4))
            lo = max(_threshold(s, u, state, g, -1) for g in range(4))
            for level, way in ((hi, 1), (lo, -1)):
                if np.isfinite(level):
                    def ev(tt, yy, level=level):
                        return rest(tt, yy) - level
                    ev.terminal, ev.direction, ev.what = True, float(way), ("slip", way, -1)
                    events.append(ev)
        else:
            def stop(tt, yy):
                return yy[n]
            stop.terminal, stop.direction, stop.what = True, -float(mode), ("stop", 0, -1)
            events.append(stop)
            for g in range(4):
                if state[g] == mode and s.ring and mode * u[g] < -s.cap[g] * (1 + 1e-12):
                    level = mode * (s.f[g] - s.k[g] * s.cap[g])  # (past its far ring, coming back)
                    what = ("ring_off", mode, g)
                elif state[g] == mode and s.ring and mode * u[g] >= s.cap[g] * (1 - 1e-12):
                    continue  # (sliding on into its stiff ring)
                elif state[g] == mode:
                    level = mode * (s.k[g] * s.cap[g] + s.f[g])
                    what = ("ring", mode, g)
                else:
                    level = _threshold(s, u, state, g, mode)
                    what = ("surface_slip", mode, g)
                if not np.isfinite(level):
                    continue

                def ev(tt, yy, level=level):
                    return _force(s, yy[0], frozen_u, frozen_state, frozen_mode, law) - level
                ev.terminal, ev.direction, ev.what = True, float(mode), what
                events.append(ev)
        sol, t_new, fired, y, steps = _phase(rhs, t, t_stop, y, events, mode != 0 and y[n] == 0.0, mode == 0,
                                             rtol, atol)
        ts.append(np.append(steps, t_new))
        xs.append(np.vstack([sol.y[:n, 1:1 + steps.size].T, y[None, :n]]))
        if mode:  # (the slipping surfaces moved with the force: their friction's work)
            f1 = _force(s, float(y[0]), u, state, mode)
            for g in np.flatnonzero(state == mode):
                moved = _inverse(s, g, f1 - mode * s.f[g])
                out.friction_j += float(s.f[g]) * abs(moved - u[g])
                u[g] = moved
        t = t_new
        if fired is None:
            continue
        kind, way, g = events[fired].what
        if kind == "slip":
            mode = way
            slip_from_rest(way)
            out.events.append((t, "slip", -1))
        elif kind == "stop":
            y[n] = 0.0
            state[np.abs(state) == 1] = HELD
            nxt = held_way(t, y)
            if nxt == 0:
                out.events.append((t, "stick", -1))
            else:
                slip_from_rest(nxt)
                out.events.append((t, "reversal" if nxt == -mode else "slip", -1))
            mode = nxt
        elif kind == "ring_off" or (kind == "ring" and s.ring):  # (a stiff ring: it slides on)
            on_it = kind == "ring"
            level = mode * (s.k[g] * s.cap[g] + s.f[g]) if on_it else mode * (s.f[g] - s.k[g] * s.cap[g])
            for q in range(4):  # (it, and any other slipping one whose entry or exit comes at the same force)
                mine = mode * (s.k[q] * s.cap[q] + s.f[q]) if on_it else mode * (s.f[q] - s.k[q] * s.cap[q])
                knee = mode * s.cap[q] if on_it else -mode * s.cap[q]  # (where the phase just took it)
                if q == g or (state[q] == mode and abs(u[q] - knee) <= 1e-9 * s.cap[q]
                              and abs(mine - level) <= 1e-9 * (abs(level) + s.f.sum())):
                    u[q] = mode * s.cap[q] if on_it else -mode * s.cap[q]
                    out.events.append((t, kind, q))
        elif kind == "ring":
            level = mode * (s.k[g] * s.cap[g] + s.f[g])
            scale = abs(level) + s.f.sum()
            for q in range(4):  # (it, and any other slipping one whose ring comes at the same force)
                if q == g or (state[q] == mode and abs(mode * (s.k[q] * s.cap[q] + s.f[q]) - level)
                              <= 1e-9 * scale):
                    state[q] = RING * mode
                    u[q] = mode * s.cap[q]
                    out.events.append((t, "ring", q))
            if not (state == mode).any():  # (none slips on: the rigid series jumps to the next threshold)
                nxt = min(_threshold(s, u, state, q, mode) * mode for q in range(4)) * mode
                if not np.isfinite(nxt):
                    raise ReferenceCapacity(f"every surface at its ring at t = {t!r}")
                _start(s, u, state, mode, nxt)
        else:
            level = _threshold(s, u, state, g, mode)
            state[g] = mode
            out.slip_groups.append((t, _start(s, u, state, mode, level) | {g}))
            out.events.append((t, "surface_slip", g))
    else:
        raise RuntimeError(f"more than {max_phases} phases")
    out.t = np.concatenate(ts)
    out.x = np.concatenate(xs)
    out.input_j, out.viscous_j = float(y[2 * n]), float(y[2 * n + 1])
    out.u_end = u.copy()
    return out
