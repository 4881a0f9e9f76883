"""The lab side of the paper (issue 17): shaking-table recordings in, the paper's measurements out.

So far: :class:`LabRecord` and :func:`read_test` (reading and checking a recording),
:func:`synthetic_test` (a virtual test through realistic sensors) and
:func:`analyse_stepped_sine` (Table 2's quantities per step, in a :class:`LabSweep`); the
contacts (Tables 3 and 4), plots, targets and the command line are to come.
"""

from .analysis import analyse_stepped_sine
from .lab_sweep import LabSweep
from .record import LabRecord, read_test
from .synthetic import synthetic_test

__all__ = ["LabRecord", "LabSweep", "analyse_stepped_sine", "read_test", "synthetic_test"]
