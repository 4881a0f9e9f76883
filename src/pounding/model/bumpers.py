"""Two massless bumpers behind gaps, one on each side of the mass."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, ClassVar, Optional

from .._checks import at_most, non_negative, plausible, positive
from .._errors import InputError, Problem, warn_renamed
from .contact_laws import ContactLaw, check_law, law_to_dict, refuse_clamp

MAX_GAP_M = 1e3  # refused beyond (a unit error)


@dataclass(frozen=True, init=False)
class Bumpers:
    """Left and right bumpers, each behind its gap (the paper's YBs configuration).

    A bumper only pushes.  Contact with the right bumper starts when the displacement ``D``
    reaches ``gap_right_m + d_R(t)``, where ``d_R >= 0`` is the bumper's current compression
    (it may not have recovered from the previous contact); contact ends when the force would
    become a pull; in between contacts the bumper relaxes by its own law.  Mirror for left.

    Parameters
    ----------
    gap_left_m, gap_right_m : float
        Distances in m from the mass at rest to each bumper's free surface, >= 0.  The
        paper's total gap is ``gap_left_m + gap_right_m = 0.03`` m.  (``gap_left`` and
        ``gap_right``, their names before, still work for one release, with a warning.)
    law : KelvinVoigt, HuntCrossley, Jankowski, MultilinearBumper, ElasticPlastic or Hertzdamp
        Contact law of the left bumper, and of the right one unless ``law_right`` is given.
    law_right : KelvinVoigt, HuntCrossley, Jankowski, MultilinearBumper, ElasticPlastic or Hertzdamp, optional
        Contact law of the right bumper when it differs from the left one.
    capacity_m : float, optional
        The deepest compression the bumpers take (m), > 0: what a design checks their runs'
        ``compression_max_m`` against (``StripeAnalysis.outcomes("compression")``).  It does not
        change the motion.

    Examples
    --------
    The paper's YBs bumpers, 15 mm from the mass on each side; a stiffer one on the right:

    >>> import pounding
    >>> epdm = pounding.KelvinVoigt(stiffness=1.46e6, damping=5.0)
    >>> bumpers = pounding.Bumpers(gap_left_m=0.015, gap_right_m=0.015, law=epdm)
    >>> bumpers.total_gap  # m
    0.03
    >>> stiff = pounding.Bumpers(0.015, 0.010, epdm,
    ...                          law_right=pounding.KelvinVoigt(5.0e6, 5.0))
    >>> stiff.right.stiffness, stiff.mirrored().gap_left_m
    (5000000.0, 0.01)
    """

    gap_left_m: float
    gap_right_m: float
    law: ContactLaw
    law_right: Optional[ContactLaw] = None
    capacity_m: Optional[float] = None

    FIELDS: ClassVar[tuple[str, ...]] = ("gap_left_m", "gap_right_m", "law", "law_right", "capacity_m")
    # the names before (0.1's), still read for one release with a warning: in Python, TOML and dotted names
    RENAMED: ClassVar[dict[str, str]] = {"gap_left": "gap_left_m", "gap_right": "gap_right_m"}

    def __init__(self, gap_left_m: Any = None, gap_right_m: Any = None, law: Any = None,
                 law_right: Optional[ContactLaw] = None, capacity_m: Optional[float] = None,
                 **renamed: Any) -> None:
        given = {"gap_left_m": gap_left_m, "gap_right_m": gap_right_m}
        for old, value in renamed.items():
            if old not in self.RENAMED:
                raise TypeError(f"Bumpers() got an unexpected keyword argument '{old}'")
            warn_renamed(old, self.RENAMED[old])
            given[self.RENAMED[old]] = value
        for name, value in (*given.items(), ("law", law)):
            if value is None:
                raise InputError(Problem.MISSING_INPUT, f"bumpers.{name}", None,
                                 what=f"Bumpers({name}=...)")
        object.__setattr__(self, "gap_left_m", given["gap_left_m"])
        object.__setattr__(self, "gap_right_m", given["gap_right_m"])
        object.__setattr__(self, "law", law)
        object.__setattr__(self, "law_right", law_right)
        object.__setattr__(self, "capacity_m", capacity_m)
        self.__post_init__()

    @property
    def gap_left(self) -> float:
        """``gap_left_m`` under its name before (a warning: it goes in the next release)."""
        warn_renamed("gap_left", "gap_left_m")
        return self.gap_left_m

    @property
    def gap_right(self) -> float:
        """``gap_right_m`` under its name before (a warning: it goes in the next release)."""
        warn_renamed("gap_right", "gap_right_m")
        return self.gap_right_m

    def __post_init__(self) -> None:
        for name in ("gap_left_m", "gap_right_m"):
            gap = non_negative(f"bumpers.{name}", getattr(self, name), "m")
            at_most(f"bumpers.{name}", gap, MAX_GAP_M, " m", "give the gap in m (15 mm is 0.015)")
            plausible(f"bumpers.{name}", gap, 0.0, 0.5, "gaps are in m (15 mm is 0.015)")
            object.__setattr__(self, name, gap)
        if self.capacity_m is not None:
            capacity = positive("bumpers.capacity_m", self.capacity_m, "m")
            plausible("bumpers.capacity_m", capacity, 0.0, 0.5, "a bumper's capacity is in m (20 mm is 0.02)")
            object.__setattr__(self, "capacity_m", capacity)
        for name in ("law", "law_right"):
            value = getattr(self, name)
            if value is None and name == "law_right":
                continue
            check_law(f"bumpers.{name}", value)
        refuse_clamp("bumpers.gap_left_m", self.gap_left_m, self.gap_right_m, self.left, self.right)

    @property
    def left(self) -> ContactLaw:
        """Contact law of the left bumper."""
        return self.law

    @property
    def right(self) -> ContactLaw:
        """Contact law of the right bumper."""
        return self.law if self.law_right is None else self.law_right

    @property
    def total_gap(self) -> float:
        """``Delta = gap_left_m + gap_right_m`` in m."""
        return self.gap_left_m + self.gap_right_m

    def mirrored(self) -> "Bumpers":
        """The same bumpers seen in a mirror (left and right swapped)."""
        if self.law_right is None:
            return Bumpers(self.gap_right_m, self.gap_left_m, self.law, capacity_m=self.capacity_m)
        return Bumpers(self.gap_right_m, self.gap_left_m, self.law_right, self.law, self.capacity_m)

    def to_dict(self) -> dict[str, Any]:
        """The constructor's fields as plain values (the TOML form: ``Oscillator.to_toml`` writes it)."""
        out: dict[str, Any] = {"gap_left_m": self.gap_left_m, "gap_right_m": self.gap_right_m,
                               "law": law_to_dict(self.law)}
        if self.law_right is not None:
            out["law_right"] = law_to_dict(self.law_right)
        if self.capacity_m is not None:
            out["capacity_m"] = self.capacity_m
        return out
