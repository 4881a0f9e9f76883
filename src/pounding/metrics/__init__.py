"""What is measured: per-impact quantities and hysteresis loops."""

from .hysteresis import HysteresisLoop
from .impacts import impact_table

__all__ = ["HysteresisLoop", "impact_table"]
