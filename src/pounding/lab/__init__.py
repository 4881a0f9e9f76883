"""The lab side of the paper (issue 17): shaking-table recordings in, the paper's measurements out.

So far: :class:`LabRecord` and :func:`read_test` (reading and checking a recording).
"""

from .record import LabRecord, read_test

__all__ = ["LabRecord", "read_test"]
