"""Intersphinx inventories of the projects the docs link to, written at build time from the entries below.

The docs build runs where there is no network (CI, a laptop on a train), so intersphinx cannot fetch
``objects.inv`` from numpy.org and friends.  These are the entries pounding's pages and docstrings refer to,
with the pages they have on each project's stable documentation; :func:`write_inventories` writes them in
Sphinx's inventory format (version 2) and ``conf.py`` points ``intersphinx_mapping`` at the files, so the
links in the built pages go to the real sites.  A name missing here renders as plain text: add it (name,
role, page) when a docstring starts to mention it.
"""

from __future__ import annotations

import zlib
from pathlib import Path

# project: (base URL, version, [(name, domain:role, page relative to the base URL[, title of a label])])
INVENTORIES: dict[str, tuple[str, str, list[tuple[str, ...]]]] = {
    "python": ("https://docs.python.org/3/", "3", [
        ("float", "py:class", "library/functions.html#float"),
        ("int", "py:class", "library/functions.html#int"),
        ("bool", "py:class", "library/functions.html#bool"),
        ("str", "py:class", "library/stdtypes.html#str"),
        ("dict", "py:class", "library/stdtypes.html#dict"),
        ("list", "py:class", "library/stdtypes.html#list"),
        ("tuple", "py:class", "library/stdtypes.html#tuple"),
        ("callable", "py:function", "library/functions.html#callable"),
        ("pathlib.Path", "py:class", "library/pathlib.html#pathlib.Path"),
        ("enum.Enum", "py:class", "library/enum.html#enum.Enum"),
        ("KeyboardInterrupt", "py:exception", "library/exceptions.html#KeyboardInterrupt"),
        ("ValueError", "py:exception", "library/exceptions.html#ValueError"),
        ("UserWarning", "py:exception", "library/exceptions.html#UserWarning"),
        ("tomllib", "py:module", "library/tomllib.html#module-tomllib"),
        ("None", "py:data", "library/constants.html#None"),
        ("complex", "py:class", "library/functions.html#complex"),
        ("enum.IntEnum", "py:class", "library/enum.html#enum.IntEnum"),
        ("typing.Any", "py:data", "library/typing.html#typing.Any"),
        ("ModuleNotFoundError", "py:exception", "library/exceptions.html#ModuleNotFoundError"),
        ("object", "py:class", "library/functions.html#object"),
        ("sequence", "std:term", "glossary.html#term-sequence"),
        ("iterable", "std:term", "glossary.html#term-iterable"),
        ("mapping", "std:term", "glossary.html#term-mapping"),
        ("file object", "std:term", "glossary.html#term-file-object"),
        ("bltin-boolean-values", "std:label", "library/stdtypes.html#bltin-boolean-values", "Boolean Values"),
    ]),
    "numpy": ("https://numpy.org/doc/stable/", "stable", [
        ("numpy.ndarray", "py:class", "reference/generated/numpy.ndarray.html#numpy.ndarray"),
        ("numpy.random.Generator", "py:class", "reference/random/generator.html#numpy.random.Generator"),
        ("numpy.interp", "py:function", "reference/generated/numpy.interp.html#numpy.interp"),
        ("array_like", "std:term", "glossary.html#term-array_like"),
    ]),
    "scipy": ("https://docs.scipy.org/doc/scipy/", "stable", [
        ("scipy.integrate.solve_ivp", "py:function",
         "reference/generated/scipy.integrate.solve_ivp.html#scipy.integrate.solve_ivp"),
        ("scipy.optimize.least_squares", "py:function",
         "reference/generated/scipy.optimize.least_squares.html#scipy.optimize.least_squares"),
        ("scipy.optimize.brentq", "py:function",
         "reference/generated/scipy.optimize.brentq.html#scipy.optimize.brentq"),
        ("scipy.signal.butter", "py:function",
         "reference/generated/scipy.signal.butter.html#scipy.signal.butter"),
    ]),
    "pandas": ("https://pandas.pydata.org/docs/", "stable", [
        ("pandas.DataFrame", "py:class", "reference/api/pandas.DataFrame.html#pandas.DataFrame"),
    ]),
    "xarray": ("https://docs.xarray.dev/en/stable/", "stable", [
        ("xarray.Dataset", "py:class", "generated/xarray.Dataset.html#xarray.Dataset"),
        ("xarray.DataArray", "py:class", "generated/xarray.DataArray.html#xarray.DataArray"),
        ("xarray.open_zarr", "py:function", "generated/xarray.open_zarr.html#xarray.open_zarr"),
    ]),
    "matplotlib": ("https://matplotlib.org/stable/", "stable", [
        ("matplotlib.axes.Axes", "py:class", "api/_as_gen/matplotlib.axes.Axes.html#matplotlib.axes.Axes"),
        ("matplotlib.figure.Figure", "py:class",
         "api/_as_gen/matplotlib.figure.Figure.html#matplotlib.figure.Figure"),
        ("matplotlib.artist.Artist", "py:class", "api/artist_api.html#matplotlib.artist.Artist"),
        ("matplotlib.lines.Line2D", "py:class",
         "api/_as_gen/matplotlib.lines.Line2D.html#matplotlib.lines.Line2D"),
    ]),
    "distributed": ("https://distributed.dask.org/en/stable/", "stable", [
        ("distributed.Client", "py:class", "api.html#distributed.Client"),
        ("distributed.LocalCluster", "py:class", "api.html#distributed.LocalCluster"),
        ("dask.distributed.Client", "py:class", "api.html#distributed.Client"),
    ]),
}


def inventory_bytes(project: str, version: str, entries: list[tuple[str, ...]]) -> bytes:
    """One inventory in Sphinx's format version 2: a plain header, then zlib-compressed lines
    ``name domain:role priority uri display-name`` (``-``: the name itself)."""
    header = (f"# Sphinx inventory version 2\n# Project: {project}\n# Version: {version}\n"
              "# The remainder of this file is compressed using zlib.\n").encode()
    lines = []
    for name, role, uri, *title in entries:
        # labels have priority -1 and a title; everything else priority 1 and its own name ("-")
        lines.append(f"{name} {role} -1 {uri} {title[0]}\n" if title else f"{name} {role} 1 {uri} -\n")
    body = "".join(lines).encode()
    return header + zlib.compress(body)


def write_inventories(directory: Path) -> dict[str, tuple[str, str]]:
    """Write every inventory into ``directory``; returns the ``intersphinx_mapping`` for them."""
    directory.mkdir(parents=True, exist_ok=True)
    mapping = {}
    for project, (url, version, entries) in INVENTORIES.items():
        path = directory / f"{project}.inv"
        path.write_bytes(inventory_bytes(project, version, entries))
        mapping[project] = (url, str(path))
    return mapping
