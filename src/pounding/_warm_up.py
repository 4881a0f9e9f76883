"""``warm_up``: compile the engine now, rather than in the first call of a session.

The compiled kernels are built by Numba on their first call: after installing, that takes
about a minute on an idle 2-core machine (68 s for all of them one after the other; 50-70 s for
``warm_up``, which compiles two groups in two processes at once; ``benchmarks/RESULTS.md``: where
the time goes), and Numba caches the result on disk (next to the sources, or in
``NUMBA_CACHE_DIR``), so that later sessions, worker processes included, load it in about 3 s.
``warm_up`` (or ``pounding warm-up``) pays that once, e.g. when a Docker image or a cluster's
environment is built.
"""

from __future__ import annotations

import os
import time
from dataclasses import dataclass

import numpy as np

from ._checks import integer


@dataclass(frozen=True)
class WarmUp:
    """What :func:`warm_up` did.

    Attributes
    ----------
    seconds : float
        Wall time of the warm-up, s.
    compiled : tuple of str
        Kernels compiled now (and written to Numba's cache).
    loaded : tuple of str
        Kernels loaded from Numba's cache.
    in_memory : tuple of str
        Kernels this process had already compiled or loaded.
    cache_dirs : tuple of str
        Where Numba keeps the compiled kernels.
    workers : int
        Worker processes that compiled kernels (0: this process compiled whatever was missing).

    Examples
    --------
    >>> import pounding
    >>> done = pounding.warm_up()
    >>> # every kernel, one way or another
    >>> names = sorted(set(done.compiled + done.loaded + done.in_memory))
    >>> print(", ".join(names[:3]))
    impact_row, law_force_many, monodromy_kernel
    >>> print(", ".join(names[3:]))
    run_kernel, spectrum_kernel, step_kernel
    >>> len(done.cache_dirs) > 0  # where the cache is (its time: benchmarks/)
    True
    """

    seconds: float
    compiled: tuple[str, ...]
    loaded: tuple[str, ...]
    in_memory: tuple[str, ...]
    cache_dirs: tuple[str, ...]
    workers: int = 0

    @property
    def message(self) -> str:
        """One line for people: what was compiled, loaded or already there, in how long."""
        parts = []
        for names, done in ((self.compiled, "compiled and cached"),
                            (self.loaded, "loaded from Numba's cache"),
                            (self.in_memory, "already in memory")):
            if names:
                parts.append(f"{len(names)} {'kernel' if len(names) == 1 else 'kernels'} {done}")
        at_once = f"in {self.workers} processes at once, " if self.workers > 1 else ""
        return f"{', '.join(parts)} ({at_once}{self.seconds:.1f} s)"


def _kernels() -> dict:
    """The compiled entry points Python calls, by name."""
    from .analysis._hybrid import monodromy_kernel
    from .engine._kernel import run_kernel
    from .excitation._spectrum_kernel import spectrum_kernel
    from .metrics._impacts import impact_row
    from .model.contact_laws import law_force_many
    from .protocols._step_kernel import step_kernel

    return {"run_kernel": run_kernel, "step_kernel": step_kernel, "impact_row": impact_row,
            "law_force_many": law_force_many, "spectrum_kernel": spectrum_kernel,
            "monodromy_kernel": monodromy_kernel}


def kernels_cached(names: tuple[str, ...] = ("run_kernel", "step_kernel")) -> bool:
    """Whether Numba's cache holds these kernels for the current sources (so that the first
    call loads them in a few seconds instead of compiling for about a minute).

    Reads Numba's cache index (an internal of Numba's: any surprise there answers True, so
    that callers at worst skip a notice).
    """
    kernels = _kernels()
    try:
        return all(bool(kernels[n]._cache._cache_file._load_index()) for n in names)
    except Exception:  # noqa: BLE001 - a notice, never a failure
        return True


def _counts(kernels: dict) -> dict:
    return {name: (sum(k.stats.cache_hits.values()), sum(k.stats.cache_misses.values()))
            for name, k in kernels.items()}


# The kernels in two groups that share no compiled code but small helpers: when neither is in
# Numba's cache, each compiles in a process of its own (the first group about 45 s, the second
# about 25 s on an idle 2-core machine: benchmarks/RESULTS.md)
GROUPS = (("run_kernel", "step_kernel", "impact_row"),
          ("monodromy_kernel", "spectrum_kernel", "law_force_many"))


def _exercise(names: tuple[str, ...]) -> None:
    """Call what compiles each named kernel, with the argument types of real use."""
    from . import presets
    from .analysis._hybrid import Hybrid, monodromy
    from .engine import State, simulate
    from .engine._layout import EVENT_COLS
    from .excitation import Harmonic, Record
    from .excitation.spectrum import response_spectrum
    from .identification.contact_law import _force
    from .protocols import sweep

    osc = presets.paper_printed()
    start = State.at_rest(osc, velocity_m_s=0.6)
    if {"run_kernel", "step_kernel", "impact_row"} & set(names):
        run = simulate(osc, Harmonic(0.05, 2.2), 0.5, start, sample_rate_hz=100.0)
        _ = run.impacts  # the impact table's kernel
    if "step_kernel" in names:
        sweep(osc, 0.05, [2.0], steady="fixed", cycles=2, measure_cycles=1, progress=False)
    if "law_force_many" in names:
        _force(osc.bumpers.left, np.array([0.0, 1e-3]), np.array([0.1, -0.1]))
    if "spectrum_kernel" in names:
        response_spectrum(Record([0.0, 0.01, 0.02], [0.0, 1.0, 0.0]), [0.5])
    if "monodromy_kernel" in names:  # (periodic orbits, continuation, Lyapunov exponents)
        monodromy(Hybrid.of(osc), np.array(start.vector), np.empty((0, EVENT_COLS)), 0.1, 13.8, 0.49, 0.0)


def _compile_group(names: tuple[str, ...]) -> tuple[str, ...]:
    """In a worker process: compile (or load) the named kernels; the names it compiled."""
    kernels = _kernels()
    before = _counts(kernels)
    _exercise(names)
    after = _counts(kernels)
    return tuple(n for n in kernels if after[n][1] > before[n][1])


def _usable_cpus() -> int:
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # (not on every platform)
        return os.cpu_count() or 1


def _in_parallel(groups: list[tuple[str, ...]]) -> tuple[str, ...]:
    """Compile the groups in worker processes, one each; the kernels they compiled.  A group
    whose worker failed, or all of them where processes cannot be started, is left to the caller,
    which compiles what it finds missing; Ctrl-C stops the workers at once.

    The workers are fresh interpreters (``python -c``), not ``multiprocessing``'s: those import the
    caller's main script again, which a script read from standard input does not allow.
    """
    import json
    import subprocess
    import sys

    env = dict(os.environ)
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))  # (this pounding, first)
    env["PYTHONPATH"] = os.pathsep.join([root, *filter(None, [env.get("PYTHONPATH")])])
    workers: list[subprocess.Popen] = []
    done: list[str] = []
    try:
        for group in groups:
            code = ("import json\nfrom pounding._warm_up import _compile_group\n"
                    f"print(json.dumps(_compile_group({tuple(group)!r})))")
            workers.append(subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE,
                                            stderr=subprocess.DEVNULL, text=True, env=env))
        for worker in workers:
            out, _ = worker.communicate()
            if worker.returncode == 0:
                try:
                    done.extend(json.loads(out.strip().splitlines()[-1]))
                except (ValueError, IndexError):  # (that group compiles here instead)
                    pass
    except OSError:  # (no process could be started: this one compiles)
        pass
    finally:
        for worker in workers:  # (interrupted: nothing of theirs to wait for)
            if worker.poll() is None:
                worker.kill()
                worker.wait()
    return tuple(done)


def warm_up(workers: int | None = None) -> WarmUp:
    """Compile (or load from Numba's cache) every kernel pounding runs, now.

    Runs a short simulation, one sweep step, the impact table, a contact-law force
    evaluation of the printed system, a one-period elastic response spectrum and a monodromy
    matrix, with the argument types of real use, so that no later call compiles anything.  The
    kernels missing from the cache compile in two worker processes at once where two CPUs are
    free: the first time after installing this takes 50-70 s on an idle 2-core machine (about 70 s
    one after the other); afterwards about 3 s per new process (the cache is read).

    Parameters
    ----------
    workers : int, optional
        Processes compiling at once: 1 compiles everything in this process; the default is the
        number of kernel groups (2) or of CPUs this process may use, whichever is smaller (more
        than 2 changes nothing: there are two groups).

    Returns
    -------
    WarmUp
        The time taken and which kernels were compiled or loaded (``.message`` says it).

    Examples
    --------
    Once per environment (e.g. when building a Docker image), or at the start of a session:

    >>> import pounding
    >>> # about a minute the first time after installing, then a few seconds
    >>> done = pounding.warm_up()
    >>> again = pounding.warm_up()  # the same process: nothing left to do
    >>> again.compiled, again.loaded, len(again.in_memory)
    ((), (), 6)
    >>> # the first: e.g. "6 kernels compiled and cached
    >>> # (in 2 processes at once, 55.1 s)"
    >>> print(again.message)
    6 kernels already in memory (... s)
    """
    if workers is None:
        workers = min(len(GROUPS), _usable_cpus())
    else:
        workers = integer("workers", workers, 1, 64)
    kernels = _kernels()
    t0 = time.perf_counter()
    elsewhere: tuple[str, ...] = ()
    to_compile = [g for g in GROUPS if any(not kernels[n].signatures and not kernels_cached((n,)) for n in g)]
    if workers > 1 and len(to_compile) > 1:
        elsewhere = _in_parallel(to_compile[:workers])
    before = _counts(kernels)
    _exercise(tuple(kernels))
    seconds = time.perf_counter() - t0
    after = _counts(kernels)
    here = tuple(n for n in kernels if after[n][1] > before[n][1])
    compiled = tuple(n for n in kernels if n in here or n in elsewhere)
    loaded = tuple(n for n in kernels if after[n][0] > before[n][0] and n not in compiled)
    in_memory = tuple(n for n in kernels if n not in loaded and n not in compiled)
    dirs = tuple(sorted({k.stats.cache_path for k in kernels.values()}))
    return WarmUp(seconds=seconds, compiled=compiled, loaded=loaded, in_memory=in_memory, cache_dirs=dirs,
                  workers=len(to_compile[:workers]) if elsewhere else 0)
