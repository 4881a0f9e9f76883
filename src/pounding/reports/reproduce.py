"""``reproduce``: run the paper's campaign and write its tables and figures beside the measurements."""

from __future__ import annotations

import datetime as _dt
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pandas as pd

from .. import __version__
from .._io import atomic_write, output_dir
from ..identification import evaluate, paper_targets
from .._errors import InputError, Problem
from ..engine.assembly import is_single_mass
from ..model import MeasurementChain, Oscillator
from ..protocols import CampaignResult, campaign
from .._runner.progress import Progress, announce, progress_reporter
from .branches import add_branches, coexistence_of, continuation_statuses, fig_coexistence
from .compare import comparison, inconsistency_notes
from .figures import fig05_measured, paper_figures
from .html import table_html, untargeted_notes, write_page
from .measured_story import MeasuredStory, measured_story, story_html
from .stands import StandsTest, stands_html, stands_test
from .verdict import Verdict, verdict

TABLE_TITLES = {"targets": "Calibration targets (Tables 2-4; sweeps up, fixed 30 cycles per step): systems "
                           "side by side",
                "2": "Table 2: maximum non-dimensional accelerations and excursions",
                "3": "Table 3: impact characterization at resonance, contact forces and times",
                "4": "Table 4: impact characterization at resonance, dissipated energies and restitution"}


@dataclass(frozen=True, eq=False)
class Report:
    """What :func:`reproduce` wrote, and the campaign behind it.

    Attributes
    ----------
    out_dir : Path
        The directory written (it also holds the campaign as ``campaign.nc``).
    index_html : Path
        The report's page, ``out_dir / "index.html"``.
    tables : dict of str to Path
        ``"2"``, ``"3"``, ``"4"`` (and ``"targets"`` with ``beside``; ``"coexistence"``: the test
        points, each with its witnesses and verdict, when the branches were continued; ``"stands"``
        with ``stands=True``: the YBs system on each stand) -> the CSV.
    figures : dict of str to Path
        Figure name (``"fig04"`` ... ``"fig17"``, the paper's numbering, and ``"coexistence"`` when the
        YBs branches could be continued) -> its PNG.
    campaign : CampaignResult
        The campaign that was run.
    comparisons : dict of str to DataFrame
        The tables themselves, keyed as ``tables``: :func:`comparison` of each (``"targets"``: the
        paper's targets with the ``beside`` systems' model values).
    verdict : Verdict
        How many of :func:`pounding.paper_targets` the YBs system meets (``met`` of ``total``), its
        worst misses and the measurements no model can meet together.
    measured : MeasuredStory or None
        With ``measured=``: the campaign, Tables 2-4 and verdict as measured through the chain.
    laser : MeasuredStory or None
        With ``laser=``: the same, through the chain that times the contacts by the laser.
    stands : StandsTest or None
        With ``stands=True`` (and bumpers): the YBs system on each stand, and the verdict in words.

    Examples
    --------
    A tiny report: one a_G per configuration, two steps of 5 cycles (the verdict still judges the
    YBs system against all the paper's targets):

    >>> import pounding
    >>> report = pounding.reports.reproduce(
    ...     pounding.presets.paper_damped(bumpers=False),
    ...     pounding.presets.paper_damped(), "report",
    ...     freqs_hz=[1.5, 2.0], nbs_a_g=(0.05,), ybs_a_g=(0.05,),
    ...     directions=("up",), steady="fixed", cycles=5)
    >>> report.index_html.name, sorted(report.tables), "fig05" in report.figures
    ('index.html', ['2', '3', '4', 'coexistence'], True)
    >>> # the paper's 36 targets
    >>> report.verdict.total, 0 < report.verdict.met < report.verdict.total
    (36, True)
    """

    out_dir: Path
    index_html: Path
    tables: dict[str, Path]
    figures: dict[str, Path]
    campaign: CampaignResult
    comparisons: dict[str, pd.DataFrame]
    verdict: Verdict
    measured: MeasuredStory | None = None
    stands: StandsTest | None = None
    laser: MeasuredStory | None = None


def targets_beside(systems: dict[str, Oscillator], evaluated: dict[int, pd.DataFrame] | None = None,
                   workers: int | None = None, progress: Progress = False) -> pd.DataFrame:
    """The paper's targets (:func:`pounding.paper_targets`) with each YBs system's model value
    beside them: sweeps up, fixed 30 cycles per step, as the calibration ran.

    ``evaluated`` maps ``id(system)`` to its residual table where it was computed already.

    Returns
    -------
    DataFrame
        ``configuration``, ``a_g``, ``quantity``, ``measured``, ``allowed`` (the tolerance),
        then per system ``<label>`` (model value) and ``<label> met`` (within tolerance).
    """
    targets = paper_targets()
    evaluated = evaluated or {}
    out = None
    for label, osc in systems.items():
        res = (evaluated[id(osc)] if id(osc) in evaluated
               else evaluate(osc, targets, workers=workers, progress=progress, label=f"targets of {label}"))
        if out is None:
            out = res[["configuration", "a_g", "quantity"]].copy()
            out["measured"] = res["target"]
            out["allowed"] = res["allowed"]
        out[label] = res["model"]
        out[f"{label} met"] = res["within"]
    return out


def reproduce(nbs_system: Oscillator, ybs_system: Oscillator, out_dir: str | Path = "report", *,
              system_label: str = "custom systems", freqs_hz: Any = None, workers: int | None = None,
              progress: Progress = False, beside: dict[str, Oscillator] | None = None,
              measured: tuple[Oscillator, MeasurementChain] | None = None,
              profile: pd.DataFrame | None = None, stands: bool = False,
              laser: tuple[Oscillator, MeasurementChain] | None = None,
              laser_profile: pd.DataFrame | None = None, **sweep_options: Any) -> Report:
    """Run the paper's campaign and write Tables 2-4 (CSV), the figure analogues (PNG) and
    ``index.html`` into ``out_dir``.

    Parameters
    ----------
    nbs_system, ybs_system : Oscillator
        Without and with bumpers.
    out_dir : path
        Created if needed; files in it are overwritten.
    system_label : str
        How the page names the systems (e.g. the preset).
    freqs_hz, workers, progress, **sweep_options
        As :func:`pounding.campaign` (default: the paper's grid, adaptive steady state);
        ``sweep_options`` may hold its ``nbs_a_g``, ``ybs_a_g`` and ``directions`` too.  The
        verdict (and ``beside``) evaluate the paper's targets with the calibration's own sweeps
        (up, fixed 30 cycles per step, the paper's grid), whatever these say.
    beside : dict, optional
        ``label -> YBs system``: the report adds a table of the paper's targets with these
        systems' model values side by side (:func:`targets_beside`), e.g. the calibrated
        preset beside the printed one.
    measured : (Oscillator, MeasurementChain), optional
        A YBs system and the chain its metrics are measured through (e.g.
        ``presets.paper_calibrated_measured()``): the report then tells both stories, the exact
        metrics and the measured ones (a second campaign through the chain), with their verdicts,
        Tables 2-4 and Fig. 5 as measured, and says the paper states no filter.
    profile : DataFrame, optional
        With ``measured``: targets met against the chain's cutoff, shown beside it.
    laser : (Oscillator, MeasurementChain), optional
        A third story told the same way: a YBs system and a chain that times the contacts by the laser's
        gap crossings (``contact_timing="laser"``, e.g. ``presets.paper_calibrated_laser()``): its
        campaign, Tables 2-4 (``table2_laser.csv`` ...), Fig. 5 and verdict as measured.
    laser_profile : DataFrame, optional
        With ``laser``: its fits against the cutoff (``presets.measurement_profile("laser")``).
    stands : bool
        Also test whether stands under the bumpers explain the YBs accelerations: the YBs system with
        each bumper on a stand of its own (10 kg; 1e8, 1e7, 1e6 and 1e5 N/m), each evaluated on the
        paper's targets (four more evaluations, a few seconds); ``stands.csv`` and a section of the page.

    Returns
    -------
    Report
        The paths written, the campaign, the tables and the verdict.

    Examples
    --------
    The cheapest report: one a_G per configuration, sweeps up only, two steps of 5 cycles (a
    couple of seconds, most of it writing the figures):

    >>> import pounding
    >>> ybs = pounding.presets.paper_damped()
    >>> report = pounding.reports.reproduce(ybs.without_bumpers(), ybs, "report",
    ...                                     freqs_hz=[1.5, 2.0], nbs_a_g=(0.05,),
    ...                                     ybs_a_g=(0.05,), directions=("up",),
    ...                                     steady="fixed", cycles=5)
    >>> sorted(p.name for p in report.out_dir.iterdir())[:6]
    ['campaign.nc', 'coexistence.csv', 'coexistence.png', 'fig04.png', 'fig05.png',
     'fig06.png']
    >>> report.tables["2"].name, len(report.figures)
    ('table2.csv', 13)
    """
    import matplotlib.pyplot as plt

    out = output_dir("out_dir", out_dir)  # before the campaign: no work lost to a bad path
    if "measurement" in sweep_options:
        raise InputError(Problem.UNKNOWN_KEY, "measurement", sweep_options["measurement"],
                         choices="measured=(system, chain): the report's own campaign keeps the exact "
                                 "metrics, and the chain tells the second story")
    for name, pair, example in (("measured", measured, "presets.paper_calibrated_measured()"),
                                ("laser", laser, "presets.paper_calibrated_laser()")):
        if pair is not None and (not isinstance(pair, tuple) or len(pair) != 2
                                 or not is_single_mass(pair[0])
                                 or not isinstance(pair[1], MeasurementChain)):
            raise InputError(Problem.WRONG_TYPE, name, pair, got=type(pair).__name__,
                             expected=f"(Oscillator, MeasurementChain), e.g. {example}")
    if laser is not None and laser[1].contact_timing != "laser":
        raise InputError(Problem.BAD_STATE, "laser", laser[1].describe(),
                         why="its chain times the contacts by their force pulses",
                         fix="give a chain with contact_timing=\"laser\" (or tell that story as measured=)")
    result = campaign(nbs_system, ybs_system, freqs_hz=freqs_hz, workers=workers, progress=progress,
                      label="campaign, exact metrics", **sweep_options)
    out.mkdir(parents=True, exist_ok=True)
    result.to_netcdf(out / "campaign.nc")
    comparisons = {t: comparison(result, t) for t in ("2", "3", "4")}

    def evaluate_of(system: Oscillator, targets: Any, label: str, **options: Any) -> pd.DataFrame:
        return evaluate(system, targets, workers=workers, progress=progress, label=label, **options)

    # the verdict: the paper's targets, sweeps up, fixed 30 cycles
    own = evaluate_of(ybs_system, paper_targets(), "targets (the verdict's sweeps)")
    judged = verdict(own)
    stories: dict[str, MeasuredStory] = {}  # (the measured stories, by their tables' suffix)
    for key, pair, known, timed in (("measured", measured, profile, ""),
                                    ("laser", laser, laser_profile, ", timed by the laser")):
        if pair is None:
            continue

        def campaign_of(nbs: Oscillator, ybs: Oscillator, timed: str = timed, **chain: Any) -> CampaignResult:
            return campaign(nbs, ybs, freqs_hz=freqs_hz, workers=workers, progress=progress,
                            label=f"campaign, as measured{timed}", **sweep_options, **chain)

        stories[key] = measured_story(*pair, campaign_of, known, evaluate_of)
        for t in ("2", "3", "4"):
            comparisons[f"{t} {key}"] = stories[key].comparisons[t]
    story, laser_story = stories.get("measured"), stories.get("laser")
    stands_result = stands_test(ybs_system, own, evaluate_of) if stands else None
    if beside:
        comparisons["targets"] = targets_beside(beside, {id(ybs_system): own}, workers, progress)
    tables = {t: out / ("targets.csv" if t == "targets" else f"table{t.replace(' ', '_')}.csv")
              for t in comparisons}
    for t, df in comparisons.items():
        atomic_write(tables[t], lambda tmp, df=df: df.to_csv(tmp, index=False))
    if stands_result is not None:
        tables["stands"] = out / "stands.csv"
        atomic_write(tables["stands"], lambda tmp: stands_result.table.to_csv(tmp, index=False))
    announce(progress, "coexistence: following the YBs branches and their folds ...")
    cmap, why_not = coexistence_of(result, ybs_system, progress=progress)
    if cmap is not None:  # (each test point with its witnesses)
        tables["coexistence"] = out / "coexistence.csv"
        atomic_write(tables["coexistence"], lambda tmp: cmap.matrix.to_csv(tmp, index=False))
    figures, captions = {}, {}
    with plt.ioff():  # (written, never shown; the caller's backend, a notebook's too, left as it is)
        announce(progress, "drawing the figures ...")
        made = paper_figures(result)
        for key, told in stories.items():
            made[f"fig05_{key}"] = fig05_measured(told.campaign, told.chain.describe())
        more = {}
        if cmap is not None:
            more["fig05"] = add_branches(made["fig05"], cmap, float(result.data.attrs["f_ref_hz"]))
            made["coexistence"] = fig_coexistence(cmap)
        with progress_reporter(progress, len(made), "figures") as advance:
            for name, fig in made.items():
                figures[name] = out / f"{name}.png"
                captions[name] = " ".join(filter(None, (fig.get_suptitle(), more.get(name))))
                atomic_write(figures[name], lambda tmp, fig=fig: fig.savefig(tmp, dpi=110))
                plt.close(fig)
                advance(1)
    ds = result.data
    settings = {k: ds.attrs[k] for k in ("steady_mode", "cycles", "measure_cycles", "f_ref_hz",
                                         "omega_min_rad_s")}
    settings.update({"frequencies [Hz]": f"{float(ds.freq_hz.min()):g} to {float(ds.freq_hz.max()):g} "
                                         f"({ds.freq_hz.size} steps)",
                     "pounding": __version__, "written": _dt.datetime.now().isoformat(timespec="seconds")})
    targets = paper_targets().to_dataframe()
    statuses = pd.DataFrame([_sweep_status(key, sw) for key, sw in result.sweeps.items()])
    statuses = pd.concat([statuses, continuation_statuses(cmap, why_not)], ignore_index=True)
    systems = {k.removeprefix("system_"): v for k, v in ds.attrs.items() if k.startswith("system_")}
    index = write_page(
        out / "index.html", title="pounding: the paper's tables and figures, model beside measurement",
        system_label=system_label, systems=systems, settings=settings,
        tables={_title(t): df for t, df in comparisons.items()},
        table_notes={_title(t): untargeted_notes(df, targets) for t, df in comparisons.items()
                     if t != "targets"},
        figures={name: (path, captions[name]) for name, path in figures.items()},
        notes=inconsistency_notes(), statuses=statuses, verdict=judged,
        story=([part for told in stories.values()
                for part in story_html(judged, told, system_label, table_html)]
               + ([] if stands_result is None else stands_html(stands_result, table_html))) or None)
    return Report(out, index, tables, figures, result, comparisons, judged, story, stands_result, laser_story)


MEASURED_TITLES = {"measured": " (as measured through the chain)",
                   "laser": " (as measured through the chain, the contacts timed by the laser)"}


def _title(key: str) -> str:
    """A table's heading (a measured one: the exact one's, said so)."""
    base, _, measured = key.partition(" ")
    return TABLE_TITLES[base] + MEASURED_TITLES.get(measured, "")


def _sweep_status(key: tuple, sw: Any) -> dict:
    """A sweep's row of the status table, with what its end means for the figures."""
    conf, a_g, direction = key
    unsettled = int((~sw.to_dataframe()["steady"].iloc[: sw.steps_done]).sum())
    drawn = "every step drawn in the figures" if sw.steps_done == sw.freqs_hz.size else (
        f"drawn up to {sw.freqs_hz[sw.steps_done - 1]:g} Hz, where it stopped" if sw.steps_done
        else "not drawn")
    if unsettled:
        drawn += (f"; {unsettled} step(s) are drawn from their last {sw.measure_cycles} cycles though the "
                  "response had not settled: a point of a motion still changing, not of a periodic response")
    return {"configuration": conf, "a_g": a_g, "direction": direction, "steps": sw.steps_done,
            "not steady": unsettled, "message": sw.message, "in the figures": drawn}
