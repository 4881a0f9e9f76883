"""Measured targets for model updating: what a campaign should reproduce, and how closely.

A target is one quantity of one sweep: ``(configuration, a_g, direction, quantity)`` with
the measured ``value`` and a ``tolerance``, absolute or relative to the value.  The fit
works on the normalised residuals ``(model - value) / allowed``, where ``allowed`` is the
tolerance (times ``|value|`` when relative): a target is met when its residual is within
+-1 (``pounding.identify``'s ``loss`` says what it minimises).

TOML (``pounding identify TARGETS.toml``)::

    eta_gap_total_m = 0.03   # optional: the Delta the measured eta was normalised by (below)

    [defaults]            # optional
    direction = "up"

    [tolerances]          # optional: per quantity, overrides DEFAULT_TOLERANCES
    alpha = {tolerance = 0.15, relative = true}

    [[target]]
    configuration = "YBs"
    a_g = 0.05
    quantity = "alpha"
    value = 16.8
    # direction, tolerance, relative, weight: optional
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from .._checks import at_most, boolean, gap_total, instance_of, one_of, positive, read_toml, real
from .._errors import InputError, Problem
from ..data import paper_gap_total_m, paper_measurements
from ..excitation import MAX_A_G

# quantity -> (tolerance, relative): the targets (nu_R within one 0.1 Hz step, alpha
# 10 %, eta or e 5 %, contact times 30 %, restitution 0.05)
DEFAULT_TOLERANCES: dict[str, tuple[float, bool]] = {
    "nu_r": (0.1, False),
    "alpha": (0.10, True),
    "eta": (0.05, True),
    "e": (0.05, True),
    "contact_nu_min": (0.1, False),
    "contact_nu_max": (0.1, False),
    "contact_time_ms": (0.30, True),
    "restitution": (0.05, False),
    "dissipated_energy_per_mass": (0.30, True),
    "peak_force_over_mg": (0.30, True),
    "excursion_max_m": (0.05, True),
}
POSITIVE_QUANTITIES = ("nu_r", "contact_nu_min", "contact_nu_max", "contact_time_ms", "alpha", "eta", "e",
                       "excursion_max_m")
CONFIGURATIONS = ("NBs", "YBs")
DIRECTIONS = ("up", "down")
TARGET_KEYS = ("configuration", "a_g", "quantity", "value", "direction", "tolerance", "relative", "weight")
COLUMNS = ("configuration", "a_g", "direction", "quantity", "value", "tolerance", "relative", "weight")
# the paper's printed values left out of paper_targets(), and why (docs/paper.md)
PAPER_EXCLUDED = {
    ("NBs", 0.03, "e"): "printed 1.03 but E / D_tmax = 0.0356 / 0.02073 = 1.72 (docs/paper.md)",
}
PAPER_QUANTITIES = ("nu_r", "alpha", "eta", "e", "contact_nu_min", "contact_nu_max", "contact_time_ms",
                    "restitution")


@dataclass(frozen=True, eq=False)
class Targets:
    """Measured targets, one row each.

    Attributes
    ----------
    data : pandas.DataFrame
        Columns ``configuration`` ("NBs"/"YBs"), ``a_g`` (g), ``direction`` ("up"/"down"),
        ``quantity`` (a name of ``DEFAULT_TOLERANCES``), ``value``, ``tolerance``,
        ``relative`` (bool) and ``weight`` (multiplies the residual, default 1).
    eta_gap_total_m : float or None
        The total gap ``Delta`` (m) the measured ``eta = E / Delta`` was normalised by: the
        nominal one of the test rig (the paper's 2 x 15 mm).  When given, a model's eta is
        compared as its largest excursion over this ``Delta``, not over the model's own gap, so
        that a fit with the gap free compares excursions with excursions (the lab's E over
        its nominal Delta).  None: the model's own gap (the same when the gap is the nominal
        one).

    Examples
    --------
    Two measurements of a YBs sweep at a_G = 0.05 g, with the default tolerances:

    >>> import pounding
    >>> targets = pounding.Targets.from_records(
    ...     [{"configuration": "YBs", "a_g": 0.05, "quantity": "alpha",
    ...       "value": 16.8},
    ...      {"configuration": "YBs", "a_g": 0.05, "quantity": "contact_time_ms",
    ...       "value": 15.0}],
    ...     eta_gap_total_m=0.03)
    >>> len(targets), targets.cases
    (2, [('YBs', 0.05, 'up')])
    >>> # alpha within 10 %, the contact time within 30 %
    >>> targets.allowed.round(3).tolist()
    [1.68, 4.5]
    """

    data: pd.DataFrame
    eta_gap_total_m: float | None = None

    def __post_init__(self) -> None:
        if self.eta_gap_total_m is not None:
            object.__setattr__(self, "eta_gap_total_m", gap_total("eta_gap_total_m", self.eta_gap_total_m))

    def __len__(self) -> int:
        return len(self.data)

    @property
    def cases(self) -> list[tuple[str, float, str]]:
        """The sweeps the targets need: ``(configuration, a_g, direction)``, sorted."""
        keys = {(c, float(a), d) for c, a, d in self.data[["configuration", "a_g",
                                                            "direction"]].itertuples(index=False)}
        return sorted(keys)

    @property
    def allowed(self) -> np.ndarray:
        """The allowed difference of each target, in the quantity's unit, shape (n,)."""
        t = self.data
        return np.where(t["relative"], t["tolerance"] * t["value"].abs(), t["tolerance"]).astype(float)

    def to_xarray(self) -> Any:
        """The targets as a Dataset along ``target``."""
        from .._tables import frame_to_xarray

        return frame_to_xarray(self.to_dataframe(), "target")

    def to_dataframe(self) -> pd.DataFrame:
        """A copy of :attr:`table`."""
        return self.data.copy()

    @classmethod
    def from_lab(cls, sweep: Any, configuration: str, a_g: float | None = None) -> Targets:
        """The paper's quantities of a measured sweep (a :class:`pounding.lab.LabSweep`) as targets
        for :func:`pounding.identify`, with the default tolerances.

        Parameters
        ----------
        sweep : pounding.lab.LabSweep
            What :func:`pounding.lab.analyse_stepped_sine` returned.
        configuration : {"NBs", "YBs"}
            Which configuration the sweep tested: Table 2's ``nu_r``, ``alpha`` and ``eta`` (over
            the sweep's ``gap_total_m``, kept as ``eta_gap_total_m``), the contact range, contact
            time and restitution for YBs; ``nu_r``, ``alpha`` and ``e`` for NBs.
        a_g : float, optional
            The table acceleration the model's sweeps will use, g (default: the measured
            amplitude rounded to 0.001 g).

        Returns
        -------
        Targets

        Examples
        --------
        >>> import pounding
        >>> rec = pounding.lab.synthetic_test(pounding.presets.paper_damped(), 0.05,
        ...                                   [1.5, 2.0], cycles=10)
        >>> sweep = pounding.lab.analyse_stepped_sine(rec, mass_kg=500.0)
        >>> pounding.Targets.from_lab(sweep, "NBs").data["quantity"].tolist()
        ['nu_r', 'alpha', 'e']
        """
        return cls.from_records(sweep.target_records(configuration, a_g), eta_gap_total_m=sweep.gap_total_m)

    @classmethod
    def from_records(cls, records: list[dict[str, Any]], *, defaults: dict[str, Any] | None = None,
                     tolerances: dict[str, Any] | None = None,
                     eta_gap_total_m: float | None = None) -> Targets:
        """Build and check targets from dicts with the keys of ``TARGET_KEYS``.

        ``defaults`` may set ``direction``; ``tolerances`` maps a quantity to
        ``{"tolerance": x, "relative": bool}`` (else ``DEFAULT_TOLERANCES``);
        ``eta_gap_total_m`` as the attribute.
        """
        for name, table in (("defaults", defaults), ("tolerances", tolerances)):
            if table is not None and not isinstance(table, dict):
                raise InputError(Problem.WRONG_TYPE, name, table, got=type(table).__name__,
                                 expected="table" + (" such as {direction = \"up\"}" if name == "defaults"
                                                     else " of quantity = {tolerance = x, relative = true}"))
        defaults = dict(defaults or {})
        for key in defaults:
            if key != "direction":
                raise InputError(Problem.UNKNOWN_KEY, f"defaults.{key}", defaults[key], choices="direction")
        tol_table = dict(DEFAULT_TOLERANCES)
        for q, spec in (tolerances or {}).items():
            _known_quantity(f"tolerances.{q}", q)
            instance_of(f"tolerances.{q}", spec, dict, "table such as {tolerance = 0.1, relative = true}")
            for key in spec:
                if key not in ("tolerance", "relative"):
                    raise InputError(Problem.UNKNOWN_KEY, f"tolerances.{q}.{key}", spec[key],
                                     choices="tolerance, relative")
            tol = positive(f"tolerances.{q}.tolerance", spec.get("tolerance", tol_table[q][0]),
                           "the quantity's unit")
            relative = boolean(f"tolerances.{q}.relative", spec.get("relative", tol_table[q][1]))
            tol_table[q] = (tol, relative)
        if not isinstance(records, list) or not records:
            raise InputError(Problem.EMPTY, "target", records)
        rows = []
        seen = set()
        for i, rec in enumerate(records):
            where = f"target[{i}]"
            instance_of(where, rec, dict, "table")
            for key in rec:
                if key not in TARGET_KEYS:
                    raise InputError(Problem.UNKNOWN_KEY, f"{where}.{key}", rec[key],
                                     choices=", ".join(TARGET_KEYS))
            for key in ("configuration", "a_g", "quantity", "value"):
                if key not in rec:
                    raise InputError(Problem.MISSING_KEY, f"{where}.{key}", None,
                                     choices=", ".join(TARGET_KEYS))
            conf = rec["configuration"]
            if conf not in CONFIGURATIONS:
                raise InputError(Problem.NOT_ONE_OF, f"{where}.configuration", conf,
                                 choices=", ".join(CONFIGURATIONS))
            direction = rec.get("direction", defaults.get("direction", "up"))
            if direction not in DIRECTIONS:
                raise InputError(Problem.NOT_ONE_OF, f"{where}.direction", direction,
                                 choices=", ".join(DIRECTIONS))
            quantity = _known_quantity(f"{where}.quantity", rec["quantity"])
            if conf == "NBs" and quantity == "eta":
                raise InputError(Problem.NOT_ONE_OF, f"{where}.quantity", quantity,
                                 choices="the NBs quantities (eta = E / Delta is YBs only: for NBs use e or "
                                         "excursion_max_m)")
            a_g = at_most(f"{where}.a_g", positive(f"{where}.a_g", rec["a_g"], "g"), MAX_A_G, " g",
                          "a_g is in g: 0.05 is 5 % of g")
            value = real(f"{where}.value", rec["value"])
            if quantity in POSITIVE_QUANTITIES and value <= 0.0:
                raise InputError(Problem.NOT_POSITIVE, f"{where}.value", rec["value"],
                                 unit=f"the unit of {quantity} (a frequency ratio, time or ratio is > 0)")
            tol, relative = tol_table[quantity]
            if "tolerance" in rec:
                tol = positive(f"{where}.tolerance", rec["tolerance"],
                               "the quantity's unit (or a fraction when relative)")
            if "relative" in rec:
                relative = boolean(f"{where}.relative", rec["relative"])
            weight = positive(f"{where}.weight", rec.get("weight", 1.0), "(a factor)")
            key = (conf, a_g, direction, quantity)
            if key in seen:
                raise InputError(Problem.DUPLICATE, where, key,
                                 repeated="(configuration, a_g, direction, quantity)")
            seen.add(key)
            rows.append(dict(zip(COLUMNS, (conf, a_g, direction, quantity, value, tol, relative, weight))))
        return cls(pd.DataFrame(rows, columns=list(COLUMNS)), eta_gap_total_m)

    @classmethod
    def from_toml(cls, path: str | Path) -> Targets:
        """Read targets from a TOML file (format in the module docstring)."""
        table = read_toml("targets", path, ("defaults", "tolerances", "target", "eta_gap_total_m"))
        if "target" not in table:
            raise InputError(Problem.MISSING_KEY, "target", None, choices="[[target]] tables")
        return cls.from_records(table["target"], defaults=table.get("defaults"),
                                tolerances=table.get("tolerances"),
                                eta_gap_total_m=table.get("eta_gap_total_m"))

    def check_consistency(self, mass_kg: float, gap_total_m: float | None = None,
                          **kwargs: Any) -> pd.DataFrame:
        """Flag measured combinations that no mass obeying Newton's law can produce.

        See :func:`pounding.identification.consistency.check_consistency` (``gap_total_m``
        defaults to :attr:`eta_gap_total_m`; ``g``, ``f_ref_hz`` and ``omega_min_rad_s`` as
        keywords): one row per check and case, with
        the bound that the case's other numbers imply and ``consistent`` False where the
        measured value misses it by more than its tolerance.
        """
        from .consistency import check_consistency

        return check_consistency(self, mass_kg, gap_total_m, **kwargs)

    def to_toml_text(self) -> str:
        """TOML that :meth:`from_toml` reads back to the same targets."""
        import tomli_w

        recs = []
        for row in self.data.itertuples(index=False):
            recs.append({"configuration": row.configuration, "a_g": float(row.a_g),
                         "direction": row.direction, "quantity": row.quantity, "value": float(row.value),
                         "tolerance": float(row.tolerance),
                         "relative": bool(row.relative), "weight": float(row.weight)})
        head = {} if self.eta_gap_total_m is None else {"eta_gap_total_m": self.eta_gap_total_m}
        return tomli_w.dumps({**head, "target": recs})


def paper_targets(direction: str = "up", quantities: tuple[str, ...] = PAPER_QUANTITIES) -> Targets:
    """The paper's shaking-table results as targets: Table 2 (``nu_r``, ``alpha``, ``eta``
    or ``e``, the contact range), Table 3 contact times and Table 4 restitution, with the
    default tolerances (``DEFAULT_TOLERANCES``: nu_R 0.1, alpha 10 %, eta or e 5 %, contact
    times 30 %, restitution 0.05): 36 numbers.  ``eta`` was measured
    over the rig's nominal gap: ``eta_gap_total_m`` is 0.03 m (``pounding.data.paper_gap_total_m``).

    ``quantities`` chooses others (names of :data:`DEFAULT_TOLERANCES`), e.g. the NBs
    ``excursion_max_m`` of Sect. 3.2 and Table 4's ``dissipated_energy_per_mass`` for
    :meth:`Targets.check_consistency` (``consistency.CONSISTENCY_QUANTITIES``).
    Left out: ``PAPER_EXCLUDED`` (the values that are inconsistent with the paper's own numbers).

    Parameters
    ----------
    direction : {"up", "down"}
        The direction of the model's sweeps each target is compared with (every target the same).
    quantities : tuple of str
        The quantities kept, names of :data:`DEFAULT_TOLERANCES` (default
        :data:`PAPER_QUANTITIES`: those of Tables 2-4 above).

    Returns
    -------
    Targets
        One row per printed value of those quantities, NBs and YBs, with ``eta_gap_total_m``
        0.03 m.

    Examples
    --------
    >>> import pounding
    >>> targets = pounding.paper_targets()
    >>> len(targets), targets.eta_gap_total_m
    (36, 0.03)
    >>> # Table 2's alpha: NBs, then YBs
    >>> alphas = pounding.paper_targets(quantities=("alpha",)).data
    >>> alphas["value"].tolist()
    [1.8, 2.99, 3.89, 1.96, 16.8, 16.18, 15.04]
    """
    one_of("direction", direction, DIRECTIONS)
    if isinstance(quantities, str) or not isinstance(quantities, (tuple, list)) or not quantities:
        raise InputError(Problem.WRONG_TYPE, "quantities", quantities, got=type(quantities).__name__,
                         expected="a non-empty tuple of quantity names, e.g. ('alpha', 'nu_r')")
    for i, q in enumerate(quantities):
        _known_quantity(f"quantities[{i}]", q)
    df = paper_measurements()
    df = df[df["configuration"].isin(CONFIGURATIONS) & df["quantity"].isin(quantities) & df["a_g"].notna()]
    records = []
    for row in df.itertuples(index=False):
        if (row.configuration, float(row.a_g), row.quantity) in PAPER_EXCLUDED:
            continue
        records.append({"configuration": row.configuration, "a_g": float(row.a_g), "quantity": row.quantity,
                        "value": float(row.value), "direction": direction})
    return Targets.from_records(records, eta_gap_total_m=paper_gap_total_m())


def _known_quantity(field: str, quantity: Any) -> str:
    if not isinstance(quantity, str) or quantity not in DEFAULT_TOLERANCES:
        raise InputError(Problem.NOT_ONE_OF, field, quantity, choices=", ".join(DEFAULT_TOLERANCES))
    return quantity
