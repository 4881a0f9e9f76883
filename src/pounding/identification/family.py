"""A model family for model updating: which system, and which of its numbers are free.

The family fixes the structure (mass, number of backbone branches, hysteresis rule,
contact law) and names every number of it; each number is either fixed (``fixed``) or
fitted within bounds (the ``bounds`` of :func:`pounding.identify`).  Names:

- ``slope_1`` ... ``slope_n``: backbone slopes, N/m (any order of size: hardening allowed);
- ``breakpoint_1`` ... ``breakpoint_{n-1}``: backbone breakpoints, m (increasing);
- ``isolator_damping``: ``C_d``, N s/m;
- with ``bouc_wen = true``: ``bw_stiffness`` (N/m), ``bw_yield_displacement`` (m) and ``bw_n`` of the
  isolator's Bouc-Wen spring;
- ``bumper_stiffness``, ``bumper_damping`` (and ``bumper_exponent`` for Hunt-Crossley):
  the contact law's parameters, both bumpers alike; for the elastic-plastic law
  ``bumper_stiffness`` (K1, N/m), ``bumper_post_yield_ratio`` (K2 / K1, in (0, 1)) and
  ``bumper_yield_compression`` (m); for the multi-linear bumper ``bumper_slope_1`` ...
  ``bumper_slope_k`` (N/m), ``bumper_breakpoint_1`` ... ``bumper_breakpoint_{k-1}`` (m) and
  ``bumper_damping`` (N s/m), ``k`` the family's ``bumper_branches``;
- ``gap``: the gap on each side, m.

Each name is a number of the system's file, by its path (``ModelFamily.paths``: ``slope_1`` is
``isolator.slopes_n_m[0]``, ``gap`` is ``bumpers.gap_m``), the name a :class:`~pounding.SystemFamily`
gives it; a candidate is built by setting them in the file's tables, as a ``SystemFamily``'s is.

TOML (``pounding identify ... --family FAMILY.toml``)::

    mass = 500.0
    branches = 3
    hysteresis = "kinematic"
    law = "kelvin_voigt"
    [fixed]
    gap = 0.015
    [bounds]
    slope_1 = [20e3, 60e3]
    isolator_damping = [100.0, 3000.0]
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from .._checks import instance_of, integer, one_of, positive, read_toml, real
from .._errors import InputError, PoundingWarning, Problem
from ..model import MultilinearBumper, Oscillator
from ..model.dotted import get_value, set_value

WIDE_DECADES = 6  # bounds spanning more decades than this are warned about
FAMILY_KEYS = ("mass", "branches", "hysteresis", "law", "fixed", "bounds", "bumper_branches", "bouc_wen")
BOUC_WEN_PARAMETERS = ("bw_stiffness", "bw_yield_displacement", "bw_n")  # (a = 1, beta = gamma = 0.5)
LAW_PARAMETERS = {"kelvin_voigt": ("bumper_stiffness", "bumper_damping"),
                  "hunt_crossley": ("bumper_stiffness", "bumper_exponent", "bumper_damping"),
                  "elastic_plastic": ("bumper_stiffness", "bumper_post_yield_ratio",
                                      "bumper_yield_compression"),
                  "multilinear": (),  # (named by its number of branches: ModelFamily.law_parameters)
                  "multilinear_kinematic": ()}  # (the same, MultilinearBumper(hysteresis="kinematic"))
MULTILINEAR_LAWS = {"multilinear": "elastic", "multilinear_kinematic": "kinematic"}  # -> the law's hysteresis


@dataclass(frozen=True)
class ModelFamily:
    """The structure of the fitted system and the values of its fixed numbers.

    Parameters
    ----------
    mass : float
        kg, > 0 (weighed, never fitted).
    branches : int
        Number of backbone slopes ``n`` (>= 1).
    hysteresis : {"kinematic", "elastic"}
        The isolator's backbone hysteresis (as :class:`~pounding.Isolator`'s).
    law : {"kelvin_voigt", "hunt_crossley", "elastic_plastic", "multilinear", "multilinear_kinematic"}
        The bumpers' contact law (the last: :class:`MultilinearBumper` with kinematic hysteresis).
    fixed : dict
        ``name -> value`` for the numbers not fitted (names in the module docstring).
    bumper_branches : int
        Slopes of a multi-linear bumper's backbone (1 to 4; default 3: the D-shaped bumper's
        stiff start, plateau and steep rise); ignored by the other laws.
    bouc_wen : bool
        A :class:`~pounding.BoucWen` spring in the isolator, in parallel with its backbone (numbers
        ``bw_stiffness`` N/m, ``bw_yield_displacement`` m and ``bw_n``; ``a = 1``,
        ``beta = gamma = 0.5``).  Every phase is then integrated numerically: some 30 times the
        cost of a campaign.

    Examples
    --------
    A one-branch isolator on Kelvin-Voigt bumpers, with ``C_d`` and the bumpers' damping to be fitted:

    >>> import pounding
    >>> family = pounding.ModelFamily(500.0, branches=1, law="kelvin_voigt",
    ...                               fixed={"slope_1": 38e3,
    ...                                      "bumper_stiffness": 1.46e6,
    ...                                      "gap": 0.015})
    >>> family.parameter_names
    ('slope_1', 'isolator_damping', 'bumper_stiffness', 'bumper_damping', 'gap')
    >>> family.free_names({"isolator_damping": (100.0, 5000.0),
    ...                    "bumper_damping": (0.0, 5000.0)})
    ('isolator_damping', 'bumper_damping')
    >>> family.oscillator({"isolator_damping": 1000.0,
    ...                    "bumper_damping": 500.0}).bumpers.law
    KelvinVoigt(stiffness=1460000.0, damping=500.0)
    >>> family.paths["isolator_damping"]  # its name in a SystemFamily
    'isolator.damping_n_s_m'
    """

    mass: float
    branches: int = 3
    hysteresis: str = "kinematic"
    law: str = "kelvin_voigt"
    fixed: dict[str, float] = field(default_factory=dict)
    bumper_branches: int = 3
    bouc_wen: bool = False

    def __post_init__(self) -> None:
        instance_of("family.bouc_wen", self.bouc_wen, bool, "true or false")
        object.__setattr__(self, "bumper_branches", integer("family.bumper_branches", self.bumper_branches, 1,
                                                            MAX_BUMPER_BRANCHES,
                                                            fix=f"give 1 to {MAX_BUMPER_BRANCHES} bumper "
                                                                "slopes"))
        object.__setattr__(self, "mass", positive("family.mass", self.mass, "kg"))
        object.__setattr__(self, "branches", integer("family.branches", self.branches, 1, MAX_BRANCHES,
                                                                fix=f"give at most {MAX_BRANCHES} backbone "
                                                                    "branches"))
        one_of("family.hysteresis", self.hysteresis, ("kinematic", "elastic"))
        one_of("family.law", self.law, tuple(LAW_PARAMETERS))
        instance_of("family.fixed", self.fixed, dict, "dict of name -> value")
        names = self.parameter_names
        fixed = {}
        for name, value in self.fixed.items():
            if name not in names:
                raise InputError(Problem.UNKNOWN_KEY, f"family.fixed.{name}", value, choices=", ".join(names))
            fixed[name] = real(f"family.fixed.{name}", value)
        object.__setattr__(self, "fixed", fixed)

    @property
    def parameter_names(self) -> tuple[str, ...]:
        """Every number of the family, fixed or free, in a fixed order."""
        n = self.branches
        return (tuple(f"slope_{i + 1}" for i in range(n)) + tuple(f"breakpoint_{i + 1}" for i in range(n - 1))
                + ("isolator_damping",) + (BOUC_WEN_PARAMETERS if self.bouc_wen else ()) + self.law_parameters
                + ("gap",))

    @property
    def law_parameters(self) -> tuple[str, ...]:
        """The contact law's numbers, in a fixed order."""
        if self.law not in MULTILINEAR_LAWS:
            return LAW_PARAMETERS[self.law]
        k = self.bumper_branches
        return (tuple(f"bumper_slope_{i + 1}" for i in range(k)) + tuple(f"bumper_breakpoint_{i + 1}"
                                                                         for i in range(k - 1))
                + ("bumper_damping",))

    def free_names(self, bounds: dict[str, Any]) -> tuple[str, ...]:
        """The names ``bounds`` frees, checked: every number is fixed or bounded, not both."""
        names = self.parameter_names
        for name in bounds:
            if name not in names:
                raise InputError(Problem.UNKNOWN_KEY, f"bounds.{name}", bounds[name],
                                 choices=", ".join(names))
            if name in self.fixed:
                raise InputError(Problem.DUPLICATE, f"bounds.{name}", bounds[name],
                                 repeated="a number the family fixes; fix it or bound it, not both")
        for name in names:
            if name not in bounds and name not in self.fixed:
                raise InputError(Problem.MISSING_KEY, f"bounds.{name}", None,
                                 choices=f"{', '.join(names)} (each bounded here or fixed in the family)")
        return tuple(n for n in names if n in bounds)

    @property
    def paths(self) -> dict[str, str]:
        """Each number's path in the system's file, as a :class:`~pounding.SystemFamily` names it
        (``slope_1`` is ``isolator.slopes_n_m[0]``, ``gap`` is ``bumpers.gap_m``: both gaps), in
        :attr:`parameter_names`' order; ``bumper_post_yield_ratio`` has none (the file's
        ``bumpers.law.post_yield_stiffness`` is it times ``bumper_stiffness``)."""
        n, k = self.branches, self.bumper_branches
        law = {"bumper_stiffness": "stiffness", "bumper_damping": "damping", "bumper_exponent": "exponent",
               "bumper_yield_compression": "yield_compression",
               **{f"bumper_slope_{i + 1}": f"slopes[{i}]" for i in range(k)},
               **{f"bumper_breakpoint_{i + 1}": f"breakpoints[{i}]" for i in range(k - 1)}}
        paths = {f"slope_{i + 1}": f"isolator.slopes_n_m[{i}]" for i in range(n)}
        paths.update({f"breakpoint_{i + 1}": f"isolator.breakpoints_m[{i}]" for i in range(n - 1)})
        paths.update(isolator_damping="isolator.damping_n_s_m",
                     bw_stiffness="isolator.bouc_wen.stiffness_n_m",
                     bw_yield_displacement="isolator.bouc_wen.yield_displacement_m",
                     bw_n="isolator.bouc_wen.n", gap="bumpers.gap_m",
                     **{name: f"bumpers.law.{key}" for name, key in law.items()})
        return {name: paths[name] for name in self.parameter_names if name in paths}

    def _table(self) -> dict[str, Any]:
        """The system's file as tables, every number of the family still to be set (None)."""
        n, k = self.branches, self.bumper_branches
        isolator: dict[str, Any] = {"slopes_n_m": [None] * n, "breakpoints_m": [None] * (n - 1),
                                    "hysteresis": self.hysteresis, "damping_n_s_m": None}
        if self.bouc_wen:  # (a = 1, beta = gamma = 0.5: BoucWen's defaults)
            isolator["bouc_wen"] = {"stiffness_n_m": None, "yield_displacement_m": None, "n": None}
        if self.law in MULTILINEAR_LAWS:
            law: dict[str, Any] = {"type": MultilinearBumper.TYPE, "slopes": [None] * k,
                                   "breakpoints": [None] * (k - 1), "damping": None,
                                   "hysteresis": MULTILINEAR_LAWS[self.law]}
        elif self.law == "elastic_plastic":
            law = {"type": self.law, "stiffness": None, "post_yield_stiffness": None,
                   "yield_compression": None}
        else:
            law = {"type": self.law, "stiffness": None, "damping": None,
                   **({"exponent": None} if self.law == "hunt_crossley" else {})}
        return {"mass_kg": self.mass, "isolator": isolator,
                "bumpers": {"gap_left_m": None, "gap_right_m": None, "law": law}}

    def oscillator(self, values: dict[str, float]) -> Oscillator:
        """The YBs system for ``values`` (free numbers) plus the fixed ones: each set by its path
        (:attr:`paths`) in the system's file, which is then read as any system's.

        Raises :class:`~pounding.InputError` when they make no valid system (e.g.
        breakpoints out of order).
        """
        p = {**self.fixed, **values}
        table = self._table()
        for name, path in self.paths.items():
            set_value(table, path, p[name])
        if self.law == "elastic_plastic":
            ratio = p["bumper_post_yield_ratio"]
            if not 0.0 < ratio < 1.0:
                raise InputError(Problem.OUT_OF_RANGE, "bumper_post_yield_ratio", ratio, range="(0, 1)",
                                 hint=" (K2 / K1: the yield line is the softer one)")
            table["bumpers"]["law"]["post_yield_stiffness"] = ratio * p["bumper_stiffness"]
        return Oscillator.from_dict(table)

    def values_of(self, oscillator: Oscillator) -> dict[str, float]:
        """Every number of the family read from a system of this family (YBs), by its path."""
        iso, b = oscillator.isolator, oscillator.bumpers
        multilinear = self.law in MULTILINEAR_LAWS
        if (b is None or iso.n_branches != self.branches or (iso.bouc_wen is not None) != self.bouc_wen
                or b.law.TYPE != (MultilinearBumper.TYPE if multilinear else self.law)
                or (multilinear and (len(b.law.slopes) != self.bumper_branches
                                     or b.law.hysteresis != MULTILINEAR_LAWS[self.law]))):
            raise InputError(Problem.WRONG_TYPE, "oscillator", oscillator, got="another structure",
                             expected=f"a YBs system with {self.branches} branches and {self.law} bumpers")
        if self.bouc_wen:
            bw = iso.bouc_wen
            if (bw.a, bw.beta, bw.gamma) != (1.0, 0.5, 0.5):
                raise InputError(Problem.WRONG_TYPE, "oscillator", oscillator,
                                 got=f"a Bouc-Wen spring with a = {bw.a:g}, "
                                 f"beta = {bw.beta:g}, gamma = {bw.gamma:g}",
                                 expected="the family's: a = 1, beta = gamma = 0.5")
        table = oscillator.to_dict()
        paths = self.paths
        return {name: float(get_value(table, paths[name])) if name in paths
                else float(b.law.post_yield_stiffness / b.law.stiffness)  # (bumper_post_yield_ratio)
                for name in self.parameter_names}

    @classmethod
    def from_toml(cls, path: str | Path) -> tuple[ModelFamily, dict[str, tuple[float, float]]]:
        """Read a family and its bounds (format in the module docstring)."""
        table = read_toml("family", path, FAMILY_KEYS)
        if "mass" not in table:
            raise InputError(Problem.MISSING_KEY, "mass", None, choices=", ".join(FAMILY_KEYS))
        bounds = table.get("bounds", {})
        family = cls(table["mass"], table.get("branches", 3), table.get("hysteresis", "kinematic"),
                     table.get("law", "kelvin_voigt"), table.get("fixed", {}),
                     table.get("bumper_branches", 3), table.get("bouc_wen", False))
        return family, check_bounds(family, bounds)


MAX_BRANCHES = 50
MAX_BUMPER_BRANCHES = 4  # (contact_laws.MAX_BRANCHES)


def check_bounds(family: ModelFamily, bounds: Any) -> dict[str, tuple[float, float]]:
    """``bounds`` as ``name -> (low, high)`` floats, checked (finite, low < high, known names)."""
    instance_of("bounds", bounds, dict,
                "dict of name -> (low, high), e.g. {\"isolator_damping\": (100, 5000)}")
    if not bounds:
        raise InputError(Problem.EMPTY, "bounds", bounds)
    out = {}
    for name in family.free_names(bounds):
        pair = bounds[name]
        if not isinstance(pair, (list, tuple, np.ndarray)) or len(pair) != 2:
            raise InputError(Problem.WRONG_TYPE, f"bounds.{name}", pair, got=type(pair).__name__,
                             expected="pair [low, high]")
        low, high = real(f"bounds.{name}[0]", pair[0]), real(f"bounds.{name}[1]", pair[1])
        if not low < high:
            raise InputError(Problem.NOT_INCREASING, f"bounds.{name}", list(pair))
        decades = math.log10(high) - math.log10(low) if low > 0.0 else 0.0
        if decades > WIDE_DECADES:
            warnings.warn(PoundingWarning(
                f"bounds.{name} = [{low:g}, {high:g}] spans {decades:.0f} decades: the search "
                "samples it logarithmically, so nearly every candidate is far from a physical value, and "
                "candidates with extreme numbers can take long to simulate; give bounds a decade or two "
                "either side of the value you expect"), stacklevel=3)
        out[name] = (low, high)
    return out
