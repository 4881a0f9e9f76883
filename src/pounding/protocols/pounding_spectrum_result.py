"""The result of :func:`pounding.pounding_spectrum`: labelled peaks, their statistics over a record set."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
import pandas as pd

from .._tables import percentiles

if TYPE_CHECKING:  # pragma: no cover
    import xarray as xr

    from ..excitation import Record

# per run: what a run's quantities() give, in this order
QUANTITIES = ("acc_max_g", "disp_max_m", "impacts", "impact_force_max_n", "impact_speed_max_m_s", "status")
# a building's (``structure=``): the same, ``disp_max_m`` its base's and ``acc_max_g`` the largest over its
# floors, and its top floor's acceleration and largest storey drift ratio
STRUCTURE_QUANTITIES = QUANTITIES + ("top_acc_max_g", "drift_ratio_max")
# a building in plan's (``structure=PlanBuilding``): a building's, ``disp_max_m`` its largest bearing
# displacement in plan, its base's largest rotation, the moat's smallest clearance and the moat's demand (its
# floor's corners' largest displacement towards a wall)
PLAN_QUANTITIES = STRUCTURE_QUANTITIES + ("theta_max_rad", "clearance_min_m", "moat_demand_m")
UNITS = {"acc_max_g": "g", "disp_max_m": "m", "impacts": "1", "impact_force_max_n": "N",
         "impact_speed_max_m_s": "m/s",
         "status": "pounding.Status", "amplification": "1", "disp_ratio": "1", "acc_max_free_g": "g",
         "disp_max_free_m": "m", "top_acc_max_g": "g", "drift_ratio_max": "1", "top_acc_max_free_g": "g",
         "drift_ratio_max_free": "1", "theta_max_rad": "rad", "clearance_min_m": "m",
         "theta_max_rad_free": "rad", "clearance_min_m_free": "m", "moat_demand_m": "m",
         "moat_demand_m_free": "m"}
PERCENTILES = (16.0, 50.0, 84.0)


@dataclass(frozen=True, eq=False)
class PoundingSpectrum:
    """Peaks of the isolated mass under records, with bumpers (per gap) and without.

    Attributes
    ----------
    data : xarray.Dataset
        Dims ``(record, period_s, gap_m)``: ``acc_max_g`` (peak absolute acceleration, g),
        ``disp_max_m`` (peak ``|D|``), ``impacts`` (number of contacts), ``impact_force_max_n``,
        ``impact_speed_max_m_s`` (the fastest approach), ``status`` (the run's, 0 for success), and
        the amplification by pounding ``amplification = acc_max_g / acc_max_free_g`` and
        ``disp_ratio = disp_max_m / disp_max_free_m``; dims ``(record, period_s)``: the same without
        bumpers, ``acc_max_free_g``, ``disp_max_free_m``, ``status_free``.  NaN where a run did not
        finish (interrupted).  Each record's metadata (``pga_g``, ``event``...) as coordinates on
        ``record`` (a pair's ``pga_g`` its peak vector).

    Examples
    --------
    >>> import pounding
    >>> quake = pounding.records.el_centro().scaled(pga_g=0.3)
    >>> ps = pounding.pounding_spectrum([quake], [1.0, 2.0], gaps_m=[0.02, 0.05])
    >>> dict(ps.data.sizes)
    {'record': 1, 'period_s': 2, 'gap_m': 2}
    >>> # with bumpers / without
    >>> median = ps.summary()["amplification"].sel(percentile=50.0)
    >>> print(median.round(1).to_pandas())
    gap_m     0.02  0.05
    period_s
    1.0        6.0   7.5
    2.0       22.5  48.3
    >>> ps.to_dataframe().shape  # one row per record, period and gap
    (4, 20)
    """

    data: "xr.Dataset"

    @classmethod
    def build(cls, recs: list["Record"], periods: np.ndarray, gaps: np.ndarray, free: np.ndarray,
              hit: np.ndarray, attrs: dict, names: tuple = QUANTITIES) -> "PoundingSpectrum":
        """Assemble the result from the kernel's arrays (internal: ``pounding_spectrum`` calls it)."""
        import xarray as xr

        from ..excitation.spectrum import record_names

        dims = ("record", "period_s", "gap_m")
        data = {q: (dims, hit[..., k], {"units": UNITS[q]}) for k, q in enumerate(names)}
        data["acc_max_free_g"] = (dims[:2], free[..., 0], {"units": "g"})
        data["disp_max_free_m"] = (dims[:2], free[..., 1], {"units": "m"})
        data["status_free"] = (dims[:2], free[..., 5], {"units": "pounding.Status"})
        for k, q in enumerate(names[len(QUANTITIES):], start=len(QUANTITIES)):  # (a building's own)
            if q == "clearance_min_m":  # (no moat, no clearance)
                continue
            free_name = q.replace("_g", "_free_g") if q.endswith("_g") else f"{q}_free"
            data[free_name] = (dims[:2], free[..., k], {"units": UNITS[free_name]})
        with np.errstate(divide="ignore", invalid="ignore"):
            data["amplification"] = (dims, hit[..., 0] / free[..., 0][..., None],
                                     {"long_name": "peak acceleration with bumpers over without"})
            data["disp_ratio"] = (dims, hit[..., 1] / free[..., 1][..., None],
                                  {"long_name": "peak displacement with bumpers over without"})
        from ..excitation.pair import RecordPair

        coords = {"record": record_names(recs), "period_s": periods, "gap_m": gaps,
                  "pga_g": ("record", np.array([r.peak_vector_g if isinstance(r, RecordPair) else r.pga_g
                                                for r in recs]))}
        for key in ("event", "year", "station", "component", "magnitude"):
            values = [r.meta.get(key) for r in recs]
            if all(v is not None for v in values):
                coords[key] = ("record", np.array(values))
        return cls(xr.Dataset(data, coords=coords, attrs=attrs))

    def summary(self) -> "xr.Dataset":
        """The 16th, 50th (median) and 84th percentiles over the records (dim ``percentile``) of every
        quantity; runs that did not finish, or ended early (``status`` not 0), are left out.  A percentile
        that reaches a rigid stop's unbounded acceleration or force (inf) is inf."""
        import xarray as xr

        full = self.data
        hit_ok, free_ok = full["status"] == 0, full["status_free"] == 0
        ds = full.drop_vars(["status", "status_free"])
        for name in ds.data_vars:
            ok = free_ok if "gap_m" not in ds[name].dims else hit_ok & free_ok if name in (
                "amplification", "disp_ratio") else hit_ok
            ds[name] = ds[name].where(ok)
        # (inf kept: a rigid stop's impulses; _tables.percentiles)
        stats = xr.apply_ufunc(lambda v: np.moveaxis(percentiles(v, list(PERCENTILES), axis=-1), 0, -1), ds,
                               input_core_dims=[["record"]], output_core_dims=[["percentile"]])
        return stats.assign_coords(percentile=list(PERCENTILES)).transpose("percentile", ...)

    def to_dataframe(self) -> pd.DataFrame:
        """One row per record, period and gap, every quantity a column (the free-run ones repeated)."""
        return self.data.to_dataframe().reset_index()

    def to_xarray(self) -> "xr.Dataset":
        """The spectrum as an ``xarray.Dataset`` (dims ``record``, ``period_s``, ``gap_m``)."""
        return self.data

    def to_netcdf(self, path: str | Path) -> Path:
        """Save :attr:`data` (netCDF; ``xarray.open_dataset`` reads it back), written atomically."""
        from .._io import atomic_write, output_file

        return atomic_write(output_file("path", path), self.data.to_netcdf)

    def plot(self, ax: Any = None, *, kind: str = "curves", quantity: str = "amplification") -> Any:
        """``kind="curves"``: the median over the records against the period, one curve per gap, the 16-84 %
        band shaded; ``kind="map"``: the median over period and gap.  See
        :func:`pounding.plots.plot_pounding_spectrum`.

        Returns its Figure.
        """
        from ..plots.spectrum import plot_pounding_spectrum
        from ..plots import figure_of

        return figure_of(plot_pounding_spectrum(self, ax=ax, kind=kind, quantity=quantity), ax)
