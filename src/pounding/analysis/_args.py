"""The arguments the periodic-orbit functions share (``periodic_orbit``, ``continuation``,
``bifurcation_curve``, ``coexistence_map``): checked once, here."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .._checks import instance_of, integer, one_of, real
from .._errors import InputError, Problem
from ..engine.assembly import structures_of
from ..engine.layout import X_D_MAX, X_D_MIN
from ..engine.simulate import ShortRun, simulate
from ..excitation import Harmonic
from . import _hybrid as hy

METHODS = ("auto", "exact", "finite-difference")


def tolerance(tol: Any, low: float, high: float, default: float) -> float:
    """``tol`` in ``[low, high]``."""
    tol = real("tol", tol)
    if not low <= tol <= high:
        raise InputError(Problem.OUT_OF_RANGE, "tol", tol, range=f"[{low:g}, {high:g}]",
                         hint=f" (relative to the orbit's size; {default:g} by default)")
    return tol


def orbit_arguments(excitation: Any, period_multiple: Any, tol: Any, max_iter: Any, settle_cycles: Any,
                    samples_per_period: Any) -> tuple[int, float, int, int, int]:
    """:func:`pounding.periodic_orbit`'s arguments, one mass's or a structure's alike, checked:
    ``(period_multiple, tol, max_iter, settle_cycles, samples_per_period)``."""
    instance_of("excitation", excitation, Harmonic,
                "pounding.Harmonic (a periodic orbit needs a periodic forcing)")
    period_multiple = integer("period_multiple", period_multiple, 1, 64, "give the orbit's period in forcing "
                              "periods: 1, 2 for a period-doubled response, ...")
    tol = tolerance(tol, 1e-15, 1e-2, 1e-10)
    max_iter = integer("max_iter", max_iter, 1, 1000, "100 Newton iterations are plenty")
    settle_cycles = integer("settle_cycles", settle_cycles, 1, 100_000, "give a guess instead")
    samples_per_period = integer("samples_per_period", samples_per_period, 2, 1_000_000,
                                 "the run's extrema are exact whatever the sampling")
    return period_multiple, tol, max_iter, settle_cycles, samples_per_period


def step_size(max_step: Any, low: float, what: str) -> float:
    """The largest arclength step ``max_step`` in ``[low, 0.5]``, in units where ``what`` is 1."""
    max_step = real("max_step", max_step)
    if not low <= max_step <= 0.5:
        raise InputError(Problem.OUT_OF_RANGE, "max_step", max_step, range=f"[{low:g}, 0.5]",
                         hint=f" (in units of {what})")
    return max_step


def exact_monodromy(oscillator: Any, method: Any) -> bool:
    """Whether the monodromy is composed exactly: ``method`` one of ``METHODS``, ``"exact"``
    refused for a system (one mass, a structure or a pair) whose phases are not all linear."""
    method = one_of("method", method, METHODS)
    why = hy.unsupported(oscillator)
    if method == "exact" and why is not None:
        raise InputError(Problem.BAD_STATE, "method", method, why=f"cannot be exact for this system: {why}",
                         fix='use method="finite-difference" (or "auto")')
    return why is None and method != "finite-difference"


def section_angle(phase_rad: Any) -> float:
    """The forcing's angle at the section, rad, reduced to ``[0, 2 pi)`` (beyond 1e8 rad in size,
    refused: the reduction would keep less than 1e-8 rad of the angle)."""
    phase_rad = real("phase_rad", phase_rad)
    if abs(phase_rad) > 1e8:
        raise InputError(Problem.OUT_OF_RANGE, "phase_rad", phase_rad, range="[-1e8, 1e8]",
                         hint=" (an angle, rad: give it within [0, 2 pi))")
    return phase_rad % (2.0 * math.pi)


def settled(oscillator: Any, excitation: Harmonic, settle_cycles: int) -> Any:
    """``settle_cycles`` forcing periods from rest (the default guess: the response a sweep would
    settle on); a run too long for the engine's budget is refused naming the frequency and
    ``settle_cycles``, not the run's duration."""
    duration = settle_cycles / excitation.freq_hz
    try:
        return simulate(oscillator, excitation, duration, sample_rate_hz=0)
    except InputError as exc:
        if exc.field != "duration":
            raise
        raise InputError(Problem.BAD_STATE, "settle_cycles", settle_cycles,
                         why=f"periods at {excitation.freq_hz:g} Hz last {duration:.3g} s, a run beyond the "
                             "engine's budget (the default guess settles from rest)",
                         fix="start at a higher frequency, lower settle_cycles, or give a guess (a state)"
                         ) from None


def length_scale(system: Any, run: ShortRun) -> float:
    """The lengths' scale of a family of orbits, m: half the narrowest wall's (a single mass's bumpers') or
    link's total gap, or the levels' largest displacement over ``run`` if larger (1e-6 m at least)."""
    levels = [d for dofs in run.asm.dofs for d in dofs if d >= 0]
    ex = run.extrema[levels]
    size = max(float(np.abs(ex[:, X_D_MAX]).max()), float(np.abs(ex[:, X_D_MIN]).max()))
    structures, links = structures_of(system)
    gaps = [w.gap_left_m + w.gap_right_m for s in structures for w in s.walls] + [k.gap_m for k in links]
    return max(min(gaps) / 2.0 if gaps else 0.0, size, 1e-6)
