"""A slow, obviously-correct reference for a building in plan against the rigid walls of a rectangular moat:
scipy's solve_ivp (DOP853) with events, restarted at each of them.

The structure restated directly, sharing no code with the engine (tests/reference_plan.py's PlanModel: n
coordinates q, ``M q'' + C q' + K q = -M R a_g(t) + wall forces``, M diagonal, linear springs only).  Each
wall is struck by a point of a floor whose displacement towards the wall is ``d = sign w . q`` (``w`` its
weights: ``x - y_c theta`` for a corner), at ``d = gap``.

* Flight: every wall open (none held).
* An impact of restitution ``e > 0`` (no wall held then: a hold comes from plastic impacts only here): the
  velocity jumps by ``dv`` from the saddle-point system ``[M w^T; w 0] [dv; p] = [0; -(1 + e) u]``, ``u``
  the struck point's closing speed, ``p >= 0`` its impulse.  Two walls touched at one instant raise
  :class:`Chatter` (Newton's law one wall after the other is not Moreau's).
* A plastic impact (``e = 0``): Moreau's law, the velocities after it the projection, in M's metric, of
  those before onto the cone ``J v <= 0`` of every wall touched (held or not): found by trying the walls'
  independent subsets, smallest first, for the one whose equality ``J_S v+ = 0`` has impulses ``>= 0`` and
  leaves no touched wall closing (the projection's KKT point).
* Held: of the walls at rest on their points, the smallest set whose held forces push (``f >= 0``) with no
  other pushed shut; its constrained motion, accelerations and forces from ``[M J^T; J 0] [q''; f] = [F; 0]``;
  a hold lets go where its force comes back to zero.  More walls at rest than independent (a floor held in a
  corner of the moat by three or four corners: the forces not unique) raise :class:`Chatter`.
* A rebound too small to follow (the same wall struck again within ``MIN_FLIGHT_S``: a chatter the engine
  sums in closed form) raises :class:`Chatter`: the draw is not compared.

A ring (a circular moat's rigid wall, radius R, PlanModel's ``rings``: its stiffness and damping unused) is
struck by a point at ``P = (p_x + w_x . q, p_y + w_y . q)`` from its centre where ``|P| = R``, along its
normal ``n = P / |P|``: its row is ``n_x w_x + n_y w_y`` there, and it changes as the point moves.  Held, the
point slides along the ring: ``d/dt (row . q') = row . q'' + (|P'|^2 - (n . P')^2) / |P|``, the last term the
centripetal one, so the held motion's bottom row is minus it instead of 0 (integrated as it is: a held
point drifts off its ring by the integration's error, within 4e-15 m on drawn buildings).
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field

import numpy as np
from scipy.integrate import solve_ivp

from reference_ndof import _stepped_over
from reference_plan import PlanModel

MIN_FLIGHT_S = 1e-6
TOUCH_M = 1e-12  # (a point this close to its wall touches it: struck with it at once)
MAX_STRETCHES = 100_000  # (solve_ivp's calls, each to an event or a record's kink: a bound on the loop)


class Chatter(RuntimeError):
    """A wall struck again within MIN_FLIGHT_S of its last impact: a chatter this reference cannot follow."""


@dataclass
class RigidResult:
    impacts: list = field(default_factory=list)   # (wall, t, closing speed in m/s, impulse N s)
    holds: list = field(default_factory=list)     # (wall, t): held from t
    releases: list = field(default_factory=list)  # (wall, t): let go
    y: np.ndarray | None = None                   # the final (q, q')


def _saddle(mass: np.ndarray, rows: np.ndarray, top: np.ndarray, bottom: np.ndarray):
    """Solve ``[M J^T; J 0] [x; l] = [top; bottom]`` (M = diag(mass)): ``x`` and ``l``."""
    n, m = mass.size, rows.shape[0]
    kkt = np.zeros((n + m, n + m))
    kkt[:n, :n] = np.diag(mass)
    kkt[:n, n:] = rows.T
    kkt[n:, :n] = rows
    sol = np.linalg.solve(kkt, np.concatenate((top, bottom)))
    return sol[:n], sol[n:]


def rigid_reference(s: PlanModel, restitution: float, t_end: float, y0: np.ndarray, rtol: float = 1e-12,
                    atol: float = 1e-15) -> RigidResult:
    n = s.mass.size
    if s.plastic or s.bouc_wen:
        raise ValueError("rigid_reference takes linear springs and rigid walls or rings only")
    towards = [sign * np.asarray(w, dtype=float) for w, sign, *_ in s.walls]  # (d = towards . q)
    gaps = [float(gap) for _, _, gap, *_ in s.walls]
    rings = [(np.asarray(wx, dtype=float), np.asarray(wy, dtype=float), float(px), float(py), float(radius))
             for wx, wy, px, py, radius, *_ in s.rings]
    n_walls = len(towards)

    def point(c, y):  # (a ring's point from its centre, and its velocity)
        wx, wy, px, py, _ = rings[c - n_walls]
        return (np.array([px + wx @ y[:n], py + wy @ y[:n]]), np.array([wx @ y[n:2 * n], wy @ y[n:2 * n]]))

    def gap(c, y):  # (>= 0 open)
        if c < n_walls:
            return gaps[c] - float(towards[c] @ y[:n])
        p, _ = point(c, y)
        return rings[c - n_walls][4] - math.hypot(*p)

    def row(c, y):  # (the closing rate is row . q')
        if c < n_walls:
            return towards[c]
        wx, wy, *_ = rings[c - n_walls]
        p, _ = point(c, y)
        nx, ny = p / math.hypot(*p)
        return nx * wx + ny * wy

    def curvature(c, y):  # (d/dt (row . q') - row . q'': 0 on a wall, centripetal on a ring)
        if c < n_walls:
            return 0.0
        p, dp = point(c, y)
        r = math.hypot(*p)
        along = float(p @ dp) / r
        return (float(dp @ dp) - along * along) / r

    n_cons = n_walls + len(rings)
    t_rec, ax, ay = (np.asarray(a, dtype=float) for a in s.record)
    w_max = math.sqrt(max(float(np.max(np.linalg.eigvals(s.k / s.mass[:, None]).real)), 0.0))
    max_step = 2.0 * math.pi / w_max / 100.0 if w_max > 0.0 else np.inf
    held: list[int] = []
    last_impact = {}
    out = RigidResult()

    def free_force(t, y):
        g = np.array([float(np.interp(t, t_rec, ax, left=0.0, right=0.0)),
                      float(np.interp(t, t_rec, ay, left=0.0, right=0.0))])
        return -s.k @ y[:n] - s.c @ y[n:] - s.mass * (s.influence @ g)

    def motion(t, y, walls):  # (accelerations and the held walls' forces)
        f = free_force(t, y)
        if not walls:
            return f / s.mass, np.zeros(0)
        a, lam = _saddle(s.mass, np.array([row(c, y) for c in walls]), f,
                         np.array([-curvature(c, y) for c in walls]))
        return a, lam  # (M a = F - J^T f: each wall pushes its point back by f)

    def rhs(t, y):
        return np.concatenate((y[n:], motion(t, y, held)[0]))

    def events(t0, y0):
        # (a free point at its wall at the stretch's start, let go or left at rest by an impulse, is watched
        # by its gap over the time since, gap / (t - t0), its rate -row . q' at t0: its gap starts at zero, so
        # that solve_ivp's sign change would not mark its meeting the wall again within the first step, and a
        # short excursion passes between _stepped_over's samples (a corner let go at a ring by its mate's
        # impact met it again 8.4e-5 s later, 4 nm away at most: missed, the corner went on through the ring)
        evs = []
        for c in range(n_cons):
            if c in held:
                def let_go(t, y, k=held.index(c)):
                    return motion(t, y, held)[1][k]
                let_go.wall, let_go.held, let_go.contact = c, True, c
                evs.append(let_go)
            else:
                if abs(gap(c, y0)) <= TOUCH_M:
                    def strike(t, y, c=c):
                        return gap(c, y) / (t - t0) if t > t0 else -float(row(c, y) @ y[n:])
                else:
                    def strike(t, y, c=c):
                        return gap(c, y)
                strike.wall, strike.held, strike.contact = c, False, c
                evs.append(strike)
        for f in evs:
            f.terminal, f.direction = True, -1.0
        return evs

    def touching(y):  # (the walls whose points are at them, to TOUCH_M, held or not)
        return [k for k in range(n_cons) if gap(k, y) <= TOUCH_M]

    def independent(rows):
        return rows.shape[0] == 0 or np.linalg.matrix_rank(rows) == rows.shape[0]

    def smallest_consistent(walls, test, y):  # (the first subset, smallest first, that passes test)
        for size in range(len(walls) + 1):
            for subset in itertools.combinations(walls, size):
                rows = np.array([row(k, y) for k in subset]).reshape(len(subset), n)
                if independent(rows):
                    found = test(list(subset), rows)
                    if found is not None:
                        return found
        raise Chatter("no consistent set of walls")

    def plastic(t, y):  # (e = 0: the velocities' projection, in M's metric, onto J v <= 0 of the touching)
        walls = touching(y)
        v = y[n:]
        scale = float(np.max(np.abs(v)))
        every = np.array([row(k, y) for k in walls])

        def kkt(subset, rows):  # (J_S v+ = 0 with impulses >= 0, and no other touching wall closing)
            dv, p = _saddle(s.mass, rows, np.zeros(n), -rows @ v) if subset else (np.zeros(n), np.zeros(0))
            if np.any(p < -1e-12 * max(float(np.max(np.abs(p), initial=0.0)), 1.0)):
                return None
            if np.any(every @ (v + dv) > 1e-13 * scale):
                return None
            return subset, p, v + dv
        subset, impulses, v_plus = smallest_consistent(walls, kkt, y)
        resting = [k for k in walls if abs(float(row(k, y) @ v_plus)) <= 1e-12 * scale]
        if not independent(np.array([row(k, y) for k in resting]).reshape(len(resting), n)):
            raise Chatter(f"more walls at rest than the floor has motions, t = {t}")  # (forces not unique)
        for k, p in zip(subset, impulses):
            if k not in held:
                out.impacts.append((k, t, float(row(k, y) @ v), float(p)))
        return np.concatenate((y[:n], v_plus)), resting

    def hold(t, y, resting):  # (the smallest set of resting walls that push, with none of the others pushed)
        def pushing(subset, rows):
            a, f = motion(t, y, subset)
            big = float(np.max(np.abs(a)))
            others = [k for k in resting if k not in subset]
            if np.any(f < 0.0) or any(float(row(k, y) @ a) + curvature(k, y) > 1e-12 * big for k in others):
                return None
            return subset
        now = smallest_consistent(resting, pushing, y)
        for k in held:
            if k not in now:
                out.releases.append((k, t))
        for k in now:
            if k not in held:
                out.holds.append((k, t))
        held[:] = now

    def strike(t, y, c):
        if float(row(c, y) @ y[n:]) <= 0.0:
            return y
        if t - last_impact.get(c, -np.inf) < MIN_FLIGHT_S:
            raise Chatter(f"wall {c} struck again at t = {t} within {MIN_FLIGHT_S} s")
        last_impact[c] = t
        if restitution == 0.0:
            y, resting = plastic(t, y)
            hold(t, y, resting)
            return y
        if len(touching(y)) > 1:  # (at once, Newton's law one after the other is not Moreau's: not followed)
            raise Chatter(f"impacts at one instant, t = {t}")
        u = float(row(c, y) @ y[n:])
        dv, p = _saddle(s.mass, row(c, y)[None, :], np.zeros(n), np.array([-(1.0 + restitution) * u]))
        out.impacts.append((c, t, u, float(p[0])))
        return np.concatenate((y[:n], y[n:] + dv))

    t, y = 0.0, np.asarray(y0, dtype=float).copy()
    for _ in range(MAX_STRETCHES):
        if t >= t_end:
            break
        after = t_rec[t_rec > t * (1.0 + 1e-15) + 1e-15]
        t_next = min(t_end, float(after[0])) if after.size else t_end
        evs = events(t, y)
        sol = solve_ivp(rhs, (t, t_next), y, method="DOP853", rtol=rtol, atol=atol, events=evs,
                        dense_output=True, max_step=max_step)
        if sol.status == -1:
            raise RuntimeError(sol.message)
        hits = [(float(te[0]), k) for k, te in enumerate(sol.t_events) if te.size and te[0] > t + 1e-13]
        dip = _stepped_over(evs, sol, t)  # (a wall's function through zero and back within a step)
        if dip is not None:
            hits.append(dip)
        if not hits:
            t, y = float(sol.t[-1]), sol.y[:, -1]
            continue
        t_hit, k = min(hits)
        t, y = t_hit, sol.sol(t_hit)
        f = evs[k]
        if f.held:
            held.remove(f.wall)
            out.releases.append((f.wall, t))
        else:
            y = strike(t, y, f.wall)
    else:
        raise RuntimeError(f"more than {MAX_STRETCHES} stretches by t = {t}")
    out.y = y
    return out
