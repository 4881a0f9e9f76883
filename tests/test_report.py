"""`pounding reproduce`: files written, the page in a real browser, the measured data."""

from __future__ import annotations

import shutil
from pathlib import Path

import pandas as pd
import pytest
from typer.testing import CliRunner

import pounding as pd_
from pounding.cli import app
from pounding.data import measured, paper_measurements
from pounding.reports import reproduce

FIGURES = ["fig04", "fig05", "fig06", "fig07", "fig08", "fig09", "fig10", "fig11", "fig14", "fig15", "fig16",
           "fig17", "coexistence"]


COVERED: dict[str, list] = {}  # per figure saved by the report: its legends that cover data


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    from matplotlib.figure import Figure

    from pounding.plots.legend import legends_over_data

    ybs = pd_.presets.paper_damped()
    out = tmp_path_factory.mktemp("report")
    save = Figure.savefig

    def checked(fig, path, *args, **kwargs):  # (each figure as the report saves it)
        COVERED[fig.get_suptitle()] = [leg.get_texts()[0].get_text() for _, leg in legends_over_data(fig)]
        return save(fig, path, *args, **kwargs)

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(Figure, "savefig", checked)
        return reproduce(ybs.without_bumpers(), ybs, out, system_label="paper-damped (test)",
                         freqs_hz=[1.0, 1.5, 2.0, 2.5], steady="fixed", cycles=6, measure_cycles=2)


def test_no_legend_of_the_report_covers_data(report):
    assert len(COVERED) == len(FIGURES)
    assert {title: legends for title, legends in COVERED.items() if legends} == {}


def test_reduced_report_writes_every_file(report):
    out = report.out_dir
    for name in ["index.html", "table2.csv", "table3.csv", "table4.csv"] + [f"{f}.png" for f in FIGURES]:
        assert (out / name).stat().st_size > 0, name
    t2 = pd.read_csv(out / "table2.csv")
    assert {"alpha_model", "alpha_measured", "alpha_diff", "nu_r_model", "eta_measured"} <= set(t2.columns)
    assert len(t2) == 14  # 7 measured (configuration, a_G) pairs, up and down
    row = t2.query("configuration == 'YBs' and a_g == 0.05 and direction == 'up'").iloc[0]
    assert row["alpha_measured"] == 16.80
    assert row["alpha_diff"] == pytest.approx(row["alpha_model"] - 16.80)
    t3 = pd.read_csv(out / "table3.csv")
    assert t3["mean_force_over_mg_diff"].isna().all()  # printed scale unclear: not differenced
    page = (out / "index.html").read_text(encoding="utf-8")
    # ... and the page says so in the cell, where it was blank; no cell is blank or "nan"
    assert page.count("not compared: the paper&#x27;s scale factor is unclear") + page.count(
        "not compared: the paper's scale factor is unclear") == len(t3)
    assert "<td></td>" not in page and ">nan<" not in page
    # each continuation's status says what its end means for its figure
    assert "drawn under Fig. 5 from" in page and "drawn in the coexistence map" in page
    assert page.count("<img src='data:image/png;base64,") == len(FIGURES)
    assert "paper-damped (test)" in page and "[isolator]" in page and "0.02073" in page
    assert "1.96/1.80 = 1.09" in page  # the notes on the paper's inconsistencies
    # the continued branches: one per YBs level, under the Fig. 5 sweeps; their statuses on the page
    assert page.count("YBs branch") >= 4 and "YBs fold curve" in page
    assert "YBs FRFs + branches" in page and "fold curves in (a_G, f)" in page


def test_every_table_of_the_page_scrolls_inside_it(report):
    page = Path(report.index_html).read_text(encoding="utf-8")
    assert page.count("<table") > 5 and page.count("<table") == page.count("<div class='wide'><table")


def _browser():
    chromium, driver = shutil.which("chromium"), shutil.which("chromedriver")
    if not (chromium and driver):
        pytest.skip("headless Chromium not installed (Debian packages chromium and chromium-driver; "
                    ".ci/run installs them)")
    webdriver = pytest.importorskip("selenium.webdriver",
                                    reason="selenium not installed (pip install -e '.[test]')")
    from selenium.webdriver.chrome.service import Service

    options = webdriver.ChromeOptions()
    options.binary_location = chromium
    for flag in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                 "--disable-background-networking", "--disable-component-update", "--disable-sync",
                 "--disable-dev-shm-usage"):
        options.add_argument(flag)
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    return webdriver.Chrome(service=Service(driver), options=options)


def test_page_opens_offline_in_headless_chromium(report):
    browser = _browser()
    try:
        browser.get(Path(report.index_html).resolve().as_uri())
        widths = browser.execute_script(
            "return Array.from(document.images).map(i => i.complete ? i.naturalWidth : 0);")
        assert len(widths) == len(FIGURES) and all(w > 0 for w in widths), widths
        errors = [e for e in browser.get_log("browser") if e["level"] in ("SEVERE", "ERROR")]
        assert errors == []
        assert "Table 2" in browser.find_element("tag name", "body").text
    finally:
        browser.quit()


# the paper's Tables 2-4, typed in again from the paper (not read from the package data)
PAPER_TABLES = {
    ("NBs", 0.03): {"nu_r": 1.2, "alpha": 1.80, "e": 1.03},
    ("NBs", 0.05): {"nu_r": 1.1, "alpha": 2.99, "e": 1.72},
    ("NBs", 0.1): {"nu_r": 1.0, "alpha": 3.89, "e": 2.48},
    ("YBs", 0.03): {"nu_r": 1.3, "alpha": 1.96, "eta": 1.04, "contact_nu_min": 1.3, "contact_nu_max": 1.3,
                    "mean_force_over_mg": 0, "contact_time_ms": 9, "dissipated_energy_per_mass": 0,
                    "restitution": 1},
    ("YBs", 0.05): {"nu_r": 2.2, "alpha": 16.80, "eta": 1.23, "contact_nu_min": 0.7, "contact_nu_max": 2.3,
                    "mean_force_over_mg": 14, "contact_time_ms": 15, "dissipated_energy_per_mass": 3.81e-4,
                    "restitution": 0.89},
    ("YBs", 0.075): {"nu_r": 2.5, "alpha": 16.18, "eta": 1.25, "contact_nu_min": 0.7, "contact_nu_max": 2.6,
                     "mean_force_over_mg": 12, "contact_time_ms": 23, "dissipated_energy_per_mass": 17.6e-4,
                     "restitution": 0.80},
    ("YBs", 0.1): {"nu_r": 2.9, "alpha": 15.04, "eta": 1.29, "contact_nu_min": 0.7, "contact_nu_max": 3.1,
                   "mean_force_over_mg": 7, "contact_time_ms": 31, "dissipated_energy_per_mass": 15.52e-4,
                   "restitution": 0.75},
}


def test_every_number_of_tables_2_to_4_is_in_the_package_data():
    tables = pd.concat([measured(t) for t in ("2", "3", "4")]).groupby(["configuration", "a_g"]).first()
    n = 0
    for (conf, a_g), values in PAPER_TABLES.items():
        for quantity, value in values.items():
            assert tables.loc[(conf, a_g), quantity] == pytest.approx(value, rel=1e-12), (conf, a_g, quantity)
            n += 1
    assert n == 9 + 4 * 9
    data = paper_measurements()
    assert (data["source"] != "").all()
    assert data.query("quantity == 'd_tmax_m'")["value"].tolist() == [0.02073, 0.03455, 0.0691]
    assert data.query("quantity == 'acceleration_ratio'")["value"].tolist() == [1.9, 5.62, 3.87]
    assert data.query("quantity == 'excursion_ratio'")["value"].tolist() == [0.88, 0.62, 0.23]
    assert data.query("quantity == 'excursion_max_m'")["value"].tolist() == [0.0356, 0.0593, 0.171]
    flagged = data[data["note"].str.contains("inconsistent")]
    assert set(flagged["quantity"]) == {"e", "acceleration_ratio"}


def test_cli_reproduce_refuses_half_a_pair():
    """(The command's run itself, the default preset over the whole campaign, is the README's first
    block: tests/test_readme.py checks what it prints and writes.)"""
    bad = CliRunner().invoke(app, ["reproduce", "--nbs", "x.toml"])
    assert bad.exit_code == 2 and "--ybs" in bad.output


def test_page_reads_well_headers_in_words_percent_differences_and_the_paper_cited(report):
    page = (report.out_dir / "index.html").read_text(encoding="utf-8")
    assert "MODEL.md" not in page  # a file users do not have
    assert "A preliminary experimental study about two-sided impacting SDOF oscillator" in page
    assert "difference [%]" in page and "nu_r_model" not in page and "alpha_diff" not in page
    assert ">True<" not in page and ">False<" not in page
    assert "restitution s = -v_o/v_i slightly above 1" in page
    t2 = report.comparisons["2"]
    row = t2.query("configuration == 'YBs' and a_g == 0.05 and direction == 'up'").iloc[0]
    assert row["alpha_diff_pct"] == pytest.approx(100 * (row["alpha_model"] - 16.80) / 16.80)


def test_figures_tell_their_markers_apart(report):
    import matplotlib.pyplot as plt
    from matplotlib.colors import to_rgba

    from pounding.reports.figures import paper_figures

    figs = paper_figures(report.campaign)
    try:
        for name in ("fig04", "fig05"):  # one measured peak per a_G, each in its curve's colour
            peaks = [ln for ln in figs[name].axes[0].lines if ln.get_label().startswith("measured peak")]
            assert len(peaks) >= 3
            assert len({to_rgba(ln.get_markeredgecolor()) for ln in peaks}) == len(peaks)
        for name in ("fig09", "fig16", "fig17"):  # NBs and YBs measured in shapes of their own
            measured = {ln.get_label(): ln.get_marker() for ln in figs[name].axes[0].lines
                        if "measured" in ln.get_label()}
            assert measured["NBs measured"] != measured["YBs measured"]
        for name in ("fig10", "fig11"):  # up and down sweeps look different, legend included
            lines = {ln.get_label(): ln for ln in figs[name].axes[1].lines}
            up, down = lines["YBs model (up sweep)"], lines["YBs model (down sweep)"]
            assert (up.get_linestyle(), up.get_markerfacecolor()) != (down.get_linestyle(),
                                                                        down.get_markerfacecolor())
        assert len(figs["fig10"].axes) == 2  # measured forces on the model's axis, no second scale
        for name in ("fig07", "fig15"):  # the bumpers at d = +-1, as the paper's figures
            ax = figs[name].axes[0]
            surfaces = sorted(ln.get_xdata()[0] for ln in ax.lines if ln.get_linestyle() == ":")
            assert surfaces[0] == pytest.approx(-1.0) and surfaces[-1] == pytest.approx(1.0)
            assert "+-1" in ax.get_xlabel() or "pm 1" in ax.get_xlabel()
    finally:
        plt.close("all")


def test_the_page_opens_with_the_verdict(report):
    v = report.verdict
    assert v.total == 36 and v.met == int(v.residuals["within"].sum())
    page = (report.out_dir / "index.html").read_text(encoding="utf-8")
    assert page.index("<h2>Verdict</h2>") < page.index("<h2>Campaign</h2>")
    assert f"meets {v.met} of 36 targets" in page and "Worst misses" in page
    worst = v.worst_misses
    assert (worst["normalized"].abs().diff().dropna() <= 0).all()  # worst first
    row = worst.iloc[0]
    assert row["difference_pct"] == pytest.approx(100 * (row["model"] - row["target"]) / abs(row["target"]))
    # the paper's a_G = 0.03 accelerations, too low for a sinusoidal response of their excursions,
    # and the 15 ms contacts at a_G 0.05, too short for the compression eta 1.23 says
    assert len(v.flags) == 3 and "Are the measurements consistent?" in page
    flagged = v.residuals[v.residuals["flagged"]]
    assert set(zip(flagged["configuration"], flagged["a_g"], flagged["quantity"])) == {
        ("NBs", 0.03, "alpha"), ("YBs", 0.03, "alpha"), ("YBs", 0.05, "contact_time_ms")}


def test_table_2_compares_eta_over_the_rigs_nominal_gap():
    # a model with 13 mm gaps: its own eta is E / 26 mm, the paper's E / 30 mm; the report
    # compares the latter, as identify and the verdict do
    from pounding.reports.compare import comparison

    text = pd_.presets.paper_damped().to_toml_text()
    ybs = pd_.Oscillator.from_toml_text(text.replace("gap_left_m = 0.015", "gap_left_m = 0.013")
                                        .replace("gap_right_m = 0.015", "gap_right_m = 0.013"))
    result = pd_.campaign(None, ybs, ybs_a_g=(0.05,), freqs_hz=[1.5, 2.0], directions=("up",),
                          steady="fixed", cycles=6, measure_cycles=2)
    own = result.table2().iloc[0]
    assert own["eta"] == pytest.approx(own["excursion_max_m"] / 0.026)
    row = comparison(result, "2").iloc[0]
    assert row["eta_model"] == pytest.approx(own["excursion_max_m"] / 0.03)
    assert row["eta_diff"] == pytest.approx(row["eta_model"] - 1.23)


def test_reproduce_leaves_the_callers_backend_and_its_results_compare(tmp_path):
    import matplotlib

    before = matplotlib.get_backend()
    matplotlib.use("pdf")  # (a backend of the caller's: a notebook's would be inline)
    try:
        ybs = pd_.presets.paper_damped()
        small = dict(freqs_hz=[1.5, 2.0], nbs_a_g=(0.05,), ybs_a_g=(0.05,), directions=("up",),
                     steady="fixed", cycles=5)
        one = reproduce(ybs.without_bumpers(), ybs, tmp_path / "a", **small)
        assert matplotlib.get_backend() == "pdf"
    finally:
        matplotlib.use(before)
    # a report asked for nothing more tells the exact story alone, without the stands' section (the
    # measured and stands tests read this one report: tests/test_measured_report.py, test_report_stands.py)
    assert one.stands is None and "stands" not in one.tables
    assert one.measured is None and one.laser is None
    assert "Which story" not in one.index_html.read_text(encoding="utf-8")
    # results holding tables compare by identity (dataclass __eq__ over DataFrames raised)
    assert one == one and one.verdict == one.verdict
    assert not (one == object()) and one != one.verdict
