"""``lyapunov``: the Lyapunov spectrum of a harmonically driven response, from the exact tangent
dynamics (state-transition matrices between the engine's events, a saltation matrix at each).

The stroboscopic map is followed one forcing period at a time: the engine runs the period, and its
Jacobian (the period's monodromy, as :func:`pounding.periodic_orbit` composes it: exactly for
systems whose phases are all linear, else by central differences of the map) carries an
orthonormal frame of tangent vectors, re-orthonormalised after every period (Benettin's method
with QR).  The exponents are the averages of the logarithms of the diagonal of R per second.

The tangent coordinates are the state's (:func:`pounding.periodic_orbit`'s names): every level's
displacement and velocity (a single mass's ``x_0`` and ``v_0``), the compression of a Kelvin-Voigt or
elastic multi-linear contact with a dashpot (out of contact it relaxes: a state of its own), the slip of each
spring that slips during the run (a spring that never does is a constant, a parameter of the
response, as in :func:`pounding.periodic_orbit`), the Bouc-Wen z.  At each section a coordinate
that follows the mass there (a touched bumper's compression, a slipping spring's slip) is put back
on its constraint.

Two choices make the estimates exact where a closed form exists:

- Lengths and velocities are measured in the real modal coordinates of the free motion (no contact,
  every spring on its stiffest slope), each mode's pair scaled so that its largest displacement is
  ``1 / omega_d``: the free linear flow is a rotation times each mode's decay, and every frame vector
  shrinks at exactly its rate.  A single mass's are its isolator's own units, ``(omega_d x, v + zeta
  omega_n x)`` of its stiffest slope.  A system with a real mode (overdamped) is measured as
  ``(omega x, v)``, ``omega`` its slowest undamped frequency.  The other coordinates (compressions,
  slips) are in units of the slowest mode's frequency, a Bouc-Wen ``z`` (of order 1) a thousandth of
  it.  (Exponents do not depend on a fixed change of coordinates; finite-time estimates do, by O(1/t).)
- The frame is carried for ``align_cycles`` periods before the count starts, so on a periodic
  orbit whose largest multiplier is real and alone it is aligned and each period's R gives the
  multipliers' moduli.

A contact that slaves a compression, a spring that starts slipping, a relaxation that ends within
a period: the map erases a direction.  Its exponent is ``-inf`` (also one whose contraction in a
period is beyond what double precision resolves next to the others, 1e-13).
"""

from __future__ import annotations

import math
from dataclasses import replace
from collections.abc import Iterator
from typing import Any, Optional

import numpy as np
from scipy.linalg import lapack

from .._checks import instance_of, integer
from .._errors import InputError, Interrupted, Problem, Status, renamed_keyword
from .._runner.progress import Progress, progress_reporter
from ..engine import State, simulate
from ..engine.simulate import check_state
from ..excitation import Harmonic
from ..protocols.bifurcation_diagram import BifurcationDiagram, periods
from . import _hybrid as hy
from ._args import exact_monodromy
from .lyapunov_result import LyapunovSpectrum
from ..engine.assembly import assemble, check_system
from ._shooter import _Shooter
from ._shooting import _Failed, at_section

MAX_CYCLES = 10_000_000
MAX_PERIOD = 8  # the longest period (in forcing periods) a response is checked for
KEEP_RUNS = 20_000  # periods whose runs are kept between the two passes (about 1 kB each); more run twice
PERIODIC_RTOL = 1e-9  # sections that repeat to this (of the motion's size) make a periodic response
RESOLVED = 1e-13  # a diagonal of R below this times the largest: the direction is erased (-inf)


@renamed_keyword("oscillator", "system")
def lyapunov(system: Any, excitation: Harmonic, *, cycles: int = 1000,
             transient_cycles: int = 200, align_cycles: int = 20, state: Optional[Any] = None,
             method: str = "auto", progress: Progress = False) -> LyapunovSpectrum:
    """The Lyapunov spectrum of the response to a harmonic table motion, from the exact tangent
    dynamics through every phase and every event.

    Parameters
    ----------
    system : Oscillator, Structure or Adjacent
        The system: one mass, or a structure of several (or two adjacent ones), whose tangent
        coordinates are then every mass's displacement and velocity (measured in the real modal
        coordinates of its free motion), the relaxing contacts' compressions and the slips.
    excitation : Harmonic
        The table's harmonic acceleration.
    cycles : int
        Forcing periods counted (1000 by default; the estimates converge as 1/cycles, see
        ``history``).
    transient_cycles : int
        Periods run first, by the engine alone, for the response to settle.
    align_cycles : int
        Periods the tangent frame is carried before the count starts (it turns towards the
        directions that grow most).
    state : State, optional
        Where to start (its time sets the section's phase); default: at rest at time 0.
    method : {"auto", "exact", "finite-difference"}
        The Jacobian of each period: composed exactly (systems whose phases are all linear:
        ``"auto"`` takes it where it can) or by central differences of the map.
    progress : bool or callable
        True: a progress bar; a callable is called with the number of periods just finished.

    Returns
    -------
    LyapunovSpectrum
        The exponents, their running estimates, the Kaplan-Yorke dimension. On Ctrl-C,
        :class:`pounding.Interrupted` carries the spectrum over the periods counted.

    Examples
    --------
    A linear isolator without bumpers: both exponents are ``-zeta omega_n``.

    >>> import pounding
    >>> iso = pounding.Isolator(slopes_n_m=[4000.0], damping_n_s_m=40.0)
    >>> osc = pounding.Oscillator(mass_kg=100.0, isolator=iso)
    >>> spec = pounding.lyapunov(osc, pounding.Harmonic(0.05, 1.0), cycles=50)
    >>> [round(float(x), 12) for x in spec.exponents]  # -c / (2 m)
    [-0.2, -0.2]
    """
    check_system(system)
    instance_of("excitation", excitation, Harmonic,
                "pounding.Harmonic (the exponents are of the stroboscopic map of a "
                                  "periodic forcing)")
    cycles = integer("cycles", cycles, 1, MAX_CYCLES, "count fewer periods; the estimates' history shows "
                     "when they have settled")
    transient_cycles = integer("transient_cycles", transient_cycles, 0, MAX_CYCLES)
    align_cycles = integer("align_cycles", align_cycles, 0, MAX_CYCLES)
    exact = exact_monodromy(system, method)
    if state is not None:
        instance_of("state", state, State, "pounding.State (e.g. run.final_state)")
    state = check_state(state, system)
    if transient_cycles:
        run = simulate(system, excitation, transient_cycles / excitation.freq_hz, state, sample_rate_hz=0)
        if not run.success:
            raise InputError(Problem.BAD_STATE, "transient_cycles", transient_cycles,
                             why=f"the transient did not run through: {run.message}",
                             fix="start from another state, or count fewer transient cycles")
        state = run.final_state
    return _Tangent(system, excitation, exact, state).run(align_cycles, cycles, progress)


class _Tangent:
    """The map's Jacobian, period by period, in the spectrum's coordinates."""

    def __init__(self, oscillator: Any, excitation: Harmonic, exact: bool, state: Any) -> None:
        self.exc = excitation
        self.period = 1.0 / excitation.freq_hz
        self.sh = _Shooter(oscillator, excitation, self.period, exact)
        self.start = np.array(state.vector, dtype=float)
        self.fell_back = 0  # periods whose exact Jacobian gave way to finite differences

    def _metric(self, keep: np.ndarray) -> np.ndarray:
        """``W``: the tangent vectors measured as ``W dx`` (the free motion's real modal coordinates)."""
        return _modal_metric(self.sh.free_state_matrix(), keep.size, self.sh.z_max > 0.0)

    def _jacobian(self, vec: np.ndarray, run: Any) -> np.ndarray:
        """The period's Jacobian in every coordinate of ``_Shooter.coords``, perturbations put on
        their constraints at the start."""
        sh = self.sh
        free_idx, emb = sh._layout(vec)
        n = emb.shape[0]
        select = np.zeros((free_idx.size, n))
        select[np.arange(free_idx.size), free_idx] = 1.0
        if sh.exact:
            try:
                full, x_end = sh._propagate(vec, run)
                gap = np.abs(x_end - sh.coords(run.final_state.vector)).max() / sh.scale_d
                if np.isfinite(full).all() and gap < 1e-6:
                    return full @ emb @ select
            except hy.NoExactMonodromy:
                pass
            self.fell_back += 1
        return sh.differences(vec, free_idx, emb) @ select

    def _periods(self, count: int) -> Iterator[tuple[np.ndarray, Any]]:
        """``(state vector at the section, the period's run)`` for ``count`` periods from the start
        (the same each time: the engine is deterministic)."""
        vec = self.start
        for _ in range(count):
            end, run = self.sh._image(vec)
            yield vec, run
            vec = end

    def run(self, align: int, cycles: int, progress: Progress) -> LyapunovSpectrum:
        total = align + cycles
        status, why, ran = Status.SUCCESS, "", 0
        slips: set = set()
        size = 1e-6
        kept: list = []  # the periods' runs, for the second pass when they are few (else run again)
        with progress_reporter(progress, 2 * total, f"Lyapunov spectrum, {self.exc.freq_hz:g} Hz") as advance:
            # the trajectory first, by the engine alone: the springs that slip in it (the spectrum's
            # coordinates) and its size (the finite differences' steps, the periodicity's tolerance)
            try:
                for vec, run in self._periods(total):
                    ran += 1
                    if total <= KEEP_RUNS:
                        kept.append((vec, run))
                    size = max(size, self.sh._size_of(run))
                    ev = run.event_table  # (the elastic rule has no yields)
                    slips.update(ev[ev[:, hy.E_ACTION] == hy.ACT_YIELD, hy.E_INDEX].astype(int).tolist())
                    slips.update(self.sh.moved_surfaces(vec, np.asarray(run.vector)))
                    advance(1)
            except _Failed as exc:
                status, why = Status.STEP_FAILED, str(exc)
            except KeyboardInterrupt:
                status, ran = Status.INTERRUPTED, 0  # (stop now: no period counted)
            self.sh.scale_d = size
            keep = self.sh.spectrum_coordinates(slips)
            counted, hist, exps, recent, sections, final = self._count(
                keep, align, ran, kept if len(kept) == ran else self._periods(ran), advance)
        if counted < ran - align and status == Status.SUCCESS:
            status, why = self.stopped
        period = self._periodic(sections) if counted else 0
        if period:
            exps = self._floquet(recent[-period:], period)
        order = np.argsort(-exps, kind="stable")  # (largest first; the history's columns alike)
        exps, hist = exps[order], hist[:, order]
        labels = self.sh.labels()
        names = tuple(labels[i] for i in keep)
        message = self._message(status, why, align, cycles, counted, exps, period)
        out = LyapunovSpectrum(exps, names, hist, self.exc, counted, "exact" if self.sh.exact else
                               "finite-difference", period, final, status, message)
        if status == Status.INTERRUPTED:
            raise Interrupted(out, counted, cycles, "cycles")
        return out

    def _count(self, keep: np.ndarray, align: int, ran: int, periods: Any, advance: Any) -> tuple:
        """The tangent pass: ``(periods counted, history (counted, n), exponents, the last
        Jacobians, the last sections (D, V), the final state)``; a Ctrl-C or a failed run ends it
        (``self.stopped`` says which)."""
        w = self._metric(keep)
        w_inv = np.linalg.inv(w)
        q = np.eye(keep.size)
        block = np.ix_(keep, keep)
        logs = np.zeros(keep.size)
        history = np.full((max(ran - align, 0), keep.size), np.nan)
        recent: list[np.ndarray] = []  # the last MAX_PERIOD periods' Jacobians (for a periodic response)
        sections: list[np.ndarray] = []  # the last sections (D, V), the end of the last period included
        counted = 0
        final = self.sh._state(self.start)
        self.stopped = (Status.SUCCESS, "")
        with hy.one_blas_thread():
            try:
                for k, (vec, run) in enumerate(periods):
                    jac = w @ self._jacobian(vec, run)[block] @ w_inv
                    # Q R of the carried frame (LAPACK's, without numpy.linalg.qr's 35 us of Python)
                    qr, tau, _, _ = lapack.dgeqrf(jac @ q)
                    q = lapack.dorgqr(qr, tau)[0]
                    diag = np.diag(qr).copy()
                    q = q * np.where(diag < 0.0, -1.0, 1.0)  # (the frame keeps its orientation)
                    if k >= align:
                        d = np.abs(diag)
                        with np.errstate(divide="ignore"):
                            logs = logs + np.where(d > RESOLVED * d.max(), np.log(d), -np.inf)
                        history[counted] = logs / ((counted + 1) * self.period)
                        counted += 1
                        recent = (recent + [jac])[-MAX_PERIOD:]
                        sections = (sections + [self.sh.section(vec)])[-4 * MAX_PERIOD:]
                        final = run.final_state
                    advance(1)
            except _Failed as exc:  # (a perturbed run of the finite differences)
                self.stopped = (Status.STEP_FAILED, str(exc))
            except KeyboardInterrupt:
                self.stopped = (Status.INTERRUPTED, "")
        hist = history[:counted]
        exps = hist[-1].copy() if counted else np.full(keep.size, np.nan)
        if counted:
            sections.append(self.sh.section(np.asarray(final.vector)))
        return counted, hist, exps, recent, sections, final

    def _periodic(self, sections: list) -> int:
        """The response's period in forcing periods (the counted sections repeat with it to
        ``PERIODIC_RTOL`` of the motion's size), 0 when they do not (or too few were counted)."""
        if len(sections) <= 2 * MAX_PERIOD:
            return 0
        dv = np.array(sections)
        return int(periods(dv[None], np.array([self.sh.scale_d]), np.array([self.exc.omega_rad_s]),
                           MAX_PERIOD, PERIODIC_RTOL)[0])

    def _floquet(self, jacs: list, period: int) -> np.ndarray:
        """The exponents of a periodic response: ``ln|mu| / (period T)`` of the multipliers of the
        product of its last ``period`` Jacobians, largest first (-inf below ``RESOLVED``)."""
        prod = np.eye(jacs[0].shape[0])
        for jac in jacs:
            prod = jac @ prod
        mu = np.sort(np.abs(np.linalg.eigvals(prod)))[::-1]
        with np.errstate(divide="ignore"):
            return np.where(mu > RESOLVED**period * mu[0], np.log(mu), -np.inf) / (period * self.period)

    def _message(self, status: Status, why: str, align: int, cycles: int, counted: int,
                 exps: np.ndarray, period: int) -> str:
        if status == Status.INTERRUPTED:
            head = f"interrupted: {counted} of {cycles} periods counted"
        elif status != Status.SUCCESS:
            head = f"stopped after {counted} of {cycles} periods counted: {why}"
        else:
            head = f"{counted} periods counted after {align} to align the frame"
        if period:
            head += (f"; a periodic response (period {period}): the exponents are its Floquet multipliers' "
                     f"ln|mu| / ({period} T), the running estimates in history")
        erased = int(np.sum(np.isneginf(exps)))
        if erased:
            head += (f"; {erased} direction{'s' if erased > 1 else ''} erased by the map (-inf: a contact or "
                     "a slip slaves a coordinate, or a contraction beyond double precision in a period)")
        if self.fell_back:
            head += (f"; {self.fell_back} period{'s' if self.fell_back > 1 else ''} by finite differences "
                     "(an event met tangentially, or the exact propagation did not end where the engine did)")
        return head


def _modal_metric(a: np.ndarray, size: int, z_last: bool) -> np.ndarray:
    """``W`` (size, size) whose first block takes the masses' (x, v) to the real modal coordinates of the
    state matrix ``a`` (2n, 2n): each complex pair's ``(Re, Im)`` of its eigenvector (``Im lambda > 0``)
    scaled so that its largest displacement is ``1 / Im lambda``, in which the free motion is a rotation times
    its decay, so a linear system's frame vectors shrink at exactly their rates (one mass: ``(omega_d x,
    v + zeta omega_n x)``, whatever phase LAPACK gives the vector); the other coordinates (compressions,
    slips) in units of the slowest mode's frequency, and ``z`` (the last, when ``z_last``: of order 1 against
    lengths of a millimetre) a thousandth of it.  A system with a real mode (overdamped, or critically
    damped: its eigenvectors parallel) is measured as ``(omega x, v)``, ``omega`` its slowest undamped
    frequency (one mass: ``omega_n``)."""
    lam, vecs = np.linalg.eig(a)
    n = a.shape[0] // 2
    if (lam.imag == 0.0).any():
        omega = math.sqrt(max(float(np.linalg.eigvals(-a[n:, :n]).real.min()), 0.0))
        w = np.eye(size) * max(omega, 1e-6)
        w[n:2 * n, n:2 * n] = np.eye(n)
        if z_last:
            w[-1, -1] *= 1e-3
        return w
    cols, done = [], np.zeros(lam.size, dtype=bool)
    for i in np.argsort(np.abs(lam), kind="stable"):
        if done[i]:
            continue
        done[i] = True
        j = int(np.argmin(np.where(done, np.inf, np.abs(lam - lam[i].conj()))))
        done[j] = True
        k = i if lam[i].imag > 0.0 else j
        v = vecs[:, k]
        v = v / (v[int(np.argmax(np.abs(v[:n])))] * lam[k].imag)
        cols += [v.real, v.imag]
    t = np.array(cols).T
    n2 = a.shape[0]
    w = np.eye(size) * max(float(np.abs(lam).min()), 1e-6)
    w[:n2, :n2] = np.linalg.inv(t)
    if z_last:
        w[-1, -1] *= 1e-3
    return w


def largest_exponents(diagram: BifurcationDiagram, *, cycles: int = 200, align_cycles: int = 20,
                      method: str = "auto", progress: Progress = False) -> BifurcationDiagram:
    """A bifurcation diagram with the largest Lyapunov exponent of the response at every direction
    and frequency: :func:`lyapunov` from the state the diagram's sweep recorded from (its settled
    state at table phase 0), no transient.

    Parameters
    ----------
    diagram : BifurcationDiagram
        From :func:`pounding.bifurcation_diagram`.
    cycles : int
        Periods counted at every step (as :func:`lyapunov`'s).
    align_cycles : int
        Periods the tangent frame is carried first at every step.
    method : {"auto", "exact", "finite-difference"}
        The Jacobian of each period (as :func:`lyapunov`'s).
    progress : bool or callable
        True: a progress bar; a callable is called with the number of steps just finished.

    Returns
    -------
    BifurcationDiagram
        The same diagram, its dataset with ``largest_exponent`` (direction, freq_hz), 1/s: negative
        on a periodic response, positive on a chaotic one; NaN where the step did not run or the
        engine stopped the count. On
        Ctrl-C, :class:`pounding.Interrupted` carries it with the steps finished.

    Examples
    --------
    >>> import pounding
    >>> osc = pounding.presets.paper_damped()
    >>> d = pounding.bifurcation_diagram(osc, 0.05, [1.5, 2.5], direction="up",
    ...                                  transient_cycles=60, record_cycles=10)
    >>> d = pounding.largest_exponents(d, cycles=50)
    >>> (d.data["largest_exponent"] < 0).values.tolist()  # periodic: both stable
    [[True, True]]
    """
    instance_of("diagram", diagram, BifurcationDiagram,
                "pounding.BifurcationDiagram (from pounding.bifurcation_diagram)")
    cycles = integer("cycles", cycles, 1, MAX_CYCLES)
    align_cycles = integer("align_cycles", align_cycles, 0, MAX_CYCLES)
    exact_monodromy(diagram.oscillator, method)  # (checked once, before any step)
    ds = diagram.data
    dirs = ds["direction"].values.tolist()
    freqs = ds["freq_hz"].values
    out = np.full((len(dirs), freqs.size), np.nan)
    total = sum(sw.steps_done for sw in diagram.sweeps)

    def result() -> BifurcationDiagram:
        new = ds.assign(largest_exponent=(("direction", "freq_hz"), out.copy(),
                                          {"units": "1/s", "cycles": cycles, "method": method}))
        return replace(diagram, data=new)

    done = 0
    asm = assemble(diagram.oscillator)  # (a single mass: the one-level structure it is)
    layout, n_contacts = asm.layout, len(asm.pairs)

    def state_of(vec: np.ndarray) -> Any:
        return State._of(vec, asm.dofs, layout)

    with progress_reporter(progress, total, "largest Lyapunov exponents") as advance:
        try:
            for sw in diagram.sweeps:
                i = dirs.index(sw.direction)
                for f, vec in zip(sw.freqs_hz[:sw.steps_done], sw.window_states[:sw.steps_done]):
                    # (the window starts at table phase 0: the forcing's time 0, a contact in progress
                    # keeping its start relative to it)
                    start = at_section(np.array(vec, dtype=float), layout, n_contacts)
                    spec = lyapunov(diagram.oscillator, Harmonic(sw.a_g, float(f), g=sw.g), cycles=cycles,
                                    transient_cycles=0, align_cycles=align_cycles, state=state_of(start),
                                    method=method)
                    # (a count the engine cut short is no estimate: NaN, as a step not run)
                    out[i, np.searchsorted(freqs, f)] = spec.largest if spec.success else np.nan
                    done += 1
                    advance(1)
        except KeyboardInterrupt:
            raise Interrupted(result(), done, total, "steps") from None
    return result()
