"""Lognormal fragility curves: the probability of an event given the intensity.

``P(E | IM = x) = Phi(ln(x / theta) / beta)``, with the median ``theta`` (g) and the
dispersion ``beta``, fitted by maximum likelihood:

- **stripes** (multiple-stripe analysis): at each intensity ``x_j``, ``k_j`` of ``n_j`` runs
  had the event; the likelihood is binomial, ``prod C(n_j, k_j) p_j^k_j (1 - p_j)^(n_j - k_j)``.
  That is a probit regression on ``ln x``, ``p = Phi(a + b ln x)`` (``beta = 1 / b``,
  ``theta = exp(-a / b)``), solved by Fisher scoring (Newton on the expected information) to
  machine precision.  The estimate exists only when the stripes overlap: some run survives at
  an intensity above one where another run had the event;
- **capacities** (incremental dynamic analysis): :mod:`.capacities`.

Confidence bands come from the bootstrap: runs resampled within each stripe (records resampled
for capacities), refitted, and the curves' pointwise percentiles.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy import special

from .._docs import fill_doc
from .._checks import float_array, integer, positive
from .._errors import InputError, Problem

MAX_SCORING_STEPS = 100
SCORING_TOL = 1e-13  # on the Newton step of (a, b)
LOG_SQRT_2PI = 0.5 * math.log(2.0 * math.pi)


@dataclass(frozen=True, eq=False)
class Fragility:
    """A lognormal fragility curve with its bootstrap (:func:`fit_fragility`,
    :func:`fit_fragility_capacities`).

    Attributes
    ----------
    median_g : float
        ``theta``: the intensity (g) at which the event has probability 0.5.
    beta : float
        The dispersion (the standard deviation of ``ln`` capacity).
    event : str
        What the curve is the probability of (a label).
    method : {"stripes", "capacities"}
    data : dict of numpy.ndarray
        What it was fitted to: ``im_g``, ``n_runs``, ``n_events`` (stripes) or ``capacity_g``,
        ``censored`` (capacities).
    bootstrap : numpy.ndarray, shape (b, 2)
        The refitted ``(median_g, beta)`` of each bootstrap sample (resamples without an
        estimate, whose stripes separate or are all-or-nothing, are kept as steps: ``beta`` 0 and
        the median at the separation, 0 when every run had the event and ``inf`` when none did).
    confidence : float
        The band's level (0.9: the 5-95 % percentiles).
    n_failed_resamples : int
        Bootstrap resamples without a finite estimate (kept as steps; a large share says the
        stripes hardly constrain the dispersion).

    Examples
    --------
    >>> from pounding import design
    >>> curve = design.fit_fragility([0.2, 0.4, 0.6, 0.8], [20, 20, 20, 20],
    ...                              [1, 7, 13, 17], event="pounding")
    >>> round(curve.probability(0.5), 3)
    0.528
    >>> [round(v, 2) for v in curve.interval()["median_g"]]  # 90 % band, g
    [0.42, 0.56]
    """

    median_g: float
    beta: float
    event: str
    method: str
    data: dict
    bootstrap: np.ndarray
    confidence: float
    n_failed_resamples: int = 0

    def probability(self, im_g: Any) -> Any:
        """``P(E | IM = im_g)`` at intensities (g, >= 0; scalar or array)."""
        x = np.asarray(im_g, dtype=float)
        if np.any(~(x >= 0.0)):
            raise InputError(Problem.NEGATIVE, "im_g", x.tolist() if x.ndim else float(x), unit="g")
        with np.errstate(divide="ignore"):
            p = special.ndtr(np.log(x / self.median_g) / self.beta)
        return float(p) if p.ndim == 0 else p

    def band(self, im_g: Any) -> tuple[np.ndarray, np.ndarray]:
        """The bootstrap band's lower and upper curves at intensities ``im_g`` (g), each of
        ``im_g``'s shape."""
        x = np.atleast_1d(np.asarray(im_g, dtype=float))
        if self.bootstrap.shape[0] == 0:
            p = self.probability(x)
            return p, p
        median, beta = self.bootstrap[:, :1], self.bootstrap[:, 1:]
        with np.errstate(divide="ignore", invalid="ignore"):
            curves = np.where(
                beta > 0.0,
                special.ndtr(np.log(x[None, :] / median) / np.where(beta > 0.0, beta, 1.0)),
                (x[None, :] >= median).astype(float),
            )
        tail = 50.0 * (1.0 - self.confidence)
        return np.percentile(curves, tail, axis=0), np.percentile(curves, 100.0 - tail, axis=0)

    def interval(self) -> dict[str, tuple[float, float]]:
        """The bootstrap percentile intervals of ``median_g`` and ``beta`` at ``confidence``."""
        tail = 50.0 * (1.0 - self.confidence)
        if self.bootstrap.shape[0] == 0:
            return {"median_g": (self.median_g, self.median_g), "beta": (self.beta, self.beta)}
        lo = np.percentile(self.bootstrap, tail, axis=0)
        hi = np.percentile(self.bootstrap, 100.0 - tail, axis=0)
        return {"median_g": (float(lo[0]), float(hi[0])), "beta": (float(lo[1]), float(hi[1]))}

    def to_xarray(self) -> Any:
        """The curve of :meth:`to_dataframe` as a Dataset on ``im_g``."""
        from .._tables import frame_to_xarray

        return frame_to_xarray(self.to_dataframe(), "row", index="im_g")

    def to_dataframe(self, im_g: Any = None) -> Any:
        """``im_g``, ``probability``, ``lower``, ``upper`` (the band) at ``im_g`` (default: 200
        intensities to 3 medians)."""
        import pandas as pd

        x = np.linspace(0.0, 3.0 * self.median_g, 201) if im_g is None else float_array("im_g", im_g)
        lo, hi = self.band(x)
        return pd.DataFrame({"im_g": x, "probability": self.probability(x), "lower": lo, "upper": hi})

    def plot(self, ax: Any = None, *, data: bool = True, **line: Any) -> Any:
        """The curve, its band and (``data``) the stripes' fractions or the capacities' empirical
        distribution; returns its Figure."""
        from ..plots.design import plot_fragility
        from ..plots import figure_of

        return figure_of(plot_fragility(self, ax=ax, data=data, **line), ax)

    def __repr__(self) -> str:
        ci = self.interval()
        return (
            f"Fragility({self.event or 'event'}: median {self.median_g:.4g} g "
            f"[{ci['median_g'][0]:.3g}, {ci['median_g'][1]:.3g}], beta {self.beta:.3g} "
            f"[{ci['beta'][0]:.3g}, {ci['beta'][1]:.3g}], {self.method}"
            + (
                f"; {self.n_failed_resamples} resamples without an estimate"
                if self.n_failed_resamples
                else ""
            )
            + ")"
        )


@fill_doc
def fit_fragility(
    im_g: Any,
    n_runs: Any,
    n_events: Any,
    *,
    event: str = "",
    n_bootstrap: int = 1000,
    confidence: float = 0.9,
    seed: int = 0,
) -> Fragility:
    """Fit a lognormal fragility curve to stripes by maximum likelihood (binomial likelihood).

    Parameters
    ----------
    im_g : array_like, shape (s,)
        The stripes' intensities (g), > 0, at least two distinct.
    n_runs : array_like of int, shape (s,)
        Runs at each stripe, >= 1.
    n_events : array_like of int, shape (s,)
        Runs with the event at each stripe, in ``[0, n_runs]``.
    event : str
        A label (e.g. ``"pounding"``).
    n_bootstrap : int
        Bootstrap resamples for the band (0: none).
    {band}

    Returns
    -------
    Fragility

    Raises
    ------
    InputError
        A bad argument, or stripes with no estimate: every run at the intensities up to some
        level without the event and every run above it with the event (the dispersion would be
        0), or no event at all, or the event in every run.

    Examples
    --------
    >>> from pounding import design
    >>> curve = design.fit_fragility([0.2, 0.4, 0.6, 0.8], [20, 20, 20, 20],
    ...                              [1, 7, 13, 17], event="pounding")
    >>> round(curve.median_g, 3), round(curve.beta, 3)
    (0.482, 0.518)
    """
    x = float_array("im_g", im_g)
    for i, v in enumerate(x):
        positive(f"im_g[{i}]", v, "g")
    n = _counts("n_runs", n_runs, x.size, 1)
    k = _counts("n_events", n_events, x.size, 0)
    over = np.flatnonzero(k > n)
    if over.size:
        i = int(over[0])
        raise InputError(
            Problem.OUT_OF_RANGE, f"n_events[{i}]", int(k[i]), range=f"[0, n_runs[{i}] = {n[i]}]"
        )
    if np.unique(x).size < 2:
        raise InputError(
            Problem.NO_FIT,
            "im_g",
            x.tolist(),
            why="has one intensity only, so the dispersion cannot be fitted",
            fix="run at least two intensity levels",
        )
    level = _confidence(confidence)
    n_reps = integer("n_bootstrap", n_bootstrap, 0, 100_000)
    rng = _seed(seed)
    a, b = _probit_fit(x, n, k)  # raises when there is no estimate
    median = math.exp(-a / b) if -a / b < 700.0 else math.inf
    if not math.isfinite(median):
        raise InputError(
            Problem.NO_FIT,
            "n_events",
            k.tolist(),
            why="puts the median beyond any intensity",
            fix="run stripes where the event happens",
        )
    reps, failed = _bootstrap_stripes(x, n, k, n_reps, rng, (a, b))
    return Fragility(
        median,
        float(1.0 / b),
        str(event),
        "stripes",
        {"im_g": x, "n_runs": n, "n_events": k},
        reps,
        level,
        failed,
    )


def _counts(field: str, values: Any, size: int, minimum: int) -> np.ndarray:
    arr = np.asarray(values)
    if arr.ndim != 1 or arr.size != size:
        raise InputError(
            Problem.SIZE_MISMATCH,
            field,
            f"array of shape {arr.shape}",
            got=arr.size,
            expected=size,
            other="im_g",
        )
    return np.array(
        [integer(f"{field}[{i}]", v, minimum) for i, v in enumerate(arr.tolist())], dtype=np.int64
    )


def _confidence(value: Any) -> float:
    c = positive("confidence", value, "(a fraction)")
    if c >= 1.0:
        raise InputError(Problem.OUT_OF_RANGE, "confidence", value, range="(0, 1)", hint=" (0.9 is 90 %)")
    return c


def _seed(seed: Any) -> np.random.Generator:
    return np.random.default_rng(integer("seed", seed, 0))


def _overlap(x: np.ndarray, n: np.ndarray, k: np.ndarray) -> tuple[float, float]:
    """The highest intensity with a survivor and the lowest with an event: the maximum-likelihood
    estimate exists when the first is above the second (no separation)."""
    survivors = x[k < n]
    events = x[k > 0]
    return (
        float(survivors.max()) if survivors.size else -math.inf,
        float(events.min()) if events.size else math.inf,
    )


def _probit_fit(x: np.ndarray, n: np.ndarray, k: np.ndarray) -> tuple[float, float]:
    """``(a, b)`` of ``p = Phi(a + b ln x)`` maximising the binomial likelihood (Fisher scoring)."""
    high_survivor, low_event = _overlap(x, n, k)
    if not high_survivor > low_event:
        if math.isinf(low_event):
            why = "has no run with the event, so the curve lies beyond the intensities run"
        elif math.isinf(high_survivor):
            why = "has the event in every run, so the curve lies below the intensities run"
        else:
            why = (
                f"separates: no run below {low_event:g} g has the event and no run above {high_survivor:g} g "
                "is without it, so the dispersion has no estimate (it would be 0)"
            )
        raise InputError(
            Problem.NO_FIT,
            "n_events",
            k.tolist(),
            why=why,
            fix="add stripes where some runs have the event and others not",
        )
    u = np.log(x)
    f = k / n
    # start from least squares on the probits of the fractions, pulled into (0, 1)
    z = special.ndtri(np.clip((k + 0.5) / (n + 1.0), 1e-6, 1.0 - 1e-6))
    b, a = np.polyfit(u, z, 1, w=np.sqrt(n)) if np.ptp(z) > 0 else (1.0, -float(np.mean(u)))
    if not b > 0:
        a, b = -float(np.average(u, weights=n)) / 0.5, 1.0 / 0.5
    for _ in range(MAX_SCORING_STEPS):
        eta = a + b * u
        p = np.clip(special.ndtr(eta), 1e-300, 1.0 - 1e-16)
        phi = np.exp(-0.5 * eta * eta - LOG_SQRT_2PI)
        w = n * phi * phi / (p * (1.0 - p))  # the expected information's weights
        score_eta = n * phi * (f - p) / (p * (1.0 - p))
        grad = np.array([score_eta.sum(), (score_eta * u).sum()])
        info = np.array([[w.sum(), (w * u).sum()], [(w * u).sum(), (w * u * u).sum()]])
        step = np.linalg.solve(info, grad)
        # keep the likelihood rising (halve a step that overshoots)
        ll0 = _loglik(a, b, u, n, k)
        for _ in range(60):
            if _loglik(a + step[0], b + step[1], u, n, k) >= ll0 - 1e-12 * abs(ll0):
                break
            step = step / 2.0
        a, b = a + step[0], b + step[1]
        if abs(step[0]) + abs(step[1]) * (1.0 + abs(u).max()) < SCORING_TOL * (1.0 + abs(a) + abs(b)):
            break
    if not b > 0:  # the event less likely at higher intensity: not a fragility
        raise InputError(
            Problem.NO_FIT,
            "n_events",
            k.tolist(),
            why="falls as the intensity rises, so no lognormal fragility fits it",
            fix="check the stripes' order and counts",
        )
    return float(a), float(b)


def _loglik(a: float, b: float, u: np.ndarray, n: np.ndarray, k: np.ndarray) -> float:
    eta = a + b * u
    return float(np.sum(k * special.log_ndtr(eta) + (n - k) * special.log_ndtr(-eta)))


def _bootstrap_stripes(
    x: np.ndarray,
    n: np.ndarray,
    k: np.ndarray,
    reps: int,
    rng: np.random.Generator,
    start: tuple[float, float],
) -> tuple[np.ndarray, int]:
    """Runs resampled within each stripe (the counts binomial with the stripe's fraction), each
    resample refitted (:func:`refit_stripes`)."""
    draws = rng.binomial(n[None, :], (k / n)[None, :], size=(reps, x.size))
    return refit_stripes(x, np.broadcast_to(n, draws.shape), draws, start)


def refit_stripes(
    x: np.ndarray, runs: np.ndarray, events: np.ndarray, start: tuple[float, float]
) -> tuple[np.ndarray, int]:
    """The ``(median_g, beta)`` of each resample (rows of ``runs`` and ``events``, shape
    (resamples, stripes)): Fisher scoring on all at once from ``start``, the scalar fit for any
    that did not converge; resamples without an estimate kept as steps (``beta`` 0).  Returns the
    fits and the number of resamples without one."""
    reps = runs.shape[0]
    xs = np.broadcast_to(x, runs.shape)
    survivor = np.where(events < runs, xs, -np.inf).max(axis=1)
    first = np.where(events > 0, xs, np.inf).min(axis=1)
    separated = ~(survivor > first)
    steps = (
        np.array([_step_median(x, nb, kb) for nb, kb in zip(runs[separated], events[separated])])
        if separated.any()
        else np.empty((0, 2))
    )
    n, fits = runs[~separated], events[~separated]  # the others have no estimate: kept as steps
    u = np.log(x)
    with np.errstate(all="ignore"):
        f = np.where(n > 0, fits / np.where(n > 0, n, 1), 0.0)
    a = np.full(fits.shape[0], start[0])
    b = np.full(fits.shape[0], start[1])
    done = np.zeros(fits.shape[0], dtype=bool)
    with np.errstate(all="ignore"):
        for _ in range(MAX_SCORING_STEPS):
            eta = a[:, None] + b[:, None] * u
            p = np.clip(special.ndtr(eta), 1e-300, 1.0 - 1e-16)
            phi = np.exp(-0.5 * eta * eta - LOG_SQRT_2PI)
            w = n * phi * phi / (p * (1.0 - p))
            score = n * phi * (f - p) / (p * (1.0 - p))
            g0, g1 = score.sum(axis=1), (score * u).sum(axis=1)
            i00, i01, i11 = w.sum(axis=1), (w * u).sum(axis=1), (w * u * u).sum(axis=1)
            det = i00 * i11 - i01 * i01
            da = (i11 * g0 - i01 * g1) / det
            db = (i00 * g1 - i01 * g0) / det
            a, b = np.where(done, a, a + da), np.where(done, b, b + db)
            done |= np.abs(da) + np.abs(db) * (1.0 + np.abs(u).max()) < SCORING_TOL * (
                1.0 + np.abs(a) + np.abs(b)
            )
            if done.all():
                break
    with np.errstate(all="ignore"):  # (a median beyond floating point: that resample is dropped)
        out = np.column_stack([np.exp(-a / b), 1.0 / b])
        for i in np.flatnonzero(~done | ~(b > 0) | ~np.isfinite(out).all(axis=1)):
            keep = n[i] > 0
            try:
                ai, bi = _probit_fit(x[keep], n[i][keep], fits[i][keep])
                out[i] = (np.exp(-ai / bi), 1.0 / bi)
            except InputError:
                out[i] = np.nan
    out = out[np.isfinite(out).all(axis=1) & (out[:, 1] > 0.0)]
    failed = reps - out.shape[0]  # (the steps, and any resample whose fractions fall: left out)
    return np.vstack([out, steps]), failed


def _step_median(x: np.ndarray, n: np.ndarray, k: np.ndarray) -> tuple[float, float]:
    """The limit of the likelihood for stripes that separate: a step (``beta`` 0) at the geometric
    mean of the last stripe without the event in any run and the first with it in every run (at a
    mixed stripe between them, there); 0 when every run had the event, ``inf`` when none did.
    Stripes without runs are left out."""
    x, n, k = x[n > 0], n[n > 0], k[n > 0]
    if k.sum() == 0:
        return (math.inf, 0.0)
    if (k == n).all():
        return (0.0, 0.0)
    below = x[k == 0].max(initial=0.0)
    above = x[k == n].min(initial=math.inf)
    mixed = x[(k > 0) & (k < n)]
    if mixed.size:
        return (float(mixed.min()), 0.0)
    if below <= 0.0:
        return (float(above), 0.0)
    if not math.isfinite(above):
        return (float(below), 0.0)
    return (math.sqrt(below * above), 0.0)
