"""What one point of a study keeps for a structure (or two adjacent ones): its peaks over the levels,
storeys, walls and links (``points.STRUCTURE_QUANTITIES``; ``engine.structure_peaks.peaks_of``)."""

from __future__ import annotations

from typing import Any

import numpy as np

from ..engine.structure_peaks import peaks_of


def structure_point(system: Any, options: dict[str, Any], max_steps: int, names: tuple, excitation: Any,
                    sweep_args: dict[str, Any]) -> np.ndarray:
    """One study point of a structure: its quantities ``names`` in order (``excitation``: the run's, None
    for a sweep; ``sweep_args``: a sweep's options)."""
    from ..engine.simulate import simulate
    from ..protocols.sweep import sweep

    if options["kind"] == "sweep":
        freqs = options.get("freqs_hz")
        res = sweep(system, options["a_g"], None if freqs is None else np.asarray(freqs, dtype=float),
                    options.get("direction", "up"), max_steps=max_steps, **sweep_args)
        q = res.quantities()
        q["steps_done"] = float(res.steps_done)
        q["status"] = float(res.status)
    else:
        duration = options.get("duration_s")
        if duration is None:  # (a record's own length)
            duration = float(excitation.t[-1])
        run = simulate(system, excitation, duration, sample_rate_hz=0, max_steps=max_steps)
        q = peaks_of(run, excitation.g)
    return np.array([q[k] for k in names], dtype=float)
