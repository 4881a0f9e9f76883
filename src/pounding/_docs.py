"""Docstring fragments that many public functions share, written once (as scipy's ``doccer`` and
matplotlib's ``_docstring``): a line holding only ``{name}`` in a docstring becomes the fragment ``name``,
at that line's indentation, when the function is defined."""

from __future__ import annotations

import re
from typing import Callable, TypeVar

F = TypeVar("F", bound=Callable)

_BUMPERS = ("bumpers : bool\n"
            "    True: the YBs configuration (with bumpers); False: the same system without them (NBs).")
FRAGMENTS = {
    "ax": ("ax : matplotlib Axes, optional\n"
           "    Where to draw (a new figure if omitted)."),
    "bumpers": _BUMPERS,
    # a preset read from its file in pounding/data: its Parameters and Returns sections
    "data_preset": ("Parameters\n"
                    "----------\n"
                    + _BUMPERS + "\n\n"
                    "Returns\n"
                    "-------\n"
                    "Oscillator\n"
                    "    The system, as its file in ``pounding/data`` holds it (named above)."),
    # a preset measured through a chain (its system and its chain read from its file in pounding/data)
    "measured_preset": ("Parameters\n"
                        "----------\n"
                        + _BUMPERS + "\n\n"
                        "Returns\n"
                        "-------\n"
                        "(Oscillator, MeasurementChain)\n"
                        "    The system, as its file in ``pounding/data`` holds it (named above), and\n"
                        "    the chain its metrics are measured through (give it as ``measurement=``)."),
    # a bumper's measured history (a contact law's fit)
    "bumper_history": ("displacement_m : array_like, shape (n,)\n"
                       "    Compression of the bumper, m (> 0 in contact; samples <= 0 are left out).\n"
                       "force_n : array_like, shape (n,)\n"
                       "    Force the bumper pushes with, N.\n"
                       "time_s : array_like, shape (n,), optional\n"
                       "    Sample times, s, strictly increasing: the compression rate is their numerical\n"
                       "    derivative (second order).  Give this or ``velocity_m_s``.\n"
                       "velocity_m_s : array_like, shape (n,), optional\n"
                       "    Compression rate, m/s, when it was measured."),
    # a fit's bootstrap band (a fragility's)
    "band": ("confidence : float\n"
             "    The band's level, in (0, 1).\n"
             "seed : int\n"
             "    The bootstrap's random seed (the same seed, the same band)."),
    # a stripe analysis's example: El Centro at two stripes of Sa(1 s) on the damped paper system with two
    # gaps (``msa``)
    "two_gaps_msa": (">>> import pounding\n"
                     ">>> from pounding import design\n"
                     ">>> ybs = pounding.presets.paper_damped()\n"
                     ">>> msa = design.stripe_analysis(ybs, \"el-centro\", [0.2, 0.5], period_s=1.0,\n"
                     "...                              store=\"msa.zarr\", progress=False,\n"
                     "...                              grid={\"bumpers.gap_m\": [0.02, 0.2]})"),
    # a contact law's example: the paper's isolated 500 kg mass on bumpers of the law ``law``, 15 mm away,
    # pushed at 0.6 m/s into them (``run``: half a second of it)
    "pushed_run": (">>> osc = pounding.Oscillator(500.0, pounding.presets.paper_damped().isolator,\n"
                   "...                           pounding.Bumpers(0.015, 0.015, law))\n"
                   ">>> push = pounding.State.at_rest(osc, velocity_m_s=0.6)\n"
                   ">>> run = pounding.simulate(osc, pounding.Harmonic(a_g=0.05, freq_hz=2.2),\n"
                   "...                         duration=0.5, state=push)"),
}

_PLACE = re.compile(r"^(\s*)\{([A-Za-z_]\w*)\}\s*$")  # (a name: not a doctest's output such as {1})


def fill_doc(func: F) -> F:
    """``func`` with its docstring's ``{name}`` lines replaced by :data:`FRAGMENTS`' texts (an unknown name
    is a KeyError at import: a typo is seen at once)."""
    if not func.__doc__:  # (python -OO)
        return func
    lines = []
    for line in func.__doc__.splitlines():
        place = _PLACE.match(line)
        if place is None:
            lines.append(line)
            continue
        indent, name = place.groups()
        lines.extend(indent + part if part else part for part in FRAGMENTS[name].splitlines())
    func.__doc__ = "\n".join(lines)
    return func
