"""The sliding isolators, single and triple: what a system asks of either (whether it is one, and the stops
it cannot have beside it)."""

from __future__ import annotations

from typing import Any

from .._errors import InputError, Problem
from .friction import FrictionIsolator
from .triple_friction import TripleFrictionPendulum

SLIDERS = (FrictionIsolator, TripleFrictionPendulum)


def is_friction(isolator: Any) -> bool:
    """Is this isolator a friction isolator (a slider: a single one or a triple friction pendulum)?"""
    return isinstance(isolator, SLIDERS)


def refuse_rigid_stops(isolator: Any, laws: Any) -> None:
    """A friction isolator's system has no rigid stop yet (``laws``: ``(field, law)`` pairs): an impulse on a
    sticking base is not resolved.  Raises naming the first rigid one."""
    from .contact_laws import is_rigid

    if not is_friction(isolator):
        return
    for field_name, law in laws:
        if law is not None and is_rigid(law):
            raise InputError(Problem.WRONG_CONFIGURATION, field_name, law,
                             got="with a rigid stop on a friction isolator (not supported yet: an impulse "
                                 "on a sticking base)",
                             fix="give it a compliant law (KelvinVoigt or Hertzdamp with the stop's "
                                 "stiffness), or the isolator an elastic pre-slip (preslip_m)")
