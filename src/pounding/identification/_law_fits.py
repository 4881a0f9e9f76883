"""The least-squares fits behind :func:`~pounding.fit_contact_law`, one per kind of law: non-negative
least squares where the force is linear in the law's numbers (Kelvin-Voigt, Hunt-Crossley and Jankowski at
a fixed exponent, a multi-linear law at fixed breakpoints), searches over the rest (the breakpoints, an
elastic-plastic law's yield).  Each takes the contact's samples, checked: compressions ``d`` (m), rates
``v`` (m/s) and forces (N), shape (p,) each."""

from __future__ import annotations

import numpy as np

from .._errors import InputError, Problem
from ..engine.kernels import law_forces
from ..model.contact_laws import (ELASTIC_PLASTIC, MULTILINEAR_KINEMATIC, N_LAW_PARAMS, ContactLaw,
                                  HuntCrossley, Jankowski)

MIN_RATIO = 1e-6  # the elastic-plastic fit's least K2 / K1


def law_force(law: ContactLaw, d: np.ndarray, v: np.ndarray) -> np.ndarray:
    return law_forces(law.LAW_ID, law.params(), d, v)


def nnls_fit(d, v, force, exponent=None, law=HuntCrossley.TYPE):
    """Non-negative (stiffness, damping) and the residual norm: ``F = k d + c v`` (Kelvin-Voigt,
    ``exponent`` None), ``F = d^n (k + c v)`` (Hunt-Crossley) or ``F = k d^n + c d^((n-1)/2) v``
    while ``v > 0`` (Jankowski)."""
    if exponent is None:
        cols = np.column_stack([d, v])
    elif law == Jankowski.TYPE:
        cols = np.column_stack([d**exponent, d ** (0.5 * (exponent - 1.0)) * np.maximum(v, 0.0)])
    else:
        dn = d**exponent
        cols = np.column_stack([dn, dn * v])
    scale = np.linalg.norm(cols, axis=0)
    scale[scale == 0.0] = 1.0  # columns of very different sizes: solve the scaled problem
    from scipy.optimize import nnls  # here: scipy.optimize costs 0.3 s of `import pounding`

    (k, c), resid = nnls(cols / scale, force)
    return k / scale[0], c / scale[1], resid


def segments(d: np.ndarray, breakpoints: np.ndarray) -> np.ndarray:
    """How much of each compression lies on each branch: ``R(d) = segments @ slopes``, shape (n, m)."""
    edges = np.concatenate([[0.0], breakpoints, [np.inf]])
    return np.clip(d[:, None] - edges[None, :-1], 0.0, np.diff(edges)[None, :])


def multilinear_fit(d, v, force, breakpoints):
    """Non-negative slopes and damping of a multi-linear law with these breakpoints, and the
    residual norm (``F = segments(d) @ slopes + c v``)."""
    cols = np.column_stack([segments(d, breakpoints), v])
    scale = np.linalg.norm(cols, axis=0)
    scale[scale == 0.0] = 1.0
    from scipy.optimize import nnls

    x, resid = nnls(cols / scale, force)
    x = x / scale
    return x[:-1], x[-1], resid


def slip_column(d, b):
    """The strain (m) of a spring that slips at +-``b`` along the path ``d`` from the unloaded
    bumper: a kinematic law's softening, per N/m of it."""
    p = np.zeros(N_LAW_PARAMS)
    p[1], p[2], p[6] = 2.0, 1.0, b  # slopes (1, 0): the slipping spring alone
    return law_forces(MULTILINEAR_KINEMATIC, p, d, np.zeros_like(d))


def kinematic_fit(d, v, force, breakpoints):
    """Slopes and damping of a kinematic multi-linear law with these breakpoints, and the
    residual norm.  Its force is linear in ``k_lin``, each step's size and the damping, for each
    choice of which steps soften (a slipping spring) and which harden (an elastic ramp): every
    choice by non-negative least squares, the best kept."""
    from itertools import product

    from scipy.optimize import nnls

    slips = [slip_column(d, b) for b in breakpoints]
    ramps = [np.maximum(d - b, 0.0) for b in breakpoints]
    best = (np.inf, None, 0.0)
    for soft in product((True, False), repeat=len(breakpoints)):
        cols = np.column_stack([d, *[slips[i] if soft[i] else ramps[i] for i in range(len(soft))], v])
        scale = np.linalg.norm(cols, axis=0)
        scale[scale == 0.0] = 1.0
        x, resid = nnls(cols / scale, force)
        x = x / scale
        if resid < best[0]:
            slopes = [x[0] + sum(x[1 + i] for i in range(len(soft)) if soft[i])]
            for i in range(len(soft)):
                slopes.append(slopes[-1] - x[1 + i] if soft[i] else slopes[-1] + x[1 + i])
            best = (resid, np.maximum(np.array(slopes), 0.0), x[-1])
    return best[1], best[2], best[0]


def multilinear_search(d, v, force, n_branches, kinematic=False):
    """Breakpoints minimising the residual: Nelder-Mead on their fractions of the deepest
    compression, from a grid of starts (the residual is piecewise smooth in them)."""
    from itertools import combinations

    from scipy.optimize import minimize

    top = float(d.max())

    def breaks_of(u):
        return top * np.sort(np.clip(u, 1e-3, 1.0 - 1e-3))

    def cost(u):
        b = breaks_of(u)
        if np.any(np.diff(b) <= 1e-6 * top):
            return np.inf
        return (kinematic_fit if kinematic else multilinear_fit)(d, v, force, b)[2]

    grid = np.linspace(0.1, 0.9, 9)
    starts = sorted(combinations(grid, n_branches - 1), key=lambda u: cost(np.array(u)))[:3]
    best = min((minimize(cost, np.array(u), method="Nelder-Mead",
                         options={"xatol": 1e-10, "fatol": 0.0, "maxiter": 600 * n_branches})
                for u in starts),
               key=lambda r: r.fun)
    return breaks_of(best.x)


def elastic_plastic_force(k1, ratio, dy, d):
    p = np.zeros(N_LAW_PARAMS)
    p[:3] = k1, ratio * k1, dy
    return law_forces(ELASTIC_PLASTIC, p, d, d)


def elastic_plastic_search(d, force):
    """``(K1, K2, delta_y)`` of the elastic-plastic law closest to the path: the force is
    ``K1`` times that of the law with ``K1 = 1``, so a grid over ``delta_y`` and ``K2 / K1``
    with ``K1`` by linear least squares, then a local least-squares polish of all three (in
    logarithms, the ratio through a logistic: every trial stays a valid law)."""
    from scipy.optimize import least_squares

    d = np.ascontiguousarray(d)
    top = float(d.max())
    best = (np.inf, 0.0, 0.0, 0.0)
    for dy in top * np.geomspace(0.01, 0.9, 15):
        for ratio in (0.003, 0.03, 0.1, 0.3, 0.6, 0.9):
            unit = elastic_plastic_force(1.0, ratio, dy, d)
            k1 = float(unit @ force) / max(float(unit @ unit), 1e-300)
            if k1 <= 0.0:
                continue
            cost = float(np.sum((force - k1 * unit) ** 2))
            if cost < best[0]:
                best = (cost, k1, ratio, dy)
    if not np.isfinite(best[0]):
        raise InputError(Problem.NO_FIT, "force_n", "the forces given",
                         why="fit no elastic-plastic law (they fall as the bumper is compressed)",
                         fix="give the force the bumper pushes with, positive in compression")
    _, k1, ratio, dy = best

    def ratio_of(u):  # K2 / K1 kept in [1e-6, 1 - 1e-6]: a valid law, and no degenerate flat line
        return float(np.clip(1.0 / (1.0 + np.exp(-u)), MIN_RATIO, 1.0 - MIN_RATIO))

    def resid(x):
        return elastic_plastic_force(np.exp(x[0]), ratio_of(x[1]), np.exp(x[2]), d) - force

    x0 = np.array([np.log(k1), np.log(ratio / (1.0 - ratio)), np.log(dy)])
    x = least_squares(resid, x0, x_scale=1.0, xtol=1e-14, ftol=1e-14, gtol=1e-14, diff_step=1e-7).x
    return float(np.exp(x[0])), float(np.exp(x[0]) * ratio_of(x[1])), float(np.exp(x[2]))
