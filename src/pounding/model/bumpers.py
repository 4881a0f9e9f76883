"""The module of ``Bumpers`` before: a single mass's bumpers now live beside ``Wall``, the pair of sides they
are, in :mod:`pounding.model.structure_parts` (``pounding.Bumpers`` is where it was).  Its names answer here
for one release, with a ``FutureWarning`` (a pickle made before names this module)."""

from __future__ import annotations

from typing import Any

from .._errors import old_names


def _moved(name: str) -> Any:
    from . import structure_parts

    return getattr(structure_parts, name)


__getattr__ = old_names(__name__, {
    name: (f"pounding.model.structure_parts.{name}", lambda name=name: _moved(name),
           "a single mass's bumpers are a wall's pair of sides")
    for name in ("Bumpers", "MAX_GAP_M")})
