"""The runs of a multiple-stripe analysis and what they say of events: :class:`StripeAnalysis`
(made by :func:`pounding.design.stripe_analysis`)."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from .._checks import one_of, positive
from .._docs import fill_doc
from .._errors import InputError, Problem, Status
from .fragility import Fragility, fit_fragility

EVENTS = {
    "contact": "the mass reaches a bumper (with a limit: the peak displacement of a run without bumpers "
    "reaches that gap, m)",
    "acceleration": "the peak absolute acceleration exceeds the limit (g)",
    "compression": "a bumper is compressed beyond the limit (m; default: the bumpers' capacity_m)",
    "displacement": "the peak displacement exceeds the limit (m; the gap plus the bumper's stroke; a "
    "building's: its base's)",
    "drift": "a building's largest storey drift ratio exceeds the limit (e.g. 0.005)",
    "top_acceleration": "a building's top floor's peak absolute acceleration exceeds the limit (g)",
}
# each event's quantity in the store (every system's run's names: a building's displacement its base's)
_QUANTITY = {"contact": "disp_max_m", "acceleration": "acc_max_g", "compression": "compression_max_m",
             "displacement": "disp_max_m", "drift": "drift_ratio_max", "top_acceleration": "top_acc_max_g"}
RESERVED = ("sa_g", "record")


@fill_doc
@dataclass(frozen=True, eq=False)
class StripeAnalysis:
    """The runs of a multiple-stripe analysis, and what they say of events (:func:`stripe_analysis`).

    Attributes
    ----------
    data : xarray.Dataset
        The study's store: dims ``sa_g`` (the stripes, g), ``record`` and the design grid's
        (e.g. ``bumpers.gap_m``); per run every run's quantities (``Run.quantities()``):
        ``acc_max_g`` (over every level), ``disp_max_m`` (a building's: its base's), ``impacts``,
        ``impact_force_max_n``, ``impact_speed_max_m_s``, ``compression_max_m``, ``top_disp_max_m``,
        ``top_acc_max_g``, ``drift_ratio_max`` (NaN without storeys), ``status``; ``done``.
    period_s : float
        The period (s) of the intensity measure, ``Sa(period_s)``.
    damping_ratio : float
        The damping of the intensity measure's spectrum.
    has_bumpers : bool
        Whether the runs had bumpers (without, a contact is the peak displacement reaching a gap).
    capacity_m : float or None
        The bumpers' capacity (``Bumpers.capacity_m``): the "compression" event's default limit.

    Examples
    --------
    El Centro at two stripes of Sa(1 s) on the damped paper system with two gaps:

    {two_gaps_msa}
    >>> print(msa.fraction("contact").to_pandas())
    bumpers.gap_m  0.02  0.20
    sa_g
    0.2           0.0   0.0
    0.5           1.0   0.0
    """

    data: Any
    period_s: float
    damping_ratio: float
    has_bumpers: bool
    capacity_m: float | None = None

    @property
    def design_dims(self) -> tuple[str, ...]:
        """The design grid's dimensions (all but ``sa_g`` and ``record``)."""
        return tuple(d for d in self.data["done"].dims if d not in RESERVED)

    def unit(self, dim: str) -> str:
        """The unit of a design dimension (``"m"`` for ``bumpers.gap_m``), as the store records it."""
        from ..model.dotted import unit_of

        recorded = self.data[dim].attrs.get("units") if dim in self.data.coords else None
        return recorded if recorded and recorded != "1" else unit_of(dim)

    @property
    def levels_g(self) -> np.ndarray:
        """The stripes' intensities (g)."""
        return np.asarray(self.data["sa_g"].values, dtype=float)

    def outcomes(self, event: str = "contact", limit: float | None = None) -> Any:
        """1.0 where a run had the event, 0.0 where not, NaN where the run is not done or ended
        early (its status not SUCCESS): dims those of :attr:`data`.

        Parameters
        ----------
        event : {"contact", "acceleration", "compression", "displacement", "drift", "top_acceleration"}
            See ``EVENTS`` (the last two a building's).
        limit : float, optional
            The event's threshold (g or m); "contact" takes none with bumpers, a gap (m) without.

        Returns
        -------
        xarray.DataArray
        """
        ds = self.data
        event = one_of("event", event, tuple(EVENTS))
        if event == "contact" and limit is None:
            if not self.has_bumpers:
                raise InputError(
                    Problem.MISSING_INPUT,
                    "limit",
                    None,
                    what="the gap (m): these runs had no bumpers, so a contact is the peak "
                    "displacement reaching it",
                )
            hit = ds["impacts"] > 0.0
        elif event == "contact" and self.has_bumpers and "moat_demand_m" in ds:
            raise InputError(Problem.WRONG_MODE, "limit", limit, mode="runs without a moat",
                             fix="leave limit out: these runs had their moat, and a contact is an impact on "
                                 "it (run the building without its moat to ask at which gap its corners "
                                 "reach)")
        else:
            if limit is None and event == "compression" and self.capacity_m is not None:
                limit = self.capacity_m
            if limit is None:
                raise InputError(Problem.MISSING_INPUT, "limit", None, what=f"the threshold: {EVENTS[event]}")
            lim = positive("limit", limit, {"acceleration": "g", "top_acceleration": "g",
                                            "drift": "(a ratio)"}.get(event, "m"))
            quantity = _QUANTITY[event]
            if event == "contact" and "moat_demand_m" in ds:  # (a building in plan: its corners reach a wall)
                quantity = "moat_demand_m"
            if quantity not in ds:
                raise InputError(
                    Problem.NOT_IN_RESULT, "event", event, choices=", ".join(v for v in ds.data_vars)
                )
            hit = ds[quantity] >= lim if event == "contact" else ds[quantity] > lim
        # a run that stopped early (over its budget, a Zeno sequence) counts when it had the event
        # before it stopped (its peaks only grow); otherwise it is not known, and left out
        done = ds["done"] == 1
        valid = done & ((ds["status"] == float(Status.SUCCESS)) | hit)
        return hit.astype(float).where(valid)

    def finished(self) -> Any:
        """True where a run is done and ended with SUCCESS (dims those of :attr:`data`)."""
        ds = self.data
        return (ds["done"] == 1) & (ds["status"] == float(Status.SUCCESS))

    def counts(self, event: str = "contact", limit: float | None = None) -> tuple[Any, Any]:
        """Per stripe and design point, the runs counted and the runs with the event (the
        records' dimension summed): two ``xarray.DataArray`` of dims ``sa_g`` and the design's."""
        out = self.outcomes(event, limit)
        return out.notnull().sum("record"), out.sum("record", skipna=True)

    def fraction(self, event: str = "contact", limit: float | None = None) -> Any:
        """The fraction of the counted runs with the event, per stripe and design point."""
        n, k = self.counts(event, limit)
        return (k / n.where(n > 0)).rename(f"{event}_fraction")

    def fragility(
        self,
        event: str = "contact",
        limit: float | None = None,
        *,
        at: Mapping[str, float] | None = None,
        n_bootstrap: int = 1000,
        confidence: float = 0.9,
        seed: int = 0,
    ) -> Fragility:
        """The event's lognormal fragility over the stripes at one design point (``at``: a value for
        each design dimension, e.g. ``{"bumpers.gap_m": 0.1}``), by maximum likelihood
        (:func:`fit_fragility`).  Its band resamples *records* (each with its runs at every stripe):
        the same records are in every stripe, so resampling runs within stripes would understate
        the record-to-record spread."""
        from dataclasses import replace

        from .._checks import integer
        from .fragility import _seed, refit_stripes

        sel = self._point(at)
        outcomes = self.outcomes(event, limit).sel(sel).transpose("sa_g", "record").values  # (s, r)
        n = np.isfinite(outcomes).sum(axis=1)
        k = np.nansum(outcomes, axis=1).astype(int)
        keep = n > 0
        label = event if limit is None else f"{event} > {limit:g}"
        where = ", ".join(f"{d} {v:g}" for d, v in sel.items())
        fit = fit_fragility(
            self.levels_g[keep],
            n[keep],
            k[keep],
            event=f"{label} ({where})" if where else label,
            n_bootstrap=0,
            confidence=confidence,
            seed=seed,
        )
        reps = integer("n_bootstrap", n_bootstrap, 0, 100_000)
        if reps == 0:
            return fit
        rng = _seed(seed)
        picks = rng.integers(0, outcomes.shape[1], size=(reps, outcomes.shape[1]))
        chosen = outcomes[keep][:, picks]  # (s, reps, r)
        runs = np.isfinite(chosen).sum(axis=2).T  # (reps, s)
        events = np.nansum(chosen, axis=2).T.astype(int)
        start = (-np.log(fit.median_g) / fit.beta, 1.0 / fit.beta)
        boot, failed = refit_stripes(self.levels_g[keep], runs, events, start)
        return replace(fit, bootstrap=boot, n_failed_resamples=failed)

    def capacities(
        self, event: str = "contact", limit: float | None = None, *, at: Mapping[str, float] | None = None
    ) -> np.ndarray:
        """Each record's capacity at one design point, as an incremental dynamic analysis on the
        stripes' levels reads it: the first level (g) at which its run has the event, ``inf`` when
        none has (censored at the last level), NaN when a run before it did not finish.

        Returns
        -------
        numpy.ndarray, shape (records,)
        """
        out = self.outcomes(event, limit).sel(self._point(at)).transpose("sa_g", "record").values
        levels = self.levels_g
        cap = np.full(out.shape[1], np.inf)
        for r in range(out.shape[1]):
            for j in range(out.shape[0]):
                if np.isnan(out[j, r]):
                    cap[r] = np.nan
                    break
                if out[j, r] == 1.0:
                    cap[r] = levels[j]
                    break
        return cap

    def capacity_fragility(
        self,
        event: str = "contact",
        limit: float | None = None,
        *,
        at: Mapping[str, float] | None = None,
        n_bootstrap: int = 200,
        confidence: float = 0.9,
        seed: int = 0,
    ) -> Fragility:
        """The fragility from :meth:`capacities` (incremental dynamic analysis on the stripes' levels),
        by maximum likelihood with interval censoring (:func:`fit_fragility_intervals`): a record's
        capacity lies between the level before its first event and that level (below the first
        level when it had the event there; above the last when it never had it).  Records with an
        unfinished run before their first event are left out."""
        from .capacities import fit_fragility_intervals

        cap = self.capacities(event, limit, at=at)
        cap = cap[~np.isnan(cap)]
        levels = self.levels_g
        upper = cap
        index = np.searchsorted(levels, np.where(np.isinf(cap), levels[-1], cap))
        lower = np.where(
            np.isinf(cap), levels[-1], np.where(index > 0, levels[np.maximum(index - 1, 0)], 0.0)
        )
        label = event if limit is None else f"{event} > {limit:g}"
        return fit_fragility_intervals(
            lower, upper, event=label, n_bootstrap=n_bootstrap, confidence=confidence, seed=seed
        )

    def probability(self, sa_g: float, event: str = "contact", limit: float | None = None) -> Any:
        """The event's probability at the intensity ``sa_g`` (g) at every design point: the fitted
        fragility's, or where it has no estimate, the stripes' own fractions
        (:func:`empirical_probability`: NaN outside the stripes unless an end stripe had the event
        in no run, or in every run).

        Returns
        -------
        xarray.DataArray
            Dims the design grid's.
        """
        x = positive("sa_g", sa_g, "g")
        n, k = self.counts(event, limit)
        dims = self.design_dims
        out = np.full(tuple(n.sizes[d] for d in dims), np.nan)
        for index in np.ndindex(out.shape) if dims else [()]:
            sel = {d: i for d, i in zip(dims, index)}
            nn, kk = n.isel(sel).values, k.isel(sel).values
            keep = nn > 0
            if keep.sum() == 0:
                continue
            out[index] = _probability(self.levels_g[keep], nn[keep].astype(int), kk[keep].astype(int), x)
        import xarray as xr

        return xr.DataArray(
            out,
            dims=dims,
            coords={d: self.data[d].values for d in dims},
            name=f"{event}_probability",
            attrs={"sa_g": x},
        )

    def to_xarray(self) -> Any:
        """The runs (:attr:`data`, loaded)."""
        return self.data.load()

    def to_dataframe(self) -> Any:
        """One row per run: the stripe, the record, the design point and the run's quantities."""
        return self.data.drop_vars(["session"], errors="ignore").to_dataframe().reset_index()

    def plot(self, event: str = "contact", limit: float | None = None, *, ax: Any = None) -> Any:
        """The fraction of runs with the event per stripe (markers) and the fitted curves, one per
        design point (the design grid's first dimension; the others at their first value).

        Returns its Figure.
        """
        from ..plots.design import plot_stripes
        from ..plots import figure_of

        return figure_of(plot_stripes(self, event, limit, ax=ax), ax)

    def __repr__(self) -> str:
        ds = self.data
        grid = ", ".join(f"{d} {ds.sizes[d]}" for d in self.design_dims)
        done = f"{int(ds['done'].sum())} of {ds['done'].size} runs done"
        return (
            f"StripeAnalysis({ds.sizes['sa_g']} stripes of Sa({self.period_s:g} s) x "
            f"{ds.sizes['record']} records{' x ' + grid if grid else ''}, {done})"
        )

    def _point(self, at: Mapping[str, float] | None) -> dict[str, float]:
        dims = self.design_dims
        at = {} if at is None else dict(at)
        unknown = sorted(set(at) - set(dims))
        if unknown:
            raise InputError(
                Problem.NOT_IN_RESULT,
                f"at[{unknown[0]!r}]",
                at[unknown[0]],
                choices=", ".join(dims) or "none (no design grid)",
            )
        missing = [d for d in dims if d not in at]
        if missing:
            raise InputError(
                Problem.MISSING_INPUT,
                "at",
                at,
                what=f"a value for {missing[0]} (one of {self.data[missing[0]].values.tolist()})",
            )
        out = {}
        for d, v in at.items():
            values = np.asarray(self.data[d].values, dtype=float)
            hit = np.flatnonzero(np.isclose(values, float(v), rtol=1e-12, atol=0.0))
            if hit.size == 0:
                raise InputError(
                    Problem.NOT_ONE_OF, f"at[{d!r}]", v, choices=", ".join(f"{x:g}" for x in values)
                )
            out[d] = float(values[hit[0]])
        return out


def _probability(x: np.ndarray, n: np.ndarray, k: np.ndarray, at: float) -> float:
    """``P(E | at)`` from stripes: the maximum-likelihood curve where it has an estimate; else the
    stripes' own fractions (made non-decreasing, pooling adjacent stripes that fall, weighted by
    their runs), linear in ``ln x`` between stripes, 0 below the lowest stripe if its fraction is
    0 and 1 above the highest if its fraction is 1, and NaN elsewhere (not known from these runs)."""
    from .fragility import _overlap, _probit_fit

    survivor, first = _overlap(x, n, k)
    if np.unique(x).size >= 2 and survivor > first:
        try:
            a, b = _probit_fit(x, n, k)
        except InputError:  # (the fractions fall with the intensity: no lognormal curve)
            pass
        else:
            from scipy import special

            return float(special.ndtr(a + b * math.log(at)))
    return empirical_probability(x, n, k, at)


def empirical_probability(x: np.ndarray, n: np.ndarray, k: np.ndarray, at: float) -> float:
    """The stripes' fractions at ``at``: isotonic (pool adjacent violators, weighted by ``n``),
    linear in ``ln x`` between stripes; outside them 0 or 1 only where the end stripe says so."""
    order = np.argsort(x)
    xs, ns, ks = x[order], n[order].astype(float), k[order].astype(float)
    blocks = [[ks[i] / ns[i], ns[i], 1] for i in range(xs.size)]  # (value, weight, stripes pooled)
    merged: list[list[float]] = []
    for b in blocks:
        merged.append(b)
        while len(merged) > 1 and merged[-2][0] > merged[-1][0]:
            v2, w2, c2 = merged.pop()
            v1, w1, c1 = merged.pop()
            merged.append([(v1 * w1 + v2 * w2) / (w1 + w2), w1 + w2, c1 + c2])
    fractions = np.concatenate([[v] * int(c) for v, _, c in merged])
    if at < xs[0]:
        return 0.0 if fractions[0] == 0.0 else math.nan
    if at > xs[-1]:
        return 1.0 if fractions[-1] == 1.0 else math.nan
    return float(np.interp(math.log(at), np.log(xs), fractions))
