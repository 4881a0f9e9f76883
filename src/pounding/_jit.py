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

Developers: Numba's cache does not notice when a cached kernel's callees in *other files*
change (``step_kernel`` in ``protocols/`` holds the engine's code from ``engine/``).  After
editing the engine, clear the caches (``find src -name '*.nb[ic]' -delete``) or set
``NUMBA_CACHE_DIR`` to a fresh folder; an installed release changes every file at once.
"""

from __future__ import annotations

import numba

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
