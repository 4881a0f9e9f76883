"""Pseudo-arclength continuation of periodic orbits: the family of maps, its points, the
corrector and the tangent.

A *family* is the stroboscopic map ``P(x; p)`` of :mod:`periodic` at a fixed forcing angle
(the state at time 0, the forcing ``Harmonic(a_g, f, phase)``) as one parameter ``p`` varies:
the frequency, the table's peak acceleration, or a number of the system.  A point of the
branch solves ``P(x; p) = x`` in the orbit's shooting coordinates ``w`` (which may change
along the branch: a spring that starts to yield becomes a coordinate, a bumper touched at the
section follows the mass); distances and tangents are therefore measured in the full
coordinates ``x`` of ``_hybrid`` (each over a fixed scale) and in ``p`` over the range's length.

The corrector is Newton on ``[P(x; p) - x = 0, tau . (y - y_pred) = 0]``, reusing the last
point's Jacobian while it contracts (a chord method: one engine run per iteration), with a
fresh one when it does not.  ``dP/dp`` is a central difference of the map.
"""

from __future__ import annotations

import copy
import math
from dataclasses import dataclass
from typing import Any, Optional

import numpy as np

from .._errors import InputError

from ..engine import Run
from ..excitation import Harmonic
from ..model.dotted import get_value, set_value
from ._shooter import _Shooter
from ._shooting import _Failed


@dataclass
class Point:
    """One solved orbit of the family (all the corrector and the detectors need)."""

    vec: np.ndarray        # the engine's state vector at the section (time 0)
    p: float               # the parameter's value
    run: Run               # one period from vec
    jac: np.ndarray        # monodromy in the free coordinates, (r, r)
    dp: np.ndarray         # dP/dp in the free coordinates, (r,)
    free: np.ndarray       # indices of the free coordinates in x
    emb: np.ndarray        # dx = emb dw, (n, r)
    frozen: tuple          # isolator springs elastic over the period
    tau_x: np.ndarray      # unit tangent: scaled x part, (n,)
    tau_q: float           # ... and scaled parameter part
    residual: float        # largest scaled residual
    mult: np.ndarray       # Floquet multipliers, largest modulus first
    iterations: int = 0    # the corrector's
    phase: float = 0.0     # the forcing's angle at the section, rad



class Family:
    """The maps ``P(.; p)``, with fixed scales: ``length_m`` for the displacements, compressions and
    slips, ``length_m * omega_ref`` for the velocities, 1 for the Bouc-Wen z, ``p_scale`` for p.  The
    system is one mass, or a structure or a pair (its shooter's coordinates, the same way)."""

    def __init__(self, oscillator: Any, a_g: float, freq_hz: float, parameter: str,
                 period_multiple: int,
                 exact: bool, phase: float, length_m: float, p_scale: float, omega_ref: float) -> None:
        self.osc = oscillator
        self.table = oscillator.to_dict() if parameter not in ("freq_hz", "a_g") else None
        self.a_g = a_g
        self.freq_hz = freq_hz
        self.parameter = parameter
        self.k = period_multiple
        self.exact = exact
        self.phase = phase
        self.p_scale = p_scale
        self._cache: dict[tuple[float, float], _Shooter] = {}
        self._borders: dict[tuple, tuple] = {}  # (see _bordering)
        self.fell_back = ""
        self.length_m = length_m
        sh = self._ref = self.shooter(self.start_value)  # (for what does not depend on p: the coordinates)
        labels = sh.labels()
        self.n = len(labels)
        self.scales = np.full(self.n, length_m)
        self.scales[[i for i, name in enumerate(labels) if name.startswith("v_")]] *= omega_ref
        if sh.z_max > 0.0:
            self.scales[-1] = 1.0

    @property
    def start_value(self) -> float:
        return {"freq_hz": self.freq_hz, "a_g": self.a_g}.get(self.parameter, np.nan) if self.table is None \
            else float(get_value(self.table, self.parameter))

    def system(self, p: float, a_g: Optional[float] = None) -> tuple[Any, Harmonic]:
        """The system and forcing at parameter value ``p`` and table acceleration ``a_g`` (g; default
        the family's: a two-parameter curve passes its own), ``_Failed`` where there is none (a value
        the continuation stepped to, not one the caller gave)."""
        a_g = self.a_g if a_g is None else a_g
        try:
            if self.parameter == "freq_hz":
                return self.osc, Harmonic(a_g, p, phase=self.phase)
            if self.parameter == "a_g":
                return self.osc, Harmonic(p, self.freq_hz, phase=self.phase)
            table = copy.deepcopy(self.table)
            set_value(table, self.parameter, float(p))
            return type(self.osc).from_dict(table), Harmonic(a_g, self.freq_hz, phase=self.phase)
        except InputError as exc:  # (the model's checks' words, as the solver's failure)
            raise _Failed(f"no system at {self.parameter} = {p:g} ({exc})") from None

    def set_length(self, length_m: float) -> None:
        """A new length scale (the orbits grew): lengths and velocities are measured against it."""
        ratio = length_m / self.length_m
        self.length_m = length_m
        self.scales[: self.scales.size - int(self._ref.z_max > 0.0)] *= ratio

    def set_phase(self, phase: float) -> None:
        """Move the section to the forcing angle ``phase`` (rad, in [0, 2 pi))."""
        self.phase = float(phase) % (2.0 * np.pi)
        self._cache.clear()

    def omega(self, p: float) -> float:
        return self.shooter(p).exc.omega_rad_s

    def shooter(self, p: float, a_g: Optional[float] = None) -> Any:
        key = (p, self.a_g if a_g is None else a_g)  # (a two-parameter curve passes its a_g)
        sh = self._cache.get(key)
        if sh is None:
            osc, exc = self.system(p, a_g)
            sh = _Shooter(osc, exc, self.k / exc.freq_hz, self.exact, getattr(self, "_ref", None))
            if len(self._cache) > 32:
                self._cache.clear()
            self._cache[key] = sh
        sh.scale_d = self.length_m
        return sh

    def coords(self, vec: np.ndarray) -> np.ndarray:
        return self._ref.coords(vec)

    def orbit_size(self, run: Run) -> float:
        """The orbit's size, m: its largest extent from rest (displacement or compression)."""
        return max(abs(x) for x in self._ref.extent(run))

    # ------------------------------------------------------------------ pieces
    def image(self, vec: np.ndarray, p: float, a_g: Optional[float] = None,
              checked: bool = False) -> tuple[np.ndarray, Run]:
        """``(x of P(vec; p), the run)``; raises _Failed where the engine cannot run it (``checked``:
        ``vec`` ran from before on the system at ``p``, not checked again)."""
        end, run = self.shooter(p, a_g)._image(vec, checked)
        return self.coords(end), run

    def residual(self, vec: np.ndarray, p: float,
                 a_g: Optional[float] = None) -> tuple[np.ndarray, Run, tuple, np.ndarray, np.ndarray]:
        """``(scaled residual in the free coordinates, run, frozen springs, free, emb)``."""
        sh = self.shooter(p, a_g)
        end, run = sh._image(vec)
        frozen = sh.frozen(vec, run)
        free, emb = sh._layout(vec, frozen)
        r = (self.coords(end) - self.coords(vec))[free] / self.scales[free]
        return r, run, frozen, free, emb

    def linearize(self, vec: np.ndarray, p: float, run: Run, frozen: tuple) -> tuple[np.ndarray, np.ndarray]:
        """``(monodromy, dP/dp)`` in the free coordinates (unscaled; dP/dp per unit of p)."""
        sh = self.shooter(p)
        jac = sh.jacobian(vec, run, frozen)
        if sh.fell_back and not self.fell_back:
            self.fell_back = sh.fell_back
        free, _ = sh._layout(vec, frozen)
        h = 1e-6 * self.p_scale
        # (vec ran at p: the same system at p +- h where p is the forcing's, so not checked again)
        same = self.table is None
        try:
            diff = (self.image(vec, p + h, checked=same)[0]
                    - self.image(vec, p - h, checked=same)[0]) / (2.0 * h)
        except _Failed:  # (p next to a bound of its values, e.g. a gap of 0: one-sided)
            x0 = self.coords(run.final_state.vector)
            try:
                diff = (self.image(vec, p + h, checked=same)[0] - x0) / h
            except _Failed:
                diff = (x0 - self.image(vec, p - h, checked=same)[0]) / h
        return jac, diff[free]

    def bordered(self, jac: np.ndarray, dp: np.ndarray, free: np.ndarray, emb: np.ndarray,
                 row_x: np.ndarray, row_q: float) -> np.ndarray:
        """The scaled extended Jacobian ``[[S^-1 (M - I) S_w, S^-1 dP/dp s_p], [row]]``, (r+1, r+1).

        ``row_x`` (n,) and ``row_q``: the last row's tangent in the full scaled coordinates."""
        s_w, eye, ratio, lift = self._bordering(free, emb)
        r = free.size
        a = np.empty((r + 1, r + 1))
        a[:r, :r] = (jac - eye) * ratio
        a[:r, r] = dp / s_w * self.p_scale
        a[r, :r] = row_x @ lift
        a[r, r] = row_q
        return a

    def _bordering(self, free: np.ndarray, emb: np.ndarray) -> tuple:
        """What :meth:`bordered` takes of the layout and the scales alone, ``(s_w, I, s_w / s_w^T, E s_w /
        s)``: made once for each (a corrector borders the same layout at every iteration)."""
        key = (free.tobytes(), emb.shape, emb.tobytes(), self.scales.tobytes())
        got = self._borders.get(key)
        if got is None:
            if len(self._borders) >= 64:
                self._borders.clear()
            s_w = self.scales[free]
            got = self._borders[key] = (s_w, np.eye(free.size), s_w[None, :] / s_w[:, None],
                                        emb * s_w[None, :] / self.scales[:, None])
        return got

    def tangent(self, pt: Point, prev_x: np.ndarray, prev_q: float) -> tuple[np.ndarray, float]:
        """The unit tangent at ``pt`` oriented along ``(prev_x, prev_q)`` (full scaled coordinates)."""
        a = self.bordered(pt.jac, pt.dp, pt.free, pt.emb, prev_x, prev_q)
        rhs = np.zeros(a.shape[0])
        rhs[-1] = 1.0
        try:
            t = np.linalg.solve(a, rhs)
        except np.linalg.LinAlgError:
            t = np.linalg.svd(a[:-1])[2][-1]
        s_w = self.scales[pt.free]
        tx = (pt.emb @ (t[:-1] * s_w)) / self.scales
        tq = float(t[-1])
        norm = float(np.sqrt(tx @ tx + tq * tq))
        tx, tq = tx / norm, tq / norm
        if tx @ prev_x + tq * prev_q < 0.0:
            tx, tq = -tx, -tq
        return tx, tq

    def correct(self, vec: np.ndarray, p: float, target_x: np.ndarray, target_p: float, tau_x: np.ndarray,
                tau_q: float, tol: float, chord: Optional[Point] = None,
                max_iter: int = 12) -> Optional[Point]:
        """Newton from ``(vec, p)`` onto the branch in the hyperplane through ``(target_x, target_p)``
        normal to ``(tau_x, tau_q)`` (``tau_x = 0, tau_q = 1``: p fixed).  None where it fails."""
        jac = dp = None
        key = None
        last = np.inf
        for it in range(max_iter):
            try:
                r, run, frozen, free, emb = self.residual(vec, p)
            except _Failed:
                return None
            x = self.coords(vec)
            arc = float(tau_x @ ((x - target_x) / self.scales) + tau_q * (p - target_p) / self.p_scale)
            largest = float(np.abs(r).max(initial=0.0))
            norm = max(largest, abs(arc))
            if not math.isfinite(norm):
                return None
            if norm <= tol:
                try:
                    jac, dp = self.linearize(vec, p, run, frozen)
                except _Failed:
                    return None
                mult = np.linalg.eigvals(jac) if jac.size else np.zeros(0, complex)
                mult = mult[np.argsort(-np.abs(mult), kind="stable")]
                return Point(vec, p, run, jac, dp, free, emb, frozen, tau_x, tau_q, largest, mult, it,
                             self.phase)
            here = (tuple(free), frozen)
            if chord is not None and jac is None and (tuple(chord.free), chord.frozen) == here:
                jac, dp, key = chord.jac, chord.dp, here
            if jac is None or key != here or norm > 0.5 * last:
                try:
                    jac, dp = self.linearize(vec, p, run, frozen)
                except _Failed:
                    return None
                key = here
            last = norm
            a = self.bordered(jac, dp, free, emb, tau_x, tau_q)
            try:
                step = np.linalg.solve(a, -np.concatenate((r, [arc])))
            except np.linalg.LinAlgError:
                return None
            p_new = p + step[-1] * self.p_scale
            dx = emb @ (step[:-1] * self.scales[free])
            try:
                vec = self.shooter(p_new)._moved(vec, dx)
            except _Failed:
                return None
            p = p_new
        return None


def fold_test(mult: np.ndarray) -> float:
    """The fold's test function: the real part of the multiplier nearest 1, minus 1, among the
    real multipliers when there are any (a complex pair of real part 1 is no fold); 0 at a smooth
    fold, NaN without multipliers."""
    if mult.size == 0:
        return float("nan")
    real = mult[np.abs(mult.imag) <= 1e-9 * np.maximum(np.abs(mult), 1.0)]
    mult = real if real.size else mult
    return float(mult[int(np.argmin(np.abs(mult - 1.0)))].real - 1.0)


# A follower has closed on itself when a step passes by the point it must come back to nearer than
# this fraction of the step, heading the way the curve left that point.  Why 0.06: a step's chord
# lies within theta / 8 of its length from the arc it cuts, theta the angle the tangent turns over
# the step, and both followers refuse a step whose tangent turns by more than arccos(0.9) = 0.45 rad
# (their MIN_COS); the heading test keeps a curve that only crosses its own signature from closing.
CLOSE_TOL = 0.06


@dataclass
class Closure:
    """Watches a follower's steps for its return to ``anchor`` (points of an orbit's signature:
    what does not depend on the section, scaled).  Feed it each accepted step, ``u`` to ``v``, the
    first from ``anchor`` itself (it sets the heading the curve left by); the curve closes once it
    has been more than two steps away and a step then passes by ``anchor`` within ``CLOSE_TOL``
    of the step, heading the same way (a cosine above 0.5)."""

    anchor: np.ndarray
    heading: Optional[np.ndarray] = None
    far: bool = False

    def passed(self, u: np.ndarray, v: np.ndarray, ds: float) -> bool:
        seg = v - u
        if self.heading is None:
            self.heading = seg / max(float(np.linalg.norm(seg)), 1e-300)
            return False
        ds = max(ds, 1e-12)
        if not self.far:
            self.far = bool(np.linalg.norm(v - self.anchor) > 2.0 * ds)
            return False
        length = float(np.linalg.norm(seg))
        t = float((self.anchor - u) @ seg / max(length * length, 1e-300))
        if not 0.0 < t <= 1.0 or seg @ self.heading <= 0.5 * length:
            return False
        return float(np.linalg.norm(u + t * seg - self.anchor)) < CLOSE_TOL * ds


def system_at(osc: Any, parameter: str, value: float) -> Any:
    """The system (one mass, a structure or a pair) with its number ``parameter`` set to ``value``."""
    if parameter in ("freq_hz", "a_g"):
        return osc
    table = osc.to_dict()
    set_value(table, parameter, float(value))
    return type(osc).from_dict(table)
