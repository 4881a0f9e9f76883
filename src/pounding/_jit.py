"""The one place where Numba compilation flags are set.

Every compiled function of the engine is decorated with :data:`jit`.  ``fastmath`` stays
off everywhere: event location compares values against zero and relies on IEEE rounding.
"""

from __future__ import annotations

import numba

jit = numba.njit(cache=True, fastmath=False, nogil=True, error_model="numpy")
