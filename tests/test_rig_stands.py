"""The rig's stands as a tested hypothesis (issue 50): the shipped fit of the paper's rig with its bumpers
on stands of their own (``presets.paper_rig_stands``, made by ``scripts/rig_stands.py``) reproduces its
stored residual table, and the guide's account of it (docs/calibration.md, "The stands hypothesis") quotes
that table's numbers."""

from __future__ import annotations

import math
import re
import tomllib
from pathlib import Path

import numpy as np

import pounding as pd_
from pounding.identification import evaluate
from pounding.presets import RIG_STANDS_FILE

ROOT = Path(__file__).resolve().parents[1]


def test_the_shipped_rig_on_stands_reproduces_its_residuals():
    stored = pd_.presets.residuals("paper-rig-stands")
    rig = pd_.presets.paper_rig_stands()
    now = evaluate(rig, pd_.paper_targets())
    assert list(now["quantity"]) == list(stored["quantity"]) and list(now["a_g"]) == list(stored["a_g"])
    np.testing.assert_allclose(now["model"], stored["model"], rtol=1e-9, atol=0, equal_nan=True)
    assert list(now["within"]) == list(stored["within"])
    # the rig is what the script fits: the calibrated preset's mass and backbone, each bumper on a stand
    preset = pd_.presets.paper_calibrated()
    assert rig.n_levels == 1 and rig.base_mass_kg == preset.mass_kg
    assert rig.isolator.slopes_n_m == preset.isolator.slopes_n_m
    assert rig.walls[0].stand is not None and rig.walls[0].stand.mass_kg > 0
    meta = tomllib.loads((ROOT / "src" / "pounding" / "data" / RIG_STANDS_FILE).read_text())["meta"]
    assert meta["targets_met"] == f"{int(stored['within'].sum())} of {len(stored)}"


def test_the_guide_quotes_the_shipped_fit():
    stored = pd_.presets.residuals("paper-rig-stands")
    stand = pd_.presets.paper_rig_stands().walls[0].stand
    text = (ROOT / "docs" / "calibration.md").read_text()
    section = text[text.index("## The stands hypothesis"):]
    section = section[:section.index("\n## ", 4)] if "\n## " in section[4:] else section
    assert f"meets **{int(stored['within'].sum())} of the 36 targets**" in section
    freq_hz = math.sqrt(stand.stiffness_n_m / stand.mass_kg) / (2 * math.pi)
    quoted = {float(v) for v in re.findall(r"([0-9.]+) Hz", section)}
    assert any(math.isclose(v, freq_hz, rel_tol=0.05) for v in quoted), (freq_hz, quoted)
    ybs_alpha = stored[(stored["configuration"] == "YBs") & (stored["quantity"] == "alpha")
                       & (stored["a_g"] > 0.04)]["model"]
    for value in ybs_alpha:
        assert f"{value:.1f}" in section, value


def test_the_scan_of_stands_reproduces_its_rows():
    import sys

    sys.path.insert(0, str(ROOT / "scripts"))
    try:
        from rig_stands import SCAN_MASSES_KG, SCAN_STIFFNESSES_N_M, scan_stand
    finally:
        sys.path.remove(str(ROOT / "scripts"))
    stored = pd_.presets.rig_stands_scan()
    assert len(stored) == len(SCAN_MASSES_KG) * len(SCAN_STIFFNESSES_N_M)
    targets = pd_.paper_targets()
    for mass, stiffness in ((10.0, 1e8), (10.0, 3e5)):  # (a steel post, and a soft mount)
        row = stored[(stored["mass_kg"] == mass) & (stored["stiffness_n_m"] == stiffness)].iloc[0]
        now = scan_stand(mass, stiffness, targets)
        assert list(now) == list(stored.columns)
        np.testing.assert_allclose([now[c] for c in stored.columns], row.to_numpy(float), rtol=1e-9)
    # what the guide says of it: a steel-like stand leaves the YBs alphas within 2 % of the preset's own;
    # none of the stands meets more targets than the preset without stands (27)
    own = pd_.presets.residuals()
    own_alpha = own[(own["configuration"] == "YBs") & (own["quantity"] == "alpha")].set_index("a_g")["model"]
    steel = stored[stored["stiffness_n_m"] >= 1e8]
    for a_g in (0.05, 0.075, 0.1):
        np.testing.assert_allclose(steel[f"alpha_{a_g:g}"], own_alpha[a_g], rtol=0.02)
    assert stored["met"].max() <= int(own["within"].sum())
