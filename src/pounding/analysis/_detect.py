"""The continuation follower's detectors: between two consecutive points, the test functions of
folds, branch points, period-doublings, Neimark-Sacker points and grazings, each sign change located
on the branch, and what a located point reports (a :class:`~pounding.Bifurcation`)."""

from __future__ import annotations

import math
from dataclasses import replace
from typing import TYPE_CHECKING, Callable, Optional

import numpy as np

from ._arclength import Point
from ._grazing import locate_grazing, map_scaling
from .branch import Bifurcation

if TYPE_CHECKING:
    from ._follower import Follower


def tests_at(fl: "Follower", pt: Point) -> dict[str, float]:
    """The detectors' test functions at a point (sign changes mark the bifurcations)."""
    out = {"fold": pt.tau_q}
    mult = pt.mult
    real_ = np.abs(mult.imag) <= 1e-9 * np.maximum(np.abs(mult), 1e-300)
    out["period-doubling"] = float(np.count_nonzero(real_ & (mult.real < -1.0)))
    out["neimark-sacker"] = float(np.count_nonzero(~real_ & (np.abs(mult) > 1.0)))
    for side, clearance in fl.fam.shooter(pt.p).clearances(pt.run).items():  # (bumpers, walls, links)
        out[f"grazing {side}"] = clearance / fl.fam.length_m
    return out

def psi_bp(fl: "Follower", pt: Point) -> float:
    """The branch-point test: the bordered Jacobian's determinant, which changes sign where
    two branches cross (at a fold it does not: the tangent turns with it)."""
    fam = fl.fam
    return float(np.linalg.det(fam.bordered(pt.jac, pt.dp, pt.free, pt.emb, pt.tau_x, pt.tau_q)))

def branch_point(fl: "Follower", a: Point, b: Point, ds: float) -> bool:
    """A branch point between ``a`` and ``b`` (a symmetric orbit's pitchfork): located, recorded,
    and the other branch taken when ``switch``; True when the follower switched."""
    same = (tuple(a.free), a.frozen) == (tuple(b.free), b.frozen)
    if not same or psi_bp(fl, a) * psi_bp(fl, b) >= 0.0:
        return False
    scale = max(abs(psi_bp(fl, a)), abs(psi_bp(fl, b)))
    pt = locate(fl, a, ds, lambda q: psi_bp(fl, q) / scale, b)
    if pt is None:
        return False
    fam = fl.fam
    own = np.append((fam.coords(b.vec) - fam.coords(a.vec)) / fam.scales, (b.p - a.p) / fam.p_scale)
    other = other_direction(fl, pt, own / np.linalg.norm(own))
    bif = bifurcation_at(fl, "branch-point", "", pt, abs(psi_bp(fl, pt) / scale) <= 1e-8)
    object.__setattr__(bif, "direction", np.append(fam.scales * other[:-1], other[-1] * fam.p_scale))
    fl.bifs.append(bif)
    if not fl.switch_branches:
        return False
    where = np.append(pt.p / fam.p_scale, np.array(fam._ref.extent(pt.run)) / fam.length_m)
    if any(np.abs(where - w).max() < 1e-5 for w in fl.switched):
        fl._append(pt, fl._s(a, pt))
        fl.looped = True
        return True
    fl.switched.append(where)
    toward = math.copysign(1.0, fl.p1 - fl.p0)
    start = replace(pt)
    sign = 1.0 if other[-1] * toward >= 0.0 else -1.0
    start.tau_x, start.tau_q = sign * other[:-1], sign * other[-1]
    for grow in (1.0, 4.0, 16.0):
        c = fl.step(start, grow * ds, chord=False)  # (the Jacobian at a branch point is singular)
        if c is not None and abs(float(c.tau_x @ a.tau_x + c.tau_q * a.tau_q)) < 0.9:
            fl._append(pt, fl._s(a, pt))
            fl._append(c, grow * ds)
            return True
    return False

def other_direction(fl: "Follower", pt: Point, own: np.ndarray) -> np.ndarray:
    """At a branch point, the tangent of the other branch (full scaled coordinates, then p):
    the null space of ``[M - I, dP/dp]`` is two-dimensional there (so the tangent computed
    there is any of it); its direction orthogonal to ``own``, the secant the follower came along."""
    fam = fl.fam
    a = fam.bordered(pt.jac, pt.dp, pt.free, pt.emb, pt.tau_x, pt.tau_q)[:-1]
    vt = np.linalg.svd(a)[2]
    s_w = fam.scales[pt.free]
    lifted = [np.append((pt.emb @ (v[:-1] * s_w)) / fam.scales, v[-1]) for v in vt[-2:]]
    best = max(lifted, key=lambda u: np.linalg.norm(u - (u @ own) * own))
    u = best - (best @ own) * own
    return u / np.linalg.norm(u)

def detect(fl: "Follower", a: Point, b: Point, ds: float, known: str = "") -> None:
    """The bifurcations between ``a`` and ``b``, located and recorded (``known``: a grazing crossed by
    its normal form, recorded already with the fold it makes when the branch turns there).  Across a
    grazing the multipliers jump (the map is not smooth there: unbounded on a rigid stop's impacting
    side), so a change in the count of those past -1 or outside the unit circle on that step is reported
    only where a multiplier is on the circle at its located point (a crossing just past the grazing, as a
    soft stop's can have), not where the count jumped at the grazing."""
    ta, tb = tests_at(fl, a), tests_at(fl, b)
    found = []
    grazes = bool(known) or any(name.startswith("grazing") and va * tb[name] < 0.0 for name, va in ta.items())
    for name, va in ta.items():
        vb = tb[name]
        counted = name in ("period-doubling", "neimark-sacker")
        if name == known or (known and name == "fold"):
            continue  # (crossed by the normal form: a turn there is the grazing's own, recorded with it)
        if name.startswith("grazing") and va * vb < 0.0:
            side = name.partition(" ")[2]
            got = locate_grazing(fl, a, b, side)
            if got is not None:
                pt, ok = got
                found.append((fl._s(a, pt), name, pt, ok))
                continue
        if (counted and va != vb) or (not counted and va * vb < 0.0):
            if counted:
                def fn(pt: Point, name: str = name, mid: float = 0.5 * (va + vb)) -> float:
                    return tests_at(fl, pt)[name] - mid  # (+-0.5 on either side of the count's change)
            elif (name == "fold" and a.mult.size == b.mult.size
                  and _crossing(a.mult) * _crossing(b.mult) < 0.0):
                # a smooth fold: a multiplier through 1 locates it better than the tangent,
                # which turns fast there (and, next to a grazing, not smoothly)
                def fn(pt: Point, size: int = a.mult.size) -> float:
                    return _crossing(pt.mult) if pt.mult.size == size else math.nan
            else:
                def fn(pt: Point, name: str = name) -> float:
                    return tests_at(fl, pt)[name]
            pt = locate(fl, a, ds, fn, b)
            if pt is None:
                continue
            ok = abs(fn(pt)) <= 1e-8 or (counted and fl.bracket <= 1e-9 * ds)
            if counted and grazes and not (ok and _on_the_circle(pt.mult, name)):
                continue  # (the count jumped at the grazing: no multiplier there is -1 or on the circle)
            found.append((fl._s(a, pt), name, pt, ok))
    for _, name, pt, ok in sorted(found, key=lambda item: item[0]):
        kind, _, side = name.partition(" ")
        fl.bifs.append(grazing_at(fl, pt, side, ok) if kind == "grazing"
                       else bifurcation_at(fl, kind, side, pt, ok))


def grazing_at(fl: "Follower", pt: Point, side: str, located: bool = True) -> Bifurcation:
    """The grazing of ``side`` at the clear orbit ``pt``, with the map's scaling there when located."""
    bif = bifurcation_at(fl, "grazing", side, pt, located)
    if not located:
        return bif
    gamma, term = map_scaling(fl, pt, side, side in fl.fam.shooter(pt.p).rigid_sides())
    return replace(bif, scaling_exponent=gamma, scaling_term=term)

def locate(fl: "Follower", a: Point, ds: float, fn: Callable[[Point], float], b: Point) -> Optional[Point]:
    """Illinois regula falsi on the step length for the zero of ``fn`` between ``a`` (0) and ``b`` (ds);
    ``fl.bracket`` is left the final bracket's length (a step that fails stops it early)."""
    lo, hi, f_lo, f_hi = 0.0, ds, fn(a), fn(b)
    fl.bracket = hi - lo
    if f_lo == 0.0:
        return a
    best, side = b, 0
    at_lo, at_hi = a, b  # (the bracket's ends, solved: steps go from the nearer)
    for _ in range(60):
        s = (lo * f_hi - hi * f_lo) / (f_hi - f_lo) if f_hi != f_lo else 0.5 * (lo + hi)
        if not lo < s < hi:
            s = 0.5 * (lo + hi)
        near, far = ((at_lo, s - lo), (at_hi, s - hi)) if s - lo <= hi - s else ((at_hi, s - hi),
                                                                                 (at_lo, s - lo))
        pt = fl.step(*near) or fl.step(*far)  # (e.g. across a grazing: from the other side)
        if pt is None:
            return best
        v = fn(pt)
        fl.bracket = hi - lo
        if not math.isfinite(v):  # (the coordinates changed within the step)
            return best
        best = pt
        if abs(v) <= 1e-8 or hi - lo <= 1e-9 * ds:
            return pt
        if (v < 0.0) == (f_lo < 0.0):
            lo, f_lo, at_lo = s, v, pt
            if side == -1:
                f_hi *= 0.5
            side = -1
        else:
            hi, f_hi, at_hi = s, v, pt
            if side == 1:
                f_lo *= 0.5
            side = 1
    return best

def bifurcation_at(fl: "Follower", kind: str, side: str, pt: Point, located: bool) -> Bifurcation:
    fam = fl.fam
    osc, exc = fam.system(pt.p)
    tangent = np.append(fam.scales * pt.tau_x, fam.p_scale * pt.tau_q)
    direction = tangent[:-1]
    if kind == "period-doubling" and pt.jac.size:
        w, v = np.linalg.eig(pt.jac)
        i = int(np.argmin(np.abs(w + 1.0)))
        direction = pt.emb @ np.real(v[:, i])
    sh = fam.shooter(pt.p)
    return Bifurcation(kind, pt.p, exc.freq_hz, exc.a_g, pt.mult.copy(), sh._state(pt.vec), len(fl.points),
                       side, direction, fam.k, sh.summary(pt.run, exc)["alpha"], located, pt.phase, tangent,
                       fam.parameter)

# ---- the result


def _on_the_circle(mult: np.ndarray, name: str) -> bool:
    """Whether a multiplier at a located count change crosses the unit circle there (a real one at -1 for
    a period-doubling, a complex pair of modulus 1 for a Neimark-Sacker point) to 1e-3, rather than
    jumping past it (at a grazing)."""
    real_ = np.abs(mult.imag) <= 1e-9 * np.maximum(np.abs(mult), 1e-300)
    if name == "period-doubling":
        return bool(np.any(real_ & (np.abs(mult.real + 1.0) <= 1e-3)))
    return bool(np.any(~real_ & (np.abs(np.abs(mult) - 1.0) <= 1e-3)))


def _crossing(mult: np.ndarray) -> float:
    """``prod(mu - 1)``, real: it changes sign where one real multiplier crosses 1."""
    return float(np.real(np.prod(mult - 1.0)))
