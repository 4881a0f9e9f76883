"""The lab side of the paper (issue 17): shaking-table recordings in, the paper's measurements out.

So far: :class:`LabRecord` and :func:`read_test` (reading and checking a recording), and
:func:`synthetic_test` (a virtual test through realistic sensors).
"""

from .record import LabRecord, read_test
from .synthetic import synthetic_test

__all__ = ["LabRecord", "read_test", "synthetic_test"]
