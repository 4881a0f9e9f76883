"""A slow, obviously-correct reference for a structure on a friction isolator: scipy's solve_ivp (DOP853)
with stick and slip as events, restarted at each of them (the reference the engine's friction isolators are
to be tested against).

The model restated directly: n levels with displacements x relative to the ground, level 0 the base on the
isolator, M x'' + C x' + K x = -M 1 a_g(t) + e_0 f.  K and C hold the storeys (a shear building: storey i
between levels i and i + 1) and the isolator's restoring spring ``k_r`` (a friction pendulum's W / R; 0 for a
flat slider) and dashpot ``c_r``; f is the Coulomb friction on the base, |f| <= F = mu W, W = g sum(M) the
weight the isolator carries.
- Slipping, the base's velocity v_0 of sign s: f = -s F.  The slip ends where v_0 returns to 0.
- Sticking, v_0 = 0 and x_0 held: f = -D, with D = -m_0 a_g - (K x)_0 - (C x')_0 the rest of the force on the
  base.  The stick ends where |D| reaches F, and the base slips the way D pushes.
- Where a slip ends the base sticks if |D| <= F; otherwise it slips on, the other way (a reversal).
- With a velocity dependence (``mu_fast``, ``rate_s_m``: OpenSees' VelDependent) a slip's friction is
  W (mu_fast - (mu_fast - mu) e^(-rate |v_0|)); F = mu W still decides the sticks and their ends.

The works are integrated alongside: the input's -int a_g (M 1 . x') dt, the dashpots' int x' C x' dt and the
friction's F int |v_0| dt, so that the ledger can be checked: input = viscous + friction + the change of the
kinetic and elastic energies.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq


@dataclass
class FrictionStructure:
    masses_kg: np.ndarray                 # (n,), level 0 the base
    storey_k: np.ndarray                  # (n - 1,), N/m
    storey_c: np.ndarray                  # (n - 1,), N s/m
    k_r: float                            # the isolator's restoring stiffness, N/m (W / R; 0: a flat slider)
    c_r: float                            # its dashpot, N s/m
    mu: float                             # its friction coefficient
    accel: Callable[[float], float]       # the table's acceleration a_g(t), m/s^2
    g: float = 9.81
    mu_fast: float | None = None          # a velocity-dependent friction's coefficient at high velocity
    rate_s_m: float = 0.0                 # and its rate: mu_fast - (mu_fast - mu) exp(-rate |v_0|)

    @property
    def n(self) -> int:
        return len(self.masses_kg)

    @property
    def friction_n(self) -> float:
        """F = mu W, N."""
        return self.mu * self.g * float(np.sum(self.masses_kg))

    def slip_friction_n(self, mode: int, v0: float) -> float:
        """The friction's magnitude in a slip the way ``mode`` at the base's velocity ``v0``, N: mu W, or
        W (mu_fast - (mu_fast - mu) exp(-rate mode v0)) (mode v0 = |v0| in the slip, smooth past its end)."""
        if self.mu_fast is None:
            return self.friction_n
        weight = self.g * float(np.sum(self.masses_kg))
        # (the exponent bounded: a solver's trial step far past a slip's end must not overflow; unchanged
        #  wherever the slip is, mode v0 >= 0)
        return weight * (self.mu_fast - (self.mu_fast - self.mu)
                         * math.exp(min(-self.rate_s_m * mode * v0, 700.0)))

    def matrices(self) -> tuple[np.ndarray, np.ndarray]:
        """K and C, (n, n)."""
        n = self.n
        k, c = np.zeros((n, n)), np.zeros((n, n))
        k[0, 0], c[0, 0] = self.k_r, self.c_r
        for i, (ks, cs) in enumerate(zip(self.storey_k, self.storey_c)):
            for mat, v in ((k, ks), (c, cs)):
                mat[i, i] += v
                mat[i + 1, i + 1] += v
                mat[i, i + 1] -= v
                mat[i + 1, i] -= v
        return k, c


@dataclass
class FrictionResult:
    t: np.ndarray                                    # (k,) every step's end, and each event
    x: np.ndarray                                    # (k, n)
    v: np.ndarray                                    # (k, n)
    sticks: list = field(default_factory=list)      # times a stick began
    slips: list = field(default_factory=list)       # (time, direction) a slip began (from rest or reversing)
    reversals: list = field(default_factory=list)   # times a slip turned without a stick
    input_work_j: float = 0.0
    viscous_j: float = 0.0
    friction_j: float = 0.0
    stick_force_max_n: float = 0.0                   # the largest |D| over the sticks' samples


class ReferenceStuck(RuntimeError):
    """Phases of zero length one after another: a degenerate case this simple reference cannot step past."""


def _mode_at(s: FrictionStructure, k: np.ndarray, c: np.ndarray, t: float, x: np.ndarray,
             v: np.ndarray) -> int:
    """The base at rest at t: 0 (it sticks) or the direction it slips (+1, -1)."""
    d = _rest_force(s, k, c, t, x, v)
    f = s.friction_n
    return 0 if abs(d) <= f else (1 if d > 0 else -1)


def _rest_force(s: FrictionStructure, k: np.ndarray, c: np.ndarray, t: float, x: np.ndarray,
                v: np.ndarray) -> float:
    """D: the force on the base but the friction's, N."""
    return float(-s.masses_kg[0] * s.accel(t) - k[0] @ x - c[0] @ v)


def _first_crossing(sol, events: list, per_step: int = 32) -> tuple[float, int | None]:
    """The phase's end: the first instant where one of its event functions crosses zero in its direction, and
    which (None: none did, the phase ran to its bracket's end).

    solve_ivp looks at an event function's sign at its steps' ends only: a function that crosses zero and
    comes back within one step goes unseen (a slip that ends and would slip on the same way 0.4 ms later,
    inside a 4 ms step, was found so).  Its dense output is scanned here at ``per_step`` points in each step,
    from the phase's start, and the first sign change is solved for with brentq on it."""
    lo = sol.t[:-1, None]
    grid = (lo + (sol.t[1:, None] - lo) * np.linspace(0.0, 1.0, per_step + 1)[None, 1:]).ravel()
    grid = np.concatenate([sol.t[:1], grid])
    ys = sol.sol(grid)
    best_t, best = float(sol.t[-1]), None
    if sol.status == 1:  # (the solver's own: the first crossing unless an earlier one hid inside a step)
        best = next(i for i, te in enumerate(sol.t_events) if te.size)
    for which, fn in enumerate(events):
        vals = fn.direction * np.array([fn(tt, ys[:, i]) for i, tt in enumerate(grid)])
        if vals[0] == 0.0 and vals.size > 1 and vals[1] > 0.0:  # (at zero at the start, and crossing at once)
            best_t, best = float(grid[0]), which
            continue
        hits = np.flatnonzero((vals[:-1] < 0.0) & (vals[1:] >= 0.0))
        if hits.size == 0:
            continue
        a, b = grid[hits[0]], grid[hits[0] + 1]
        root = b if vals[hits[0] + 1] == 0.0 else brentq(lambda tt: fn(tt, sol.sol(tt)), a, b, xtol=1e-15,
                                                          rtol=4 * np.finfo(float).eps)
        if root < best_t:
            best_t, best = float(root), which
    return best_t, best


def _phase(rhs, t: float, t_stop: float, y: np.ndarray, events: list, from_rest: bool, held: bool,
           rtol: float, atol: float):
    """One phase from ``t`` to its first event or ``t_stop``: ``(its solution, its end, the event that fired
    (None: none), the state there, the solver's steps before it)``.  A slip from rest (``from_rest``) starts
    with its event function at zero: a first step short against any slip, so that a slip which comes back to
    rest inside the solver's first step is not taken for one that ended where it started, the bracket's end;
    a ``held`` phase's steps are at most 1 ms."""
    first = min(1e-7, 0.5 * (t_stop - t)) if from_rest else None
    sol = solve_ivp(rhs, (t, t_stop), y, method="DOP853", rtol=rtol, atol=atol, events=events,
                    dense_output=True, first_step=first, max_step=1e-3 if held else np.inf)
    if sol.status < 0:
        raise RuntimeError(sol.message)
    t_new, fired = _first_crossing(sol, events)
    y_new = sol.sol(t_new) if fired is not None and t_new < sol.t[-1] else sol.y[:, -1].copy()
    return sol, t_new, fired, y_new, sol.t[1:][sol.t[1:] < t_new]


def reference(s: FrictionStructure, t_end: float, x0: np.ndarray, v0: np.ndarray, rtol: float = 1e-12,
              atol: float = 1e-15, max_phases: int = 100_000,
              knots: np.ndarray | None = None) -> FrictionResult:
    """Integrate from (x0, v0) at t = 0 to ``t_end``: the histories at every step and event, the stick and
    slip events, the works.

    ``knots``: the instants where the table's acceleration has a kink (a record's samples).  Each
    integration stops at the next one: a held base's force is then linear in t between two of them (its rest
    force, the table's piece, for a single mass), and a stick's steps are at most 1 ms (a stuck single mass
    has a right-hand side of zero: the solver's steps would be as long as the run).  Each phase's dense output
    is scanned for a crossing the solver's steps stepped over (``_first_crossing``)."""
    n = s.n
    k, c = s.matrices()
    m = np.asarray(s.masses_kg, dtype=float)
    f = s.friction_n
    y = np.concatenate([np.asarray(x0, float), np.asarray(v0, float), np.zeros(3)])
    t = 0.0
    mode = _mode_at(s, k, c, t, y[:n], y[n:2 * n]) if y[n] == 0.0 else (1 if y[n] > 0 else -1)
    if mode == 0:
        y[n] = 0.0
    out = FrictionResult(t=np.array([t]), x=y[None, :n].copy(), v=y[None, n:2 * n].copy())
    (out.sticks if mode == 0 else out.slips).append(t if mode == 0 else (t, mode))
    ts, xs, vs = [np.array([t])], [y[None, :n]], [y[None, n:2 * n]]
    short = 0
    cuts = np.unique(np.append(np.asarray(knots if knots is not None else [], float), t_end))
    cuts = cuts[cuts <= t_end]
    for _ in range(max_phases):
        if t >= t_end:
            break
        t_stop = float(cuts[np.searchsorted(cuts, t, side="right")])

        def rhs(tt: float, yy: np.ndarray, mode: int = mode) -> np.ndarray:
            x, v = yy[:n], yy[n:2 * n]
            ag = s.accel(tt)
            force = -m * ag - k @ x - c @ v
            fv = s.slip_friction_n(mode, v[0]) if mode != 0 else 0.0
            if mode == 0:
                force[0] = 0.0  # (held: the friction takes the rest)
            else:
                force[0] -= mode * fv
            acc = force / m
            dy = np.empty_like(yy)
            dy[:n] = v
            dy[n:2 * n] = acc
            if mode == 0:
                dy[0], dy[n] = 0.0, 0.0
            dy[2 * n] = -ag * float(m @ v)
            dy[2 * n + 1] = float(v @ c @ v)
            dy[2 * n + 2] = fv * mode * v[0]  # (|v0| in the slip, smooth past its end: the last step's
            #  dense output, which places the end, would cut a kink of abs(v0) there; 0 when held)
            return dy

        if mode == 0:
            def up(tt: float, yy: np.ndarray) -> float:
                return _rest_force(s, k, c, tt, yy[:n], yy[n:2 * n]) - f

            def down(tt: float, yy: np.ndarray) -> float:
                return _rest_force(s, k, c, tt, yy[:n], yy[n:2 * n]) + f

            up.terminal, up.direction = True, 1.0
            down.terminal, down.direction = True, -1.0
            events = [up, down]
        else:
            def stop(tt: float, yy: np.ndarray) -> float:
                return yy[n]

            stop.terminal, stop.direction = True, -float(mode)
            events = [stop]
        sol, t_new, fired, y, steps = _phase(rhs, t, t_stop, y, events, mode != 0 and y[n] == 0.0, mode == 0,
                                             rtol, atol)
        if mode == 0:  # (the friction needed to hold the base, over the stick)
            grid = np.linspace(t, t_new, 64)
            ys = sol.sol(grid)
            held = [abs(_rest_force(s, k, c, tt, ys[:n, i], ys[n:2 * n, i])) for i, tt in enumerate(grid)]
            out.stick_force_max_n = max(out.stick_force_max_n, max(held))
        inside = sol.y[:, 1:1 + steps.size]  # (the solver's steps before the phase's end)
        ts.append(np.append(steps, t_new))
        xs.append(np.vstack([inside[:n].T, y[None, :n]]))
        vs.append(np.vstack([inside[n:2 * n].T, y[None, n:2 * n]]))
        if fired is None:  # (t_stop: a knot, or the end)
            t = t_new
            continue
        short = short + 1 if t_new - t <= 1e-12 * max(1.0, t) else 0
        if short > 3:
            raise ReferenceStuck(f"phases of zero length at t = {t_new!r}")
        t = t_new
        if mode == 0:  # a stick ended: the base slips the way D pushes
            mode = 1 if fired == 0 else -1
            out.slips.append((t, mode))
        else:  # a slip ended: a stick, or a reversal
            y[n] = 0.0
            nxt = _mode_at(s, k, c, t, y[:n], y[n:2 * n])
            if nxt == mode:  # (D still pushes on: at rounding, the slip's own end; it sticks)
                nxt = 0
            if nxt == 0:
                out.sticks.append(t)
            else:
                out.reversals.append(t)
                out.slips.append((t, nxt))
            mode = nxt
    else:
        raise RuntimeError(f"more than {max_phases} phases")
    out.t = np.concatenate(ts)
    out.x = np.concatenate(xs)
    out.v = np.concatenate(vs)
    out.input_work_j, out.viscous_j, out.friction_j = (float(w) for w in y[2 * n:])
    return out


def energy(s: FrictionStructure, x: np.ndarray, v: np.ndarray) -> float:
    """Kinetic plus elastic energy at a state, J."""
    k, _ = s.matrices()
    return 0.5 * float(np.asarray(s.masses_kg) @ (v * v)) + 0.5 * float(x @ k @ x)


def den_hartog(mass_kg: float, k_n_m: float, friction_n: float, force_amplitude_n: float,
               omega_rad_s: float) -> tuple[float, float]:
    """Den Hartog's (1931) exact steady state without stops of m x'' + k x + F sign(x') = P0 cos(w t + phi):
    its amplitude x0 (m; the motion runs from x0 to -x0 in half a period, its velocity never zero between) and
    the phase phi (rad) at which it is at x0 with t = 0; NaN where no such motion exists.

    From the half period from x0 to -x0 (x' < 0, the friction +F): x = F/k + A cos(wn t) + B sin(wn t)
    + Q cos(w t + phi) with Q = (P0/k) / (1 - b^2), b = w/wn; x'(0) = x'(pi/w) = 0 and x(0) = -x(pi/w) = x0
    give Q sin(phi) = -(F/k) U, U = sin(pi/b) / (b (1 + cos(pi/b))), and x0 = Q cos(phi), so
    x0 = sqrt(Q^2 - (F U / k)^2)."""
    wn = math.sqrt(k_n_m / mass_kg)
    b = omega_rad_s / wn
    q = force_amplitude_n / k_n_m / (1.0 - b * b)
    xf = friction_n / k_n_m
    denominator = b * (1.0 + math.cos(math.pi / b))  # (0 at b = 1/3, 1/5, ...: no such motion with friction)
    if xf == 0.0:
        return abs(q), math.atan2(0.0, q)
    if denominator == 0.0:
        return math.nan, math.nan
    u = math.sin(math.pi / b) / denominator
    inside = q * q - (xf * u) ** 2
    if inside <= 0.0:
        return math.nan, math.nan
    x0 = math.sqrt(inside)
    return x0, math.atan2(-xf * u / q, x0 / q)
