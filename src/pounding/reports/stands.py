"""Do the bumpers' stands explain the YBs accelerations?  The report's test of the hypothesis on its own
YBs system: each bumper put on a stand of its own (a mass on a spring and a dashpot to the table), from a
steel post's stiffness down to a soft mount, each evaluated on the paper's targets."""

from __future__ import annotations

import dataclasses
import html
import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, Optional

import pandas as pd

from ..identification import paper_targets
from ..model import Oscillator
from ..model.structure import Structure
from ..model.structure_parts import Stand

STAND_MASS_KG = 10.0
STAND_STIFFNESSES_N_M = (1e8, 1e7, 1e6, 1e5)  # a steel post's stiffness down to a soft mount
STAND_DAMPING_RATIO = 0.05
# a square hollow steel post 80 x 5 mm to 100 x 8 mm, 0.3 to 0.4 m tall, as a cantilever (3 E I / L^3)
STEEL_POST_N_M = (1.4e7, 9.8e7)
A_GS = (0.05, 0.075, 0.1)  # the impacting levels: their YBs alpha and contact times
QUANTITIES = (("alpha", "YBs alpha", "YBs alphas met"), ("contact_time_ms", "contact time [ms]",
                                                          "contact times met"))


@dataclass(frozen=True)
class StandsTest:
    """The YBs system on each stand: ``table`` (a row per stand, then without stands and as measured) and
    ``verdict`` (in words, from the table's numbers)."""

    table: pd.DataFrame
    verdict: str


def _row(label: str, residuals: pd.DataFrame, stiffness: float = math.nan) -> dict:
    ybs = residuals[residuals["configuration"] == "YBs"]
    row: dict[str, Any] = {"stand": label, "stiffness [N/m]": stiffness,
                           "frequency [Hz]": math.sqrt(stiffness / STAND_MASS_KG) / (2.0 * math.pi),
                           "targets met": int(residuals["within"].sum())}
    for q, name, met in QUANTITIES:
        at = ybs[ybs["quantity"] == q].set_index("a_g")
        for a in A_GS:
            row[f"{name} {a:g}"] = float(at.loc[a, "model"])
        row[met] = int(sum(bool(at.loc[a, "within"]) for a in A_GS))
    return row


def stands_test(ybs_system: Oscillator, own: pd.DataFrame,
                evaluate_of: Callable[..., pd.DataFrame]) -> Optional[StandsTest]:
    """The test on ``ybs_system`` (None without bumpers); ``own`` its residuals without stands,
    ``evaluate_of(system, targets, label)`` evaluates a system on the targets."""
    if ybs_system.bumpers is None:
        return None
    base = Structure.from_oscillator(ybs_system)
    rows = []
    for k in STAND_STIFFNESSES_N_M:
        stand = Stand(STAND_MASS_KG, k, 2.0 * STAND_DAMPING_RATIO * math.sqrt(k * STAND_MASS_KG))
        rig = dataclasses.replace(base, walls=(dataclasses.replace(base.walls[0], stand=stand),))
        label = f"{STAND_MASS_KG:g} kg on {_sci(k)} N/m"
        rows.append(_row(label, evaluate_of(rig, paper_targets(), f"targets, stands of {_sci(k)} N/m"), k))
    rows.append(_row("none (the system as it is)", own))
    measured = {"stand": "measured (the paper)"}
    targets = own[own["configuration"] == "YBs"]
    for q, name, _ in QUANTITIES:
        at = targets[targets["quantity"] == q].set_index("a_g")
        measured.update({f"{name} {a:g}": float(at.loc[a, "target"]) for a in A_GS})
    table = pd.DataFrame(rows + [measured])
    return StandsTest(table, _verdict(table))


def _sci(value: float) -> str:
    """``1e8``, ``2.5e5``: a stiffness as people write it."""
    mantissa, exponent = f"{value:.1e}".split("e")
    return f"{mantissa.rstrip('0').rstrip('.')}e{int(exponent)}"


def _verdict(table: pd.DataFrame) -> str:
    stands = table[table["stiffness [N/m]"].notna()]
    alone = table[table["stand"].str.startswith("none")].iloc[0]
    n = len(A_GS)
    both = stands[(stands["YBs alphas met"] == n) & (stands["contact times met"] == n)]
    alphas = stands[stands["YBs alphas met"] == n]
    lo, hi = STEEL_POST_N_M
    steel = f"a steel post is {_sci(lo)} to {_sci(hi)} N/m"
    met = f"targets met against {int(alone['targets met'])} without stands"
    if len(both):
        k = float(both["stiffness [N/m]"].max())
        where = ("within that range" if lo <= k <= hi else
                 f"{lo / k:.2g} times softer than the softest" if k < lo else "stiffer than that")
        return (f"Yes: on stands of {_sci(k)} N/m ({STAND_MASS_KG:g} kg) the YBs accelerations and the "
                f"contact times at a_G 0.05 to 0.1 are all met ({steel}: this stand is {where}).")
    if len(alphas):
        r = alphas.loc[alphas["stiffness [N/m]"].idxmax()]
        k = float(r["stiffness [N/m]"])
        return (f"No: the YBs accelerations are met only on stands of {_sci(k)} N/m and softer "
                f"({lo / k:.2g} times softer than a steel post; {steel}), and there only "
                f"{int(r['contact times met'])} of the {n} contact times are, with "
                f"{int(r['targets met'])} {met}.")
    best = stands.loc[stands["YBs alphas met"].idxmax()]
    stiff = stands.iloc[0]

    def alphas_of(row: pd.Series) -> str:
        return ", ".join(f"{row[f'YBs alpha {a:g}']:.1f}" for a in A_GS)

    return (f"No: no stand tried brings every YBs acceleration within its tolerance (the most: "
            f"{int(best['YBs alphas met'])} of {n}, on {_sci(float(best['stiffness [N/m]']))} N/m, with "
            f"{int(best['targets met'])} {met}); on a steel-like stand "
            f"({_sci(float(stiff['stiffness [N/m]']))} N/m; {steel}) the YBs alphas are "
            f"{alphas_of(stiff)} (without stands {alphas_of(alone)}).")


def stands_html(test: StandsTest, table: Callable[[pd.DataFrame], str]) -> list[str]:
    """The report's section (``table``: the page's table writer)."""
    e = html.escape
    return ["<h2>Do the bumpers' stands explain the YBs accelerations?</h2>",
            "<p>The rig's bumpers are bolted to steel stands. Each bumper put on a stand of its own "
            f"({STAND_MASS_KG:g} kg on a spring, {100 * STAND_DAMPING_RATIO:g} % of critical damping), "
            "from a steel post's stiffness down to a soft mount, the YBs system evaluated on the paper's "
            f"targets (a structure of one level, <code>pounding.Stand</code>): <b>{e(test.verdict)}</b></p>",
            table(test.table)]
