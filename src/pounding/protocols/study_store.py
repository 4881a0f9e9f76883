"""A study's Zarr store: the template, and the regions its batches write.

The store is an xarray Dataset in Zarr (format 2, readable by every Zarr library): one dim per
grid axis, one float64 variable per quantity, ``done`` (bool) and ``session`` (int32: the run of
:func:`pounding.study` that computed the point, 1 for the first; 0 not yet).  A batch is one
chunk; it is written only by the task that computes it, data first and ``done`` last, each
chunk file replaced atomically (Zarr's local store writes a temporary file, then renames).
A task killed at any instant leaves its chunk's points either done with their data or not done.
"""

from __future__ import annotations

import functools
import json
import math
import os
import shutil
from pathlib import Path
from typing import Any

import numpy as np

from .._errors import InputError, Problem
from .study_points import QUANTITIES, UNITS
from .study_spec import StudySpec

SPEC_ATTR = "pounding_study"
SHA_ATTR = "pounding_study_sha256"
BOOKKEEPING = ("done", "session")


def is_url(store: str) -> bool:
    return "://" in store


def check_store(store: Any) -> str:
    """The store as a string: a local path (its folder must exist; a file is refused) or an
    fsspec URL (``s3://bucket/study.zarr``: written through fsspec, as xarray does)."""
    if isinstance(store, Path):
        store = str(store)
    if not isinstance(store, str) or not store:
        raise InputError(Problem.WRONG_TYPE, "store", store, got=type(store).__name__,
                         expected="path of a .zarr folder, or an fsspec URL")
    if is_url(store):
        return store
    path = Path(store)
    if path.exists() and not path.is_dir():
        raise InputError(Problem.BAD_OUTPUT, "store", store, why="is a file, not a Zarr folder",
                         fix="give a new folder name such as study.zarr")
    if not path.parent.exists():
        raise InputError(Problem.BAD_OUTPUT, "store", store, why=f"is in {path.parent}, which does not exist",
                         fix="create that folder first, or give another path")
    return str(path.resolve())


def store_exists(store: str) -> bool:
    """True when ``store`` holds a Zarr group (any: whether it is a study is checked on opening)."""
    if is_url(store):
        import fsspec

        mapper = fsspec.get_mapper(store)
        return ".zgroup" in mapper or "zarr.json" in mapper
    path = Path(store)
    return path.is_dir() and any(path.iterdir())


def chunk_shape(shape: tuple[int, ...], batch: int) -> tuple[int, ...]:
    """Chunks of about ``batch`` points: whole trailing axes while they fit, then part of the next."""
    chunks = [1] * len(shape)
    room = max(1, batch)
    for axis in range(len(shape) - 1, -1, -1):
        take = min(shape[axis], room)
        chunks[axis] = take
        if take < shape[axis]:
            break
        room //= max(take, 1)
        if room <= 1:
            break
    return tuple(chunks)


def create(store: str, spec: StudySpec, chunks: tuple[int, ...]) -> None:
    """Write the template: coordinates, attributes, ``done`` False, ``session`` 0; the quantities
    as chunks not yet written (read as NaN)."""
    import dask.array as da
    import xarray as xr

    dims = spec.dims
    shape = spec.shape
    data: dict[str, Any] = {}
    for q in QUANTITIES[spec.kind]:
        data[q] = (dims, da.full(shape, np.nan, chunks=chunks), {"units": UNITS.get(q, "1")})
    data["done"] = (dims, np.zeros(shape, dtype=bool), {"description": "the point is computed and written"})
    data["session"] = (dims, np.zeros(shape, dtype=np.int32),
                       {"description": "the run of pounding.study that computed the point (0: not yet)"})
    coords = {name: (name, np.array(values)) for name, values in spec.grid.items()}
    ds = xr.Dataset(data, coords=coords)
    ds.attrs.update({SPEC_ATTR: spec.to_json(), SHA_ATTR: spec.sha256, "kind": spec.kind,
                     "quantities": list(QUANTITIES[spec.kind])})
    encoding = {name: {"chunks": chunks} for name in (*QUANTITIES[spec.kind], *BOOKKEEPING)}
    for name in BOOKKEEPING:
        encoding[name]["_FillValue"] = None
    if is_url(store):  # (object storage: no rename; a template cut short is written anew next time)
        ds.to_zarr(store, mode="w", compute=False, encoding=encoding, zarr_format=2, consolidated=True)
        return
    # a local template is written beside the store and renamed into place: a study killed while
    # writing it leaves no store (and a stray .tmp folder, replaced next time), never half a one
    path = Path(store)
    tmp = path.with_name(f".{path.name}.tmp")
    shutil.rmtree(tmp, ignore_errors=True)
    ds.to_zarr(str(tmp), mode="w", compute=False, encoding=encoding, zarr_format=2, consolidated=True)
    if path.exists():
        shutil.rmtree(path)
    os.replace(tmp, path)


def open_checked(store: str, spec: StudySpec | None) -> Any:
    """The store's Zarr group; a store of another spec (or no study) is refused."""
    import zarr

    try:
        group = zarr.open_group(store, mode="r+" if spec is not None else "r", zarr_format=2)
    except Exception as exc:  # (not a Zarr v2 group at all)
        raise InputError(Problem.BAD_OUTPUT, "store", store, why=f"is not a study store ({exc})",
                         fix="give a new folder, or the store a study made") from None
    attrs = dict(group.attrs)
    if SPEC_ATTR not in attrs:
        raise InputError(Problem.BAD_OUTPUT, "store", store, why="is a Zarr store, but not a study's",
                         fix="give a new folder, or resume=False to overwrite it")
    if spec is not None and attrs.get(SHA_ATTR) != spec.sha256:
        theirs = json.loads(attrs[SPEC_ATTR])
        mine = spec.to_dict()
        differ = [k for k in ("system", "compute", "grid") if theirs.get(k) != mine.get(k)]
        raise InputError(Problem.BAD_OUTPUT, "store", store,
                         why=f"was made by another study (its {' and '.join(differ) or 'spec'} differ)",
                         fix="give a new store for this study, resume=False (--restart) to overwrite it, "
                             "or run the study that made it")
    return group


def chunk_grid(shape: tuple[int, ...], chunks: tuple[int, ...]) -> list[tuple[int, ...]]:
    """Every chunk's index, in order."""
    import itertools

    counts = [math.ceil(n / c) for n, c in zip(shape, chunks)]
    return list(itertools.product(*(range(n) for n in counts)))


def region(index: tuple[int, ...], shape: tuple[int, ...], chunks: tuple[int, ...]) -> tuple[slice, ...]:
    return tuple(slice(i * c, min((i + 1) * c, n)) for i, c, n in zip(index, chunks, shape))


@functools.lru_cache(maxsize=8)
def _spec_tables(spec_json: str) -> dict:
    """The spec's canonical tables, parsed once per process (a worker's batches share them)."""
    return json.loads(spec_json)


def run_chunk(spec_json: str, store: str, index: tuple[int, ...], session: int, max_steps: int | None = None,
              should_stop: Any = None, advance: Any = None) -> int:
    """Compute the points of chunk ``index`` not done yet and write them: the data, then
    ``session`` and ``done``.  Runs where the store is reachable (a thread, a worker process, a
    Dask worker); takes plain data only.  ``should_stop()`` True between points: write what is
    finished and return.  Returns the number of points computed."""
    import zarr

    from .study_points import compute_point
    from .study_spec import point_of

    tables = _spec_tables(spec_json)
    kind = tables["compute"]["kind"]
    names = list(tables["grid"])
    group = zarr.open_group(store, mode="r+", zarr_format=2)
    done_arr = group["done"]
    shape = tuple(done_arr.shape)
    chunks = tuple(done_arr.chunks)
    sel = region(index, shape, chunks)
    done = np.asarray(done_arr[sel])
    if done.all():
        return 0
    quantities = QUANTITIES[kind]
    partly = bool(done.any())  # (a chunk cut short before: its finished points are kept as they are)
    block = {q: np.asarray(group[q][sel], dtype=float) if partly else np.full(done.shape, np.nan)
             for q in quantities}
    new = np.zeros(done.shape, dtype=bool)
    computed = 0
    for local in np.ndindex(done.shape):
        if done[local]:
            continue
        if should_stop is not None and should_stop():
            break
        values = {name: tables["grid"][name][s.start + i] for name, s, i in zip(names, sel, local)}
        system, options = point_of(tables["system"], tables["compute"], values)
        out = compute_point(system, options, max_steps)
        for q, v in zip(quantities, out):
            block[q][local] = v
        new[local] = True
        computed += 1
        if advance is not None:
            advance(1)
    if computed == 0:
        return 0
    for q in quantities:  # the data first ...
        group[q][sel] = block[q]
    sessions = np.asarray(group["session"][sel]) if partly else np.zeros(done.shape, dtype=np.int32)
    sessions[new] = session
    group["session"][sel] = sessions
    group["done"][sel] = done | new  # ... and last what says it is there
    return computed
