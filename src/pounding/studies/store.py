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
import time
from pathlib import Path
from typing import Any

import numpy as np

from .._errors import InputError, Problem
from .points import NAMES_BEFORE, UNITS, quantities_of
from .spec import StudySpec
from ..model.dotted import unit_of

SPEC_ATTR = "pounding_study"
SHA_ATTR = "pounding_study_sha256"
RECORDS_ATTR = "pounding_study_records"  # the record files read, with the SHA-256 of their contents
BOOKKEEPING = ("done", "session")
FLUSH_S = 2.0  # a chunk being computed is written at least this often, s (and when it ends)


def is_url(store: str) -> bool:
    return "://" in store


def check_store(store: Any) -> str:
    """The store as a string: a local path (its folder must exist; a file is refused) or an
    fsspec URL (``s3://bucket/study.zarr``: written through fsspec, as xarray does);
    ``file://`` URLs are local paths."""
    if isinstance(store, Path):
        store = str(store)
    if not isinstance(store, str) or not store:
        raise InputError(Problem.WRONG_TYPE, "store", store, got=type(store).__name__,
                         expected="path of a .zarr folder, or an fsspec URL")
    if store.startswith("file://"):
        store = store[len("file://"):]
    if is_url(store):
        protocol = store.split("://", 1)[0]
        try:
            import fsspec

            fsspec.get_filesystem_class(protocol)
        except (ImportError, ValueError) as exc:
            raise InputError(Problem.BAD_OUTPUT, "store", store,
                             why=f"has a protocol fsspec cannot use ({exc})",
                             fix="give a local path, or install the fsspec package for that protocol "
                                 "(s3fs for s3://, gcsfs for gs://)") from None
        return store
    path = Path(store).expanduser().resolve()
    if path.exists() and not path.is_dir():
        raise InputError(Problem.BAD_OUTPUT, "store", store, why="is a file, not a Zarr folder",
                         fix="give a new folder name such as study.zarr")
    parent = path.parent
    if not parent.is_dir():
        raise InputError(Problem.BAD_OUTPUT, "store", store, why=f"is in {parent}, which is not a folder",
                         fix="create that folder first, or give another path")
    if not os.access(parent, os.W_OK) or (path.exists() and not os.access(path, os.W_OK)):
        raise InputError(Problem.BAD_OUTPUT, "store", store, why="cannot be written (no permission)",
                         fix="give a folder you can write in")
    return str(path)


ABSENT, EMPTY, STUDY, OTHER = "absent", "empty", "study", "other"


def store_state(store: str) -> str:
    """What ``store`` holds: nothing (``absent``, ``empty``), a study's store, or something else
    (files, another Zarr store), which a study never overwrites."""
    if is_url(store):
        import fsspec

        mapper = fsspec.get_mapper(store)
        try:
            keys = list(mapper.keys())
        except (FileNotFoundError, OSError):
            return ABSENT
        if not keys:
            return ABSENT
        return STUDY if _is_study_attrs(mapper.get(".zattrs")) else OTHER
    path = Path(store)
    if not path.exists():
        return ABSENT
    if not any(path.iterdir()):
        return EMPTY
    attrs = path / ".zattrs"
    return STUDY if attrs.is_file() and _is_study_attrs(attrs.read_bytes()) else OTHER


def _is_study_attrs(raw: bytes | None) -> bool:
    if raw is None:
        return False
    try:
        return SPEC_ATTR in json.loads(raw)
    except (ValueError, TypeError):
        return False


def refuse_other(store: str) -> None:
    raise InputError(Problem.BAD_OUTPUT, "store", store,
                     why="holds files that are not a study's store (a study writes only into a new folder, "
                         "an empty one, or its own store)",
                     fix="give a new folder name such as study.zarr")


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
    names = quantities_of(spec.kind, spec.system)
    for q in names:
        data[q] = (dims, da.full(shape, np.nan, chunks=chunks), {"units": UNITS.get(q, "1")})
    data["done"] = (dims, np.zeros(shape, dtype=bool), {"description": "the point is computed and written"})
    data["session"] = (dims, np.zeros(shape, dtype=np.int32),
                       {"description": "the run of pounding.study that computed the point (0: not yet)"})
    system = spec.system.to_dict()
    coords = {name: (name, np.array(values), {"units": unit_of(name, system) or "1"})
              for name, values in spec.grid.items()}
    ds = xr.Dataset(data, coords=coords)
    ds.attrs.update({SPEC_ATTR: spec.to_json(), SHA_ATTR: spec.sha256, RECORDS_ATTR: spec._record_files(),
                     "kind": spec.kind,
                     "quantities": list(names)})
    encoding = {name: {"chunks": chunks} for name in (*names, *BOOKKEEPING)}
    for name in BOOKKEEPING:
        encoding[name]["_FillValue"] = None
    if is_url(store):  # (object storage: no rename; a template cut short is written anew next time)
        ds.to_zarr(store, mode="w", compute=False, encoding=encoding, zarr_format=2, consolidated=True)
        return
    # a local template is written beside the store and renamed into place: a study killed while
    # writing it leaves no store (and a stray .tmp folder, replaced next time), never half a one;
    # a store written anew is first renamed away, then deleted once the new one is in place
    path = Path(store)
    tmp = path.with_name(f".{path.name}.tmp")
    old = path.with_name(f".{path.name}.old")
    shutil.rmtree(tmp, ignore_errors=True)
    ds.to_zarr(str(tmp), mode="w", compute=False, encoding=encoding, zarr_format=2, consolidated=True)
    if path.exists():
        shutil.rmtree(old, ignore_errors=True)
        os.replace(path, old)
    os.replace(tmp, path)
    shutil.rmtree(old, ignore_errors=True)


def open_dataset(store: str) -> Any:
    """A study's store as an ``xarray.Dataset`` (read lazily), each quantity by its name now (a store written
    before a quantity was renamed, e.g. a building's ``base_disp_max_m``, reads as ``disp_max_m``)."""
    import xarray as xr

    ds = xr.open_zarr(store, consolidated=True)
    return ds.rename({old: new for new, old in NAMES_BEFORE.items() if old in ds and new not in ds})


def open_checked(store: str, spec: StudySpec | None) -> Any:
    """The store's Zarr group; a store of another spec (or no study) is refused."""
    import zarr

    try:
        group = zarr.open_group(store, mode="r+" if spec is not None else "r", zarr_format=2)
    except Exception as exc:  # (not a Zarr v2 group at all)
        raise InputError(Problem.BAD_OUTPUT, "store", store, why=f"is not a study's store ({exc})",
                         fix="give the folder (or URL) a study wrote") from None
    attrs = dict(group.attrs)
    if SPEC_ATTR not in attrs:
        raise InputError(Problem.BAD_OUTPUT, "store", store, why="is a Zarr store, but not a study's",
                         fix="give the folder (or URL) a study wrote")
    if spec is not None and attrs.get(SHA_ATTR) != spec.sha256:
        theirs = json.loads(attrs[SPEC_ATTR])
        mine = spec.to_dict()
        differ = [k for k in ("system", "compute", "grid") if theirs.get(k) != mine.get(k)]
        raise InputError(Problem.BAD_OUTPUT, "store", store,
                         why=f"was made by another study (its {' and '.join(differ) or 'spec'} differ)",
                         fix="give a new store for this study, resume=False (--restart) to overwrite it, "
                             "or run the study that made it")
    if spec is not None:
        then = attrs.get(RECORDS_ATTR, {})
        for path, sha in spec._record_files().items():
            if path in then and then[path] != sha:
                now = "is gone" if sha == "missing" else "has other contents"
                raise InputError(Problem.BAD_OUTPUT, "store", store,
                                 why=f"was started with the record file {path}, which {now} now: its points "
                                     "and the ones left would come from different records",
                                 fix="put the record back as it was, or resume=False (--restart) to compute "
                                     "every point from the record as it is")
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

    from .points import compute_point
    from .spec import point_of, split_values

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
    # (a store written before a quantity was added has no array for it: it resumes without it; one written
    # before a quantity was renamed has it under its name before)
    computed_names = quantities_of(kind, tables["system"])
    stored = {}
    for q in computed_names:
        name = q if q in group else NAMES_BEFORE.get(q)
        if name is not None and name in group:
            stored[q] = name
    quantities = list(stored)
    partly = bool(done.any())  # (a chunk cut short before: its finished points are kept as they are)
    block = {q: np.asarray(group[stored[q]][sel], dtype=float) if partly else np.full(done.shape, np.nan)
             for q in quantities}
    new = np.zeros(done.shape, dtype=bool)
    sessions = np.asarray(group["session"][sel]) if partly else np.zeros(done.shape, dtype=np.int32)

    def flush() -> None:  # the data first, and last what says it is there
        for q in quantities:
            group[stored[q]][sel] = block[q]
        sessions[new] = session
        group["session"][sel] = sessions
        group["done"][sel] = done | new

    computed = 0
    systems: dict[tuple, Any] = {}
    last_flush = time.monotonic()
    for local in np.ndindex(done.shape):
        if done[local]:
            continue
        if should_stop is not None and should_stop():
            break
        values = {name: tables["grid"][name][s.start + i] for name, s, i in zip(names, sel, local)}
        system_values, options = split_values(tables["compute"], values)
        key = tuple(system_values.items())
        if key not in systems:  # (a system is built once a chunk: the points of a record study share few)
            systems[key] = point_of(tables["system"], tables["compute"], system_values)[0]
        system = systems[key]
        out = dict(zip(computed_names, compute_point(system, options, max_steps)))
        for q in quantities:
            block[q][local] = out[q]
        new[local] = True
        computed += 1
        if advance is not None:
            advance(1)
        if time.monotonic() - last_flush > FLUSH_S:  # (a kill loses at most the last seconds' points)
            flush()
            last_flush = time.monotonic()
    if computed:
        flush()
    return computed
