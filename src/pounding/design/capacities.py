"""Lognormal fragility curves from capacities: each record's intensity at the event, exactly or
between two intensities (an incremental dynamic analysis on a grid of levels).

``ln theta`` and ``beta`` are the maximum-likelihood normal fit of the capacities' logarithms: the
mean and the ``1/n`` standard deviation when every capacity is known; a record that never had the
event up to the largest intensity run is right-censored (its likelihood ``1 - Phi``); a capacity
known only between two levels is interval-censored (``Phi(hi) - Phi(lo)``).  Bands come from the
bootstrap over records.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from scipy import optimize, special

from .._docs import fill_doc
from .._checks import integer, positive
from .._errors import InputError, Problem
from .fragility import LOG_SQRT_2PI, Fragility, _confidence, _seed


@fill_doc
def fit_fragility_capacities(
    capacity_g: Any,
    *,
    max_im_g: float | None = None,
    event: str = "",
    n_bootstrap: int = 1000,
    confidence: float = 0.9,
    seed: int = 0,
) -> Fragility:
    """Fit a lognormal fragility curve to capacities (incremental dynamic analysis).

    Parameters
    ----------
    capacity_g : array_like, shape (r,)
        Each record's intensity (g) at the event's first occurrence; ``inf`` for a record that
        did not have the event up to ``max_im_g`` (censored).
    max_im_g : float, optional
        The largest intensity run (needed when a capacity is ``inf``).
    event : str
        A label.
    n_bootstrap : int
        Bootstrap resamples (records drawn with replacement) for the band (0: none).
    {band}

    Returns
    -------
    Fragility

    Examples
    --------
    >>> from pounding import design
    >>> curve = design.fit_fragility_capacities([0.3, 0.45, 0.5, 0.7, 0.9])
    >>> round(curve.median_g, 4), round(curve.beta, 4)
    (0.5318, 0.3773)
    """
    c = np.asarray(capacity_g, dtype=float)
    if c.ndim != 1 or c.size < 2:
        raise InputError(Problem.TOO_SHORT, "capacity_g", f"array of shape {c.shape}", got=c.size, expected=2)
    censored = np.isposinf(c)
    for i, v in enumerate(c):
        if not censored[i]:
            positive(f"capacity_g[{i}]", v, "g")
    top = None
    if censored.any():
        if max_im_g is None:
            raise InputError(
                Problem.MISSING_INPUT,
                "max_im_g",
                None,
                what="the largest intensity run (g), which the records with capacity inf survived",
            )
        top = positive("max_im_g", max_im_g, "g")
        if np.any(c[~censored] > top):
            raise InputError(
                Problem.OUT_OF_RANGE,
                "capacity_g",
                float(c[~censored].max()),
                range=f"(0, {top:g}]",
                hint=" (max_im_g, the largest intensity run)",
            )
    if (~censored).sum() < 2:
        raise InputError(
            Problem.NO_FIT,
            "capacity_g",
            c.tolist(),
            why="has fewer than two records with the event",
            fix="run higher intensities, or more records",
        )
    level = _confidence(confidence)
    n_reps = integer("n_bootstrap", n_bootstrap, 0, 100_000)
    rng = _seed(seed)
    mu, beta = _lognormal_fit(c, censored, top)
    reps, failed = _bootstrap_capacities(c, censored, top, n_reps, rng)
    return Fragility(
        float(math.exp(mu)),
        float(beta),
        str(event),
        "capacities",
        {"capacity_g": c, "censored": censored},
        reps,
        level,
        failed,
    )


def _lognormal_fit(c: np.ndarray, censored: np.ndarray, top: float | None) -> tuple[float, float]:
    """``(mu, beta)`` of ``ln C ~ N(mu, beta^2)``: closed form without censoring, else the
    censored likelihood maximised from it."""
    logs = np.log(c[~censored])
    mu, beta = float(np.mean(logs)), float(np.std(logs))
    if beta <= 0.0:
        raise InputError(
            Problem.NO_FIT,
            "capacity_g",
            c.tolist(),
            why="has one value only among the records "
            "with the event, so the dispersion has no estimate (it would be 0)",
            fix="run intensities more finely, or more records",
        )
    if not censored.any():
        return mu, beta
    n_cens = int(censored.sum())
    log_top = math.log(top)

    def neg(theta: np.ndarray) -> tuple[float, np.ndarray]:
        # minus the log-likelihood of (mu, ln beta) and its gradient: the records with the event
        # by their density, the censored ones by 1 - Phi((ln top - mu) / beta)
        m, s = theta[0], math.exp(theta[1])
        r = (logs - m) / s
        w = (m - log_top) / s
        mills = math.exp(-0.5 * w * w - LOG_SQRT_2PI - float(special.log_ndtr(w)))  # phi(w) / Phi(w)
        ll = float(np.sum(-0.5 * r * r) - logs.size * math.log(s)) + n_cens * float(special.log_ndtr(w))
        d_m = float(np.sum(r)) / s + n_cens * mills / s
        d_ls = float(np.sum(r * r)) - logs.size - n_cens * mills * w
        return -ll, -np.array([d_m, d_ls])

    res = optimize.minimize(neg, [mu, math.log(beta)], jac=True, method="BFGS", options={"gtol": 1e-10})
    return float(res.x[0]), float(math.exp(res.x[1]))


def _bootstrap_capacities(
    c: np.ndarray, censored: np.ndarray, top: float | None, reps: int, rng: np.random.Generator
) -> tuple[np.ndarray, int]:
    out = np.empty((reps, 2))
    kept = 0
    for _ in range(reps):
        idx = rng.integers(0, c.size, c.size)
        cb, sb = c[idx], censored[idx]
        if (~sb).sum() < 2 or np.ptp(cb[~sb]) == 0.0:
            continue
        mu, beta = _lognormal_fit(cb, sb, top)
        out[kept] = (math.exp(mu), beta)
        kept += 1
    return out[:kept], reps - kept


@fill_doc
def fit_fragility_intervals(
    lower_g: Any,
    upper_g: Any,
    *,
    event: str = "",
    n_bootstrap: int = 200,
    confidence: float = 0.9,
    seed: int = 0,
) -> Fragility:
    """Fit a lognormal fragility curve to capacities known only between two intensities, by maximum
    likelihood (interval censoring): an incremental dynamic analysis on a grid of levels, where a
    record's capacity lies between the last level without the event and the first with it.

    Parameters
    ----------
    lower_g : array_like, shape (r,)
        Each record's highest intensity without the event (g), 0 when it had it at the first level.
    upper_g : array_like, shape (r,)
        Its lowest intensity with the event (g), ``inf`` when it never had it (right-censored).
    event : str
        A label.
    n_bootstrap : int
        Bootstrap resamples of the records (each a numerical fit: 200 by default).
    {band}

    Returns
    -------
    Fragility
        ``method`` ``"intervals"``; ``data`` holds ``lower_g`` and ``upper_g``.

    Examples
    --------
    Five records on levels 0.2, 0.4, 0.6 and 0.8 g:

    >>> from pounding import design
    >>> curve = design.fit_fragility_intervals([0.2, 0.4, 0.4, 0.6, 0.8],
    ...                                        [0.4, 0.6, 0.6, 0.8, float("inf")],
    ...                                        n_bootstrap=0)
    >>> round(curve.median_g, 3), round(curve.beta, 3)
    (0.559, 0.397)
    """
    lo = np.asarray(lower_g, dtype=float)
    hi = np.asarray(upper_g, dtype=float)
    if lo.ndim != 1 or lo.size < 2:
        raise InputError(Problem.TOO_SHORT, "lower_g", f"array of shape {lo.shape}", got=lo.size, expected=2)
    if hi.shape != lo.shape:
        raise InputError(
            Problem.SIZE_MISMATCH,
            "upper_g",
            f"array of shape {hi.shape}",
            got=hi.size,
            expected=lo.size,
            other="lower_g",
        )
    for i in range(lo.size):
        if not (np.isfinite(lo[i]) and lo[i] >= 0.0):
            raise InputError(Problem.NEGATIVE, f"lower_g[{i}]", float(lo[i]), unit="g")
        if not hi[i] > lo[i]:
            raise InputError(Problem.OUT_OF_RANGE, f"upper_g[{i}]", float(hi[i]), range=f"({lo[i]:g}, inf]")
    level = _confidence(confidence)
    n_reps = integer("n_bootstrap", n_bootstrap, 0, 100_000)
    rng = _seed(seed)
    mu, beta = _interval_fit(lo, hi)
    out = np.empty((n_reps, 2))
    kept = 0
    for _ in range(n_reps):
        idx = rng.integers(0, lo.size, lo.size)
        try:
            m, b = _interval_fit(lo[idx], hi[idx])
        except InputError:
            continue
        out[kept] = (math.exp(m), b)
        kept += 1
    return Fragility(
        float(math.exp(mu)),
        float(beta),
        str(event),
        "intervals",
        {"lower_g": lo, "upper_g": hi},
        out[:kept],
        level,
        n_reps - kept,
    )


def _interval_fit(lo: np.ndarray, hi: np.ndarray) -> tuple[float, float]:
    """``(mu, beta)`` maximising ``sum ln(Phi((ln hi - mu)/beta) - Phi((ln lo - mu)/beta))``."""
    with np.errstate(divide="ignore"):
        a, b = np.log(lo), np.log(hi)
    pairs = {(float(x), float(y)) for x, y in zip(lo, hi)}
    if len(pairs) < 2 or np.all(np.isinf(b)) or np.all(np.isinf(a)):
        raise InputError(
            Problem.NO_FIT,
            "upper_g",
            hi.tolist(),
            why="puts every record in the same interval, or "
            "all beyond or below the levels run, so the dispersion has no estimate",
            fix="run more levels, or more records",
        )
    finite = np.concatenate([a[np.isfinite(a)], b[np.isfinite(b)]])
    start = [float(np.mean(finite)), math.log(max(float(np.std(finite)), 0.1))]

    def neg(theta: np.ndarray) -> float:
        m, s = theta[0], math.exp(theta[1])
        zb, za = (b - m) / s, (a - m) / s
        lb, la = special.log_ndtr(zb), special.log_ndtr(za)
        # ln(Phi(zb) - Phi(za)), stable: the upper tail's form where both are high
        upper = special.log_ndtr(-za) + np.log1p(
            -np.exp(np.minimum(special.log_ndtr(-zb) - special.log_ndtr(-za), 0.0))
        )
        lower = lb + np.log1p(-np.exp(np.minimum(la - lb, 0.0)))
        return -float(np.sum(np.where(za > 0.0, upper, lower)))

    res = optimize.minimize(
        neg, start, method="Nelder-Mead", options={"xatol": 1e-10, "fatol": 1e-12, "maxiter": 4000}
    )
    beta = math.exp(res.x[1])
    if not res.success or not math.isfinite(res.fun) or beta < 1e-4:
        raise InputError(
            Problem.NO_FIT,
            "upper_g",
            hi.tolist(),
            why="gives no finite dispersion (the records' intervals separate)",
            fix="run more levels between the intervals, or more records",
        )
    return float(res.x[0]), beta
