"""Protocols: the virtual shaking table (stepped-sine sweeps) and the paper's campaign."""

from .campaign import CampaignResult, campaign
from .sweep import SweepPlan, paper_frequencies_hz, sweep
from .sweep_result import SweepResult

__all__ = ["CampaignResult", "SweepPlan", "SweepResult", "campaign", "paper_frequencies_hz", "sweep"]
