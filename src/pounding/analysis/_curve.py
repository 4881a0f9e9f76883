"""The follower of :func:`pounding.bifurcation_curve`: a fold or a grazing continued in two
parameters, the frequency and the table's peak acceleration.

A point of the curve solves, in the unknowns ``y = (w, f, a_g)``, the orbit's equations and one
test equation::

    P(x(w); f, a_g) - x(w) = 0      (r equations: a periodic orbit)
    g(x(w); f, a_g) = 0             (a fold: the real multiplier nearest 1 is 1;
                                     a grazing: the orbit's clearance to the bumper is 0)

``P`` is the family's stroboscopic map (:mod:`_arclength`), its Jacobian in ``w`` the exact (or
finite-difference) monodromy; the columns in ``f`` and ``a_g`` and the row of ``g`` are central
differences.  The curve is followed by pseudo-arclength in ``(x, f, a_g)``, each over a fixed
scale (lengths over the orbit's, ``f`` and ``a_g`` over their ranges), so it goes through cusps,
where a fold curve turns back in ``a_g``.  The corrector is Newton with the extended Jacobian
kept while it contracts (a chord method).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional

import numpy as np

from ..engine import Run
from ._arclength import Closure, Family, fold_test
from ..engine.layout import E_T
from ._shooting import _Failed


@dataclass
class CurvePoint:
    """One solved point of a curve (what the follower and the result need)."""

    vec: np.ndarray     # the engine's state vector at the section (time 0)
    f: float            # frequency, Hz
    a: float            # a_g
    run: Run            # one period from vec
    jac: np.ndarray     # monodromy in the free coordinates, (r, r)
    free: np.ndarray
    emb: np.ndarray
    frozen: tuple
    r: np.ndarray       # scaled residual, (r,)
    g: float            # the test function
    mult: np.ndarray    # Floquet multipliers, largest modulus first
    phase: float        # the forcing's angle at the section, rad
    tau: np.ndarray = None  # unit tangent in the full scaled coordinates (x, f, a), (n + 2,)
    ext: np.ndarray = None  # the extended Jacobian in (w, f, a), scaled, (r + 1, r + 2)
    iterations: int = 0


class CurveFollower:
    """Follows a fold or grazing curve from one of its points, in both directions."""

    GROW, SHRINK, MIN_STEP, MIN_COS, MARGIN = 1.5, 0.5, 1e-6, 0.9, 0.02

    def __init__(self, fam: Family, kind: str, side: str, f_box: tuple[float, float],
                 a_box: tuple[float, float], tol: float, max_step: float) -> None:
        self.fam = fam
        self.kind, self.side = kind, side
        self.f_box, self.a_box = f_box, a_box
        self.fs, self.as_ = f_box[1] - f_box[0], a_box[1] - a_box[0]
        self.tol, self.max_step = tol, max_step
        self.gtol = max(100.0 * tol, 1e-8) if kind == "fold" else tol

    # ---- the equations
    def test(self, run: Run, jac: np.ndarray) -> float:
        """``g``: the fold's (real part of the multiplier nearest 1) - 1, or the grazing's clearance
        to its bumper over the family's length (negative: the orbit presses into it)."""
        if self.kind == "fold":
            return fold_test(np.linalg.eigvals(jac) if jac.size else np.zeros(1))
        return float(self.fam._ref.clearances(run)[self.side] / self.fam.length_m)

    def evaluate(self, vec: np.ndarray, f: float, a: float) -> CurvePoint:
        """The equations at ``(vec, f, a)``; raises _Failed where the engine cannot run them."""
        fam = self.fam
        r, run, frozen, free, emb = fam.residual(vec, f, a)
        jac = fam.shooter(f, a).jacobian(vec, run, frozen)
        if not np.isfinite(jac).all():
            raise _Failed("the monodromy is not finite")
        mult = np.linalg.eigvals(jac) if jac.size else np.zeros(0, complex)
        mult = mult[np.argsort(-np.abs(mult), kind="stable")]
        return CurvePoint(vec, f, a, run, jac, free, emb, frozen, r, self.test(run, jac), mult, fam.phase)

    def _g_at(self, vec: np.ndarray, f: float, a: float) -> float:
        fam = self.fam
        x_end, run = fam.image(vec, f, a)
        if self.kind != "fold":
            return self.test(run, np.zeros((0, 0)))
        sh = fam.shooter(f, a)
        jac = sh.jacobian(vec, run, sh.frozen(vec, run))
        if not np.isfinite(jac).all():
            raise _Failed("the monodromy is not finite")
        return self.test(run, jac)

    def extended(self, e: CurvePoint) -> np.ndarray:
        """The scaled Jacobian of ``(P - x, g)`` in ``(w, f, a)``, shape (r + 1, r + 2)."""
        fam = self.fam
        s_w = fam.scales[e.free]
        r = e.free.size
        out = np.empty((r + 1, r + 2))
        out[:r, :r] = (e.jac - np.eye(r)) * (s_w[None, :] / s_w[:, None])
        h = 1e-6
        for col, (df, da) in ((r, (h * self.fs, 0.0)), (r + 1, (0.0, h * self.as_))):
            plus = fam.image(e.vec, e.f + df, e.a + da)[0]
            minus = fam.image(e.vec, e.f - df, e.a - da)[0]
            out[:r, col] = (plus - minus)[e.free] / (2.0 * h) / s_w
        hg = 1e-5  # (g holds a monodromy: a wider difference than the map's)
        sh = fam.shooter(e.f, e.a)
        for j in range(r):
            dx = e.emb[:, j] * (hg * s_w[j])
            out[r, j] = (self._g_at(sh._moved(e.vec, dx), e.f, e.a)
                         - self._g_at(sh._moved(e.vec, -dx), e.f, e.a)) / (2.0 * hg)
        out[r, r] = (self._g_at(e.vec, e.f + hg * self.fs, e.a) - self._g_at(e.vec, e.f - hg * self.fs,
                                                                             e.a)) / (2 * hg)
        out[r, r + 1] = (self._g_at(e.vec, e.f, e.a + hg * self.as_)
                         - self._g_at(e.vec, e.f, e.a - hg * self.as_)) / (2.0 * hg)
        return out

    def _row(self, e: CurvePoint, tau: np.ndarray) -> np.ndarray:
        """A full scaled direction ``(x, f, a)`` as a row in ``(w, f, a)``."""
        fam = self.fam
        s_w = fam.scales[e.free]
        return np.concatenate((tau[:-2] @ (e.emb * s_w[None, :] / fam.scales[:, None]), tau[-2:]))

    def _full(self, e: CurvePoint, t: np.ndarray) -> np.ndarray:
        """A direction in ``(w, f, a)`` (scaled) in the full scaled coordinates ``(x, f, a)``."""
        fam = self.fam
        r = e.free.size
        return np.concatenate(((e.emb @ (t[:r] * fam.scales[e.free])) / fam.scales, t[r:]))

    def scaled(self, e: CurvePoint) -> np.ndarray:
        """The point in the full scaled coordinates ``(x, f, a)``."""
        fam = self.fam
        return np.concatenate((fam.coords(e.vec) / fam.scales, [e.f / self.fs, e.a / self.as_]))

    def tangent(self, e: CurvePoint, prev: np.ndarray) -> np.ndarray:
        """The unit tangent at ``e`` (``e.ext`` set), oriented along ``prev`` (full scaled)."""
        a = np.vstack((e.ext, self._row(e, prev)))
        rhs = np.zeros(a.shape[0])
        rhs[-1] = 1.0
        try:
            t = np.linalg.solve(a, rhs)
        except np.linalg.LinAlgError:
            t = np.linalg.svd(e.ext)[2][-1]  # (SVD of a finite matrix converges)
        tau = self._full(e, t)
        tau /= np.linalg.norm(tau)
        return tau if tau @ prev >= 0.0 else -tau

    # ---- the corrector
    def correct(self, vec: np.ndarray, f: float, a: float, target: np.ndarray, tau: np.ndarray,
                chord: Optional[CurvePoint] = None, max_iter: int = 12) -> Optional[CurvePoint]:
        """Newton from ``(vec, f, a)`` onto the curve in the hyperplane through ``target`` normal to
        ``tau`` (both full scaled).  None where it fails."""
        ext, key, last, fresh = None, None, math.inf, False
        for it in range(max_iter):
            try:
                e = self.evaluate(vec, f, a)
            except (_Failed, np.linalg.LinAlgError):
                return None
            arc = float(tau @ (self.scaled(e) - target))
            err = max(float(np.max(np.abs(e.r), initial=0.0)) / self.tol, abs(e.g) / self.gtol,
                      abs(arc) / self.tol)
            if not math.isfinite(err):
                return None
            here = (tuple(e.free), e.frozen)
            if err <= 1.0:  # (the tangent there needs a Jacobian of this point or the step before it)
                try:
                    e.ext = ext if fresh and key == here and it <= 1 else self.extended(e)
                except (_Failed, np.linalg.LinAlgError):
                    return None
                e.iterations = it
                return e
            fresh = False
            if chord is not None and ext is None and (tuple(chord.free), chord.frozen) == here:
                ext, key = chord.ext, here
            if ext is None or key != here or err > 0.5 * last:
                try:
                    ext, key, fresh = self.extended(e), here, True
                except (_Failed, np.linalg.LinAlgError):
                    return None
            last = err
            try:
                step = np.linalg.solve(np.vstack((ext, self._row(e, tau))),
                                       -np.concatenate((e.r, [e.g, arc])))
            except np.linalg.LinAlgError:
                return None
            r = e.free.size
            f_new, a_new = f + step[r] * self.fs, a + step[r + 1] * self.as_
            if not (f_new > 0.0 and a_new > 0.0):
                return None
            try:
                vec = self.fam.shooter(f)._moved(vec, e.emb @ (step[:r] * self.fam.scales[e.free]))
            except _Failed:
                return None
            f, a = f_new, a_new
        return None

    def step(self, p: CurvePoint, ds: float, tau: Optional[np.ndarray] = None) -> Optional[CurvePoint]:
        """The next point, ``ds`` along ``tau`` (default ``p.tau``)."""
        fam = self.fam
        tau = p.tau if tau is None else tau
        target = self.scaled(p) + ds * tau
        f, a = target[-2] * self.fs, target[-1] * self.as_
        if not (f > 0.0 and a > 0.0):
            return None
        try:
            vec = fam.shooter(p.f)._moved(p.vec, ds * tau[:-2] * fam.scales)
        except _Failed:
            return None
        q = self.correct(vec, f, a, target, tau, chord=p)
        if q is not None:
            q.tau = self.tangent(q, tau)
        return q

    def on_edge(self, p: CurvePoint, q: CurvePoint) -> Optional[CurvePoint]:
        """The curve where it leaves the box between ``p`` (inside) and ``q`` (outside): solved with
        the edge's value held (``p`` itself when it is on the edge; None where it cannot be solved)."""
        sp, sq = self.scaled(p), self.scaled(q)
        best = None
        for i, box, scale in ((-2, self.f_box, self.fs), (-1, self.a_box, self.as_)):
            for edge in box:
                e = edge / scale
                if sp[i] == e and sq[i] != e:  # (p is on the edge: the curve leaves there)
                    return p
                if (sp[i] - e) * (sq[i] - e) < 0.0:
                    frac = (e - sp[i]) / (sq[i] - sp[i])
                    if best is None or frac < best[0]:
                        best = (frac, i, e)
        if best is None:
            return None
        frac, i, e = best
        guess = sp + frac * (sq - sp)
        normal = np.zeros(sp.size)
        normal[i] = 1.0
        fam = self.fam
        try:
            vec = fam.shooter(p.f)._moved(p.vec, (guess[:-2] - sp[:-2]) * fam.scales)
        except _Failed:
            return None
        target = guess.copy()
        target[i] = e
        out = self.correct(vec, guess[-2] * self.fs, guess[-1] * self.as_, target, normal, max_iter=20)
        if out is None or not self.inside(out):  # (at a corner the other coordinate may be out)
            return None
        out.tau = self.tangent(out, p.tau)
        return out

    def inside(self, q: CurvePoint) -> bool:
        eps = 1e-12
        return (self.f_box[0] - eps * self.fs <= q.f <= self.f_box[1] + eps * self.fs
                and self.a_box[0] - eps * self.as_ <= q.a <= self.a_box[1] + eps * self.as_)

    # ---- following
    def follow(self, start: CurvePoint, sign: float, budget: int, pts: list[CurvePoint]) -> tuple[str, bool]:
        """Points from ``start`` (excluded) along ``sign * start.tau``, appended to ``pts`` as they
        come: (how it ended, whether the curve closed on ``start``).  The family is put back to the
        start's section and a_G first (a resection in the other direction moved it)."""
        self.fam.set_phase(start.phase)
        p = start
        p_tau = sign * start.tau
        ds = self.max_step / 4.0
        closure = Closure(self._signature(start))  # (a closed curve returns to start)
        while True:
            if len(pts) >= budget:
                return "budget", False
            q = self.step(p, ds, p_tau)
            cos = float(q.tau @ p_tau) if q is not None else -1.0
            if q is None or cos < self.MIN_COS:
                ds *= self.SHRINK
                if ds < self.MIN_STEP:
                    return (f"the corrector failed at freq_hz = {p.f:.8g}, a_g = {p.a:.8g} even with the "
                            "smallest step (a non-smooth point: a contact appearing or vanishing on the "
                            "curve)"), False
                continue
            if not self.inside(q):
                edge = self.on_edge(p, q)
                if edge is None:
                    return (f"the curve leaves the box after freq_hz = {p.f:.8g}, a_g = {p.a:.8g}, but was "
                            "not solved on its edge"), False
                if edge is not p:
                    pts.append(edge)
                return "edge", False
            pts.append(q)
            if closure.passed(self._signature(p), self._signature(q), ds):
                return "closed", True
            q = pts[-1] = self._resection(q, p)
            p, p_tau = q, q.tau
            if q.iterations <= 3:
                ds = min(ds * self.GROW, self.max_step)

    def _signature(self, q: CurvePoint) -> np.ndarray:
        """What does not depend on the section: the forcing and the orbit's extrema, scaled."""
        size = self.fam.length_m
        return np.append([q.f / self.fs, q.a / self.as_], np.array(self.fam._ref.extent(q.run)) / size)

    def _at_phase(self, pt: CurvePoint, phase: float) -> Optional[CurvePoint]:
        """``pt``'s orbit with its section at forcing angle ``phase`` (the family's section is set
        there), solved with its frequency held."""
        fam = self.fam
        sh = fam.shooter(pt.f, pt.a)
        dt = ((phase - pt.phase) % (2.0 * math.pi)) / sh.exc.omega_rad_s
        try:
            end = type(sh)(sh.osc, sh.exc, dt, False, sh)._image(pt.vec)[0] if dt > 0 else pt.vec
        except _Failed:
            return None
        fam.set_phase(phase)
        moved = sh.at_section(end)
        normal = np.zeros(fam.n + 2)
        normal[-2] = 1.0  # (f held; a_G follows from g = 0 and the orbit's equations)
        target = np.concatenate((fam.coords(moved) / fam.scales, [pt.f / self.fs, pt.a / self.as_]))
        new = self.correct(moved, pt.f, pt.a, target, normal, max_iter=20)
        return new if new is not None and abs(new.a - pt.a) <= 1e-6 * self.as_ else None

    def _resection(self, q: CurvePoint, p: CurvePoint) -> CurvePoint:
        """Move the section away from an event within ``MARGIN`` periods of it (as the branch
        follower does): ``q`` solved again there, its tangent oriented by the secant from ``p``
        moved there too (near a cusp the tangent's (f, a_G) part nearly vanishes: it cannot).
        Returns the point to go on from: ``q`` solved at the new section, or ``q`` itself."""
        fam = self.fam
        period = fam.shooter(q.f, q.a).period
        times = np.sort(np.mod(q.run.event_table[:, E_T], period))
        if times.size == 0 or min(times.min(), period - times.max()) > self.MARGIN * period:
            return q
        cyc = np.concatenate((times, [times[0] + period]))
        i = int(np.argmax(np.diff(cyc)))
        dt = 0.5 * (cyc[i] + cyc[i + 1]) % period
        old_phase = fam.phase
        new_phase = (old_phase + fam.omega(q.f) * dt) % (2.0 * math.pi)
        moved_p = self._at_phase(p, new_phase)
        fam.set_phase(old_phase)
        moved_q = self._at_phase(q, new_phase) if moved_p is not None else None
        if moved_q is None:
            fam.set_phase(old_phase)
            return q
        secant = self.scaled(moved_q) - self.scaled(moved_p)
        moved_q.tau = self.tangent(moved_q, secant / max(float(np.linalg.norm(secant)), 1e-300))
        return moved_q
