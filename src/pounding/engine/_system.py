"""What the core takes: the system (``kernel_system`` packs an ``Oscillator`` into the core's
:class:`pounding._core.System`, picklable) and the forcing (``Harmonic.kernel_arrays`` /
``Record.kernel_arrays``: its kind, its parameters and, for a record, its times and accelerations)."""

from __future__ import annotations

from .._core import Forcing, System  # noqa: F401  (the door's; re-exported for the engine's callers)
