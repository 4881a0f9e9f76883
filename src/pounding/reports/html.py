"""One self-contained HTML page: tables, figures (embedded), parameters and notes."""

from __future__ import annotations

import base64
import html
from pathlib import Path

import pandas as pd

from .._io import write_text

CSS = """
body { font-family: system-ui, sans-serif; margin: 2em auto; max-width: 1100px; color: #222; }
h1 { font-size: 1.6em; } h2 { border-bottom: 1px solid #ccc; padding-bottom: .2em; margin-top: 2em; }
table { border-collapse: collapse; font-size: .85em; margin: .5em 0 1.5em; }
th, td { border: 1px solid #ccc; padding: .25em .5em; text-align: right; }
th { background: #f3f3f3; } td:first-child, th:first-child { text-align: left; }
figure { display: inline-block; margin: .5em; vertical-align: top; }
figure img { max-width: 520px; border: 1px solid #ddd; }
figcaption { font-size: .85em; max-width: 520px; }
pre { background: #f7f7f7; padding: .8em; overflow-x: auto; }
.note { color: #8a4b00; } .wide { overflow-x: auto; }
"""

# what MODEL.md §5 says does not add up in the paper, shown on every report
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
    "d = D/Delta (MODEL.md) puts the bumpers at d = -0.5 and 0.5 here.",
)


def _table(df: pd.DataFrame) -> str:
    table = df.to_html(index=False, float_format=lambda x: f"{x:.4g}", na_rep="", border=0)
    return f"<div class='wide'>{table}</div>"


def _image(path: Path) -> str:
    data = base64.b64encode(path.read_bytes()).decode("ascii")
    return f"data:image/png;base64,{data}"


def write_page(path: Path, *, title: str, system_label: str, systems: dict[str, str], settings: dict,
               tables: dict[str, pd.DataFrame], figures: dict[str, tuple[Path, str]],
               notes: pd.DataFrame, statuses: pd.DataFrame) -> Path:
    """Write ``index.html``: every image embedded, so the page opens from disk, offline."""
    e = html.escape
    parts = [f"<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'><title>{e(title)}</title>",
             f"<style>{CSS}</style></head><body>", f"<h1>{e(title)}</h1>",
             f"<p>System: <b>{e(system_label)}</b>. Model values come from the campaign below (each sweep "
             "direction a row); measured values are the paper's (package data, "
             "<code>pounding.data.paper_measurements()</code>); <i>diff</i> is model minus measured.</p>",
             "<h2>Campaign</h2>", _table(pd.DataFrame([settings])), _table(statuses)]
    for name, df in tables.items():
        parts += [f"<h2>{e(name)}</h2>", _table(df)]
    parts.append("<h2>Figures</h2>")
    for name, (png, caption) in figures.items():
        parts.append(f"<figure><img src='{_image(png)}' alt='{e(name)}'>"
                     f"<figcaption><b>{e(name)}</b>: {e(caption)}</figcaption></figure>")
    parts.append("<h2>System parameters</h2>")
    for conf, text in systems.items():
        parts += [f"<h3>{e(conf)}</h3>", f"<pre>{e(text)}</pre>"]
    parts.append("<h2>Notes on the paper (MODEL.md §5)</h2><ul>")
    parts += [f"<li class='note'>{e(n)}</li>" for n in PAPER_INCONSISTENCIES]
    parts.append("</ul><h3>Measured values with a note</h3>")
    parts += [_table(notes), "</body></html>"]
    write_text(path, "\n".join(parts))
    return path
