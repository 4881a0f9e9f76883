"""Model updating: parameters identified so that the model reproduces measurements."""

from .contact_law import ContactLawFit, fit_contact_law, rank_contact_laws
from .family import ModelFamily
from .identify import Identification, evaluate, identify
from .system_family import SystemFamily
from .targets import Targets, paper_targets
from .._errors import old_names

__all__ = ["ContactLawFit", "Identification", "ModelFamily", "SystemFamily", "Targets", "evaluate",
           "fit_contact_law", "identify", "paper_targets", "rank_contact_laws"]

# its name before one family served every system's numbers by their paths, for one release
__getattr__ = old_names(__name__, {
    "StructureFamily": ("pounding.SystemFamily", lambda: SystemFamily, "one family for every system")})
