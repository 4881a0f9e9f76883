"""The one place where Numba compilation flags are set.

Every compiled function of the engine is decorated with :data:`jit`.  ``fastmath`` stays
off everywhere: event location compares values against zero and relies on IEEE rounding.

Compile time (the cold start): Numba compiles a function once per distinct argument types,
and it types a Python-int constant argument, or a counter initialised from one, as a literal
of its own, and a read-only array as another type.  So compiled functions pass codes to each
other as ``np.int64`` constants (``engine/_layout.py``), counters start as ``np.int64(0)``,
arrays handed to kernels are writable, and slices are copied by element loops (a slice
assignment compiles a shape-error path that formats strings).  ``tests/test_compile.py``
fails when a dispatcher ends up with more than one signature.  Functions that only compiled
code calls get no Python wrapper and no reference counting (:data:`jit`, or :data:`jit_alloc`
when they allocate); the entry points keep both (:data:`jit_entry`).

Stale caches: Numba keys a cached function to its own file only, so a kernel cached before
a callee in *another* file changed (``step_kernel`` in ``protocols/`` holds the engine's code;
every kernel reads the index constants of ``engine/_layout.py``) would load with the old
code, silently (a shifted phase-record index gave wrong contacts, once).  So at import,
:func:`clear_stale_caches` compares the size and time of every source file of the package
with what they were when the caches next to them were written, and deletes those caches when
any differs.  With ``NUMBA_CACHE_DIR`` set, clear that folder after editing the sources.
"""

from __future__ import annotations

import os
from pathlib import Path

import numba

PACKAGE = Path(__file__).resolve().parent
STAMP = "numba-sources.stamp"  # in the package's __pycache__: the sources the caches were built from


# where the compiled functions live
COMPILED = ("engine", "excitation", "model", "metrics", "protocols", "_jit.py", "_control.py")


def _sources_stamp(root: Path) -> str:
    """Every ``.py`` file of the compiled parts below ``root`` with its size and modification
    time, one line each."""
    lines = []
    paths = [p for part in COMPILED for p in ((root / part).rglob("*.py") if (root / part).is_dir()
                                              else [root / part] if (root / part).is_file() else [])]
    for path in sorted(paths):
        st = path.stat()
        lines.append(f"{path.relative_to(root)} {st.st_size} {st.st_mtime_ns}")
    return "\n".join(lines)


def clear_stale_caches(root: Path = PACKAGE) -> bool:
    """Delete Numba's cache files below ``root`` when any source file below it changed since
    they were written (the stamp in ``root/__pycache__``); True when it deleted them.

    Does nothing where the folder is not writable (an installed release: its files change
    together, and Numba then keeps its caches elsewhere) or with ``NUMBA_CACHE_DIR`` set.
    """
    if os.environ.get("NUMBA_CACHE_DIR"):
        return False
    stamp_file = root / "__pycache__" / STAMP
    try:
        now = _sources_stamp(root)
        if stamp_file.is_file() and stamp_file.read_text() == now:
            return False
        cleared = False
        for cache in (*root.rglob("*.nbi"), *root.rglob("*.nbc")):
            cache.unlink(missing_ok=True)
            cleared = True
        stamp_file.parent.mkdir(exist_ok=True)
        tmp = stamp_file.with_suffix(f".tmp{os.getpid()}")
        tmp.write_text(now)
        tmp.replace(stamp_file)
        return cleared
    except OSError:  # read-only, or another process at it: Numba's own checks remain
        return False


clear_stale_caches()

_FLAGS = dict(cache=True, fastmath=False, nogil=True, error_model="numpy")

jit_entry = numba.njit(**_FLAGS)
"""For the kernels Python calls (``run_kernel``, ``step_kernel``, ...)."""

jit = numba.njit(**_FLAGS, no_cpython_wrapper=True, no_cfunc_wrapper=True, _nrt=False)
"""For everything only compiled code calls and that allocates no array.

No Python wrapper is generated (about 2 s less cold start over the engine's functions);
calling one from Python raises a TypeError.  No reference counting either (Numba's
``_nrt=False``): with it every call that passed an array paid an atomic increment and
decrement, 12 % of a sweep's time in a profile, and the sweep runs 25 % faster without.
Such a function cannot create arrays (Numba refuses to compile it): use :data:`jit_alloc`.
"""

jit_alloc = numba.njit(**_FLAGS, no_cpython_wrapper=True, no_cfunc_wrapper=True)
"""For the compiled-only functions that allocate arrays (``np.empty`` and the like)."""
