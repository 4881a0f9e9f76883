"""A sweep's tables, for any system: the exact table (one row per step and level), the one a measurement
chain reads (a single mass's), each contact slot's, and the Dataset (:class:`~pounding.SweepResult`'s
``to_dataframe``, ``contacts_dataframe`` and ``to_xarray``)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
import pandas as pd

from ..engine.assembly import structures_of
from ..metrics.impacts import IMPACT_COLUMNS, S_COUNT, S_N_RESTITUTION, S_SUMS
from .measured_sweep import MEASURED_COLUMNS
from .sweep_window import NAMES, slot_name

if TYPE_CHECKING:  # pragma: no cover
    import xarray as xr

    from .sweep_result import SweepResult

SIDE_COLUMNS = ("contacts_per_cycle", *IMPACT_COLUMNS)
SIDES = ("left", "right")


def exact_table(sw: "SweepResult") -> pd.DataFrame:
    """The exact table of ``sw`` (see ``SweepResult.to_dataframe``)."""
    n, n_lev = len(sw.freqs_hz), len(sw.levels)
    m = sw.level_metrics
    excursion = m[:, :, 0] - m[:, :, 1]
    gaps = sw.level_gaps_m
    with np.errstate(invalid="ignore", divide="ignore"):  # (eta undefined at zero gap, as without walls)
        eta = np.where(gaps > 0, excursion / np.where(gaps > 0, gaps, 1.0), np.nan)
    ran = np.repeat(np.arange(n) < sw.steps_done, n_lev)
    # each level's wall slots, per side (a link belongs to no level's paper metrics)
    sides = np.zeros((n, n_lev, 2, sw.contact_sums.shape[2]))
    for c, (b, kind, _w, lv, side) in enumerate(sw.contact_slots):
        if kind == "wall":
            sides[:, sw.levels.index((b, lv)), SIDES.index(side)] += sw.contact_sums[:, c]
    both = sides[:, :, 0] + sides[:, :, 1]
    cycles = np.repeat(sw.window_cycles, n_lev)
    cols: dict[str, Any] = {"freq_hz": np.repeat(sw.freqs_hz, n_lev), "nu": np.repeat(sw.nu, n_lev)}
    if len({b for b, _ in sw.levels}) > 1:
        cols["structure"] = np.tile([NAMES[b] for b, _ in sw.levels], n)
    cols.update({"level": np.tile([q for _, q in sw.levels], n), "alpha": sw.alpha.ravel(),
                 "excursion_m": excursion.ravel(), "displacement_max_m": m[:, :, 0].ravel(),
                 "displacement_min_m": m[:, :, 1].ravel(), "eta": eta.ravel(),
                 "e": excursion.ravel() / sw.d_tmax_m,
                 "contact": np.where(ran, both[:, :, S_COUNT].ravel() > 0, False)})
    per_side: dict[str, np.ndarray] = {}
    for name, sums in (("", both), ("_left", sides[:, :, 0]), ("_right", sides[:, :, 1])):
        for key, value in impact_means(sums.reshape(n * n_lev, -1), cycles).items():
            per_side[key + name] = value
    cols.update({k: per_side[k] for k in SIDE_COLUMNS})
    cols.update({"steady": np.where(ran, np.repeat(sw.period_multiple > 0, n_lev), False),
                 "period_multiple": np.repeat(sw.period_multiple, n_lev),
                 "cycles_run": np.repeat(sw.cycles_run, n_lev)})
    with np.errstate(invalid="ignore", divide="ignore"):  # (a step not run: no window)
        per_cycle = sw.window_events / sw.window_cycles[:, None]
    cols.update({"events_per_cycle": np.repeat(per_cycle[:, 0], n_lev),
                 "sticks_per_cycle": np.repeat(per_cycle[:, 1], n_lev)})
    cols["abs_acceleration_max_m_s2"] = m[:, :, 2].ravel()
    drift, ratio = np.full((n, n_lev), np.nan), np.full((n, n_lev), np.nan)
    structures = structures_of(sw.system)[0]
    for s, (b, lv) in enumerate(sw.storeys):
        q = sw.levels.index((b, lv))
        drift[:, q] = sw.peak_drift[:, s]
        ratio[:, q] = drift[:, q] / structures[b].storeys[lv - 1].height_m
    cols.update({"drift_peak_m": drift.ravel(), "drift_ratio_peak": ratio.ravel()})
    for side in ("_left", "_right"):
        cols.update({k + side: per_side[k + side] for k in SIDE_COLUMNS})
    return pd.DataFrame(cols)


def measured_table(sw: "SweepResult", exact: pd.DataFrame) -> pd.DataFrame:
    """``exact`` with the metrics a measurement chain read in its place (a single mass's: one row per
    step)."""
    if sw.measured is None:
        return exact
    table = exact.copy()  # (a chain measures a single mass: one row per step)
    ran = np.arange(len(table)) < sw.steps_done
    for q in MEASURED_COLUMNS:
        table[q] = sw.measured[q].to_numpy()
    table["contact"] = np.where(ran, sw.measured["contact"].eq(True).to_numpy(), False)  # (NaN: unread)
    table["bumper_dissipation_j"] = np.nan  # (not measurable from the accelerations)
    table["abs_acceleration_max_m_s2"] = table["alpha"] * sw.peak_m_s2  # (the accelerometers' alpha)
    per_side = _measured_sides(sw.measured_impacts, sw.freqs_hz, sw.window_cycles)
    for side in ("_left", "_right"):
        for k in SIDE_COLUMNS:
            table[k + side] = per_side.get(k + side, np.full(len(table), np.nan))
    return table


def contacts_table(sw: "SweepResult") -> pd.DataFrame:
    """One row per step and contact slot (see ``SweepResult.contacts_dataframe``)."""
    n, n_c = len(sw.freqs_hz), len(sw.contact_slots)
    labels = list(zip(*sw.contact_slots)) if n_c else [()] * 5
    frame: dict[str, Any] = {"freq_hz": np.repeat(sw.freqs_hz, n_c), "nu": np.repeat(sw.nu, n_c)}
    for name, values in zip(("structure", "kind", "index", "level", "side"), labels):
        frame[name] = np.tile(np.array(values, dtype=object), n)
    cycles = np.repeat(sw.window_cycles, n_c)
    frame.update(impact_means(sw.contact_sums.reshape(n * n_c, sw.contact_sums.shape[2]), cycles))
    return pd.DataFrame(frame)


def dataset(sw: "SweepResult") -> "xr.Dataset":
    """The table as a Dataset (see ``SweepResult.to_xarray``)."""
    import xarray as xr

    n_lev = len(sw.levels)
    df = sw.to_dataframe()
    df["step"] = np.repeat(np.arange(len(sw.freqs_hz)), n_lev)
    df["level"] = np.tile(np.arange(n_lev), len(sw.freqs_hz))
    df = df.drop(columns=["nu", "structure"], errors="ignore").set_index(["freq_hz", "level"])
    df = df.sort_index()
    ds = xr.Dataset.from_dataframe(df)
    ds["step"] = ds["step"].isel(level=0, drop=True)
    for name in ("contact", "steady"):
        ds[name] = ds[name].astype(bool)
    for name in ("period_multiple", "cycles_run", "events_per_cycle", "sticks_per_cycle"):
        ds[name] = ds[name].isel(level=0, drop=True)
    order = np.argsort(sw.freqs_hz)
    ds = ds.assign_coords(nu=("freq_hz", ds["freq_hz"].values / sw.f_ref_hz),
                          level_number=("level", np.array([q for _, q in sw.levels], dtype=int)),
                          level_structure=("level", np.array([NAMES[b] for b, _ in sw.levels],
                                                             dtype=str)))
    if sw.storeys:  # (no empty dimension: netCDF 3 would take it for its record dimension)
        ds["drift_max_m"] = (("freq_hz", "storey"), sw.drift_metrics[order, :, 0])
        ds["drift_min_m"] = (("freq_hz", "storey"), sw.drift_metrics[order, :, 1])
        ds = ds.assign_coords(
            storey_number=("storey", np.array([s for _, s in sw.storeys], dtype=int)),
            storey_structure=("storey", np.array([NAMES[b] for b, _ in sw.storeys], dtype=str)))
    if sw.contact_slots:
        contacts = sw.contacts_dataframe()
        for k in SIDE_COLUMNS:
            ds[f"{k}_per_contact"] = (("freq_hz", "slot"),
                                      contacts[k].to_numpy().reshape(len(sw.freqs_hz), -1)[order])
        slots = sw.contact_slots
        ds = ds.assign_coords(slot=np.array([slot_name(slots, c) for c in range(len(slots))], dtype=str),
                              slot_kind=("slot", np.array([s[1] for s in slots], dtype=str)),
                              slot_level=("slot", np.array([s[3] for s in slots], dtype=int)),
                              slot_side=("slot", np.array([s[4] for s in slots], dtype=str)))
    if n_lev == 1:  # (a single mass, a one-level structure: one value per step, as their campaign's)
        ds = ds.isel(level=0, drop=True)
    for name in ds.data_vars:
        unit = _unit(name)
        if unit:
            ds[name].attrs.setdefault("units", unit)
    ds["freq_hz"].attrs["units"] = "Hz"
    ds.attrs.update({"a_g": sw.a_g, "direction": sw.direction, "steady_mode": sw.steady_mode,
                     "cycles": sw.cycles, "measure_cycles": sw.measure_cycles,
                     "omega_min_rad_s": sw.omega_min_rad_s, "f_ref_hz": sw.f_ref_hz,
                     "total_gap_m": sw.total_gap_m, "d_tmax_m": sw.d_tmax_m,
                     "status": str(sw.status), "message": sw.message,
                     "measurement": "exact" if sw.measurement is None else sw.measurement.describe(),
                     "system": sw.system.to_toml_text()})
    return ds


def _unit(name: str) -> str:
    """A variable's unit from its name's ending (``_m``, ``_m_s2``, ...)."""
    for tail in ("_per_contact", "_left", "_right"):
        name = name.removesuffix(tail)
    for end, unit in (("_m_s2", "m/s^2"), ("_n_s", "N s"), ("_m", "m"), ("_s", "s"), ("_n", "N"),
                      ("_j", "J"), ("_hz", "Hz")):
        if name.endswith(end):
            return unit
    return ""


def _measured_sides(impacts: pd.DataFrame | None, freqs_hz: np.ndarray,
                    window_cycles: np.ndarray) -> dict[str, np.ndarray]:
    """Per side, the measured contacts' means per step (``contacts_per_cycle`` and the impact
    columns the lab measures; NaN where it cannot)."""
    out: dict[str, np.ndarray] = {}
    for side in SIDES:
        for k in SIDE_COLUMNS:
            out[f"{k}_{side}"] = np.full(freqs_hz.size, np.nan)
        out[f"contacts_per_cycle_{side}"] = np.where(window_cycles > 0, 0.0, np.nan)
        if impacts is None or not len(impacts):
            continue
        mine = impacts[impacts["side"] == side]
        for i, f in enumerate(freqs_hz):
            at = mine[mine["freq_hz"] == f]
            if not len(at) or not window_cycles[i] > 0:
                continue
            out[f"contacts_per_cycle_{side}"][i] = len(at) / window_cycles[i]
            for k in SIDE_COLUMNS:
                if k in at.columns:
                    out[f"{k}_{side}"][i] = float(at[k].mean())
    return out


def impact_means(sums: np.ndarray, window_cycles: np.ndarray) -> dict[str, np.ndarray]:
    """Window means of the impact quantities from impact sums, shape (rows, SIDE_SUMS) (NaN without
    contact)."""
    count = sums[:, S_COUNT]
    with np.errstate(invalid="ignore", divide="ignore"):
        out = {"contacts_per_cycle": count / window_cycles}
        for j, name in enumerate(IMPACT_COLUMNS):
            n = sums[:, S_N_RESTITUTION] if j == 0 else count
            out[name] = np.where(n > 0, sums[:, S_SUMS + j] / np.where(n > 0, n, 1.0), np.nan)
    return out
