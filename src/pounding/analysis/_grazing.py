"""Grazings on a branch: located from the side where the orbit keeps clear of the contact (there its
clearance is smooth in the parameter; on the other side the map's derivative is infinite at the
grazing and Newton's reach shrinks to nothing), and the map's scaling there measured.

Near a grazing the Poincare map is ``P(x) = P_0(x) + c delta(x)^gamma + O(delta)``, with ``delta`` the
depth the free orbit would reach past the contact (0 on the clear side) and ``gamma = 1/2`` at a rigid
stop (the impact's velocity jump ``(1 + e) sqrt(2 a_n delta)``, ``a_n`` the acceleration away from the
stop at the touch); at a deformable bumper 1 where its force jumps at the touch (a dashpot's, over a
contact time ``sqrt(delta)``), 3/2 where it starts from zero (a spring's).  :func:`map_scaling`
measures ``gamma`` and ``c`` with the engine: the second difference ``P(x + s u) + P(x - s u) -
2 P(x)`` across the grazing (``u`` a direction of the state that lowers the clearance) cancels the
smooth part and keeps the singular one."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Optional

import numpy as np

from ._arclength import Point
from ._shooting import _Failed

if TYPE_CHECKING:
    from ._follower import Follower

DEPTHS = (1e-8, 1e-10)  # the would-be depths of the measurement, in the orbit's size


def locate_grazing(fl: "Follower", a: Point, b: Point, side: str) -> Optional[tuple[Point, bool]]:
    """The grazing of ``side`` between ``a`` and ``b`` (its test of opposite signs there), located by
    the parameter alone from the clear side (:func:`_secant`).  ``(point, located)``, or None where no
    point was solved."""
    ta, tb = _test(fl, a, side), _test(fl, b, side)
    clear, past = (a, b) if ta > 0.0 else (b, a)
    got = _secant(fl, [(clear.p, max(ta, tb), clear)], past.p, min(ta, tb), side)
    return got if got is not None and got[0] is not clear else None


def _test(fl: "Follower", pt: Point, side: str) -> float:
    fam = fl.fam
    return fam.shooter(pt.p).clearances(pt.run)[side] / fam.length_m


def _secant(fl: "Follower", clears: list, p_past: Optional[float], t_past: float,
            side: str) -> Optional[tuple[Point, bool]]:
    """A secant on the clearance over the parameter, from the clear orbits ``clears`` (``(p, test,
    point)``, the last the nearest) towards the grazing, each point Newton's at a fixed parameter from
    the last clear orbit; ``p_past``, where known, a value past the grazing (a bracket).  ``(point,
    located)``: the clear orbit whose clearance is 0 to the continuation's ``tol`` (to the orbit's own
    accuracy: located), or the nearest found; None where none was solved."""
    fam = fl.fam
    first, landed_past = len(clears), False
    for _ in range(60):
        (p0, c0, near) = clears[-1]
        if len(clears) > 1:  # (the clear side's two nearest: linear there)
            p1, c1 = clears[-2][0], clears[-2][1]
            guess = p0 - c0 * (p1 - p0) / (c1 - c0) if c1 != c0 else math.nan
        elif p_past is not None and not landed_past:  # (regula falsi with the far end, once)
            guess = p0 - c0 * (p_past - p0) / (t_past - c0) if t_past != c0 else math.nan
        else:
            guess = math.nan
        if p_past is not None:
            lo, hi = min(p0, p_past), max(p0, p_past)
            if not lo < guess < hi:  # (and a second clear point by bisection)
                guess = 0.5 * (p0 + p_past)
        elif not (abs(guess - p0) <= fl.max_step * fam.p_scale):  # (no bracket: a short way only)
            return None
        pt = fam.correct(near.vec, guess, fam.coords(near.vec), guess, np.zeros(fam.n), 1.0, fl.tol,
                         max_iter=40)
        t = _test(fl, pt, side) if pt is not None else -math.inf
        if t > 0.0:
            pt.tau_x, pt.tau_q = fam.tangent(pt, near.tau_x, near.tau_q)
            clears.append((guess, t, pt))
            if t <= fl.tol:
                return pt, True
        else:  # (past it, or Newton failed there: the bracket's far end moves in)
            p_past, t_past, landed_past = guess, (t if math.isfinite(t) else t_past), True
        if p_past is not None and abs(p_past - clears[-1][0]) <= 1e-14 * max(abs(p_past), fam.p_scale):
            break
    return (clears[-1][2], clears[-1][1] <= 1e-8) if len(clears) > first else None


def impacts_barely(fl: "Follower", pt: Point) -> bool:
    """Whether ``pt``'s orbit meets a rigid stop at a speed over the forcing's angular frequency below
    1e-3 of the orbit's size: next to a grazing, where steps along the impacting branch shrink to
    nothing (Newton's reach there is the orbit's depth past the grazing)."""
    fam = fl.fam
    sh = fam.shooter(pt.p)
    size = fam.orbit_size(pt.run)
    tests = sh.clearances(pt.run)
    return any(-1e-3 * size < tests[s] < 0.0 for s in sh.rigid_sides() if s in tests)


def fold_from_impacts(fl: "Follower", a: Point, c: Point, p_others: list,
                      travel: float) -> Optional[tuple]:
    """A non-smooth fold met from its impacting side: ``a``'s orbit meets a rigid stop, ``c``'s (near it)
    keeps clear of it, and the grazing where their branches meet lies ahead of both in the direction of
    ``travel`` (the sign of the parameter's change along the impacting branch) instead of between them
    (where the detectors locate a grazing the branch crosses).  The grazing is located from the clear
    side (:func:`_secant`, from ``c`` and the first clear orbit found at ``p_others``, Newton's from
    ``c``).  ``(the grazing orbit, its side)``; ``()`` where ``a`` meets a rigid stop that ``c``
    keeps clear of but ``p_others`` is empty; None where ``a`` and ``c`` are no such pair."""
    fam = fl.fam
    sh_a, sh_c = fam.shooter(a.p), fam.shooter(c.p)
    ta, tc = sh_a.clearances(a.run), sh_c.clearances(c.run)
    for side in sh_a.rigid_sides():
        if not (side in ta and side in tc and ta[side] < 0.0 < tc[side]):
            continue
        if not p_others:
            return ()
        for p_other in p_others:
            other = fam.correct(c.vec, p_other, fam.coords(c.vec), p_other, np.zeros(fam.n), 1.0, fl.tol,
                                max_iter=40)
            t_other = _test(fl, other, side) if other is not None else -math.inf
            if t_other > 0.0 and p_other != c.p:
                break
        else:
            continue
        other.tau_x, other.tau_q = fam.tangent(other, c.tau_x, c.tau_q)
        pts = sorted([(p_other, t_other, other), (c.p, tc[side] / fam.length_m, c)], key=lambda q: -q[1])
        got = _secant(fl, pts, None, math.nan, side)  # (the nearer to the grazing last)
        if got is None or not got[1]:
            continue
        g = got[0]
        if (g.p - a.p) * travel > 0.0 and (g.p - c.p) * travel > 0.0:
            return g, side
    return None


def _nearest_grazing(fl: "Follower", a: Point) -> Optional[tuple[Point, tuple[str, ...]]]:
    """From the clear orbit ``a``, the branch's last point, next to a rigid stop's grazing (its clearance
    below 1e-3 of the orbit's size): the grazing located (:func:`_secant` from the branch's last two
    points), and the rigid stops it grazes (two at once: a symmetric orbit between symmetric stops, its
    other clearance within 1e-6 of the orbit's size there).  None where there is none, or it was not
    located."""
    fam = fl.fam
    if len(fl.points) < 2 or fl.points[-1] is not a:
        return None
    sh = fam.shooter(a.p)
    tests = {s: t / fam.length_m for s, t in sh.clearances(a.run).items()}
    near = [s for s, t in tests.items() if t > 0.0]
    if not near:
        return None
    side = min(near, key=tests.get)
    size = fam.orbit_size(a.run)
    if side not in sh.rigid_sides() or tests[side] * fam.length_m > 1e-3 * size:
        return None  # (no rigid stop's grazing next to a: the steps failed for another reason)
    prev = fl.points[-2]
    got = _secant(fl, [(prev.p, _test(fl, prev, side), prev), (a.p, tests[side], a)], None, math.nan, side)
    if got is None or not got[1]:
        return None
    g = got[0]
    at_g = fam.shooter(g.p).clearances(g.run)
    others = [s for s in sh.rigid_sides() if s != side and s in at_g and abs(at_g[s]) <= 1e-6 * size]
    return g, (side, *others)


def double_grazing(fl: "Follower", a: Point) -> Optional[tuple[Point, tuple[str, ...]]]:
    """From the clear orbit ``a`` next to a grazing the steps cannot pass: the grazing, when it is of two
    rigid stops at once (a symmetric orbit between symmetric stops), and its sides.  There the map's leading
    singular term goes as the depth's fourth root (the first impact's square root moves the second's depth),
    not as one stop's normal form; None where the grazing is of one stop, or none was located."""
    got = _nearest_grazing(fl, a)
    return got if got is not None and len(got[1]) > 1 else None


def cross(fl: "Follower", a: Point) -> Optional[tuple[Point, float, Point, str]]:
    """From the clear orbit ``a`` next to a grazing that the follower's steps cannot pass (the map's
    derivative is infinite there): the grazing located (:func:`_secant` from the branch's last two
    points), and the orbit past it, Newton's from the prediction of the map's normal form

        P(x_g + y; p_g + mu) = x_g + M y + P_p mu + c sqrt(delta),   delta = -(C(mu) + g . (y - y_c)),

    (``C`` the clear orbit's clearance, ``y_c`` its state, both continued past the grazing along the
    clear branch's secant; ``g`` the clearance's gradient in the state, ``c`` :func:`map_scaling`'s
    term): with ``w = sqrt(delta)``, ``w^2 + beta w + C(mu) = 0``, ``beta = g (I - M)^-1 c``, and
    ``y = y_c + (I - M)^-1 c w``.  (``P_p`` is not taken from the grazing orbit's linearization: its
    difference in p straddles the grazing.)  ``beta > 0``: the impacting branch goes on past the grazing;
    ``beta < 0``: it turns back there (a non-smooth fold), on the clear side.  ``(orbit, arclength
    from a, the grazing orbit, its side)``, or None where none was found."""
    fam = fl.fam
    got = _nearest_grazing(fl, a)
    if got is None or len(got[1]) > 1:
        return None  # (none; or of two stops at once, which the normal form of one does not describe)
    g, (side,) = got
    prev = fl.points[-2]
    gamma, term, grad = _scaling(fl, g, side, True)
    if term.size == 0:
        return None
    # dC/dp (m per unit) and dy_c/dp along the clear branch: from the branch's previous point, not a
    # (a and g are both within tol of the grazing, so their difference would be rounding)
    slope = (_test(fl, prev, side) - _test(fl, g, side)) * fam.length_m / (prev.p - g.p)
    drift = (fam.coords(prev.vec) - fam.coords(g.vec)) / (prev.p - g.p)
    r = g.free.size
    try:
        lift = np.linalg.lstsq(g.emb, term, rcond=None)[0]  # (the term in the free coordinates)
        solve = np.linalg.inv(np.eye(r) - g.jac)
    except np.linalg.LinAlgError:
        return None
    g_w = grad @ g.emb
    beta = float(g_w @ solve @ lift)
    onward = -math.copysign(1.0, slope) if beta > 0.0 else math.copysign(1.0, slope)
    best: Optional[Point] = None
    for size in (0.01, 0.05, 0.2, 1.0):  # (on to the largest that solves: the steps are small near it)
        mu = onward * size * fl.max_step * fam.p_scale
        p_new = g.p + mu
        if best is None:  # (the normal form's prediction)
            disc = beta * beta - 4.0 * slope * mu
            if disc < 0.0:
                continue
            w = 0.5 * (-beta + math.sqrt(disc)) if beta > 0.0 else 0.5 * (-beta - math.sqrt(disc))
            dx = drift * mu + g.emb @ (solve @ lift) * w
        else:  # (the secant from the grazing through the last orbit past it)
            dx = (fam.coords(best.vec) - fam.coords(g.vec)) * mu / (best.p - g.p)
        try:
            guess = fam.shooter(p_new)._moved(g.vec, dx)
        except _Failed:
            continue
        b = _past(fl, guess, p_new, side)
        if b is None:
            if best is None:
                continue
            break
        best = b
    if best is None:
        return None
    secant = np.append((fam.coords(best.vec) - fam.coords(g.vec)) / fam.scales, (best.p - g.p) / fam.p_scale)
    secant /= np.linalg.norm(secant)
    best.tau_x, best.tau_q = fam.tangent(best, secant[:-1], secant[-1])
    return best, abs(fl._s(a, best)), g, side


def _past(fl: "Follower", vec: np.ndarray, p: float, side: str, max_iter: int = 80) -> Optional[Point]:
    """The orbit past the grazing at ``p`` by damped Newton from ``vec``: each step halved until the
    residual falls and the orbit still meets the contact.  (Newton's full steps on the map's square
    root overshoot into the clear side unless the start's depth is within 4 times the orbit's, and
    it is not, this near the grazing; halving the depth each step brings it there.)  None where
    it fails."""
    fam = fl.fam
    sh = fam.shooter(p)
    try:
        r, run, frozen, free, emb = fam.residual(vec, p)
        for _ in range(max_iter):
            norm = float(np.max(np.abs(r), initial=0.0))
            if norm <= fl.tol:
                pt = fam.correct(vec, p, fam.coords(vec), p, np.zeros(fam.n), 1.0, fl.tol)
                return pt if pt is not None and _test(fl, pt, side) < 0.0 else None
            s_w = fam.scales[free]
            jac = sh.jacobian(vec, run, frozen)
            step = emb @ np.linalg.solve(jac - np.eye(free.size), -r * s_w)
            lam = 1.0
            while True:
                new = sh._moved(vec, lam * step)
                r_new, run_new, frozen_new, free_new, emb_new = fam.residual(new, p)
                if (sh.clearances(run_new)[side] < 0.0
                        and float(np.max(np.abs(r_new), initial=0.0)) < norm):
                    break
                lam *= 0.5
                if lam < 1e-12:
                    return None
            vec, r, run, frozen, free, emb = new, r_new, run_new, frozen_new, free_new, emb_new
    except (_Failed, np.linalg.LinAlgError):
        return None
    return None


def map_scaling(fl: "Follower", pt: Point, side: str, rigid: bool) -> tuple[float, np.ndarray]:
    gamma, term, _ = _scaling(fl, pt, side, rigid)
    return gamma, term


def _scaling(fl: "Follower", pt: Point, side: str, rigid: bool) -> tuple[float, np.ndarray, np.ndarray]:
    """``(gamma, c, g)`` at the grazing orbit ``pt``: the measured exponent of the map's singular part
    against the would-be depth, and that part over ``depth ** (1/2 if rigid, else gamma to the nearest
    half)`` (state coordinates, unscaled) at the smaller depth of ``DEPTHS``.  ``(nan, [])`` where it
    cannot be measured (a run failed, or the clearance does not depend on the state); ``g`` the clearance's
    gradient in the state coordinates (unscaled, m per unit).

    The depth at ``x + s u`` is the clearance gained at ``x - s u`` less twice ``x``'s own (the clear
    side is smooth: exact to the square of the depth), so the direction ``u`` need only lower the
    clearance; the depths are fractions ``DEPTHS`` of the orbit's size."""
    fam = fl.fam
    sh = fam.shooter(pt.p)
    vec, n = pt.vec, fam.n
    size = fam.orbit_size(pt.run)
    images: dict[bytes, tuple] = {}  # (a state's image, run once: a move along a coordinate held at a bound
    # leaves the state as it was, and the depths' states give both an image and a clearance)

    def image(v: np.ndarray) -> tuple:
        key = v.tobytes()
        if key not in images:
            images[key] = fam.image(v, pt.p)
        return images[key]

    def clearance(v: np.ndarray) -> float:
        return sh.clearances(image(v)[1])[side]

    try:
        c0 = clearance(vec)
        grad = np.zeros(n)  # (per unit of the scaled coordinates)
        h = 1e-6 * size / fam.length_m
        for i in pt.free:  # (one-sided, from the clear side: the clearance is smooth there)
            dx = np.zeros(n)
            dx[i] = h * fam.scales[i]
            up, down = (clearance(sh._moved(vec, sgn * dx)) for sgn in (1.0, -1.0))
            grad[i] = (up - c0) / h if up >= down else (c0 - down) / h
        k = float(np.linalg.norm(grad))
        if not k > 0.0 or not math.isfinite(k):
            return math.nan, np.zeros(0), np.zeros(0)
        base = image(vec)[0]
        diffs, depths = [], []
        for depth in DEPTHS:
            dx = -(depth * size + max(c0, 0.0)) / k * grad / k * fam.scales
            minus = sh._moved(vec, -dx)
            plus = image(sh._moved(vec, dx))[0]
            diffs.append(plus + image(minus)[0] - 2.0 * base)
            depths.append(clearance(minus) - 2.0 * c0)
    except _Failed:
        return math.nan, np.zeros(0), np.zeros(0)
    sizes = [float(np.linalg.norm(d / fam.scales)) for d in diffs]
    if min(sizes) <= 0.0 or min(depths) <= 0.0:
        return math.nan, np.zeros(0), np.zeros(0)
    gamma = math.log(sizes[0] / sizes[1]) / math.log(depths[0] / depths[1])
    nominal = 0.5 if rigid else max(0.5, round(2.0 * gamma) / 2.0)
    return gamma, diffs[1] / depths[1] ** nominal, grad / fam.scales
