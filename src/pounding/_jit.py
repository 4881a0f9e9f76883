"""The one place where Numba compilation flags are set.

Every compiled function of the engine is decorated with :data:`jit`.  ``fastmath`` stays
off everywhere: event location compares values against zero and relies on IEEE rounding.

Compile time (the cold start): Numba compiles a function once per distinct argument types,
and it types a Python-int constant argument, or a counter initialised from one, as a literal
of its own, and a read-only array as another type.  So compiled functions pass codes to each
other as ``np.int64`` constants (``engine/_layout.py``), counters start as ``np.int64(0)``,
arrays handed to kernels are writable, and slices are copied by element loops (a slice
assignment compiles a shape-error path that formats strings).  ``tests/test_compile.py``
fails when a dispatcher ends up with more than one signature.
"""

from __future__ import annotations

import numba

jit = numba.njit(cache=True, fastmath=False, nogil=True, error_model="numpy")
