"""A slow, obviously-correct reference: scipy's solve_ivp (DOP853) with events.

It restates the model of MODEL.md §1 directly, without sharing code with the engine:
the isolator as parallel springs (kinematic) or a backbone (elastic), Kelvin-Voigt or
Hunt-Crossley bumpers whose relaxation between contacts is evaluated in closed form.
Integration restarts at every event.  The elastic-plastic law is restated as OpenSees
defines ``ImpactMaterial``: its force is the state (elastic moves of slope K1 from the force
where the branch began, held between the yield and unloading lines), not the engine's
plastic offset.
"""

from __future__ import annotations

import math
import sys
from dataclasses import dataclass, field

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

import pounding as pd_


@dataclass
class RefResult:
    t: float
    d: float
    v: float
    contact_starts: list = field(default_factory=list)  # (side, t)
    contact_ends: list = field(default_factory=list)
    u: np.ndarray | None = None
    state: dict | None = None       # pass back as ``state=`` to continue exactly
    completed: list = field(default_factory=list)  # (side, t_start, v_in, t_end, v_out, impulse, work)
    viscous: float = 0.0            # int c_d V^2 dt, J
    input_work: float = 0.0         # -int M A_g V dt, J
    d_max: float = -math.inf        # with measure=True: extrema over the run
    d_min: float = math.inf
    a_abs_max: float = 0.0


class ReferenceFailed(RuntimeError):
    """solve_ivp could not meet the tolerance (e.g. rtol 1e-13 at the start of a Jankowski
    contact, whose dashpot c0 d^((n-1)/2) has an unbounded derivative at d = 0)."""


class ReferenceStalled(RuntimeError):
    """An event that fires again and again at the same instant: a degenerate graze (the
    mass moving with the relaxing bumper surface at zero force) that this simple
    reference cannot step past."""


class _ElasticPlasticState:
    """The force of an elastic-plastic bumper as its state: on the elastic branch
    ``f_ref + K1 (d - d_ref)``, else on the yield line or the unloading line."""

    def __init__(self, law):
        self.k1, self.k2, self.dy = law.stiffness, law.post_yield_stiffness, law.yield_compression
        self.reset()

    def reset(self, rate=0.0):
        self.mode, self.f_ref, self.d_ref = "elastic", 0.0, 0.0

    def snapshot(self):
        return (self.mode, self.f_ref, self.d_ref)

    def restore(self, snap):
        self.mode, self.f_ref, self.d_ref = snap

    def upper(self, d):
        return self.k1 * self.dy + self.k2 * (d - self.dy)

    def force(self, d, dd):
        if self.mode == "yield":
            return self.upper(d)
        if self.mode == "unload":
            return self.k2 * d
        return self.f_ref + self.k1 * (d - self.d_ref)

    def events(self):
        """``(g(d, dd), new mode)``: fires when g crosses zero downwards."""
        if self.mode == "yield":
            return [(lambda d, dd: dd, "elastic")]
        if self.mode == "unload":
            return [(lambda d, dd: -dd, "elastic")]
        # where the elastic line meets the yield line and the unloading line, as compressions: the
        # difference of the forces there cancels to rounding of the force (1e-13 N of 500 N), and
        # a turn on the yield line flipped between the two modes at one instant
        k1, k2 = self.k1, self.k2
        x_up = ((k1 - k2) * self.dy + k1 * self.d_ref - self.f_ref) / (k1 - k2)
        out = [(lambda d, dd: x_up - d, "yield")]
        if self.f_ref > 0.0:  # (from the unloaded start the unloading line is met at 0, the contact's end)
            x_low = (k1 * self.d_ref - self.f_ref) / (k1 - k2)
            out.append((lambda d, dd: d - x_low, "unload"))
        return out

    def switch(self, mode, d):
        if mode == "elastic":
            self.f_ref, self.d_ref = self.force(d, 0.0), d
        self.mode = mode


class _HertzdampState:
    """Hertzdamp's damping, chosen when a contact starts (OpenSees: xi_norm K_h / v_in)."""

    def __init__(self, law):
        self.k, self.xi_norm = law.stiffness, law.xi_norm
        self.xi = 0.0

    def reset(self, rate=0.0):
        self.xi = self.xi_norm * self.k / rate if rate > 0.0 else 0.0

    def snapshot(self):
        return self.xi

    def restore(self, snap):
        self.xi = snap

    def events(self):
        return []


class _KinematicState:
    """A kinematic multi-linear bumper as Iwan's springs: the strain of each softening's
    elastic-perfectly-plastic spring is the state (elastic from a reference point, or held at
    +-b while it slips), the hardenings are elastic ramps, all in parallel with the rest of the
    first slope."""

    def __init__(self, law):
        k = law.slopes
        self.b = law.breakpoints
        self.soft = [(i, k[i] - k[i + 1]) for i in range(len(self.b)) if k[i] > k[i + 1]]
        self.hard = [(k[i + 1] - k[i], self.b[i]) for i in range(len(self.b)) if k[i] < k[i + 1]]
        self.k_lin = max(k[0] - sum(dk for _, dk in self.soft), 0.0)
        self.modes = {i: ("el", 0.0, 0.0) for i, _ in self.soft}  # (mode, strain at x_ref, x_ref)

    def snapshot(self):
        return dict(self.modes)

    def restore(self, snap):
        self.modes = dict(snap)

    def strain(self, i, x):
        mode, e, x_ref = self.modes[i]
        if mode == "el":
            return e + (x - x_ref)
        return self.b[i] if mode == "up" else -self.b[i]

    def spring(self, x):
        f = self.k_lin * x + sum(dk * max(x - b, 0.0) for dk, b in self.hard)
        return f + sum(dk * self.strain(i, x) for i, dk in self.soft)

    def reset(self, rate=0.0, x=0.0):  # a contact starts at x: springs slipping back hold there
        for i, _ in self.soft:
            self.modes[i] = ("el", self.strain(i, x), x)

    def release(self, x):  # ... and ends at x: the springs slipping in compression hold there
        self.reset(0.0, x)

    def recovered(self, x0, x):
        """The springs after a recovery (monotone) from x0 down to x: strains clipped at -b."""
        for i, _ in self.soft:
            self.modes[i] = ("el", max(self.strain(i, x0) + (x - x0), -self.b[i]), x)

    def spring_down(self, x0, x):
        """The springs' force at x on the recovery from x0 (the state as at x0)."""
        f = self.k_lin * x + sum(dk * max(x - b, 0.0) for dk, b in self.hard)
        return f + sum(dk * max(self.strain(i, x0) + (x - x0), -self.b[i]) for i, dk in self.soft)

    def events(self):
        out = []
        for i, _ in self.soft:
            mode, e, x_ref = self.modes[i]
            b = self.b[i]
            if mode == "el":
                out.append((lambda d, dd, e=e, x_ref=x_ref, b=b: b - (e + d - x_ref), (i, "up")))
                out.append((lambda d, dd, e=e, x_ref=x_ref, b=b: (e + d - x_ref) + b, (i, "down")))
            elif mode == "up":
                out.append((lambda d, dd: dd, (i, "el")))
            else:
                out.append((lambda d, dd: -dd, (i, "el")))
        return out

    def switch(self, mode, d):
        i, new = mode
        if new == "el":
            self.modes[i] = ("el", self.strain(i, d), d)
        else:
            self.modes[i] = (new, 0.0, d)


def _law(law):
    if isinstance(law, pd_.MultilinearBumper) and law.hysteresis == "kinematic":
        kin = _KinematicState(law)
        c = law.damping
        cache = {}

        def force(d, dd):
            return kin.spring(max(d, 0.0)) + c * dd

        def relax(d0, tau):  # c x' = -F(x) on the way down, to the set (F = 0) or to 0; at once without c
            if d0 <= 0.0 or kin.spring_down(d0, d0) <= 0.0:
                return max(d0, 0.0)
            if c == 0:
                if kin.spring_down(d0, 0.0) > 0.0:
                    return 0.0
                return brentq(lambda x: kin.spring_down(d0, x), 0.0, d0, xtol=1e-18, rtol=8.9e-16)
            if cache.get("d0") != d0 or cache["t"] < tau:
                span = max(tau, 1.0) * 2.0

                def rhs(t, y):
                    return [-max(kin.spring_down(d0, max(y[0], 0.0)), 0.0) / c]

                floor = lambda t, y: y[0]  # noqa: E731
                floor.terminal = True
                sol = solve_ivp(rhs, (0.0, span), [d0], method="DOP853", rtol=1e-13, atol=1e-20,
                                dense_output=True, events=floor)
                cache.update(d0=d0, t=span if sol.status == 0 else math.inf, sol=sol.sol, t_zero=sol.t[-1])
            if tau >= cache["t_zero"] and cache["t"] == math.inf:
                return 0.0
            return max(float(cache["sol"](tau)[0]), 0.0)

        def release(d, dd):
            return kin.spring(max(d, 0.0)) + c * dd

        return force, relax, release, kin
    if isinstance(law, pd_.Hertzdamp):
        hd = _HertzdampState(law)
        k, n = law.stiffness, law.exponent

        def force(d, dd):
            return max(d, 0.0) ** n * (k + hd.xi * dd)

        def relax(d0, tau):  # at the constant speed k / xi, with the last contact's xi
            if d0 <= 0.0 or hd.xi <= k / sys.float_info.max:  # (a dashpot of 1e-316: none; k / xi overflows)
                return 0.0
            return max(0.0, d0 - k / hd.xi * tau)

        def release(d, dd):
            return k + hd.xi * dd

        return force, relax, release, hd
    if isinstance(law, pd_.ElasticPlastic):
        hyst = _ElasticPlasticState(law)

        def force(d, dd):
            return hyst.force(max(d, 0.0), dd)

        def relax(d0, tau):  # no dashpot: unloaded at once
            return 0.0

        def release(d, dd):  # never pulls: the contact ends with the compression
            return 1.0

        return force, relax, release, hyst
    if isinstance(law, pd_.KelvinVoigt):
        k, c = law.stiffness, law.damping

        def force(d, dd):
            return k * d + c * dd

        def relax(d0, tau):
            return 0.0 if c == 0 else d0 * math.exp(-k / c * tau)

        def release(d, dd):
            return k * d + c * dd
    elif isinstance(law, pd_.MultilinearBumper):
        c = law.damping

        def backbone(d):
            return float(law.backbone(max(d, 0.0)))

        def force(d, dd):
            return backbone(d) + c * dd

        cache = {}

        def relax(d0, tau):  # c d' = -R(d), integrated once per relaxation and kept
            if c == 0 or d0 <= 0.0:
                return 0.0
            if cache.get("d0") != d0 or cache["t"] < tau:
                span = max(tau, 1.0) * 2.0
                sol = solve_ivp(lambda t, y: [-backbone(y[0]) / c], (0.0, span), [d0], method="DOP853",
                                rtol=1e-13, atol=1e-20, dense_output=True)
                cache.update(d0=d0, t=span, sol=sol.sol)
            return max(float(cache["sol"](tau)[0]), 0.0)

        def release(d, dd):
            return backbone(d) + c * dd
    elif isinstance(law, pd_.Jankowski):
        k, n = law.stiffness, law.exponent
        c0 = 2.0 * law.damping_ratio * math.sqrt(law.effective_mass * law.stiffness)

        def force(d, dd):  # the dashpot c0 d^((n-1)/2) on the approach only
            d = max(d, 0.0)
            return k * d**n + (c0 * d ** (0.5 * (n - 1.0)) * dd if dd > 0.0 else 0.0)

        def relax(d0, tau):  # no dashpot on the recovery: back at once
            return 0.0

        def release(d, dd):  # never pulls: the contact ends with the compression
            return 1.0
    else:
        k, n, c = law.stiffness, law.exponent, law.damping

        def force(d, dd):
            return max(d, 0.0) ** n * (k + c * dd)

        def relax(d0, tau):
            return 0.0 if c == 0 else max(0.0, d0 - k / c * tau)

        def release(d, dd):
            return k + c * dd
    return force, relax, release, None


def _stepped_over_graze(evs, minima, sol, t_start):
    """The earliest event whose function dips below zero and back inside one solver step.

    Events are checked at step ends only; a minimum (located as an event of the rate) with
    a negative value means a crossing was stepped over, and so does a negative value where
    the run stops (a minimum that coincides with another event, which ended the run just
    before the minimum's own event could be reported).  The crossing is found on the dense output
    between the last step end before the minimum, where the value is still positive, and
    the minimum.  Returns ``(t, index, y)`` or None.
    """
    hit = None
    for k_ev, te in enumerate(minima):
        f = evs[k_ev][0]
        for tm in [*te, sol.t[-1]]:
            if tm <= t_start or f(tm, sol.sol(tm)) >= -1e-12 or (hit is not None and tm >= hit[0]):
                continue
            ends = [tt for tt in sol.t if t_start <= tt < tm]
            lo = next((tt for tt in reversed(ends) if f(tt, sol.sol(tt)) > 0.0), None)
            hi = tm
            if lo is None:
                # at or below zero at every step end since the start (it started at zero: a release
                # at the bumper's surface): did it rise above zero and come back inside a step?  A
                # mass released at 3 mm/s came back 6.6 ms later, 5 um deep, inside one DOP853 step
                # (seen on a Jankowski draw: the reference had one contact fewer than the engine)
                ts = np.linspace(t_start, tm, 401)[1:]
                gs = np.array([f(tt, sol.sol(tt)) for tt in ts])
                up = np.flatnonzero(gs > 0.0)
                down = np.flatnonzero(gs <= 0.0)
                down = down[down > up[0]] if up.size else down[:0]
                if not down.size:  # negative since the start: the boundary just left, not a graze
                    continue
                lo, hi = ts[down[0] - 1], ts[down[0]]
            root = brentq(lambda tt: f(tt, sol.sol(tt)), lo, hi, xtol=1e-16, rtol=8.9e-16)
            hit = (root, k_ev, sol.sol(root))
    return hit


def reference(osc: pd_.Oscillator, exc, t_end: float, d0=0.0, v0=0.0, rtol=1e-10, atol=1e-15,
              state=None, measure=False, sample_dt=2e-5):
    """Integrate to ``t_end`` from rest at t = 0 (or from ``state``, a previous result's).

    ``measure``: also the extrema of D (at velocity zeros, located as events) and of
    |a_abs| (dense output sampled every ``sample_dt`` s, and at every event).
    """
    iso = osc.isolator
    K = np.array(iso.slopes_n_m)
    Db = np.array(iso.breakpoints_m)
    n_sp = len(Db)
    ki = K[:-1] - K[1:]
    u = np.zeros(n_sp)
    s = np.zeros(n_sp)
    m, cd = osc.mass_kg, iso.damping_n_s_m
    kinematic = iso.hysteresis == "kinematic"
    bw = iso.bouc_wen  # its z is the last of the carried states (acc[6])
    b = osc.bumpers
    sides = []
    if b is not None:
        sides = [(-1.0, b.gap_left_m, *_law(b.left)), (1.0, b.gap_right_m, *_law(b.right))]
    comp = [0.0, 0.0]        # compression at t_rel
    t_rel = [0.0, 0.0]
    inc = [False, False]
    accel = exc.acceleration
    res = RefResult(0.0, d0, v0)
    t, d, v = 0.0, d0, v0
    open_start = [None, None]   # (t, v, impulse and work integrals then) of the contact going on
    # integrals carried as extra ODE states: impulse and work of each bumper, viscous, input
    acc = np.zeros(7)
    if state is not None:
        t, d, v = state["t"], state["d"], state["v"]
        acc = state["acc"].copy()
        u, s = state["u"].copy(), state["s"].copy()
        comp, t_rel, inc = list(state["comp"]), list(state["t_rel"]), list(state["inc"])
        open_start = list(state["open_start"])
        for j, snap in enumerate(state["laws"]):
            if snap is not None:
                sides[j][5].restore(snap)

    def iso_force(dd):
        if kinematic:  # each spring's force: yielded at +-its breakpoint, or stretched by dd - u (dd: a
            # displacement, or an array of them)
            x = np.asarray(dd, dtype=float)
            f = K[-1] * x + np.where(s != 0, s * Db, x[..., None] - u) @ ki
            return float(f) if f.ndim == 0 else f
        return float(iso.backbone(dd))

    def bump_force(j, dd, vv):
        sign, gap, force = sides[j][:3]
        return force(sign * dd - gap, sign * vv)

    def z_rate(vv, z):
        if bw is None:
            return 0.0
        # (|z| held at 2 z_max in the power: the motion never leaves |z| <= z_max, but a trial stage of a
        # step that is then rejected can, and |z|^n overflowed there)
        zn = min(abs(z), 2.0 * bw.z_max) ** bw.n
        return vv / bw.yield_displacement_m * (bw.a - zn * (bw.beta * np.sign(vv * z) + bw.gamma))

    def rhs(tt, y):
        dd, vv = y[0], y[1]
        f = iso_force(dd) + cd * vv
        if bw is not None:
            f += bw.stiffness_n_m * bw.yield_displacement_m * y[8]
        rates = [0.0, 0.0, 0.0, 0.0]
        for j in range(len(sides)):
            if inc[j]:
                fb = bump_force(j, dd, vv)
                f += sides[j][0] * fb
                rates[j] = fb
                rates[2 + j] = fb * sides[j][0] * vv
        ag = float(accel(tt))
        return [vv, -f / m - ag, *rates, cd * vv * vv, -m * ag * vv, z_rate(vv, y[8])]

    def build_events():
        evs = []
        if bw is not None:  # its law's kinks: where z and where the velocity cross zero
            if acc[6] != 0.0:
                sz = math.copysign(1.0, acc[6])
                evs.append((lambda tt, y, sz=sz: sz * y[8], ("bwz", 0, 0.0)))
            # (the sign the velocity has, or heads to where it is 0: after a kink, its acceleration's)
            sv = math.copysign(1.0, v if abs(v) > 1e-12 else rhs(t, [d, v, *acc])[1])
            evs.append((lambda tt, y, sv=sv: sv * y[1], ("kink", 0, 0.0)))
        if kinematic:
            for i in range(n_sp):
                if s[i] == 0:
                    evs.append((lambda tt, y, i=i: Db[i] + u[i] - y[0], ("yield", i, 1.0)))
                    evs.append((lambda tt, y, i=i: Db[i] - u[i] + y[0], ("yield", i, -1.0)))
            if np.any(s != 0):
                sd = s[s != 0][0]
                evs.append((lambda tt, y, sd=sd: sd * y[1], ("rev", 0, 0.0)))
        else:
            for e in np.concatenate([-Db, Db]):
                # the side of the breakpoint the motion is heading into (at a kink, the velocity tells)
                near = abs(d - e) < 1e-12
                # (at rest there, e.g. turning at the breakpoint, where it heads is its acceleration's way)
                heading = v if abs(v) > 1e-12 else rhs(t, [d, v, *acc])[1]
                sgn = (-1.0 if heading > 0 else 1.0) if near else (1.0 if d < e else -1.0)
                evs.append((lambda tt, y, e=e, sgn=sgn: sgn * (e - y[0]), ("region", 0, 0.0)))
        for j in range(len(sides)):
            if inc[j]:
                if sides[j][5] is not None:  # a law's own events (in the compression and its rate)
                    for g, mode in sides[j][5].events():
                        evs.append((lambda tt, y, j=j, g=g: g(sides[j][0] * y[0] - sides[j][1],
                                                              sides[j][0] * y[1]),
                                    ("law", j, mode)))
                evs.append((lambda tt, y, j=j: sides[j][0] * y[0] - sides[j][1], ("end", j, 0.0)))
                evs.append((lambda tt, y, j=j: sides[j][4](sides[j][0] * y[0] - sides[j][1],
                                                           sides[j][0] * y[1]), ("end", j, 0.0)))
            else:
                evs.append((lambda tt, y, j=j: sides[j][1] + sides[j][3](comp[j], tt - t_rel[j])
                            - sides[j][0] * y[0], ("start", j, 0.0)))
        return evs

    def apply(kind, idx, direction):
        if kind == "bwz":
            acc[6] = 0.0
        elif kind == "yield":
            s[idx] = direction
            u[idx] = d - direction * Db[idx]
        elif kind == "rev":
            for i in range(n_sp):
                if s[i] != 0:
                    u[i] = d - s[i] * Db[i]
            s[:] = 0
        elif kind == "law":
            sides[idx][5].switch(direction, sides[idx][0] * d - sides[idx][1])
        elif kind == "start":
            inc[idx] = True
            if isinstance(sides[idx][5], _KinematicState):  # its springs, from where the bumper recovered to
                x_s = sides[idx][3](comp[idx], t - t_rel[idx])
                sides[idx][5].recovered(comp[idx], x_s)
                sides[idx][5].reset(0.0, x_s)
            elif sides[idx][5] is not None:
                sides[idx][5].reset(sides[idx][0] * v)
            res.contact_starts.append((idx, t))
            open_start[idx] = (t, v, acc[idx], acc[2 + idx])
        elif kind == "end":
            inc[idx] = False
            comp[idx] = max(0.0, sides[idx][0] * d - sides[idx][1])
            if isinstance(sides[idx][5], _KinematicState):
                sides[idx][5].release(comp[idx])
            t_rel[idx] = t
            res.contact_ends.append((idx, t))
            t0, v_in, imp0, work0 = open_start[idx]
            res.completed.append((idx, t0, v_in, t, v, acc[idx] - imp0, acc[2 + idx] - work0))
            open_start[idx] = None

    def immediate(evs):
        """An event sitting at zero and heading negative fires at once (coincident events).

        Heading negative is judged from a second-order step of 1 ns or, where that leaves
        the value at rounding level (a mass at rest against a bumper at zero gap, pushed by a
        table acceleration that starts from zero: the value goes as -t^3), from the motion
        integrated over the next 0.1 ms: every value there at or below zero, the last below.
        """
        dt = 1e-9
        motion = None
        for f, info in evs:
            if info[0] in ("region", "kink"):  # a kink of the backbone carries no state
                continue
            y0 = np.array([d, v, *acc])
            g0 = f(t, y0)
            if abs(g0) < 1e-12:
                yp = np.array(rhs(t, y0))
                y1 = y0 + dt * yp
                y1[0] += 0.5 * yp[1] * dt * dt
                g1 = f(t + dt, y1)
                if g1 < -1e-16:
                    return info
                if abs(g1) > 1e-16:
                    continue
                if motion is None:
                    ts = t + np.linspace(0.0, 1e-4, 21)[1:]
                    motion = solve_ivp(rhs, (t, ts[-1]), [d, v, *acc], method="DOP853", rtol=1e-13,
                                       atol=1e-20, t_eval=ts).y
                gs = np.array([f(tt, motion[:, k]) for k, tt in enumerate(ts)])
                if np.all(gs <= 0.0) and gs[-1] < -1e-16:
                    return info
        return None

    def a_abs(tt, dd, vv, z=0.0):
        f = iso_force(dd) + cd * vv + (0.0 if bw is None else bw.stiffness_n_m * bw.yield_displacement_m * z)
        for j in range(len(sides)):
            if inc[j]:
                f = f + sides[j][0] * bump_force(j, dd, vv)
        return -f / m

    def track(tt, dd, vv, z):
        """Extrema at the samples (arrays) of one phase."""
        res.d_max = max(res.d_max, float(np.max(dd)))
        res.d_min = min(res.d_min, float(np.min(dd)))
        res.a_abs_max = max(res.a_abs_max, float(np.max(np.abs(a_abs(tt, dd, vv, z)))))

    if measure:
        track(np.array([t]), np.array([d]), np.array([v]), np.array([acc[6]]))
    spins = 0
    stalled = 0
    while t < t_end - 1e-15:
        spins += 1
        if spins > 100_000:
            raise RuntimeError("reference made no progress")
        evs = build_events()
        info = immediate(evs)
        if info is not None:
            apply(*info)
            continue
        # an event at zero that did not fire (it heads positive: a release at the bumper's surface) is left
        # out for a first 0.1 us, until it is clear of zero: solve_ivp would report it at the start
        y_start = np.array([d, v, *acc])
        at_zero = {k for k, (f, _) in enumerate(evs) if abs(f(t, y_start)) <= 1e-15}
        funcs = []
        for k, (f, _) in enumerate(evs):
            def ev(tt, y, f=f, off=k in at_zero):
                return 1.0 if off else f(tt, y)
            ev.terminal = True
            ev.direction = -1
            funcs.append(ev)
        n_evs = len(funcs)
        for f, _ in evs:  # minima of the event functions: grazes a solver step stepped over
            def ev_min(tt, y, f=f):
                h = 1e-6
                yp = np.array(rhs(tt, y))
                return (f(tt + h, y + h * yp) - f(tt - h, y - h * yp)) / (2.0 * h)
            ev_min.direction = 1
            funcs.append(ev_min)
        if measure:
            def vel_zero(tt, y):
                return y[1]
            funcs.append(vel_zero)
        t_start = t
        # a record's acceleration is linear between its samples, with a kink at each: integration
        # restarts there (DOP853 stepped over them, its error estimate blind to a kink: state errors
        # of 1e-12 to 1e-9 at rtol 1e-13, erratic in rtol and atol, that contacts amplify 1e3-fold)
        t_stop = t_end
        if isinstance(exc, pd_.Record):
            later = exc.t[exc.t > t]
            if later.size and later[0] < t_end:
                t_stop = float(later[0])
        if at_zero:
            t_stop = min(t_stop, t + 1e-7)
        sol = solve_ivp(rhs, (t, t_stop), [d, v, *acc], method="DOP853", rtol=rtol, atol=atol, events=funcs,
                        dense_output=True)
        if sol.status < 0:  # (it used to stop there silently, as if the run had ended)
            raise ReferenceFailed(f"solve_ivp failed at t = {sol.t[-1]}: {sol.message}")
        if measure:
            ye = sol.y_events[-1]
            if len(ye):
                res.d_max = max(res.d_max, float(np.max(ye[:, 0])))
                res.d_min = min(res.d_min, float(np.min(ye[:, 0])))
            sol.t_events = sol.t_events[:-1]
            sol.y_events = sol.y_events[:-1]
        minima = sol.t_events[n_evs:]
        sol.t_events = sol.t_events[:n_evs]
        hit = _stepped_over_graze(evs, minima, sol, t_start)
        for k_ev, te in enumerate(sol.t_events):
            for n_t, tt in enumerate(te):
                if tt > t_start and (hit is None or tt < hit[0]):
                    hit = (tt, k_ev, sol.y_events[k_ev][n_t])
        if measure:
            t_hit = sol.t[-1] if hit is None else hit[0]
            ts = np.append(np.arange(t_start, t_hit, sample_dt), t_hit)
            ys = sol.sol(ts)
            track(ts, ys[0], ys[1], ys[8])
        if hit is None:
            stalled = stalled + 1 if sol.t[-1] <= t_start else 0
            if stalled > 50:  # e.g. the mass rides the relaxing bumper surface at zero force
                raise ReferenceStalled(f"reference made no progress at t = {t_start}")
            t, d, v = sol.t[-1], sol.y[0, -1], sol.y[1, -1]
            acc = sol.y[2:, -1].copy()
            if (sol.status == 1 or t_stop < t_end) and t < t_end:
                continue
            break
        t, d, v = hit[0], hit[2][0], hit[2][1]
        acc = np.array(hit[2][2:])
        apply(*evs[hit[1]][1])
        if measure:
            track(np.array([t]), np.array([d]), np.array([v]), np.array([acc[6]]))
        if kinematic:
            for i in range(n_sp):
                if s[i] != 0:
                    u[i] = d - s[i] * Db[i]
    res.t, res.d, res.v = t, d, v
    res.viscous, res.input_work = acc[4], acc[5]
    res.u = u
    res.state = {"t": t, "d": d, "v": v, "u": u.copy(), "s": s.copy(), "comp": list(comp),
                 "t_rel": list(t_rel), "inc": list(inc), "open_start": list(open_start),
                 "acc": acc.copy(), "laws": [None if sd[5] is None else sd[5].snapshot() for sd in sides]}
    return res
