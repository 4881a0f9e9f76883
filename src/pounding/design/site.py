"""A design file's site: its two target spectra (design and MCE level) and its hazard curve, checked and named
by the file's fields (``[site]``)."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

from .._checks import instance_of, one_of, positive
from .._errors import InputError, Problem
from ..model.oscillator import check_keys
from .hazard import HazardCurve
from .spectra import DesignSpectrum, asce7_spectrum, ec8_spectrum, user_spectrum

SITE_CODES = ("asce7-16", "en1998-1", "user")
SITE_KEYS = {
    "asce7-16": ("code", "s_ds_g", "s_d1_g", "t_l_s", "hazard_curve"),
    "en1998-1": (
        "code",
        "a_gr_g",
        "ground_type",
        "spectrum_type",
        "importance",
        "hazard_curve",
        "mce_factor",
    ),
    "user": ("code", "spectrum", "mce_spectrum", "hazard_curve"),
}
EC8_MCE_FACTOR = 1.5  # EN 1998-1 has no MCE: the "MCE" level is this factor times its spectrum (stated)


def site_spectra(site: Mapping[str, Any],
                 base: Path) -> tuple[DesignSpectrum, DesignSpectrum, HazardCurve | None]:
    try:
        return _site_spectra(site, base)
    except InputError as exc:  # (the spectra's own fields, named as the file names them)
        if exc.field.startswith("site."):
            raise
        raise exc.relabel("", "site.") from None


def _site_spectra(site: Mapping[str, Any], base: Path) -> tuple[DesignSpectrum, DesignSpectrum, Any]:
    code = one_of("site.code", site.get("code", "asce7-16"), SITE_CODES)
    check_keys(site, "site.", SITE_KEYS[code], ())
    if code == "asce7-16":
        for key in ("s_ds_g", "s_d1_g"):
            if key not in site:
                raise InputError(Problem.MISSING_KEY, f"site.{key}", None, choices=", ".join(SITE_KEYS[code]))
        args = (site["s_ds_g"], site["s_d1_g"], site.get("t_l_s", 8.0))
        design_spec, mce_spec = asce7_spectrum(*args), asce7_spectrum(*args, level="mce")
    elif code == "en1998-1":
        if "a_gr_g" not in site:
            raise InputError(Problem.MISSING_KEY, "site.a_gr_g", None, choices=", ".join(SITE_KEYS[code]))
        design_spec = ec8_spectrum(
            site["a_gr_g"],
            site.get("ground_type", "B"),
            site.get("spectrum_type", 1),
            importance=site.get("importance", 1.0),
        )
        factor = positive("site.mce_factor", site.get("mce_factor", EC8_MCE_FACTOR), "(a factor)")
        mce_spec = ec8_spectrum(
            site["a_gr_g"] * factor,
            site.get("ground_type", "B"),
            site.get("spectrum_type", 1),
            importance=site.get("importance", 1.0),
            name=f"{factor:g} x {design_spec.name}",
        )
    else:
        for key in ("spectrum", "mce_spectrum"):
            if key not in site:
                raise InputError(
                    Problem.MISSING_KEY,
                    f"site.{key}",
                    None,
                    choices="spectrum and mce_spectrum (CSV files: period s, Sa g)",
                )
        try:
            design_spec = user_spectrum(path=base / text_field("site.spectrum", site["spectrum"]),
                                        name="design")
        except InputError as exc:
            raise exc.relabel("path", "site.spectrum") from None
        try:
            mce_spec = user_spectrum(path=base / text_field("site.mce_spectrum", site["mce_spectrum"]),
                                     name="MCE")
        except InputError as exc:
            raise exc.relabel("path", "site.mce_spectrum") from None
    return design_spec, mce_spec, site.get("hazard_curve")


def hazard_curve_of(value: Any, base: Path, period_s: float) -> HazardCurve:
    """The hazard curve a site table names (a CSV of Sa g and annual frequency), for Sa(period_s)."""
    instance_of("site.hazard_curve", value, str,
                "the path of a CSV file (Sa in g, annual frequency of exceedance)")
    try:
        return HazardCurve.from_csv(base / value, period_s)
    except InputError as exc:
        raise exc.relabel("path", "site.hazard_curve") from None


def text_field(field: str, value: Any) -> str:
    """``value``, a text, or an error naming ``field``."""
    instance_of(field, value, str, "text (a string)")
    return value
