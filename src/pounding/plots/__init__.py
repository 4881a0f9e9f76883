"""Figures, apart from computing: every function takes ``ax=`` and returns its artists."""

from .run import plot_run

__all__ = ["plot_run"]
