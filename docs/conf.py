"""Sphinx configuration of pounding's documentation.

Build (warnings are errors; the gallery's scripts are executed):

    pip install -e ".[docs]" && sphinx-build -W -b html docs docs/_build/html
"""

from __future__ import annotations

import re
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pounding

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from _inventories import write_inventories  # noqa: E402

project = "pounding"
author = "the pounding developers"
copyright = "2026, the pounding developers"
release = pounding.__version__
version = release

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.intersphinx",
    "sphinx.ext.mathjax",
    "sphinx.ext.viewcode",
    "numpydoc",
    "myst_parser",
    "sphinx_gallery.gen_gallery",
]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
exclude_patterns = ["_build", "auto_examples/*.ipynb", "auto_examples/*.py", "auto_examples/*.zip",
                    "auto_examples/*.md5", "auto_examples/*.json", "**/sg_execution_times.rst"]
templates_path = ["_templates"]

# --- API reference -----------------------------------------------------------------------------
autosummary_generate = True
autosummary_imported_members = True
autodoc_default_options = {"members": True, "inherited-members": False, "show-inheritance": False}
autodoc_typehints = "none"  # the numpydoc sections say the types, with units
autodoc_member_order = "bysource"
numpydoc_show_class_members = False  # the class pages list their members through autodoc
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = True
numpydoc_xref_aliases = {
    "ndarray": "numpy.ndarray",
    "array_like": ":term:`array_like`",
    "DataFrame": "pandas.DataFrame",
    "pandas.DataFrame": "pandas.DataFrame",
    "Dataset": "xarray.Dataset",
    "DataArray": "xarray.DataArray",
    "Axes": "matplotlib.axes.Axes",
    "Figure": "matplotlib.figure.Figure",
    "Path": "pathlib.Path",
    "Client": "distributed.Client",
    "Generator": "numpy.random.Generator",
    "Oscillator": "pounding.Oscillator",
    "Isolator": "pounding.Isolator",
    "Bumpers": "pounding.Bumpers",
    "Harmonic": "pounding.Harmonic",
    "Record": "pounding.Record",
    "State": "pounding.State",
    "Run": "pounding.Run",
    "Status": "pounding.Status",
    "SweepResult": "pounding.SweepResult",
    "CampaignResult": "pounding.CampaignResult",
    "Targets": "pounding.Targets",
    "ModelFamily": "pounding.ModelFamily",
    "Identification": "pounding.Identification",
    "StudySpec": "pounding.StudySpec",
    "StudyResult": "pounding.StudyResult",
    "PeriodicOrbit": "pounding.PeriodicOrbit",
    "Branch": "pounding.Branch",
    "Bifurcation": "pounding.Bifurcation",
    "BifurcationCurve": "pounding.BifurcationCurve",
    "CoexistenceMap": "pounding.CoexistenceMap",
    "LabRecord": "pounding.lab.LabRecord",
    "LabSweep": "pounding.lab.LabSweep",
}
numpydoc_xref_ignore = {"optional", "or", "of", "default", "shape", "sequence", "pair", "iterable", "mapping",
                        "contact", "law", "them", "None", "path", "n", "m", "k", "matplotlib", "list", "each"}

# --- links to the projects pounding builds on: inventories written here, no network needed -------
intersphinx_mapping = write_inventories(HERE / "_build" / "inventories")
intersphinx_timeout = 5

# --- the gallery: every script executed at build time, a failure fails the build -----------------
GALLERY_LIMIT_S = 30.0
JUNIT = "../gallery-junit.xml"  # relative to the output directory: docs/_build/gallery-junit.xml
sphinx_gallery_conf = {
    "examples_dirs": "../examples/gallery",
    "gallery_dirs": "auto_examples",
    "filename_pattern": r"plot_",
    "within_subsection_order": "FileNameSortKey",
    "abort_on_example_error": True,
    "only_warn_on_example_error": False,
    "download_all_examples": False,
    "remove_config_comments": True,
    "junit": JUNIT,
    "reset_modules": ("matplotlib",),
    "image_scrapers": ("matplotlib",),
    "matplotlib_animations": False,
    "capture_repr": (),
    "show_signature": False,
}

# --- markdown (the user guide's pages are the repository's docs/*.md) -----------------------------
myst_enable_extensions = ["dollarmath", "colon_fence"]
myst_heading_anchors = 3
suppress_warnings = ["myst.header"]  # the guide's pages start at ## under the page title in places

# --- HTML --------------------------------------------------------------------------------------
html_theme = "pydata_sphinx_theme"
html_title = f"pounding {release}"
html_theme_options = {
    "navigation_with_keys": False,
    "show_toc_level": 2,
    "secondary_sidebar_items": ["page-toc"],
}
# pages without sub-pages have no section navigation to show: no empty left sidebar on them
html_sidebars = {"getting_started": [], "benchmarks": [], "paper": []}
html_static_path: list[str] = []
html_show_sourcelink = False


def _gallery_under_the_limit(app, exception) -> None:
    """Each gallery example must run in under GALLERY_LIMIT_S: a slower one is a warning (an error
    with -W)."""
    junit = Path(app.outdir, JUNIT).resolve()
    if exception is not None or not junit.exists():
        return
    from sphinx.util import logging

    logger = logging.getLogger("pounding.docs")
    for case in ET.parse(junit).getroot().iter("testcase"):
        seconds = float(case.get("time", 0.0))
        if seconds > GALLERY_LIMIT_S:
            name = re.sub(r".*/", "", case.get("file", case.get("name", "?")))
            logger.warning(f"gallery example {name} took {seconds:.1f} s, over the {GALLERY_LIMIT_S:.0f} s "
                           "limit: make it smaller (fewer frequencies, cycles, records)")


def setup(app) -> None:
    app.connect("build-finished", _gallery_under_the_limit)
