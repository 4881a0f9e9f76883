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

from .._checks import float_array, one_of, positive, real
from .._errors import InputError, Problem
from ..model.contact_laws import LAWS, ContactLaw, HuntCrossley, Jankowski, KelvinVoigt, law_force_many

MIN_SAMPLES_IN_CONTACT = 3


@dataclass(frozen=True, eq=False)
class ContactLawFit:
    """A contact law fitted to a force-displacement test.

    Attributes
    ----------
    law : KelvinVoigt, HuntCrossley or Jankowski
        The fitted law, ready for :class:`pounding.Bumpers`.
    rms_n : float
        Root-mean-square residual force, N, over the samples in compression.
    r_squared : float
        Share of the force variance the law explains.
    compression_m, velocity_m_s, force_n : ndarray, shape (n,)
        The samples in compression that were fitted.
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
        return _force(self.law, d, v)

    def to_dataframe(self) -> pd.DataFrame:
        """One row per fitted sample: compression, rate, measured and fitted force, residual."""
        model = _force(self.law, self.compression_m, self.velocity_m_s)
        return pd.DataFrame({"compression_m": self.compression_m, "velocity_m_s": self.velocity_m_s,
                             "force_n": self.force_n, "model_force_n": model,
                             "residual_n": self.force_n - model})

    def plot(self, ax=None):
        """Measured and fitted force against compression; returns the artists."""
        from ..plots.contact_law import plot_contact_law_fit

        return plot_contact_law_fit(self, ax=ax)


def _force(law: ContactLaw, d: np.ndarray, v: np.ndarray) -> np.ndarray:
    out = np.empty(d.size)
    law_force_many(law.LAW_ID, law.params(), np.ascontiguousarray(d), np.ascontiguousarray(v), out)
    return out


def _nnls_fit(d, v, force, exponent=None, law=HuntCrossley.TYPE):
    """Non-negative (stiffness, damping) and the residual norm: ``F = k d + c v`` (Kelvin-Voigt,
    ``exponent`` None), ``F = d^n (k + c v)`` (Hunt-Crossley) or ``F = k d^n + c d^((n-1)/2) v``
    while ``v > 0`` (Jankowski)."""
    if exponent is None:
        cols = np.column_stack([d, v])
    elif law == Jankowski.TYPE:
        cols = np.column_stack([d**exponent, d ** (0.5 * (exponent - 1.0)) * np.maximum(v, 0.0)])
    else:
        dn = d**exponent
        cols = np.column_stack([dn, dn * v])
    scale = np.linalg.norm(cols, axis=0)
    scale[scale == 0.0] = 1.0  # columns of very different sizes: solve the scaled problem
    from scipy.optimize import nnls  # here: scipy.optimize costs 0.3 s of `import pounding`

    (k, c), resid = nnls(cols / scale, force)
    return k / scale[0], c / scale[1], resid


def fit_contact_law(
    displacement_m: Any,
    force_n: Any,
    *,
    time_s: Any = None,
    velocity_m_s: Any = None,
    law: str = KelvinVoigt.TYPE,
    exponent_bounds: tuple[float, float] = (1.0, 3.0),
    effective_mass_kg: float | None = None,
) -> ContactLawFit:
    """Fit a bumper law to a measured force-displacement history.

    Parameters
    ----------
    displacement_m : array_like, shape (n,)
        Compression of the bumper, m (> 0 in contact; samples <= 0 are left out).
    force_n : array_like, shape (n,)
        Force the bumper pushes with, N.
    time_s : array_like, shape (n,), optional
        Sample times, s, strictly increasing: the compression rate is their numerical
        derivative (second order).  Give this or ``velocity_m_s``.
    velocity_m_s : array_like, shape (n,), optional
        Compression rate, m/s, when it was measured.
    law : {"kelvin_voigt", "hunt_crossley", "jankowski"}
        ``F = k d + c v``, ``F = d^n (k + c v)`` or ``F = k d^n + 2 xi sqrt(m k d^(n-1)) v``
        while ``v > 0`` (``k d^n`` while ``v <= 0``).
    exponent_bounds : (float, float)
        Search range of the exponent ``n`` (>= 1) of Hunt-Crossley and Jankowski.
    effective_mass_kg : float, optional
        Jankowski's effective mass, kg (the impacting mass ``M``): required for that law, whose
        damping ratio is the fitted dashpot factor over ``2 sqrt(m k)``.

    Returns
    -------
    ContactLawFit
    """
    one_of("law", law, LAWS)
    if law == Jankowski.TYPE:
        if effective_mass_kg is None:
            raise InputError(Problem.MISSING_INPUT, "effective_mass_kg", None,
                             what="effective_mass_kg (kg, the impacting mass): Jankowski's damping ratio needs it")
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
            raise InputError(Problem.NOT_INCREASING, f"time_s[{i - 1}:{i + 1}]", [float(t[i - 1]), float(t[i])])
        v = np.gradient(d, t, edge_order=2)
    else:
        raise InputError(Problem.MISSING_INPUT, "time_s", None,
                         what="time_s (sample times) or velocity_m_s: the damping needs the rate")
    contact = d > 0.0
    n_contact = int(contact.sum())
    if n_contact < MIN_SAMPLES_IN_CONTACT:
        raise InputError(Problem.TOO_FEW_IN_CONTACT, "displacement_m", f"array of {d.size}",
                         got=n_contact, expected=MIN_SAMPLES_IN_CONTACT)
    d, v, force = d[contact], v[contact], force[contact]
    if law == KelvinVoigt.TYPE:
        k, c, _ = _nnls_fit(d, v, force)
        fitted: ContactLaw = KelvinVoigt(max(k, np.finfo(float).tiny), c)
    else:
        lo = real("exponent_bounds[0]", exponent_bounds[0])
        hi = real("exponent_bounds[1]", exponent_bounds[1])
        if lo < 1.0:
            raise InputError(Problem.TOO_SMALL, "exponent_bounds[0]", lo, minimum=1, hint=" (1: linear contact)")
        if hi <= lo:
            raise InputError(Problem.NOT_INCREASING, "exponent_bounds", list(exponent_bounds))
        from scipy.optimize import minimize_scalar

        best = minimize_scalar(lambda n: _nnls_fit(d, v, force, n, law)[2], bounds=(lo, hi), method="bounded",
                               options={"xatol": 1e-10})
        k, c, _ = _nnls_fit(d, v, force, best.x, law)
        k = max(k, np.finfo(float).tiny)
        if law == Jankowski.TYPE:
            fitted = Jankowski(k, c / (2.0 * np.sqrt(effective_mass_kg * k)), effective_mass_kg, float(best.x))
        else:
            fitted = HuntCrossley(k, float(best.x), c)
    resid = force - _force(fitted, d, v)
    rms = float(np.sqrt(np.mean(resid**2)))
    var = float(np.var(force))
    r2 = 1.0 - rms**2 / var if var > 0.0 else 1.0
    return ContactLawFit(fitted, rms, r2, d, v, force)


def _same_length(field: str, arr: np.ndarray, ref: np.ndarray) -> None:
    if arr.size != ref.size:
        raise InputError(Problem.SIZE_MISMATCH, field, f"array of {arr.size}", got=arr.size,
                         expected=ref.size, other="displacement_m")
