"""Model updating: parameters identified so that the model reproduces measurements."""

from .contact_law import ContactLawFit, fit_contact_law, rank_contact_laws
from .family import ModelFamily
from .identify import Identification, evaluate, identify
from .structure_family import StructureFamily
from .targets import Targets, paper_targets

__all__ = ["ContactLawFit", "Identification", "ModelFamily", "StructureFamily", "Targets", "evaluate",
           "fit_contact_law", "identify", "paper_targets", "rank_contact_laws"]
