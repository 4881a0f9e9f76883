"""The follower of :func:`pounding.continuation`: steps along a branch, moves its section away
from events, and watches the detectors (folds, branch points, period-doublings, Neimark-Sacker
points, grazings) between consecutive points, locating each."""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Any, Optional

import numpy as np
import pandas as pd

from .._errors import InputError, Problem, Status
from ._arclength import Closure, Family, Point, system_at
from .branch import COLUMNS, Bifurcation, Branch
from ..engine.layout import E_T
from ._shooting import _Failed
from ._detect import bifurcation_at, branch_point, detect, grazing_at, locate, other_direction
from ._grazing import cross, double_grazing, fold_from_impacts, impacts_barely


class Follower:
    """Steps along the branch, watching the detectors between consecutive points."""

    GROW, SHRINK, MIN_STEP, MIN_COS = 1.5, 0.5, 1e-7, 0.95
    CREEP, CREEP_POINTS = 1e-3, 100  # steps below CREEP * max_step this many times running: stalled

    def __init__(self, fam: Family, p0: float, p1: float, tol: float, max_step: float, max_points: int,
                 f_ref_hz: float, switch_branches: bool = True) -> None:
        self.fam = fam
        self.switch_branches = switch_branches
        self.p0, self.p1 = p0, p1
        self.tol, self.max_step, self.max_points = tol, max_step, max_points
        self.f_ref_hz = f_ref_hz
        self.leaps: list[str] = []  # where the follower stepped in the parameter alone
        self.doubled = False  # a period-doubled branch started at its period-doubling
        self.points: list[Point] = []
        self.arclength: list[float] = []
        self.bifs: list[Bifurcation] = []
        self.status, self.message = Status.SUCCESS, ""
        self.bracket = math.inf  # the last location's final bracket, in arclength
        self.creep = 0  # accepted steps in a row below CREEP * max_step
        self.switched: list[np.ndarray] = []  # where the follower switched branch (parameter, extrema)
        self.looped = False  # it met a branch point it had switched at before
        self.closure: Optional[Closure] = None  # watches for the branch's return to its second point

    # ---- the first point
    def start(self, vec: np.ndarray, p_start: float, bif: Optional[Bifurcation] = None) -> None:
        """The first point, at ``p_start``; from a bifurcation of another branch, the branch that
        starts there (a period-doubling's doubled branch, a branch point's other branch)."""
        fam, n = self.fam, self.fam.n
        pt = fam.correct(vec, p_start, fam.coords(vec), p_start, np.zeros(n), 1.0, self.tol, max_iter=40)
        if pt is None:
            raise InputError(Problem.BAD_STATE, "guess", fam._ref._state(vec),
                             why="leads to no periodic orbit at the start "
                             f"value {p_start:g} (Newton did not converge from it)",
                             fix="give a guess nearer the orbit (e.g. a sweep's window state), or start "
                                 "elsewhere")
        toward = math.copysign(1.0, self.p1 - self.p0)
        self.arclength.append(0.0)
        if bif is None:
            pt.tau_x, pt.tau_q = fam.tangent(pt, np.zeros(n), toward)
            self.points.append(pt)
            self._resection()
            return
        # the tangent of the branch the bifurcation is on, and the direction to leave it by
        own = np.append(bif.tangent[:-1] / fam.scales, bif.tangent[-1] / fam.p_scale)
        own /= np.linalg.norm(own)
        other = (other_direction(self, pt, own) if bif.kind == "period-doubling" else
                 np.append(bif.direction[:-1] / fam.scales, bif.direction[-1] / fam.p_scale))
        other /= np.linalg.norm(other)
        sign = 1.0 if other[-1] * toward >= 0.0 else -1.0
        pt.tau_x, pt.tau_q = sign * other[:-1], sign * other[-1]
        ds = self.max_step / 4.0
        for grow in (1.0, 4.0, 0.25, 16.0):
            c = self.step(pt, grow * ds, chord=False)  # (the Jacobian at a bifurcation is singular)
            if c is not None and self._left(own, pt, c):
                pt.tau_x, pt.tau_q = fam.tangent(pt, c.tau_x, c.tau_q)
                self.points.append(pt)
                self._append(c, grow * ds)
                return
        raise InputError(Problem.BAD_STATE, "guess", bif.kind,
                         why="led back to the branch it is on (the other "
                         "branch was not found)", fix="continue that branch with a smaller max_step and try "
                         "this bifurcation again")

    def _left(self, own: np.ndarray, pt: Point, c: Point) -> bool:
        """Whether ``c`` left the branch through ``pt`` with tangent ``own``: for a period-doubling,
        ``c`` is no orbit of the original period; else ``c``'s tangent is not ``own``'s."""
        fam = self.fam
        if fam.k % 2 == 0 and self.doubled:
            sh = fam.shooter(c.p)
            half = type(sh)(sh.osc, sh.exc, sh.period / 2.0, False, sh)
            try:
                end, _ = half._image(c.vec)
            except _Failed:
                return True
            return float(np.max(np.abs(fam.coords(end) - fam.coords(c.vec)) / fam.scales)) > 1e3 * self.tol
        return abs(float(c.tau_x @ own[:-1] + c.tau_q * own[-1])) < 0.9

    # ---- one step
    def step(self, a: Point, ds: float, chord: bool = True) -> Optional[Point]:
        fam = self.fam
        dx = ds * fam.scales * a.tau_x
        target_x = fam.coords(a.vec) + dx
        target_p = a.p + ds * fam.p_scale * a.tau_q
        try:
            vec = fam.shooter(target_p)._moved(a.vec, a.emb @ dx[a.free])
        except _Failed:
            return None
        b = fam.correct(vec, target_p, target_x, target_p, a.tau_x, a.tau_q, self.tol, chord=a if chord
                        else None)
        if b is not None:
            b.tau_x, b.tau_q = fam.tangent(b, a.tau_x, a.tau_q)
        return b

    def follow(self) -> None:
        ds = self.max_step / 4.0
        lo, hi = min(self.p0, self.p1), max(self.p0, self.p1)
        while True:
            a = self.points[-1]
            if len(self.points) >= self.max_points:
                self.status, self.message = Status.BUDGET, f"stopped at max_points = {self.max_points}"
                return
            b = self.step(a, ds)
            cos = float(a.tau_x @ b.tau_x + a.tau_q * b.tau_q) if b is not None else -1.0
            if b is None or (cos < self.MIN_COS and ds > 4 * self.MIN_STEP):
                if ds < self.CREEP * self.max_step and impacts_barely(self, a) and self._leap_past(a):
                    ds = self.max_step / 4.0  # (past a rigid stop's grazing, from its impacting side)
                    continue
                ds *= self.SHRINK
                if ds < self.MIN_STEP:
                    if self._cross(a) or self._leap_past(a) or self._turn(a):
                        ds = self.max_step / 4.0
                        continue
                    self.status = Status.STEP_FAILED
                    if self._grazes_two(a):
                        return
                    self.message = (f"the corrector failed at {self.fam.parameter} = {a.p:.8g} even with the "
                                    "smallest step (the branch may end there: a grazing of a stiff bumper, "
                                    "or an orbit the engine cannot run)")
                    return
                continue
            if self._turn(a, b, ds):  # (a step that went round a non-smooth fold onto the clear branch)
                ds = self.max_step / 4.0
                continue
            if branch_point(self, a, b, ds):
                if self.looped:
                    self.message = (f"the branch came back to the branch point at {self.fam.parameter} = "
                                    f"{self.bifs[-1].value:.6g}, where it had switched before (the branches "
                                    f"taken form a loop), after {len(self.points)} orbits")
                    return
                continue
            detect(self, a, b, ds)
            if not lo <= b.p <= hi:
                end = self.p1 if (b.p > hi) == (self.p1 > self.p0) else self.p0
                last = locate(self, a, ds, lambda pt: (pt.p - end) / self.fam.p_scale, b)
                if last is not None:  # (solved again at the end value itself)
                    fam = self.fam
                    exact = fam.correct(last.vec, end, fam.coords(last.vec), end, np.zeros(fam.n), 1.0,
                                        self.tol, chord=last)
                    if exact is not None:
                        exact.tau_x, exact.tau_q = fam.tangent(exact, last.tau_x, last.tau_q)
                        last = exact
                    self._append(last, self._s(a, last))
                self.message = f"reached {self.fam.parameter} = {end:g} after {len(self.points)} orbits"
                return
            self._append(b, ds)
            self.creep = self.creep + 1 if ds < self.CREEP * self.max_step else 0
            # (steps stuck at a fraction of the largest: a non-smooth point)
            if self.creep >= self.CREEP_POINTS:
                self.creep = 0
                if not (self._leap_past(b) or self._turn(b)):
                    self.status = Status.STEP_FAILED
                    self.message = (f"the branch stalled at {self.fam.parameter} = {b.p:.8g}: "
                                    f"{self.CREEP_POINTS} steps below 1e-3 of the largest (a non-smooth "
                                    "point), and no step in the parameter alone got past it")
                    return
                ds = self.max_step / 4.0
                continue
            if self._closed(b, ds):
                self.message = (f"the branch closed on itself (an isola) after {len(self.points)} orbits, "
                                f"between {self.fam.parameter} = {min(q.p for q in self.points):.6g} and "
                                f"{max(q.p for q in self.points):.6g}")
                return
            self._rescale()
            self._resection()
            ds = min(ds * self.GROW, self.max_step) if b.iterations <= 4 else ds

    def _cross(self, a: Point) -> bool:
        """Past a rigid stop's grazing next to ``a`` (:func:`cross`), its bifurcations detected and the
        orbit past it taken; False where none was found."""
        got = cross(self, a)
        if got is None:
            return False
        b, ds, graze, side = got
        # (the grazing located there, reported as such: past a non-smooth fold b lies back on the clear
        # side of it in the parameter, where no secant would find it again)
        self.bifs.append(grazing_at(self, graze, side))
        if (b.p - graze.p) * (a.p - graze.p) > 0.0:  # (b back on a's side: the branch turned at the grazing)
            self.bifs.append(bifurcation_at(self, "fold", "", graze, True))
        detect(self, a, b, ds, known=f"grazing {side}")
        self._append(b, ds)
        return True

    def _turn(self, a: Point, b: Optional[Point] = None, ds: float = 0.0) -> bool:
        """Round a non-smooth fold met from its impacting side (:func:`fold_from_impacts`): the impacting
        branch through ``a`` ends at a rigid stop's grazing ahead, where the clear branch turns back.
        ``b``: a step's orbit that landed on the clear branch (None: the steps stalled at ``a``, and
        the clear orbit is Newton's at ``a``'s parameter).  The grazing and its fold reported, the
        branch goes on along the clear orbits away from the grazing; False where ``a`` is no such
        point."""
        fam = self.fam
        if b is None and not impacts_barely(self, a):
            return False
        travel = self._travel(a)
        if b is None:  # (ahead, where the impacting orbit's depth and Newton's reach shrink: the clear one)
            for size in (1e-6, 1e-5, 1e-4, 1e-3):
                p = a.p + travel * size * self.max_step * fam.p_scale
                b = fam.correct(a.vec, p, fam.coords(a.vec), p, np.zeros(fam.n), 1.0, self.tol, max_iter=40)
                if b is not None and fold_from_impacts(self, a, b, [], travel) == ():
                    break
                b = None
            if b is None:
                return False
            b.tau_x, b.tau_q = fam.tangent(b, np.zeros(fam.n), -travel)
        step = abs(b.p - a.p) if b.p != a.p else 1e-6 * self.max_step * fam.p_scale
        backs = [b.p - travel * f * step for f in (0.5, 1.0, 4.0)]  # (a second clear orbit, behind b)
        got = fold_from_impacts(self, a, b, backs, travel)
        if not got:
            return False
        g, side = got
        away = -travel  # (the clear branch lies behind the grazing: on along it, away from it)
        for pt in (g, b):
            pt.tau_x, pt.tau_q = fam.tangent(pt, np.zeros(fam.n), away)
        self.bifs.append(grazing_at(self, g, side))
        self.bifs.append(bifurcation_at(self, "fold", "", g, True))
        self._append(g, abs(self._s(a, g)))
        self._append(b, abs(self._s(g, b)))
        return True

    def _grazes_two(self, a: Point) -> bool:
        """Where the branch stops at a grazing of two rigid stops at once (:func:`double_grazing`): that
        grazing reported (its sides joined, its measured scaling) and said in the message."""
        got = double_grazing(self, a)
        if got is None:
            return False
        g, sides = got
        bif = replace(grazing_at(self, g, sides[0]), side=" and ".join(sides))
        self.bifs.append(bif)
        self.message = (f"the branch reached a grazing of two stops at once ({bif.side}: a symmetric orbit) "
                        f"at {self.fam.parameter} = {g.p:.10g}, where the map goes as depth^"
                        f"{bif.scaling_exponent:.3f} (the second impact's depth moved by the first's square "
                        "root); the follower does not go past such a grazing")
        return True

    def _leap_past(self, a: Point) -> bool:
        """A step in the parameter alone from ``a`` (``_leap``), its bifurcations detected and the
        point taken; False where none got past."""
        leap = self._leap(a)
        if leap is None:
            return False
        b, ds = leap
        detect(self, a, b, ds)
        self._append(b, ds)
        self.leaps.append(f"{a.p:.6g} -> {b.p:.6g}")
        return True

    def _leap(self, a: Point) -> Optional[tuple[Point, float]]:
        """Past a point where the branch is not smooth (a soft impact's grazing: the map's
        derivative is infinite there, and arclength steps shrink to nothing), a step in the
        parameter alone, the orbit solved at the new value by Newton from ``a``'s state."""
        fam = self.fam
        direction = self._travel(a)
        for size in (0.05, 0.2, 1.0):
            dp = direction * size * self.max_step * fam.p_scale
            p_new = a.p + dp
            b = fam.correct(a.vec, p_new, fam.coords(a.vec), p_new, np.zeros(fam.n), 1.0, self.tol,
                            max_iter=40)
            if b is None:
                continue
            # (oriented onwards in the parameter: the leap's direction, whatever the tangent at a was)
            b.tau_x, b.tau_q = fam.tangent(b, np.zeros(fam.n), direction)
            return b, abs(self._s(a, b))
        return None

    def _travel(self, a: Point) -> float:
        """The sign of the parameter's change along the branch at ``a`` (the range's, where the tangent
        is across the parameter)."""
        return math.copysign(1.0, a.tau_q) if abs(a.tau_q) > 1e-12 else math.copysign(1.0, self.p1 - self.p0)

    def _closed(self, b: Point, ds: float) -> bool:
        """Whether the step to ``b`` passed by the branch's second point again (a closed branch):
        the orbits compared by what does not depend on the section (parameter and extrema)."""
        fam = self.fam

        def sig(q: Point) -> np.ndarray:
            return np.append(q.p / fam.p_scale, np.array(fam._ref.extent(q.run)) / fam.length_m)

        if self.closure is None:
            if len(self.points) >= 2:
                self.closure = Closure(sig(self.points[1]))
            return False
        return self.closure.passed(sig(self.points[-2]), sig(b), ds)

    def _rescale(self) -> None:
        """Grow the length scale with the orbits (a resonance peak 30 times the first orbit
        would otherwise take the steps' whole length), the last tangent renormalised."""
        b, fam = self.points[-1], self.fam
        size = fam.orbit_size(b.run)
        if size <= 2.0 * fam.length_m:
            return
        old = fam.scales.copy()
        fam.set_length(size)
        tx = b.tau_x * old / fam.scales
        norm = math.sqrt(float(tx @ tx) + b.tau_q ** 2)
        b.tau_x, b.tau_q = fam.tangent(b, tx / norm, b.tau_q / norm)

    # ---- the section
    MARGIN = 0.02  # the nearest event to the section, in periods, below which the section moves

    def _resection(self) -> None:
        """Move the section to the middle of the last orbit's longest stretch without events when an
        event comes within ``MARGIN`` periods of it: a contact that starts or ends, or a spring that
        yields, at the section changes the shooting coordinates there, and the corrector cannot
        cross that (the orbit is the same; only where it is cut changes)."""
        b = self.points[-1]
        fam = self.fam
        period = fam.shooter(b.p).period
        times = np.sort(np.mod(b.run.event_table[:, E_T], period))  # (the run starts at the section, time 0)
        if times.size == 0 or min(times.min(), period - times.max()) > self.MARGIN * period:
            return
        cyc = np.concatenate((times, [times[0] + period]))
        i = int(np.argmax(np.diff(cyc)))
        dt = 0.5 * (cyc[i] + cyc[i + 1]) % period
        new_phase = fam.phase + fam.omega(b.p) * dt
        moved = [self._at_phase(pt, new_phase) for pt in self.points[-2:]]
        if any(m is None for m in moved):
            return
        fam.set_phase(new_phase)
        solved = [fam.correct(m, pt.p, fam.coords(m), pt.p, np.zeros(fam.n), 1.0, self.tol)
                  for m, pt in zip(moved, self.points[-2:])]
        if any(s is None for s in solved):
            return
        if len(solved) == 2:
            own = np.append((fam.coords(solved[1].vec) - fam.coords(solved[0].vec)) / fam.scales,
                            (solved[1].p - solved[0].p) / fam.p_scale)
            own /= np.linalg.norm(own)
        else:
            own = np.append(np.zeros(fam.n), b.tau_q)
        new = solved[-1]
        new.tau_x, new.tau_q = fam.tangent(new, own[:-1], own[-1])
        self.points[-1] = new

    def _at_phase(self, pt: Point, phase: float) -> Optional[np.ndarray]:
        """The state of ``pt``'s orbit where the forcing's angle is ``phase`` (time 0)."""
        fam = self.fam
        dt = ((phase - pt.phase) % (2.0 * math.pi)) / fam.omega(pt.p)
        sh = fam.shooter(pt.p)
        if dt <= 0:
            return pt.vec.copy()
        end = sh.advance(replace(sh.exc, phase=pt.phase), dt, pt.vec)
        return None if end is None else sh.at_section(end)

    def _append(self, pt: Point, ds: float) -> None:
        self.points.append(pt)
        self.arclength.append(self.arclength[-1] + ds)

    def _s(self, a: Point, b: Point) -> float:
        fam = self.fam
        return float(a.tau_x @ ((fam.coords(b.vec) - fam.coords(a.vec)) / fam.scales)
                     + a.tau_q * (b.p - a.p) / fam.p_scale)

    # ---- detection and location
    def branch(self, oscillator: Any, values: tuple, status: Status, message: str) -> Branch:
        fam = self.fam
        rows = []
        for pt, s in zip(self.points, self.arclength):
            sh = fam.shooter(pt.p)
            exc = replace(sh.exc, phase=pt.phase)
            mu = float(np.abs(pt.mult).max()) if pt.mult.size else 0.0
            rows.append({
                "freq_hz": exc.freq_hz, "nu": exc.freq_hz / self.f_ref_hz, "a_g": exc.a_g,
                **sh.summary(pt.run, exc), "stable": mu < 1.0, "max_abs_multiplier": mu,
                "period_multiple": fam.k, "residual": pt.residual, "arclength": s, "phase_rad": pt.phase,
            })
        df = pd.DataFrame(rows, columns=list(COLUMNS))
        if fam.parameter not in ("freq_hz", "a_g"):
            df.insert(0, fam.parameter, [pt.p for pt in self.points])
        width = max((pt.mult.size for pt in self.points), default=0)
        mult = np.full((len(self.points), width), np.nan + 0j)
        for i, pt in enumerate(self.points):
            mult[i, :pt.mult.size] = pt.mult
        states = np.array([pt.vec for pt in self.points]) if self.points else np.zeros((0, 0))
        msg = message + (fam.fell_back if fam.fell_back else "")
        if self.leaps:
            msg += (f"; stepped in {fam.parameter} alone past {len(self.leaps)} non-smooth point(s): "
                    + ", ".join(self.leaps[:5]) + (", ..." if len(self.leaps) > 5 else ""))
        return Branch(system_at(oscillator, fam.parameter, values[0]), fam.parameter, tuple(values), fam.k,
                      self.f_ref_hz, df, states, mult, tuple(self.bifs), status, msg,
                      a_g=fam.a_g if fam.parameter != "a_g" else math.nan,
                      freq_hz=fam.freq_hz if fam.parameter != "freq_hz" else math.nan)
