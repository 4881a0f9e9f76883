"""A run's chatter sequences (rigid stops, :class:`pounding.RigidStop`) as a table: one place for the one-mass
run's and the structures'."""

from __future__ import annotations

from functools import cached_property
from typing import Any

import numpy as np
import pandas as pd


SIDES = ("left", "right")


def chatter_frame(table: np.ndarray, names: Any, column: str = "side") -> pd.DataFrame:
    """The chatter sequences of a run's ``chatter_table`` (contact, first impact s, end s, impacts,
    accumulated), the contact named by ``names`` (a sequence of names by the core's slot) in ``column``."""
    table = np.asarray(table).reshape(-1, 5)
    return pd.DataFrame({
        column: [names[int(c)] for c in table[:, 0]],
        "t_first_s": table[:, 1], "t_end_s": table[:, 2],
        "impacts": table[:, 3].astype(int), "accumulated": table[:, 4] != 0.0,
    })


class NamedChatters:
    """A structure's or a pair's run's ``chatters``, built on first use from its ``chatter_table`` (the core's
    rows) and ``contact_names`` (each contact slot's name)."""

    chatter_table: np.ndarray
    contact_names: tuple

    @cached_property
    def chatters(self) -> pd.DataFrame:
        """The rigid stops' chatter sequences, one row each: ``contact`` (``wall 0 left``), ``t_first_s``,
        ``t_end_s``, ``impacts`` and ``accumulated`` (see :class:`pounding.RigidStop`)."""
        return chatter_frame(self.chatter_table, self.contact_names, "contact")
