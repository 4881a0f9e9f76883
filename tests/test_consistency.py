"""Targets.check_consistency: bounds any mass obeying Newton's law satisfies (issue 16)."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest

import pounding as pd_
from pounding.identification import evaluate
from pounding.identification.consistency import CONSISTENCY_QUANTITIES

QUANTITIES = {"NBs": ("nu_r", "alpha", "e", "excursion_max_m"),
              "YBs": ("nu_r", "alpha", "eta", "excursion_max_m", "contact_time_ms", "restitution",
                      "dissipated_energy_per_mass")}


def _targets(records):
    return pd_.Targets.from_records([dict(configuration=c, a_g=a, quantity=q, value=v) for c, a, q,
                                     v in records])


def test_a_periodic_response_cannot_cover_its_excursion_with_less_acceleration():
    # 37 mm peak to peak at 2.2 Hz needs |D''| >= 16 E f^2 = 2.86 m/s^2 somewhere: alpha >= 4.8
    # at a_G 0.05; alpha 3 (within 10 %: 3.3) cannot be
    bad = _targets([("YBs", 0.05, "nu_r", 2.2), ("YBs", 0.05, "alpha", 3.0), ("YBs", 0.05, "eta", 1.23)])
    checks = bad.check_consistency(500.0, 0.03).set_index("check")
    law = checks.loc["alpha_vs_excursion"]
    e_low = 1.23 * 0.95 * 0.03
    assert law["bound"] == pytest.approx(16 * e_low * 2.2 ** 2 / (0.05 * 9.81) - 1)
    assert law["kind"] == "law" and not law["consistent"] and law["margin"] < -1
    assert not checks.loc["alpha_vs_excursion_sinusoidal", "consistent"]
    # the same numbers with the alpha such a response gives pass
    good = _targets([("YBs", 0.05, "nu_r", 2.2), ("YBs", 0.05, "alpha", 6.0), ("YBs", 0.05, "eta", 1.23)])
    assert good.check_consistency(500.0, 0.03)["consistent"].all()


def test_an_impact_bounds_alpha_from_below():
    # E_d / M = 3.81e-4 with s = 0.89: v_i = 0.06 m/s turned to -0.054 m/s in 15 ms (7.6 m/s^2)
    records = [("YBs", 0.05, "alpha", 5.0), ("YBs", 0.05, "restitution", 0.89),
               ("YBs", 0.05, "contact_time_ms", 15.0), ("YBs", 0.05, "dissipated_energy_per_mass", 3.81e-4)]
    row = _targets(records).check_consistency(500.0, 0.03).set_index("check").loc["alpha_vs_impact"]
    # each at the end of its tolerance that lowers the bound
    s_high, ed_low, dt = 0.94, 3.81e-4 * 0.7, 15e-3 * 1.3
    v_in = math.sqrt(2 * ed_low / (1 - s_high ** 2))
    assert row["bound"] == pytest.approx(v_in * (1 + 0.84) / (dt * 0.05 * 9.81) - 1)
    assert row["bound"] > 5.5 and not row["consistent"]


def test_a_short_contact_cannot_compress_a_bumper_deeply_at_a_low_acceleration():
    # eta 1.23 over 30 mm: the bumpers compressed 6.9 mm in all (5.05 mm at eta's low end), the
    # deepest at least half; |D''| <= (16.8 + 1.68 + 1) 0.05 g = 9.55 m/s^2 brings it to rest from
    # the surface in at least sqrt(5.05 mm / 9.55 m/s^2) = 23 ms: 15 ms (19.5 ms within 30 %) cannot be
    records = [("YBs", 0.05, "alpha", 16.8), ("YBs", 0.05, "eta", 1.23),
               ("YBs", 0.05, "contact_time_ms", 15.0)]
    targets = pd_.Targets.from_records([dict(configuration=c, a_g=a, quantity=q, value=v) for c, a, q,
                                        v in records],
                                       eta_gap_total_m=0.03)
    row = targets.check_consistency(500.0).set_index("check").loc["contact_time_vs_compression"]
    s_low, a_max = 1.23 * 0.95 * 0.03 - 0.03, (16.8 * 1.1 + 1.0) * 0.05 * 9.81
    assert row["bound"] == pytest.approx(1e3 * math.sqrt(s_low / a_max))
    assert row["kind"] == "contact" and not row["consistent"]
    assert "15.7 mm a side" in row["explanation"]  # (E - a_max dt^2) / 2 at the tolerances' ends
    # the same excursion (36.9 mm measured) over a wider effective gap leaves less compression:
    # with 32 mm of Delta, 15 ms is possible
    wider = _targets([("YBs", 0.05, "alpha", 16.8), ("YBs", 0.05, "excursion_max_m", 0.0369),
                      ("YBs", 0.05, "contact_time_ms", 15.0)])
    assert wider.check_consistency(500.0, 0.032).set_index("check").loc["contact_time_vs_compression",
                                                                          "consistent"]
    # Delta is required where the targets do not say it
    with pytest.raises(pd_.InputError) as info:
        _targets(records).check_consistency(500.0)
    assert info.value.field == "gap_total_m"


def test_energy_and_restitution_have_one_sign():
    bad = _targets([("YBs", 0.1, "restitution", 0.7), ("YBs", 0.1, "dissipated_energy_per_mass", -1e-3)])
    row = bad.check_consistency(500.0, 0.03).set_index("check").loc["energy_vs_restitution"]
    assert not row["consistent"]


def test_measurements_made_by_a_model_are_consistent():
    osc = pd_.presets.paper_calibrated()  # (restitution 0.92 and 0.77 here, below 1: the impact checks apply)
    cases = [("NBs", 0.05), ("NBs", 0.1), ("YBs", 0.05), ("YBs", 0.1)]
    recs = [dict(configuration=c, a_g=a, quantity=q, value=1.0) for c, a in cases for q in QUANTITIES[c]]
    model = evaluate(osc, pd_.Targets.from_records(recs), steady="fixed", cycles=30)["model"].to_numpy()
    assert np.isfinite(model).all()
    for rec, value in zip(recs, model):
        rec["value"] = float(value)
    checks = pd_.Targets.from_records(recs).check_consistency(osc.mass_kg, osc.bumpers.total_gap)
    assert set(checks["check"]) == {"alpha_vs_excursion", "alpha_vs_excursion_sinusoidal", "alpha_vs_impact",
                                    "energy_vs_restitution", "contact_time_vs_compression"}
    assert checks["consistent"].all(), checks[~checks["consistent"]].to_string()
    # and without the tolerances' benefit, the laws still hold (the sinusoidal estimate too: the
    # NBs response is nearly sinusoidal, the YBs impacts only raise alpha)
    assert (checks["measured"] >= checks["bound"]).all()


def test_the_papers_measurements():
    checks = pd_.paper_targets(quantities=CONSISTENCY_QUANTITIES).check_consistency(500.0)  # (Delta 30 mm)
    assert len(checks) == 23
    # no law is broken; the a_G = 0.03 accelerations are half what a sinusoidal response of the
    # printed excursion at the printed resonance has (NBs: 1.80 against at least 2.27); at a_G
    # 0.05 the 15 ms contacts are too short for bumpers compressed 3.5 mm (eta 1.23) at alpha 16.8
    assert checks.query("kind == 'law'")["consistent"].all()
    flagged = checks[~checks["consistent"]]
    assert list(zip(flagged["configuration"], flagged["a_g"], flagged["check"])) == [
        ("NBs", 0.03, "alpha_vs_excursion_sinusoidal"), ("YBs", 0.03, "alpha_vs_excursion_sinusoidal"),
        ("YBs", 0.05, "contact_time_vs_compression")]
    nbs = flagged.iloc[0]
    assert nbs["bound"] == pytest.approx(2 * math.pi ** 2 * 1.2 ** 2 * 0.0356 * 0.95 / (0.03 * 9.81) - 1)


def test_paper_targets_quantities_and_bad_arguments():
    assert len(pd_.paper_targets()) == 36
    extended = pd_.paper_targets(quantities=CONSISTENCY_QUANTITIES)
    assert set(extended.data["quantity"]) == set(CONSISTENCY_QUANTITIES)
    nbs_e = extended.data.query("configuration == 'NBs' and quantity == 'excursion_max_m'")
    assert list(nbs_e["value"]) == [0.0356, 0.0593, 0.171]
    with pytest.raises(pd_.InputError) as info:
        pd_.paper_targets(quantities=("alpha", "speed"))
    assert info.value.field == "quantities[1]"
    with pytest.raises(pd_.InputError) as info:
        pd_.paper_targets(quantities="alpha")
    assert info.value.field == "quantities"
    targets = pd_.paper_targets()
    for kwargs, field in (({"mass_kg": -1.0, "gap_total_m": 0.03}, "mass_kg"),
                          ({"mass_kg": 500.0, "gap_total_m": math.nan}, "gap_total_m"),
                          ({"mass_kg": 500.0, "gap_total_m": 0.03, "g": 0.0}, "g")):
        with pytest.raises(pd_.InputError) as info:
            targets.check_consistency(**kwargs)
        assert info.value.field == field
    assert isinstance(targets.check_consistency(500.0, 0.03), pd.DataFrame)
