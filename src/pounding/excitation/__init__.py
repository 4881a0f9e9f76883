"""What shakes the system: base (table) accelerations.

The engine sees every excitation the same way: a base acceleration that is, piece by
piece, a polynomial of degree <= 1 plus one sinusoid.  :class:`Harmonic` is one sinusoid
forever; :class:`Record` is linear between samples (read from AT2 or CSV files, scaled, and
described by its elastic response spectrum, :func:`response_spectrum`).  Nothing downstream
assumes either.  :class:`RecordPair` is one ground motion's two horizontal components, applied together
(rotated, projected on a direction: a :class:`Record`, described by RotD spectra, :func:`rotd_spectrum`).
"""

from typing import Union

from .harmonic import (
                       HARMONIC,
                       MAX_A_G,
                       MAX_ACCEL_M_S2,
                       MAX_FREQ_HZ,
                       MAX_TIME_S,
                       RECORD,
                       GRAVITY_M_S2,
                       Harmonic,
                       HarmonicPair,
)
from .pair import RecordPair
from .record import Record

Excitation = Union[Harmonic, Record]

__all__ = ["HARMONIC", "MAX_ACCEL_M_S2", "MAX_A_G", "MAX_FREQ_HZ", "MAX_TIME_S", "RECORD", "GRAVITY_M_S2",
           "Excitation", "Harmonic", "HarmonicPair", "Record", "RecordPair"]
