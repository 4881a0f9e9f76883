"""Reports: the paper's tables and figures from the model, beside the measurements."""

from .compare import comparison
from .reproduce import Report, reproduce

__all__ = ["Report", "comparison", "reproduce"]
