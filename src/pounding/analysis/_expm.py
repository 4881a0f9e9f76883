"""A compiled matrix exponential for the exact monodromy's small matrices (a few rows).

``scipy.linalg.expm`` spends about 100 us of Python around LAPACK on a 7-by-7 matrix; a period's
monodromy takes one exponential per phase, and a Lyapunov spectrum or a continuation thousands of
periods.  This is the scaling-and-squaring algorithm with diagonal Padé approximants of degree 3 to
13 of Higham (2005), "The scaling and squaring method for the matrix exponential revisited", SIAM J.
Matrix Anal. Appl. 26(4), 1179-1193 (MATLAB's ``expm``, and SciPy's before 1.9): the degree is the
lowest whose bound ``theta_m`` holds the matrix's 1-norm, else the matrix is halved ``s`` times to
``theta_13`` and the approximant squared ``s`` times.  Its error is at the unit roundoff's level
(``tests/test_lyapunov.py`` compares it with SciPy's).
"""

from __future__ import annotations

import math

import numpy as np

from .._jit import jit_alloc

# theta_m: the largest 1-norm for which the degree-m approximant is accurate to the unit roundoff
THETA = (1.495585217958292e-2, 2.539398330063230e-1, 9.504178996162932e-1, 2.097847961257068e0,
         5.371920351148152e0)
B3 = (120.0, 60.0, 12.0, 1.0)
B5 = (30240.0, 15120.0, 3360.0, 420.0, 30.0, 1.0)
B7 = (17297280.0, 8648640.0, 1995840.0, 277200.0, 25200.0, 1512.0, 56.0, 1.0)
B9 = (17643225600.0, 8821612800.0, 2075673600.0, 302702400.0, 30270240.0, 2162160.0, 110880.0, 3960.0,
      90.0, 1.0)
B13 = (64764752532480000.0, 32382376266240000.0, 7771770303897600.0, 1187353796428800.0,
       129060195264000.0, 10559470521600.0, 670442572800.0, 33522128640.0, 1323241920.0, 40840800.0,
       960960.0, 16380.0, 182.0, 1.0)


@jit_alloc
def expm_small(a):
    """``exp(a)`` of a square float64 matrix ``a`` (n, n), C-contiguous."""
    n = a.shape[0]
    eye = np.eye(n)
    norm = 0.0
    for j in range(n):
        col = 0.0
        for i in range(n):
            col += abs(a[i, j])
        norm = max(norm, col)
    a2 = a @ a
    if norm <= THETA[3]:  # degree 3, 5, 7 or 9: no scaling
        if norm <= THETA[0]:
            b = B3
            u = a @ (b[3] * a2 + b[1] * eye)
            v = b[2] * a2 + b[0] * eye
        elif norm <= THETA[1]:
            b = B5
            a4 = a2 @ a2
            u = a @ (b[5] * a4 + b[3] * a2 + b[1] * eye)
            v = b[4] * a4 + b[2] * a2 + b[0] * eye
        elif norm <= THETA[2]:
            b = B7
            a4 = a2 @ a2
            a6 = a4 @ a2
            u = a @ (b[7] * a6 + b[5] * a4 + b[3] * a2 + b[1] * eye)
            v = b[6] * a6 + b[4] * a4 + b[2] * a2 + b[0] * eye
        else:
            b = B9
            a4 = a2 @ a2
            a6 = a4 @ a2
            a8 = a6 @ a2
            u = a @ (b[9] * a8 + b[7] * a6 + b[5] * a4 + b[3] * a2 + b[1] * eye)
            v = b[8] * a8 + b[6] * a6 + b[4] * a4 + b[2] * a2 + b[0] * eye
        return np.ascontiguousarray(np.linalg.solve(v - u, v + u))
    s = max(0, int(math.ceil(math.log2(norm / THETA[4]))))
    scale = 0.5**s
    a = a * scale
    a2 = a2 * (scale * scale)
    a4 = a2 @ a2
    a6 = a4 @ a2
    b = B13
    u = a @ (a6 @ (b[13] * a6 + b[11] * a4 + b[9] * a2) + b[7] * a6 + b[5] * a4 + b[3] * a2 + b[1] * eye)
    v = a6 @ (b[12] * a6 + b[10] * a4 + b[8] * a2) + b[6] * a6 + b[4] * a4 + b[2] * a2 + b[0] * eye
    x = np.ascontiguousarray(np.linalg.solve(v - u, v + u))
    for _ in range(s):
        x = x @ x
    return x
