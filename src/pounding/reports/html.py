"""One self-contained HTML page: tables, figures (embedded), parameters and notes."""

from __future__ import annotations

import base64
import html
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from .._io import write_text
from .compare import NOT_COMPARABLE

CSS = """
body { font-family: system-ui, sans-serif; margin: 2em auto; max-width: 1100px; padding: 0 1em; color: #222; }
h1 { font-size: 1.6em; } h2 { border-bottom: 1px solid #ccc; padding-bottom: .2em; margin-top: 2em; }
table { border-collapse: collapse; font-size: .8em; margin: .5em 0 1.5em; max-width: 100%; }
th, td { border: 1px solid #ccc; padding: .2em .4em; }
td.num { text-align: right; font-variant-numeric: tabular-nums; } td.text { text-align: left; }
th { background: #f3f3f3; white-space: normal; text-align: center; }
figure { display: block; margin: 1em 0 1.5em; max-width: 100%; }
figure img { display: block; max-width: 100%; height: auto; border: 1px solid #ddd; }
figure a { display: inline-block; max-width: 100%; }
figcaption { font-size: .9em; margin-top: .3em; }
.tnote { font-size: .9em; color: #555; }
pre { background: #f7f7f7; padding: .8em; overflow-x: auto; }
.note { color: #8a4b00; } .wide { overflow-x: auto; } .cite { font-size: .95em; }
"""

PAPER = ("\u201cA preliminary experimental study about two-sided impacting SDOF oscillator under harmonic "
         "excitation\u201d: shaking-table tests of a 500 kg mass on a high-damping rubber bearing between "
         "two "
         "EPDM bumpers, stepped sines of 0.5 to 5 Hz at a_G = 0.03 to 0.1 (its Sects. 2-5, Tables 2-4, "
         "Figs. 4-17). Its authors and venue are not given in the copy this package was built from.")
# quantities, in words with units, for the page's headers (the CSV files keep the short names)
QUANTITY_WORDS = {
    "nu_r": "resonance \u03bd_R [-]", "alpha": "peak acceleration \u03b1 [-]",
    "eta": "excursion \u03b7 = E/\u0394 [-]",
    "e": "excursion e = E/D_tmax [-]", "contact_nu_min": "contact from \u03bd [-]",
    "contact_nu_max": "contact to \u03bd [-]", "mean_force_over_mg": "mean contact force F_m/(M g) [-]",
    "contact_time_ms": "contact time [ms]",
    "dissipated_energy_per_mass": "dissipated energy E_d/M [m\u00b2/s\u00b2]",
    "restitution": "restitution s [-]", "peak_force_over_mg": "peak contact force / (M g) [-]",
    "excursion_max_m": "largest excursion E [m]",
    "excursion": "excursion: \u03b7 = E/\u0394 (YBs), e = E/D_tmax (NBs) [-]",
}
PART_WORDS = {"model": "model", "measured": "measured", "diff_pct": "difference [%]"}
KEY_WORDS = {"configuration": "configuration", "a_g": "a_G [-]", "direction": "sweep", "quantity": "quantity",
             "measured": "measured", "allowed": "tolerance", "steps": "steps done", "message": "message"}
READING_NOTES = (
    "A restitution s = -v_o/v_i slightly above 1 (1.003, say) is possible and not an error: during a contact "
    "the isolator and the shaking table also work on the mass, so s measures the whole system, not the "
    "bumper alone.",
    "Differences are (model - measured) / measured in percent; the CSV files beside this page also hold "
    "them in the quantities' own units.",
)
# what does not add up in the paper, shown on every report
PAPER_INCONSISTENCIES = (
    "With C_d = 1 N s/m (as printed) the isolator has about 0.01 % of critical damping: no steady state "
    "is reached in a reasonable time and YBs up-sweeps keep impacting to 5 Hz with alpha 40-140. Read as "
    "1 kN s/m (about 11 %, preset paper-damped) the a_G = 0.05 curve comes close to the paper's.",
    "With the printed backbone the isolator force at 85 mm is about 1.1 kN, so NBs alpha cannot reach the "
    "measured 3.89 at a_G = 0.1: the real isolator stiffens at large drift.",
    "NBs e at a_G = 0.03 is printed as 1.03, but E / D_tmax = 0.0356 / 0.02073 = 1.72.",
    "The ratio A_max(YBs)/A_max(NBs) at a_G = 0.03 is printed as 1.9, but Table 2 gives 1.96/1.80 = 1.09.",
    "A linear Kelvin-Voigt bumper gives a contact time near half its contact period (about 57 ms) whatever "
    "a_G, and a restitution near 1 with C_b = 5 N s/m; the measured 9-31 ms and 0.75-0.89 need a "
    "stiffer-with-depth or more dissipative contact law.",
    "Table 3's scale factor for F_m/(M g) ('x 10^-3') is unclear: those values are shown as printed and "
    "not differenced.",
    "Fig. 7's text places flight at -1 < d < 1 with d = D/Delta, which would need D over the half gap; "
    "the loops here follow the paper's figures (d = D/(Delta/2), bumpers at +-1).",
)


GROUPS_PER_TABLE = 3  # quantity groups of (model, measured, difference) per HTML table: fits 1366 px
MISSING = "\u2013"  # a cell with no number: not measured, no contact, ...
NOT_COMPARED = "not compared: the paper's scale factor is unclear"


def _excursion_merged(df: pd.DataFrame) -> pd.DataFrame:
    """eta (YBs) and e (NBs) as one quantity: each configuration has only one of them measured."""
    if not all(f"{q}_model" in df.columns for q in ("eta", "e")) or "configuration" not in df.columns:
        return df
    ybs = df["configuration"] == "YBs"
    for part in PART_WORDS:
        df[f"excursion_{part}"] = df[f"eta_{part}"].where(ybs, df[f"e_{part}"])
    cols = list(df.columns)
    order = [c for c in cols if not c.startswith(("eta_", "e_", "excursion_"))]
    after = [c for c in order if cols.index(c) > cols.index("eta_model")]  # where eta was
    at = order.index(after[0]) if after else len(order)
    order[at:at] = [f"excursion_{part}" for part in PART_WORDS]
    return df[order]


def _for_people(df: pd.DataFrame) -> pd.DataFrame:
    """Headers in words with units (grouped by quantity where a table compares model and
    measurement), differences in percent only, flags as yes / no."""
    df = _excursion_merged(df.copy())
    for q in NOT_COMPARABLE:  # (a blank cell said nothing: it says why)
        if f"{q}_diff_pct" in df.columns:
            df[f"{q}_diff_pct"] = NOT_COMPARED
    for col in df.columns:
        if df[col].dtype == bool:
            df[col] = df[col].map({True: "yes", False: "no"})
    compared = [q for q in QUANTITY_WORDS if f"{q}_model" in df.columns]
    if not compared:
        return df.rename(columns=lambda c: KEY_WORDS.get(c, QUANTITY_WORDS.get(c, c.replace("_", " "))))
    keys = [c for c in df.columns if not any(c.startswith(f"{q}_") for q in compared)]
    columns = [("", KEY_WORDS.get(c, c)) for c in keys]
    parts = [df[keys]]
    for q in compared:
        for part, words in PART_WORDS.items():
            if f"{q}_{part}" in df.columns:
                parts.append(df[[f"{q}_{part}"]])
                columns.append((QUANTITY_WORDS[q], words))
    out = pd.concat(parts, axis=1)
    out.columns = pd.MultiIndex.from_tuples(columns)
    return out


def table_html(df: pd.DataFrame) -> str:
    """The table as HTML; a wide comparison split into tables of ``GROUPS_PER_TABLE`` quantities."""
    df = _for_people(df)
    pieces = [df]
    if isinstance(df.columns, pd.MultiIndex):
        keys = [c for c in df.columns if c[0] == ""]
        groups = list(dict.fromkeys(c[0] for c in df.columns if c[0] != ""))
        pieces = [df[keys + [c for c in df.columns if c[0] in groups[i:i + GROUPS_PER_TABLE]]]
                  for i in range(0, len(groups), GROUPS_PER_TABLE)]
    return "".join(f"<div class='wide'>{_html_table(p)}</div>" for p in pieces)


def _html_table(df: pd.DataFrame) -> str:
    """A table: numbers right-aligned (``class='num'``, 4 significant digits), text left-aligned, a missing
    number as an en dash; a two-level header where the columns are grouped."""
    e = html.escape
    cols = list(df.columns)
    head = []
    if isinstance(df.columns, pd.MultiIndex):
        groups: list[list] = []
        for top, _ in cols:
            if groups and groups[-1][0] == top:
                groups[-1][1] += 1
            else:
                groups.append([top, 1])
        head.append("<tr>" + "".join(f"<th colspan='{n}'>{e(str(top))}</th>" for top, n in groups) + "</tr>")
        head.append("<tr>" + "".join(f"<th>{e(str(sub))}</th>" for _, sub in cols) + "</tr>")
    else:
        head.append("<tr>" + "".join(f"<th>{e(str(c))}</th>" for c in cols) + "</tr>")
    rows = []
    for values in df.itertuples(index=False, name=None):
        cells = []
        for v in values:
            if isinstance(v, (bool, np.bool_)) or v is None or isinstance(v, str):
                text = MISSING if v is None else str(v)
                cells.append(f"<td class='text'>{e(text)}</td>")
            elif isinstance(v, (int, float, np.integer, np.floating)):
                cells.append(f"<td class='num'>{MISSING if v != v else f'{v:.4g}'}</td>")
            else:
                cells.append(f"<td class='text'>{e(str(v))}</td>")
        rows.append("<tr>" + "".join(cells) + "</tr>")
    return f"<table><thead>{''.join(head)}</thead><tbody>{''.join(rows)}</tbody></table>"


def _verdict(v: Any, system_label: str) -> list[str]:
    """The opening section: targets met, the worst misses in percent, the consistency flags."""
    e = html.escape
    parts = ["<h2>Verdict</h2>",
             f"<p><b>{e(system_label)}</b> {e(v.summary())}. Targets: the paper's Tables 2-4 "
             "(<code>pounding.paper_targets()</code>), sweeps up with a fixed 30 cycles per step, the NBs "
             "system being the YBs one without its bumpers; a target is met within its tolerance.</p>"]
    if len(v.worst_misses):
        misses = v.worst_misses.rename(columns={"target": "measured", "difference_pct": "difference [%]",
                                                "normalized": "in tolerances", "flagged": "flagged below"})
        parts += ["<h3>Worst misses</h3>", table_html(misses)]
    parts.append("<h3>Are the measurements consistent?</h3>")
    if len(v.flags):
        parts += [f"<p>{len(v.flags)} combination(s) of the paper's numbers miss a bound by more than their "
                  "tolerances (<code>Targets.check_consistency</code>): kind <i>law</i>, no system obeying "
                  "Newton's law produces them; kind <i>sinusoidal</i>, no near-sinusoidal response does, "
                  "which a model of a smooth isolator near resonance gives.</p>",
                  table_html(v.flags.rename(columns={"measured": "measured", "bound": "least possible"}))]
    else:
        parts.append("<p>Every measured combination passes the consistency checks.</p>")
    return parts


def _image(path: Path) -> str:
    data = base64.b64encode(path.read_bytes()).decode("ascii")
    return f"data:image/png;base64,{data}"


def figure_html(name: str, png: Path, caption: str) -> str:
    """A figure at its own size (the page's width at most), embedded so that the page opens offline, and
    a link to its PNG beside the page, to open it alone at full size."""
    e = html.escape
    return (f"<figure><a href='{e(png.name)}' title='open {e(png.name)} at full size'>"
            f"<img src='{_image(png)}' alt='{e(name)}'></a>"
            f"<figcaption><b>{e(name)}</b>: {e(caption)} <a href='{e(png.name)}'>(full size)</a>"
            "</figcaption></figure>")


def write_page(path: Path, *, title: str, system_label: str, systems: dict[str, str], settings: dict,
               tables: dict[str, pd.DataFrame], figures: dict[str, tuple[Path, str]],
               notes: pd.DataFrame, statuses: pd.DataFrame, verdict: Any = None,
               story: list[str] | None = None, table_notes: dict[str, list[str]] | None = None) -> Path:
    """Write ``index.html``: every image embedded, so the page opens from disk, offline.

    ``verdict`` (a :class:`~pounding.reports.verdict.Verdict`) opens the page; ``story`` (HTML
    parts: the exact metrics against the measured ones, the stands' test) follows it; ``table_notes``
    are shown under the table of their name."""
    e = html.escape
    parts = [f"<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'><title>{e(title)}</title>",
             f"<style>{CSS}</style></head><body>", f"<h1>{e(title)}</h1>",
             f"<p class='cite'>The paper: {e(PAPER)}</p>"]
    if verdict is not None:
        parts += _verdict(verdict, system_label)
    parts += story or []
    parts += [f"<p>System: <b>{e(system_label)}</b>. Model values come from the campaign below (each sweep "
              "direction a row); measured values are the paper's, as printed (package data, "
              "<code>pounding.data.paper_measurements()</code>); differences are (model - measured) / "
              "measured in percent.</p>",
              "<h2>Campaign</h2>", table_html(pd.DataFrame([settings])), table_html(statuses)]
    for name, df in tables.items():
        parts += [f"<h2>{e(name)}</h2>", table_html(df)]
        parts += [f"<p class='tnote'>{e(n)}</p>" for n in (table_notes or {}).get(name, ())]
    parts.append("<h2>Figures</h2>")
    for name, (png, caption) in figures.items():
        parts.append(figure_html(name, png, caption))
    parts.append("<h2>System parameters</h2>")
    for conf, text in systems.items():
        parts += [f"<h3>{e(conf)}</h3>", f"<pre>{e(text)}</pre>"]
    parts.append("<h2>Reading the results</h2><ul>")
    parts += [f"<li>{e(n)}</li>" for n in READING_NOTES]
    parts.append("</ul><h2>What in the paper does not add up</h2><ul>")
    parts += [f"<li class='note'>{e(n)}</li>" for n in PAPER_INCONSISTENCIES]
    parts.append("</ul><h3>Measured values with a note</h3>")
    parts += [table_html(notes), "</body></html>"]
    write_text(path, "\n".join(parts))
    return path


NOT_A_TARGET_PCT = 25.0  # a quantity that is no calibration target gets a note when it differs by more (%)


def untargeted_notes(table: pd.DataFrame, targets: pd.DataFrame) -> list[str]:
    """Notes for a comparison table (:func:`comparison`): each quantity that differs from the
    measurement by more than ``NOT_A_TARGET_PCT`` % somewhere although it is no calibration target of
    ``targets`` (``Targets.to_dataframe()``: its configurations and quantities), so that a reader
    does not take its difference for a miss of the fit (the verdict judges the targets only)."""
    targeted = set(zip(targets["configuration"], targets["quantity"]))
    notes = []
    for col in [c for c in table.columns if c.endswith("_diff_pct")]:
        q = col[: -len("_diff_pct")]
        rows = table[table[col].notna()]
        rows = rows[[(c, q) not in targeted for c in rows["configuration"]]]
        if not len(rows) or rows[col].abs().max() <= NOT_A_TARGET_PCT:
            continue
        worst = rows.loc[rows[col].abs().idxmax()]
        confs = " and ".join(sorted(set(rows["configuration"])))
        notes.append(f"{QUANTITY_WORDS.get(q, q)} is not a calibration target ({confs}): the fit does not "
                     "try to meet it, and the verdict does not count it; its differences reach "
                     f"{worst[col]:+.0f} % ({worst['configuration']}, a_G {worst['a_g']:g}, "
                     f"{worst['direction']}).")
    return notes
