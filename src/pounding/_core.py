"""The one door into the compiled core (``pounding._pounding_core``, C++17 built with the package).

The core takes plain structures (a system, a forcing, options) and returns arrays; every argument is
checked before it gets here (the core trusts its inputs).  Nothing else in the package imports the
compiled module: the engine, the protocols and the analyses call these functions.

* :class:`System` - an oscillator as the core takes it (:func:`system`); picklable, so it travels to
  worker processes.
* :func:`run` - the event-driven run (``engine.simulate``'s kernel).
* :func:`step` - one frequency step of a sweep, cycles until steady (``protocols.sweep``'s).
* :func:`spectrum` - exact elastic response peaks under a record.
* :func:`monodromy` - the exact monodromy of a hybrid system of linear modes.
* :func:`impact_row`, :func:`law_force_many`, :func:`periodicity`, :func:`expm` - the smaller kernels.

Each run releases the GIL, and polls its run control (``pounding._control``: Ctrl-C and the work budget).
``LAYOUT`` gives the state vector's offsets and the outputs' columns as the core writes them; ``LAW_IDS``
each contact law's id, ``STATUS`` the codes a run ends with, ``ACTIONS`` the events' codes (by name).
"""

from __future__ import annotations

from typing import Any

import numpy as np

try:
    from . import _pounding_core as _c
except ImportError as exc:  # pragma: no cover  (a source tree never built)
    raise ImportError(
        "pounding's compiled core is not built: install the package (pip install -e . in a checkout, which "
        "compiles it with CMake; see docs/building.md)") from exc

System = _c.System
LAYOUT: dict[str, int] = dict(_c.LAYOUT)
LAW_IDS: dict[str, int] = dict(_c.LAW_IDS)
STATUS: dict[str, int] = dict(_c.STATUS)
ACTIONS: dict[str, int] = dict(_c.ACTIONS)


def system(mass: np.ndarray, k0: np.ndarray, c0: np.ndarray,
           elements: list[tuple[int, int, float, Any, Any, int]], bw: np.ndarray, has_b: bool,
           contacts: list[tuple[int, int, float, float, int, np.ndarray]],
           tracked: tuple[tuple[int, int], ...] = ()) -> System:
    """A system as the core takes it: ``mass`` (kg, shape (n,)), the linear springs and dashpots ``k0``,
    ``c0`` (N/m, N s/m, shape (n, n)), the hysteretic elements, each ``(i, j, c_d, slopes, breaks, rule)``
    (dof i against dof j, -1 the ground; its dashpot N s/m, backbone slopes N/m and breaks m, rule 0
    kinematic or 1 elastic; the isolator first, which carries the Bouc-Wen numbers ``bw``, zeros for none;
    no element at all: a structure fixed at its base),
    and the contact slots, each ``(i, j, sign, gap, law id, parameters)``: dof i against dof j (-1: the
    ground), compressed by ``sign (x_i - x_j) - gap``; ``has_b`` makes them active.  ``tracked``: pairs
    ``(i, j)`` whose relative displacement's exact extrema a run adds after the dofs' (4 numbers each: max,
    its time, min, its time; a storey's drift).

    The core trusts what it is given: the sizes and indices are checked here (a ``ValueError`` is a
    caller's bug; the public functions check what users give before)."""
    m = np.atleast_1d(np.asarray(mass, dtype=float))
    n = m.size
    k0, c0 = np.asarray(k0, dtype=float), np.asarray(c0, dtype=float)
    if m.ndim != 1 or n < 1 or k0.shape != (n, n) or c0.shape != (n, n):
        raise ValueError(f"mass (n,) and k0, c0 (n, n): got {m.shape}, {k0.shape}, {c0.shape}")
    if not elements and any(bw):
        raise ValueError("a Bouc-Wen spring is the isolator's: a system without elements has none")

    def pair(i: int, j: int, what: str) -> tuple[int, int]:
        if not (0 <= i < n and (j == -1 or (0 <= j < n and j != i))):
            raise ValueError(f"{what}: the pair ({i}, {j}) is not two of the {n} dofs (or one and the "
                             "ground, -1)")
        return int(i), int(j)

    packed = []
    for e, (i, j, c_d, slopes, breaks, rule) in enumerate(elements):
        slopes, breaks = [float(x) for x in slopes], [float(x) for x in breaks]
        if len(slopes) < 1 or len(breaks) != len(slopes) - 1 or int(rule) not in (0, 1):
            raise ValueError(f"element {e}: {len(slopes)} slopes need {len(slopes) - 1} breaks, rule 0 or 1")
        packed.append((*pair(i, j, f"element {e}"), float(c_d), slopes, breaks, int(rule)))
    if len(bw) != LAYOUT["BW_PARAMS"]:
        raise ValueError(f"bw: {LAYOUT['BW_PARAMS']} numbers, got {len(bw)}")
    slots = []
    for c, (i, j, sign, gap, law, p) in enumerate(contacts):
        if sign not in (-1.0, 1.0) or int(law) not in LAW_IDS.values() or len(p) > LAYOUT["N_LAW_PARAMS"]:
            raise ValueError(f"contact {c}: sign +-1, a law id of LAW_IDS, at most N_LAW_PARAMS parameters")
        slots.append((*pair(i, j, f"contact {c}"), float(sign), float(gap), int(law), [float(x) for x in p]))
    pairs = [pair(i, j, f"tracked pair {q}") for q, (i, j) in enumerate(tracked)]
    return _c.System(n, m.tolist(), k0.reshape(n * n).tolist(), c0.reshape(n * n).tolist(), packed,
                     [float(x) for x in bw], bool(has_b), slots, [i for i, _ in pairs], [j for _, j in pairs])


def _f64(a: Any) -> np.ndarray:
    return np.ascontiguousarray(a, dtype=np.float64)


def run(sy: System, forcing: Any, state0: np.ndarray, t_end: float, sample_dt: float, rtol: float,
        max_events: int, with_energy: bool, ctl: np.ndarray) -> tuple:
    """Simulate ``sy`` under ``forcing`` (``engine._system.Forcing``: kind, parameters, record times and
    accelerations) from ``state0`` to ``t_end``.

    ``sample_dt`` is the history's step (0: events only; -1: not even those); ``with_energy`` False
    skips the energy integrals outside contacts (the ledger is then NaN).  Returns ``(state, samples,
    contacts, events, ledger, extrema, status, chatters)``: ``chatters`` the rigid stops' chatter sequences
    (contact, first impact s, accumulation or last impact s, impacts, accumulated 1/0)."""
    return _c.run(sy, int(forcing.kind), _f64(forcing.p), _f64(forcing.rec_t), _f64(forcing.rec_a),
                  _f64(state0), float(t_end), float(sample_dt), float(rtol), int(max_events),
                  bool(with_energy), ctl)


def step(sy: System, amp: float, omega: float, state0: np.ndarray, steady: tuple, rtol: float,
         max_events: int, ctl: np.ndarray) -> tuple:
    """Hold ``amp sin(omega (t - t0))`` (m/s^2, rad/s) from ``state0`` (time ``t0``) cycle by cycle until
    steady; ``steady`` is ``(adaptive, n_cycles, measure_cycles, steady_rtol, max_period)``.  Returns
    ``(state, cycles_run, period_multiple, window, window_state, window_strobes, status)``."""
    adaptive, n_cycles, measure_cycles, steady_rtol, max_period = steady
    return _c.step(sy, float(amp), float(omega), _f64(state0), bool(adaptive), int(n_cycles),
                   int(measure_cycles), float(steady_rtol), int(max_period), float(rtol), int(max_events),
                   ctl)


def periodicity(strobe: np.ndarray, cyc: np.ndarray, n: int, window: int, max_period: int,
                steady_rtol: float, omega: float, round_window: bool) -> tuple[int, int]:
    """The smallest period multiple with which the last cycles repeat, and the window (the step's test)."""
    return _c.periodicity(_f64(strobe), _f64(cyc), int(n), int(window), int(max_period), float(steady_rtol),
                          float(omega), bool(round_window))


def impact_row(contact: np.ndarray, mass: float, out: np.ndarray) -> None:
    """The paper's per-impact quantities of one contact row into ``out``."""
    _c.impact_row(_f64(contact), float(mass), out)


def law_force_many(law: int, p: np.ndarray, d: np.ndarray, dd: np.ndarray, out: np.ndarray) -> None:
    """A law's force at each (compression, rate) into ``out``, a hysteretic law's along the path."""
    _c.law_force_many(int(law), _f64(p), _f64(d), _f64(dd), out)


def spectrum(t: np.ndarray, acc: np.ndarray, omegas: np.ndarray, zeta: float, out: np.ndarray,
             ctl: np.ndarray) -> int:
    """Exact peaks (max |u|, |u'|, |a_abs|) of each oscillator under the record into ``out``; the status."""
    return _c.spectrum(_f64(t), _f64(acc), _f64(omegas), float(zeta), out, ctl)


def monodromy(sy: System, state0: np.ndarray, events: np.ndarray, t_end: float, omega: float, amp: float,
              phase: float) -> tuple:
    """``(jac, x_end, code)`` of ``sy`` from the state vector ``state0`` to ``t_end`` along ``events`` (rows
    of t, action, index) under ``amp sin(omega t + phase)``: the exact Jacobian of the map of the coordinates
    (displacements, velocities, compressions, slips), those coordinates at ``t_end``, and -1, or the row of
    an event met tangentially, or ``-2 - row`` for an event of a phase that is not linear."""
    return _c.monodromy(sy, _f64(state0), _f64(events).reshape(-1, 3), float(t_end), float(omega), float(amp),
                        float(phase))


def root_guess(fa: float, fb: float, sa: float, sb: float) -> float:
    """The event locator's first guess in (0, 1) at the root of a function with values ``fa``, ``fb`` and
    slopes (per unit of the interval) ``sa``, ``sb`` at 0 and 1: inverse cubic Hermite interpolation, the
    secant's root where the slopes do not allow it."""
    return _c.root_guess(float(fa), float(fb), float(sa), float(sb))


def value_at_root(root: float, x: float, value: float, f: float, fp: float) -> float:
    """A value stationary at a root, from its ``value`` at the last point ``x`` evaluated where the rate
    was ``f`` and its derivative ``fp`` (second-order Taylor)."""
    return _c.value_at_root(float(root), float(x), float(value), float(f), float(fp))


def expm(a: np.ndarray) -> np.ndarray:
    """``exp(a)`` of a small square matrix (balanced, then Higham's scaling and squaring)."""
    return _c.expm(_f64(a))
