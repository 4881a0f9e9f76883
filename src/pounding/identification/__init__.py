"""Model updating: parameters identified so that the model reproduces measurements."""

from .contact_law import ContactLawFit, fit_contact_law

__all__ = ["ContactLawFit", "fit_contact_law"]
