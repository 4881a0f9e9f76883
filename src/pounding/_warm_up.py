"""``warm_up``: compile the engine now, rather than in the first call of a session.

The compiled kernels are built by Numba on their first call: after installing, that takes
about a minute on an idle 2-core machine (55 s measured; ``benchmarks/RESULTS.md``: where the time
goes), and Numba
caches the result on disk (next to the sources, or in ``NUMBA_CACHE_DIR``), so that later
sessions, worker processes included, load it in about 3 s.  ``warm_up`` (or ``pounding
warm-up``) pays that once, e.g. when a Docker image or a cluster's environment is built.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np


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

    @property
    def message(self) -> str:
        """One line for people: what was compiled, loaded or already there, in how long."""
        parts = []
        for names, done in ((self.compiled, "compiled and cached"),
                            (self.loaded, "loaded from Numba's cache"),
                            (self.in_memory, "already in memory")):
            if names:
                parts.append(f"{len(names)} {'kernel' if len(names) == 1 else 'kernels'} {done}")
        return f"{', '.join(parts)} ({self.seconds:.1f} s)"


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


def warm_up() -> WarmUp:
    """Compile (or load from Numba's cache) every kernel pounding runs, now.

    Runs a short simulation, one sweep step, the impact table, a contact-law force
    evaluation of the printed system and a one-period elastic response spectrum, with the argument types of
    real use, so that no
    later call compiles anything.  The first time after installing this takes about a minute on an
    idle 2-core machine; afterwards about 3 s per new process (the cache is read).

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
    >>> # the first: e.g. "6 kernels compiled and cached (55.4 s)"
    >>> print(again.message)
    6 kernels already in memory (... s)
    """
    from . import presets
    from .analysis._hybrid import Hybrid, monodromy
    from .engine import State, simulate
    from .excitation import Harmonic, Record
    from .excitation.spectrum import response_spectrum
    from .identification.contact_law import _force
    from .protocols import sweep

    kernels = _kernels()
    before = _counts(kernels)
    t0 = time.perf_counter()
    osc = presets.paper_printed()
    run = simulate(osc, Harmonic(0.05, 2.2), 0.5, State.at_rest(osc, velocity_m_s=0.6),
                   sample_rate_hz=100.0)
    _ = run.impacts  # the impact table's kernel
    sweep(osc, 0.05, [2.0], steady="fixed", cycles=2, measure_cycles=1, progress=False)
    _force(osc.bumpers.left, np.array([0.0, 1e-3]), np.array([0.1, -0.1]))
    response_spectrum(Record([0.0, 0.01, 0.02], [0.0, 1.0, 0.0]), [0.5])  # the elastic spectrum's kernel
    # the exact monodromy's propagation (periodic orbits, continuation, Lyapunov exponents)
    monodromy(Hybrid.of(osc), np.array(run.final_state.vector), run.event_table[:0],
              run.final_state.time_s + 0.1, 13.8, 0.49, 0.0)
    seconds = time.perf_counter() - t0
    after = _counts(kernels)
    loaded = tuple(n for n in kernels if after[n][0] > before[n][0])
    compiled = tuple(n for n in kernels if after[n][1] > before[n][1])
    in_memory = tuple(n for n in kernels if n not in loaded and n not in compiled)
    dirs = tuple(sorted({k.stats.cache_path for k in kernels.values()}))
    return WarmUp(seconds=seconds, compiled=compiled, loaded=loaded, in_memory=in_memory, cache_dirs=dirs)
