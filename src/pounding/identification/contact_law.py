"""Fit a bumper contact law to a cyclic force-displacement test (the paper's MTS tests, Fig. 3).

The test imposes a compression history on the bumper and records its force.  Both laws are
linear in their stiffness and damping once the exponent is fixed, so those come from
non-negative least squares; Hunt-Crossley's exponent is the one nonlinear unknown, found by
a bounded scalar search on the residual (variable projection).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
import pandas as pd

from .._docs import fill_doc
from .._checks import at_least, at_most, float_array, integer, one_of, plausible, positive, real_tuple
from .._errors import InputError, Problem
from ..model.contact_laws import (LAWS, MAX_BRANCHES, MAX_EXPONENT, ContactLaw, ElasticPlastic,
                                  Hertzdamp, HuntCrossley, Jankowski, KelvinVoigt, MultilinearBumper,
                                  RigidStop)
from ._law_fits import (elastic_plastic_search, kinematic_fit, law_force, multilinear_fit, multilinear_search,
                        nnls_fit)

MIN_SAMPLES_IN_CONTACT = 3
UNFITTED = (Hertzdamp.TYPE, RigidStop.TYPE)  # laws a cyclic test cannot fit (each says why)
# rank_contact_laws' name of MultilinearBumper(hysteresis="kinematic")
KINEMATIC_ROW = "multilinear_kinematic"
MIN_STIFFNESS = 1e-300  # the fitted stiffness's floor, N/m^n: at it, no stiffness fits (an error)
# the scales of a bumper test: beyond them the data are in other units (and the least squares overflow)
MAX_COMPRESSION_M = 1e3
MIN_COMPRESSION_M = 1e-9
MAX_FORCE_N = 1e12
MAX_RATE_M_S = 1e6


@dataclass(frozen=True, eq=False)
class ContactLawFit:
    """A contact law fitted to a force-displacement test.

    Attributes
    ----------
    law : KelvinVoigt, HuntCrossley, Jankowski, MultilinearBumper or ElasticPlastic
        The fitted law, ready for :class:`pounding.Bumpers`.  (An elastic-plastic law's force
        depends on the path: :meth:`predict` takes the samples in order, from an unloaded bumper.)
    rms_n : float
        Root-mean-square residual force, N, over the samples in compression.
    r_squared : float
        Share of the force variance the law explains.
    compression_m, velocity_m_s, force_n : ndarray, shape (n,)
        The samples in compression that were fitted.

    Examples
    --------
    Two cycles of a 1 Hz compression test, 0 to 4 mm, of a Kelvin-Voigt bumper:

    >>> import pounding
    >>> import numpy as np
    >>> t = np.linspace(0.0, 2.0, 401)                   # s
    >>> d = 0.002 * (1.0 - np.cos(2.0 * np.pi * t))       # m: compression
    >>> v = 0.004 * np.pi * np.sin(2.0 * np.pi * t)       # m/s: its rate
    >>> fit = pounding.fit_contact_law(d, 1.46e6 * d + 5e3 * v, velocity_m_s=v)
    >>> round(fit.law.stiffness), round(fit.law.damping), round(fit.r_squared, 6)
    (1460000, 5000, 1.0)
    >>> fit.predict([0.001, 0.002], [0.0, 0.01]).round(1).tolist()  # N
    [1460.0, 2970.0]
    """

    law: ContactLaw
    rms_n: float
    r_squared: float
    compression_m: np.ndarray
    velocity_m_s: np.ndarray
    force_n: np.ndarray

    def predict(self, compression_m: Any, velocity_m_s: Any) -> np.ndarray:
        """The law's force (N) at compressions (m) and compression rates (m/s), shape (n,)."""
        d = float_array("compression_m", compression_m)
        v = float_array("velocity_m_s", velocity_m_s)
        if d.size != v.size:
            raise InputError(Problem.SIZE_MISMATCH, "velocity_m_s", f"array of {v.size}",
                             got=v.size, expected=d.size, other="compression_m")
        return law_force(self.law, d, v)

    def to_xarray(self) -> Any:
        """The table of :meth:`to_dataframe` as a Dataset along ``sample``."""
        from .._tables import frame_to_xarray

        return frame_to_xarray(self.to_dataframe(), "sample")

    def to_dataframe(self) -> pd.DataFrame:
        """One row per fitted sample: compression, rate, measured and fitted force, residual."""
        model = law_force(self.law, self.compression_m, self.velocity_m_s)
        return pd.DataFrame({"compression_m": self.compression_m, "velocity_m_s": self.velocity_m_s,
                             "force_n": self.force_n, "model_force_n": model,
                             "residual_n": self.force_n - model})

    def plot(self, ax=None):
        """Measured and fitted force against compression; returns its Figure."""
        from ..plots.contact_law import plot_contact_law_fit
        from ..plots import figure_of

        return figure_of(plot_contact_law_fit(self, ax=ax), ax)


@fill_doc
def fit_contact_law(
    displacement_m: Any,
    force_n: Any,
    *,
    time_s: Any = None,
    velocity_m_s: Any = None,
    law: str = KelvinVoigt.TYPE,
    exponent_bounds: tuple[float, float] = (1.0, 3.0),
    effective_mass_kg: float | None = None,
    breakpoints: Any = None,
    n_branches: int = 3,
    hysteresis: str = "elastic",
) -> ContactLawFit:
    """Fit a bumper law to a measured force-displacement history.

    Parameters
    ----------
    {bumper_history}
    law : {"kelvin_voigt", "hunt_crossley", "jankowski", "multilinear", "elastic_plastic"}
        ``F = k d + c v``, ``F = d^n (k + c v)``, ``F = k d^n + 2 xi sqrt(m k d^(n-1)) v``
        while ``v > 0`` (``k d^n`` while ``v <= 0``), ``F = R(d) + c v`` with a multi-linear ``R``,
        or :class:`ElasticPlastic` (rate-independent: its force follows the samples in compression in
        their order, from an unloaded bumper; searched over a grid, then polished by least squares).
    exponent_bounds : (float, float)
        Search range of the exponent ``n`` (>= 1) of Hunt-Crossley and Jankowski.
    effective_mass_kg : float, optional
        Jankowski's effective mass, kg (the impacting mass ``M``): required for that law, whose
        damping ratio is the fitted dashpot factor over ``2 sqrt(m k)``.
    breakpoints : sequence of float, optional
        A multi-linear law's breakpoints, m (its slopes and damping then come from
        non-negative least squares); default: searched, for ``n_branches`` branches.
    n_branches : int
        Branches of a multi-linear law whose breakpoints are searched (1 to 4; default 3: the
        D-shaped bumper's stiff start, soft plateau and steep rise).
    hysteresis : {"elastic", "kinematic"}
        A multi-linear law's (:class:`MultilinearBumper`): ``"kinematic"`` follows the samples
        in their order from an unloaded bumper, each breakpoint a softening (a spring that
        slips) or a hardening, whichever fits.

    Returns
    -------
    ContactLawFit
        The fitted law, its residual (N) and R^2, and the samples in compression it was fitted to.

    Examples
    --------
    A 1 Hz cyclic compression test, 0 to 4 mm, of a bumper that stiffens as it is compressed
    (``F = d^1.5 (k + c v)``, k = 3e7 N/m^1.5):

    >>> import pounding
    >>> import numpy as np
    >>> t = np.linspace(0.0, 2.0, 401)                   # s
    >>> d = 0.002 * (1.0 - np.cos(2.0 * np.pi * t))       # m: compression
    >>> force = 3e7 * d**1.5 * (1.0 + 0.5 * np.gradient(d, t, edge_order=2))  # N
    >>> fit = pounding.fit_contact_law(d, force, time_s=t, law="hunt_crossley")
    >>> round(fit.law.exponent,
    ...       3), f"{fit.law.stiffness:.3g} N/m^n", round(fit.r_squared, 6)
    (1.5, '3e+07 N/m^n', 1.0)
    """
    one_of("law", law, LAWS)
    if law == RigidStop.TYPE:
        raise InputError(Problem.NOT_ONE_OF, "law", law,
                         choices=", ".join(repr(k) for k in LAWS if k not in UNFITTED)
                         + " (a rigid stop has no force against compression to fit: its restitution is the "
                           "measured impacts' v_out / v_in, pounding.RigidStop(restitution))")
    if law == Hertzdamp.TYPE:
        raise InputError(Problem.NOT_ONE_OF, "law", law,
                         choices=", ".join(repr(k) for k in LAWS if k not in UNFITTED)
                         + " (Hertzdamp's damping is set by each impact's velocity, which a cyclic test has "
                           "not: fit 'hunt_crossley', whose damping c is Hertzdamp's xi_norm k / v_in)")
    n_branches = integer("n_branches", n_branches, 1, MAX_BRANCHES)
    one_of("hysteresis", hysteresis, MultilinearBumper.HYSTERESIS)
    if hysteresis != "elastic" and law != MultilinearBumper.TYPE:
        raise InputError(Problem.NOT_ONE_OF, "law", law,
                         choices="'multilinear' (hysteresis is a multi-linear law's; leave it out otherwise)")
    if breakpoints is not None and law != MultilinearBumper.TYPE:
        raise InputError(Problem.NOT_ONE_OF, "law", law,
                         choices="'multilinear' (breakpoints are a multi-linear law's; leave them out "
                                 "otherwise)")
    if law == Jankowski.TYPE:
        if effective_mass_kg is None:
            raise InputError(Problem.MISSING_INPUT, "effective_mass_kg", None,
                             what="effective_mass_kg (kg, the impacting mass): Jankowski's damping ratio "
                                  "needs it")
        effective_mass_kg = positive("effective_mass_kg", effective_mass_kg, "kg")
    d = float_array("displacement_m", displacement_m, min_len=MIN_SAMPLES_IN_CONTACT)
    force = float_array("force_n", force_n, min_len=MIN_SAMPLES_IN_CONTACT)
    _same_length("force_n", force, d)
    if velocity_m_s is not None:
        v = float_array("velocity_m_s", velocity_m_s)
        _same_length("velocity_m_s", v, d)
    elif time_s is not None:
        t = float_array("time_s", time_s)
        _same_length("time_s", t, d)
        bad = np.flatnonzero(np.diff(t) <= 0.0)
        if bad.size:  # name the first sample that does not come after the one before
            i = int(bad[0]) + 1
            raise InputError(Problem.NOT_INCREASING, f"time_s[{i - 1}:{i + 1}]",
                             [float(t[i - 1]), float(t[i])])
        with np.errstate(all="ignore"):  # (times too close overflow: named below)
            v = np.gradient(d, t, edge_order=2)
    elif law == ElasticPlastic.TYPE:  # rate-independent: the rate is not needed
        v = np.zeros_like(d)
    else:
        raise InputError(Problem.MISSING_INPUT, "time_s", None,
                         what="time_s (sample times) or velocity_m_s: the damping needs the rate")
    contact = d > 0.0
    n_contact = int(contact.sum())
    if n_contact < MIN_SAMPLES_IN_CONTACT:
        raise InputError(Problem.TOO_FEW_IN_CONTACT, "displacement_m", f"array of {d.size}",
                         got=n_contact, expected=MIN_SAMPLES_IN_CONTACT)
    _check_test_scales(np.flatnonzero(contact), d, v, force, "velocity_m_s" if velocity_m_s is not None
                       else "time_s")
    d, v, force = d[contact], v[contact], force[contact]
    if law == KelvinVoigt.TYPE:
        k, c, _ = nnls_fit(d, v, force)
        fitted: ContactLaw = KelvinVoigt(max(k, MIN_STIFFNESS), c)
    elif law == MultilinearBumper.TYPE:
        kinematic = hysteresis == "kinematic"
        if breakpoints is None:
            b = np.empty(0) if n_branches == 1 else multilinear_search(d, v, force, n_branches, kinematic)
        else:
            b = np.array(MultilinearBumper((1.0,) * (len(real_tuple("breakpoints", breakpoints)) + 1),
                                           breakpoints).breakpoints)  # (checked as the law checks them)
        slopes, c, _ = (kinematic_fit if kinematic else multilinear_fit)(d, v, force, b)
        slopes[0] = max(slopes[0], MIN_STIFFNESS)
        fitted = MultilinearBumper(tuple(slopes), tuple(b), c, hysteresis)
    elif law == ElasticPlastic.TYPE:
        fitted = ElasticPlastic(*elastic_plastic_search(d, force))
    else:
        lo, hi = _exponent_bounds(exponent_bounds)
        from scipy.optimize import minimize_scalar

        best = minimize_scalar(lambda n: nnls_fit(d, v, force, n, law)[2], bounds=(lo, hi), method="bounded",
                               options={"xatol": 1e-10})
        k, c, _ = nnls_fit(d, v, force, best.x, law)
        k = max(k, MIN_STIFFNESS)
        if law == Jankowski.TYPE:
            fitted = Jankowski(k, c / (2.0 * np.sqrt(effective_mass_kg * k)), effective_mass_kg,
                               float(best.x))
        else:
            fitted = HuntCrossley(k, float(best.x), c)
    if _stiffness(fitted) <= MIN_STIFFNESS:  # (the least squares' floor: no force grows with compression)
        raise InputError(Problem.NO_FIT, "force_n", "the forces given",
                         why=f"fit no {law} law (no stiffness makes their force grow with the compression)",
                         fix="give the force the bumper pushes with, positive in compression, in N")
    resid = force - law_force(fitted, d, v)
    rms = float(np.sqrt(np.mean(resid**2)))
    var = float(np.var(force))
    r2 = 1.0 - rms**2 / var if var > 0.0 else 1.0
    return ContactLawFit(fitted, rms, r2, d, v, force)


def _exponent_bounds(bounds: Any) -> tuple[float, float]:
    """``(low, high)``, 1 <= low < high <= the laws' largest exponent."""
    if bounds is None or isinstance(bounds, (str, bytes, dict)) or np.ndim(bounds) != 1:
        raise InputError(Problem.WRONG_TYPE, "exponent_bounds", bounds, got=type(bounds).__name__,
                         expected="pair of numbers (low, high), e.g. (1.0, 3.0)")
    values = real_tuple("exponent_bounds", bounds)
    if len(values) != 2:
        raise InputError(Problem.LENGTH_MISMATCH, "exponent_bounds", list(values), got=len(values),
                         expected=2, hint=" (low, high), e.g. (1.0, 3.0)")
    lo, hi = values
    if lo < 1.0:
        raise InputError(Problem.TOO_SMALL, "exponent_bounds[0]", lo, minimum=1, hint=" (1: linear contact)")
    if hi > MAX_EXPONENT:
        raise InputError(Problem.TOO_LARGE, "exponent_bounds[1]", hi, maximum=MAX_EXPONENT, what="",
                         fix=f"give at most {MAX_EXPONENT:g}, the contact laws' largest exponent")
    if hi <= lo:
        raise InputError(Problem.NOT_INCREASING, "exponent_bounds", list(values))
    return lo, hi


def _check_test_scales(idx: np.ndarray, d: np.ndarray, v: np.ndarray, force: np.ndarray,
                       rate_field: str) -> None:
    """The samples ``idx`` (those in compression) in the units a bumper test has: the least squares
    square them, so compressions of 1e300 m overflowed and of 1e-300 m gave stiffnesses of 1e304 N/m."""
    d, v, force = d[idx], v[idx], force[idx]
    i = int(np.argmax(d))
    at_most(f"displacement_m[{idx[i]}]", float(d[i]), MAX_COMPRESSION_M, " m", "give the compression in m")
    at_least(f"displacement_m[{idx[i]}]", float(d[i]), MIN_COMPRESSION_M, " m",
             "the largest compression; give the compression in m: 2 mm is 0.002")
    plausible(f"displacement_m[{idx[i]}]", float(d[i]), 0.0, 1.0, "the compression is in m: 10 mm is 0.01")
    i = int(np.argmax(np.abs(force)))
    at_most(f"force_n[{idx[i]}]", float(force[i]), MAX_FORCE_N, " N", "give the force in N")
    if not np.all(np.isfinite(v)) or np.max(np.abs(v)) > MAX_RATE_M_S:
        i = int(np.argmax(np.where(np.isfinite(v), np.abs(v), np.inf)))
        rate = f"of {v[i]:.3g} m/s" if np.isfinite(v[i]) else "that overflows"
        raise InputError(Problem.TOO_LARGE, rate_field, f"a compression rate {rate} at sample {idx[i]}",
                         maximum=MAX_RATE_M_S, what=" m/s",
                         fix="give the times in s (samples this close make the rate overflow)"
                         if rate_field == "time_s" else "give the compression rate in m/s")


def _stiffness(law: ContactLaw) -> float:
    return float(law.slopes[0]) if isinstance(law, MultilinearBumper) else float(law.stiffness)


def _same_length(field: str, arr: np.ndarray, ref: np.ndarray) -> None:
    if arr.size != ref.size:
        raise InputError(Problem.SIZE_MISMATCH, field, f"array of {arr.size}", got=arr.size,
                         expected=ref.size, other="displacement_m")


@fill_doc
def rank_contact_laws(displacement_m: Any, force_n: Any, *, time_s: Any = None, velocity_m_s: Any = None,
                      effective_mass_kg: float | None = None, n_branches: int = 3) -> pd.DataFrame:
    """Fit every contact law to one test and rank them by residual (the paper's Fig. 3 question:
    which law describes the bumper).

    Arguments as :func:`fit_contact_law`; Jankowski's law is fitted only with
    ``effective_mass_kg``, and Hertzdamp never (its damping is each impact's).  Laws whose residuals agree to
    1e-6 are ranked by their number of
    parameters (fewer first: a multi-linear law with equal slopes is Kelvin-Voigt).

    Parameters
    ----------
    {bumper_history}
    effective_mass_kg : float, optional
        Jankowski's effective mass, kg: without it Jankowski's law is left out.
    n_branches : int
        Branches of the multi-linear laws (1 to 4; default 3).  Their breakpoints are searched:
        the more branches, the longer the search.

    Returns
    -------
    DataFrame
        One row per law, best first: ``law`` (its type; ``"multilinear_kinematic"`` for the
        multi-linear law with kinematic hysteresis), ``rms_n``, ``r_squared``,
        ``parameters`` (their count) and ``fit`` (the :class:`ContactLawFit`).

    Examples
    --------
    Which law describes a bumper that stiffens as it is compressed (a 1 Hz test, 0 to 4 mm)?

    >>> import pounding
    >>> import numpy as np
    >>> t = np.linspace(0.0, 2.0, 401)                   # s
    >>> d = 0.002 * (1.0 - np.cos(2.0 * np.pi * t))       # m: compression
    >>> v = 0.004 * np.pi * np.sin(2.0 * np.pi * t)       # m/s: its rate
    >>> ranking = pounding.rank_contact_laws(d, 3e7 * d**1.5 * (1.0 + 0.5 * v),
    ...                                      velocity_m_s=v, n_branches=2)
    >>> # the best
    >>> ranking.loc[0, "law"], round(ranking.loc[0, "fit"].law.exponent, 3)
    ('hunt_crossley', 1.5)
    >>> # the worst
    >>> ranking["law"].iloc[-1], round(float(ranking["r_squared"].iloc[-1]), 2)
    ('kelvin_voigt', 0.96)
    """
    counts = {KelvinVoigt.TYPE: 2, HuntCrossley.TYPE: 3, Jankowski.TYPE: 3, ElasticPlastic.TYPE: 3,
              MultilinearBumper.TYPE: 2 * integer("n_branches", n_branches, 1, MAX_BRANCHES)}
    counts[KINEMATIC_ROW] = counts[MultilinearBumper.TYPE]
    rows = []
    for name in [*LAWS, KINEMATIC_ROW]:
        if (name == Jankowski.TYPE and effective_mass_kg is None) or name in UNFITTED:
            continue
        law, hysteresis = (MultilinearBumper.TYPE, "kinematic") if name == KINEMATIC_ROW else (name,
                                                                                               "elastic")
        try:
            fit = fit_contact_law(displacement_m, force_n, time_s=time_s, velocity_m_s=velocity_m_s, law=law,
                                  effective_mass_kg=effective_mass_kg, n_branches=n_branches,
                                  hysteresis=hysteresis)
        except InputError as exc:
            if exc.problem is not Problem.NO_FIT:
                raise
            continue  # (a law that cannot describe the test at all is left out of the ranking)
        rows.append({"law": name, "rms_n": fit.rms_n, "r_squared": fit.r_squared, "parameters": counts[name],
                     "fit": fit})
    if not rows:
        raise InputError(Problem.NO_FIT, "force_n", "the forces given",
                         why="fit none of the contact laws (no stiffness makes their force grow with the "
                             "compression)",
                         fix="give the force the bumper pushes with, positive in compression, in N")
    df = pd.DataFrame(rows)
    # ties (residuals within 1e-6 of each other, e.g. a multi-linear law with and without hysteresis on a
    # test it loads once) rank by fewer parameters, then in the order above: never by rounding noise
    rms = df["rms_n"].to_numpy()
    order = np.argsort(rms, kind="stable")
    tied = rms.copy()
    for prev, cur in zip(order[:-1], order[1:]):
        if rms[cur] <= tied[prev] * (1.0 + 1e-6) + 1e-300:
            tied[cur] = tied[prev]
    df["_rms"] = tied
    return df.sort_values(["_rms", "parameters"], kind="stable").drop(columns="_rms").reset_index(drop=True)
