"""Growable output buffers of the compiled kernel (rows of floats)."""

from __future__ import annotations

import numpy as np

from .._jit import jit, jit_alloc


@jit_alloc
def grow(buf, n):
    """``buf`` with room for row ``n``: twice as many rows once it is full.

    Callers test ``n >= buf.shape[0]`` first: a call costs reference counting.
    """
    if n < buf.shape[0]:
        return buf
    out = np.empty((2 * buf.shape[0], buf.shape[1]))
    for i in range(n):  # loops, not slice assignment: no shape-check code to compile
        for j in range(buf.shape[1]):
            out[i, j] = buf[i, j]
    return out


@jit
def put(buf, n, x0, x1, x2, x3, x4, x5, x6, x7, x8):
    """Write the first ``buf.shape[1]`` of these 9 values at row ``n``.

    Every call passes all nine (no defaults): one compiled version serves every buffer.
    """
    vals = (x0, x1, x2, x3, x4, x5, x6, x7, x8)
    for j in range(buf.shape[1]):
        buf[n, j] = vals[j]
