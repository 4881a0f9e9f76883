"""A compiled matrix exponential for the exact monodromy's small matrices (a few rows).

``scipy.linalg.expm`` spends about 100 us of Python around LAPACK on a 7-by-7 matrix; a period's
monodromy takes one exponential per phase, and a Lyapunov spectrum or a continuation thousands of
periods.  This is the scaling-and-squaring algorithm with diagonal Padé approximants of degree 3 to
13 of Higham (2005), "The scaling and squaring method for the matrix exponential revisited", SIAM J.
Matrix Anal. Appl. 26(4), 1179-1193 (MATLAB's ``expm``, and SciPy's before 1.9): the degree is the
lowest whose bound ``theta_m`` holds the matrix's 1-norm, else the matrix is halved ``s`` times to
``theta_13`` and the approximant squared ``s`` times.  The matrix is balanced first (a diagonal
similarity by powers of 2): a stiff bumper's ``k / m`` beside the 1 of ``D' = V`` would otherwise
inflate the 1-norm and the squarings, and with them the rounding (5e-9 at ``k / m = 1e7``; 3e-14
balanced, as SciPy's 3e-15, against a 50-digit reference).  Products and the solve are loops: Numba's
``@`` and ``np.linalg.solve`` compile BLAS and LAPACK bindings, tens of seconds of a cold start for
matrices of a few rows.
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
def matmul(a, b):
    """``a @ b`` of small matrices (n, k) and (k, m) by loops: Numba's ``@`` compiles BLAS's
    bindings, tens of seconds of a cold start for products of a few rows."""
    n, k, m = a.shape[0], a.shape[1], b.shape[1]
    out = np.zeros((n, m))
    for i in range(n):
        for p in range(k):
            aip = a[i, p]
            if aip != 0.0:
                for j in range(m):
                    out[i, j] += aip * b[p, j]
    return out


@jit_alloc
def matvec(a, x):
    """``a @ x`` of a small matrix (n, k) and a vector (k,)."""
    out = np.zeros(a.shape[0])
    for i in range(a.shape[0]):
        acc = 0.0
        for p in range(a.shape[1]):
            acc += a[i, p] * x[p]
        out[i] = acc
    return out


@jit_alloc
def _solve(a, b):
    """``a^-1 b`` for a small square ``a`` (n, n) and ``b`` (n, m): Gaussian elimination with partial
    pivoting (LAPACK's ``getrf``/``getrs`` unblocked), by loops."""
    n, m = a.shape[0], b.shape[1]
    lu = a.copy()
    x = b.copy()
    for c in range(n):
        piv = c
        for r in range(c + 1, n):
            if abs(lu[r, c]) > abs(lu[piv, c]):
                piv = r
        if piv != c:
            for j in range(n):
                lu[c, j], lu[piv, j] = lu[piv, j], lu[c, j]
            for j in range(m):
                x[c, j], x[piv, j] = x[piv, j], x[c, j]
        for r in range(c + 1, n):
            f = lu[r, c] / lu[c, c]
            if f != 0.0:
                for j in range(c + 1, n):
                    lu[r, j] -= f * lu[c, j]
                for j in range(m):
                    x[r, j] -= f * x[c, j]
    for c in range(n - 1, -1, -1):
        for j in range(m):
            acc = x[c, j]
            for k in range(c + 1, n):
                acc -= lu[c, k] * x[k, j]
            x[c, j] = acc / lu[c, c]
    return x


@jit_alloc
def _diag(n, c):
    """``c I``, (n, n)."""
    out = np.zeros((n, n))
    for i in range(n):
        out[i, i] = c
    return out


@jit_alloc
def _add(out, c, m):
    """``out += c m`` in place, by loops (array expressions compile a shape-error path that
    formats strings: seconds of a cold start)."""
    for i in range(out.shape[0]):
        for j in range(out.shape[1]):
            out[i, j] += c * m[i, j]
    return out


@jit_alloc
def _balance(a):
    """``(b, d)``: ``b = D^-1 a D`` with ``D = diag(d)``, powers of 2, so that each row and column
    off the diagonal have comparable norms (LAPACK's ``gebal`` scaling, without permutations: exact
    in floating point).  A stiff bumper's ``k / m`` next to a 1 otherwise makes the 1-norm, and the
    squarings it asks for, thousands of times what the eigenvalues need."""
    n = a.shape[0]
    b = a.copy()
    d = np.ones(n)
    for _ in range(64):
        done = True
        for i in range(n):
            c = 0.0
            r = 0.0
            for j in range(n):
                if j != i:
                    c += abs(b[j, i])
                    r += abs(b[i, j])
            if c == 0.0 or r == 0.0:
                continue
            s = c + r
            f = 1.0
            while c < r / 2.0:
                f *= 2.0
                c *= 4.0
            while c > r * 2.0:
                f /= 2.0
                c /= 4.0
            if (c + r) / f < 0.95 * s:
                done = False
                d[i] *= f
                for j in range(n):
                    b[i, j] /= f
                    b[j, i] *= f
        if done:
            break
    return b, d


@jit_alloc
def expm_small(a):
    """``exp(a)`` of a small square float64 matrix ``a`` (n, n): balanced, then Higham's."""
    b, d = _balance(a)
    x = _pade_exponential(b)
    for i in range(x.shape[0]):
        for j in range(x.shape[1]):
            x[i, j] *= d[i] / d[j]
    return x


@jit_alloc
def _pade_exponential(a):
    """``exp(a)`` by scaling and squaring with the lowest adequate Padé degree (Higham 2005)."""
    n = a.shape[0]
    norm = 0.0
    for j in range(n):
        col = 0.0
        for i in range(n):
            col += abs(a[i, j])
        norm = max(norm, col)
    s = 0
    if norm > THETA[3]:  # degree 13, after halving s times
        s = max(0, int(math.ceil(math.log2(norm / THETA[4]))))
        a = _add(np.zeros((n, n)), 0.5**s, a)
    a2 = matmul(a, a)
    if norm <= THETA[0]:
        b = B3
        w = _add(_diag(n, b[1]), b[3], a2)
        v = _add(_diag(n, b[0]), b[2], a2)
    elif norm <= THETA[1]:
        b = B5
        a4 = matmul(a2, a2)
        w = _add(_add(_diag(n, b[1]), b[3], a2), b[5], a4)
        v = _add(_add(_diag(n, b[0]), b[2], a2), b[4], a4)
    elif norm <= THETA[2]:
        b = B7
        a4 = matmul(a2, a2)
        a6 = matmul(a4, a2)
        w = _add(_add(_add(_diag(n, b[1]), b[3], a2), b[5], a4), b[7], a6)
        v = _add(_add(_add(_diag(n, b[0]), b[2], a2), b[4], a4), b[6], a6)
    elif norm <= THETA[3]:
        b = B9
        a4 = matmul(a2, a2)
        a6 = matmul(a4, a2)
        a8 = matmul(a6, a2)
        w = _add(_add(_add(_add(_diag(n, b[1]), b[3], a2), b[5], a4), b[7], a6), b[9], a8)
        v = _add(_add(_add(_add(_diag(n, b[0]), b[2], a2), b[4], a4), b[6], a6), b[8], a8)
    else:
        b = B13
        a4 = matmul(a2, a2)
        a6 = matmul(a4, a2)
        w = matmul(a6, _add(_add(_add(np.zeros((n, n)), b[13], a6), b[11], a4), b[9], a2))
        w = _add(_add(_add(_add(w, b[7], a6), b[5], a4), b[3], a2), 1.0, _diag(n, b[1]))
        v = matmul(a6, _add(_add(_add(np.zeros((n, n)), b[12], a6), b[10], a4), b[8], a2))
        v = _add(_add(_add(_add(v, b[6], a6), b[4], a4), b[2], a2), 1.0, _diag(n, b[0]))
    u = matmul(a, w)
    x = _solve(_add(v.copy(), -1.0, u), _add(v, 1.0, u))
    for _ in range(s):
        x = matmul(x, x)
    return x
