"""Contacts in a recording's measured window (issue 17): Tables 3 and 4 from time histories.

The method (the paper's Sect. 3.5 screened the records by hand for the same instants):

- **Where**: the (Savitzky-Golay smoothed) displacement beyond the gap, ``D > Delta / 2``
  (right) or ``D < -Delta / 2`` (left), symmetric gaps about the laser's zero.  Noise makes a
  grazing mass cross the gap several times: crossings less than :data:`MERGE_S` apart are one,
  and one that never goes deeper than the displacement's noise (the standard deviation of the
  raw less the smoothed displacement) is not counted: it cannot be told from noise.
- **Confirmed by the acceleration**: a crossing is a contact only where the bumper force (below)
  rises above :data:`CONFIRM_SIGMA` times its noise in free flight (the robust spread, 1.4826
  MAD, of the force the isolator fit leaves unexplained there).  Crossings without such a
  pulse are not contacts: the laser's zero is off centre, or the gap given is smaller than the
  rig's; they are counted apart (``unconfirmed``) so that the analysis says so.
- **When**: the force pulse's own start and end, not the gap crossings (a bumper with a set, as
  a hysteretic one, is touched beyond the gap and left before the mass crosses back: the
  crossings made the calibrated preset's 20 ms contacts 12 ms longer).  The pulse is followed
  down its flanks to :data:`EDGE_SIGMA` noise deviations (or :data:`EDGE_FLOOR` of its peak),
  and each flank's lower half, fitted by a straight line (least squares), is extrapolated to
  zero force (``_zero_edge``).
- **Velocities** ``v_i`` and ``v_o``: from the free flight before the start and after the end
  (up to :data:`FLIGHT_FIT_S`, not into another contact), the raw displacement fitted by least
  squares as ``d_0 + v_0 tau + b tau^2 / 2 + P(tau)``, where ``P`` is the double integral of the
  measured relative acceleration ``a_abs - A`` from the contact instant (so the fit follows the
  isolator's varying force over a long window; ``b`` takes an accelerometer's offset):
  ``v_0`` is the velocity there.  ``b`` is one number for the window (an offset does not change
  from flight to flight): each flight is fitted with its own first, then all again with the
  median of theirs (a ``b`` per flight costs the slope about four times its noise: restitution
  errors up to 0.037 at a_G 0.05 and 1 % noise fell to 0.029 and below).
- **Bumper force**: ``M a_abs = -F_iso - F_b``; the isolator's force is fitted as
  ``k D + c V + r`` to the window's free-flight samples (``V`` the derivative of the smoothed
  displacement), and ``F_b = -M a_abs - F_iso`` during the contact: the impulse is its integral
  (trapezoids of the unsmoothed acceleration, from zero at the start to zero at the end), the mean
  force the impulse over the contact time, the peak the smoothed force's largest value.  The
  isolator's force beyond the gap is extrapolated from the flight (the lab cannot see it apart
  from the bumper's): with the presets' multi-linear isolator, whose slope halves at 15 mm, the
  impulse comes out 1.5 % low.
- **Dissipated energy** ``E_d = M (v_i^2 - v_o^2) / 2`` and restitution ``s = -v_o / v_i``, as
  the simulator reports them.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

FLIGHT_FIT_S = 0.15  # the free flight fitted before a contact and after it, s
MERGE_S = 0.010  # gap crossings closer than this are one contact, s
MIN_FLIGHT_S = 0.010  # a velocity needs at least this much free flight beside the contact, s
CONFIRM_SIGMA = 5.0  # a contact's bumper force pulse rises above this many noise standard deviations
EDGE_SIGMA = 2.0  # its flanks are followed down to this many
EDGE_FLOOR = 0.02  # or to this fraction of its peak, whichever is higher
LASER_FLIGHT_S = 0.040  # laser timing: the free flight a velocity is fitted on, s
LASER_FIT_DEGREE = 3  # laser timing: the degree of the polynomial fitted there
IMPACT_COLUMNS = ("side", "t_start_s", "t_end_s", "contact_time_s", "v_in_m_s", "v_out_m_s", "restitution",
                  "impulse_n_s", "mean_force_n", "peak_force_n", "dissipated_energy_j")


def _flight(free: np.ndarray, i: int, step: int) -> np.ndarray:
    """The run of free samples from ``i`` going by ``step`` (-1 back, +1 on), as a mask."""
    out = np.zeros(free.size, dtype=bool)
    while 0 <= i < free.size and free[i]:  # (bounded by the window)
        out[i] = True
        i += step
    return out


def _free_near(free: np.ndarray, i: int, step: int, within: int) -> int:
    """The first free sample from ``i`` going by ``step``, at most ``within`` samples on (else ``i``)."""
    for k in range(within + 1):
        j = i + k * step
        if not 0 <= j < free.size:
            break
        if free[j]:
            return j
    return i


def _crossing(t: np.ndarray, y: np.ndarray, i: int) -> float:
    """Where ``y`` crosses zero between samples ``i - 1`` and ``i``, by linear interpolation."""
    return float(t[i - 1] + (t[i] - t[i - 1]) * (-y[i - 1]) / (y[i] - y[i - 1]))


def _velocity_at(t: np.ndarray, d: np.ndarray, a_rel: np.ndarray, mask: np.ndarray, at: float,
                 b: float | None = None) -> tuple[float, float]:
    """The velocity at ``at`` from ``d[mask]`` (one run of samples on one side of ``at``): the fit
    ``d_0 + v_0 tau + b tau^2 / 2 + P(tau)`` of the module's method, with ``b`` fitted too unless
    given: (velocity, b) (NaN with less than :data:`MIN_FLIGHT_S` of flight)."""
    from scipy import integrate

    idx = np.flatnonzero(mask & np.isfinite(d))
    if idx.size < 4 or t[idx[-1]] - t[idx[0]] < MIN_FLIGHT_S:
        return float("nan"), float("nan")
    tt = t[idx[0]:idx[-1] + 1]
    v_int = integrate.cumulative_trapezoid(a_rel[idx[0]:idx[-1] + 1], tt, initial=0.0)
    p_int = integrate.cumulative_trapezoid(v_int, tt, initial=0.0)
    # P relative to the contact instant: P(at) = 0, P'(at) = 0 (at is an end of the run, or just past it)
    end = 0 if abs(tt[0] - at) < abs(tt[-1] - at) else -1
    tau = tt - at
    p_rel = p_int - p_int[end] - v_int[end] * (tt - tt[end])
    sel = idx - idx[0]
    y = d[idx] - p_rel[sel]
    if b is None:
        design = np.column_stack([np.ones(idx.size), tau[sel], 0.5 * tau[sel] ** 2])
        coef = np.linalg.lstsq(design, y, rcond=None)[0]
    else:
        coef = np.linalg.lstsq(np.column_stack([np.ones(idx.size), tau[sel]]), y - 0.5 * b * tau[sel] ** 2,
                               rcond=None)[0]
        coef = np.append(coef, b)
    # the fit's slope at tau = 0: v_0 plus P' there (P' is 0 at the run's end sample, which lies
    # a fraction of a sample from the contact instant; the flight's acceleration carries it on)
    return float(coef[1] + a_rel[idx[0]:idx[-1] + 1][end] * (at - tt[end])), float(coef[2])


def _zero_edge(t: np.ndarray, c: np.ndarray, edge: int, step: int, half: float) -> float:
    """Where the pulse ``c`` starts (``step = +1``) or ends (``step = -1``): ``edge`` its first (last)
    sample above the edge level.  A straight line fitted (least squares) to the pulse's flank, from
    ``edge`` inwards while below ``half`` its peak, extrapolated to zero: exact for a force rising
    linearly from the touch, nearly so for a half-sine's first half; with a single sample on the
    flank (a steep jump), the line from the sample outside.  Kept within two samples outside ``edge``."""
    idx = [edge]
    while 0 <= idx[-1] + step < c.size and c[idx[-1] + step] <= half and len(idx) < c.size:
        idx.append(idx[-1] + step)
    if len(idx) < 2:
        idx = [edge - step, edge]
    tt, cc = t[idx], c[idx]
    slope, icpt = np.polyfit(tt - t[edge], cc, 1)
    at = t[edge] - icpt / slope if slope * step > 0.0 else t[edge]
    outside = t[min(max(edge - 2 * step, 0), t.size - 1)]
    lo, hi = sorted((outside, t[edge]))
    return float(min(max(at, lo), hi))


def _gap_intervals(d: np.ndarray, half_gap_m: float, merge: int,
                   noise: float) -> tuple[np.ndarray, list[tuple[str, float, int, int]]]:
    """Where the displacement ``d`` is beyond the gap (a mask: contacts cut by the stretch's ends too,
    which have no free flight), and the crossings deeper than ``noise``, those less than ``merge``
    samples apart one: ``(side, sign, a, b)``, ``d`` beyond the gap from sample ``a`` to ``b - 1``."""
    in_contact = np.zeros(d.size, dtype=bool)
    intervals = []
    for side, sign in (("left", -1.0), ("right", 1.0)):
        y = sign * d - half_gap_m  # > 0 beyond the gap
        in_contact |= y > 0.0  # (contacts cut by the stretch's ends too: no free flight)
        edges = np.diff((y > 0.0).astype(np.int8))
        starts, ends = np.flatnonzero(edges == 1) + 1, np.flatnonzero(edges == -1) + 1
        merged: list[list[int]] = []
        for a in starts:  # (a contact cut by the window's start or end is not measured)
            later = ends[ends > a]
            if later.size == 0:
                break
            if merged and a - merged[-1][1] < merge:
                merged[-1][1] = int(later[0])
            else:
                merged.append([int(a), int(later[0])])
        for a, b in merged:
            in_contact[a:b] = True
            if y[a:b].max() > noise:  # (deeper than the noise: a contact, not a flicker)
                intervals.append((side, sign, a, b))
    return in_contact, intervals


def _laser_velocity(t: np.ndarray, d: np.ndarray, mask: np.ndarray, at: float) -> float:
    """The velocity at ``at`` from the laser alone: the slope there of a least-squares polynomial of
    degree :data:`LASER_FIT_DEGREE` through ``d[mask]`` (a run of free flight next to ``at``), NaN
    with less than :data:`MIN_FLIGHT_S` of it or too few samples."""
    idx = np.flatnonzero(mask & np.isfinite(d))
    if idx.size < LASER_FIT_DEGREE + 2 or t[idx[-1]] - t[idx[0]] < MIN_FLIGHT_S:
        return float("nan")
    tau = t[idx] - at
    scale = float(np.abs(tau).max())  # (tau / scale within [-1, 1]: a well-conditioned fit)
    coef = np.polynomial.polynomial.polyfit(tau / scale, d[idx], LASER_FIT_DEGREE)
    return float(coef[1] / scale)


def _laser_contacts(t: np.ndarray, d_raw: np.ndarray, f_b: np.ndarray, f_raw: np.ndarray, free: np.ndarray,
                    intervals: list, half_gap_m: float, level: float, merge: int, mass_kg: float, fs: float,
                    starts_in: tuple[float, float]) -> tuple[pd.DataFrame, int]:
    """:func:`window_contacts` timed by the laser: each contact from the gap crossing in to the gap
    crossing out of the recorded displacement (linearly between its samples), the velocities from the
    laser alone there (:func:`_laser_velocity` over up to :data:`LASER_FLIGHT_S` of free flight), the
    impulse the bumper force ``f_raw``'s integral between the crossings, the peak the smoothed ``f_b``'s
    largest value where the pulse is looked for. A crossing without a force pulse above ``level`` is a
    contact still (the laser is the witness) and is counted too."""
    from scipy import integrate

    rows, unconfirmed = [], 0
    for side, sign, a, b in intervals:
        y = sign * d_raw - half_gap_m
        t0, t1 = _crossing(t, y, a), _crossing(t, y, b)
        # (shorter than a sample: not measured)
        if not starts_in[0] <= t0 < starts_in[1] or t1 - t0 < 1.0 / fs:
            continue
        c = sign * f_raw  # compressive force, > 0
        lo, hi = max(a - merge, 1), min(b + merge, t.size - 1)
        if c[lo:hi].max() <= level:  # (no pulse in the accelerations: counted, and a contact still)
            unconfirmed += 1
        inside = np.arange(a, b)
        c0, c1 = (float(np.interp(x, t[i - 1:i + 1], c[i - 1:i + 1])) for x, i in ((t0, a), (t1, b)))
        impulse = float(integrate.trapezoid(np.concatenate([[c0], c[inside], [c1]]),
                                            np.concatenate([[t0], t[inside], [t1]])))
        before = _flight(free, a - 1, -1) & (t >= t0 - LASER_FLIGHT_S)
        after = _flight(free, b, 1) & (t <= t1 + LASER_FLIGHT_S)
        rows.append({"side": side, "t_start_s": t0, "t_end_s": t1, "contact_time_s": t1 - t0,
                     "v_in_m_s": _laser_velocity(t, d_raw, before, t0),
                     "v_out_m_s": _laser_velocity(t, d_raw, after, t1), "impulse_n_s": impulse,
                     "peak_force_n": float((sign * f_b[lo:hi]).max())})
    return _finish(rows, mass_kg), unconfirmed


def _finish(rows: list[dict], mass_kg: float) -> pd.DataFrame:
    """The contacts' table from their rows: mean force, restitution and dissipated energy added."""
    out = pd.DataFrame(rows)
    if out.empty:
        return pd.DataFrame(columns=list(IMPACT_COLUMNS))
    out["mean_force_n"] = out["impulse_n_s"] / out["contact_time_s"]
    out["restitution"] = -out["v_out_m_s"] / out["v_in_m_s"]
    out["dissipated_energy_j"] = 0.5 * mass_kg * (out["v_in_m_s"] ** 2 - out["v_out_m_s"] ** 2)
    return out[list(IMPACT_COLUMNS)].sort_values("t_start_s").reset_index(drop=True)


def window_contacts(t: np.ndarray, d_raw: np.ndarray, d: np.ndarray, a_abs: np.ndarray, a_raw: np.ndarray,
                    a_table: np.ndarray, mass_kg: float, half_gap_m: float, fs: float,
                    starts_in: tuple[float, float], timing: str = "pulse") -> tuple[pd.DataFrame, int]:
    """The contacts that start in ``starts_in = (t_from, t_to)``: one row each, :data:`IMPACT_COLUMNS`,
    and how many gap crossings there had no bumper force pulse (not counted with ``timing="pulse"``,
    counted with ``"laser"``: see the module).

    The arrays are the samples of a stretch around the window (its free flight on either side
    gives the first and last contacts their velocities): ``d_raw`` the recorded displacement,
    ``d`` its smoothed version, ``a_abs`` the mass's smoothed absolute acceleration and ``a_raw`` the
    same unsmoothed, ``a_table`` the table's.
    """
    from scipy import integrate, signal

    n = max(5, 2 * round(0.005 * fs) + 1)
    v = signal.savgol_filter(d, n, 3, deriv=1, delta=1.0 / fs) if d.size > n else np.gradient(d, t)
    noise = float(np.nanstd(d_raw - d))
    merge = max(1, round(MERGE_S * fs))
    # (the laser's timing reads its own samples; the pulse's finds the crossings on the smoothed ones)
    in_contact, intervals = _gap_intervals(d_raw if timing == "laser" else d, half_gap_m, merge, noise)
    free = ~in_contact
    if not intervals:
        return pd.DataFrame(columns=list(IMPACT_COLUMNS)), 0
    # the isolator's force from free flight: M a_abs = -(k D + c V + r); the bumpers' force on the
    # mass is what is left: F_b = -M a_abs - F_iso (smoothed for its peak, raw for times and impulse)
    design = np.column_stack([d[free], v[free], np.ones(int(free.sum()))])
    coef = np.linalg.lstsq(design, -mass_kg * a_abs[free], rcond=None)[0] if free.sum() >= 3 else np.zeros(3)
    iso = coef[0] * d + coef[1] * v + coef[2]
    f_b, f_raw = -mass_kg * a_abs - iso, -mass_kg * a_raw - iso
    force_noise = (1.4826 * float(np.median(np.abs(f_raw[free] - np.median(f_raw[free])))) if free.any()
                   else 0.0)
    level = CONFIRM_SIGMA * force_noise
    if timing == "laser":
        return _laser_contacts(t, d_raw, f_b, f_raw, free, intervals, half_gap_m, level, merge, mass_kg, fs,
                               starts_in)
    # the contacts: the force pulse at each gap crossing, from the zero before it to the zero after it
    not_free = in_contact.copy()  # (a flight ends at the gap or at the force, whichever comes first)
    rows, unconfirmed = [], 0
    for side, sign, a, b in intervals:
        c = sign * f_raw  # compressive force, > 0
        lo, hi = max(a - merge, 1), min(b + merge, t.size - 1)
        k = lo + int(np.argmax(c[lo:hi]))
        if c[k] <= level:  # (no pulse: not a contact)
            if starts_in[0] <= t[a] < starts_in[1]:
                unconfirmed += 1
            continue
        j0, j1 = k, k
        # the flanks followed down to the edge level: less bias than the detection level (and no
        # lower than EDGE_FLOOR of the peak, where the isolator fit's misfit, not noise, rules)
        edge_level = max(EDGE_SIGMA * force_noise, EDGE_FLOOR * c[k])
        while j0 > 1 and c[j0 - 1] > edge_level:  # (bounded by the stretch)
            j0 -= 1
        while j1 < t.size - 2 and c[j1 + 1] > edge_level:
            j1 += 1
        not_free[j0:j1 + 1] = True
        t0, t1 = _zero_edge(t, c, j0, 1, 0.5 * c[k]), _zero_edge(t, c, j1, -1, 0.5 * c[k])
        # (shorter than a sample: not measured)
        if not starts_in[0] <= t0 < starts_in[1] or t1 - t0 < 1.0 / fs:
            continue
        tt = np.concatenate([[t0], t[j0:j1 + 1], [t1]])
        impulse = float(integrate.trapezoid(np.concatenate([[0.0], c[j0:j1 + 1], [0.0]]), tt))
        rows.append({"side": side, "t_start_s": t0, "t_end_s": t1, "contact_time_s": t1 - t0, "j0": j0,
                     "j1": j1, "impulse_n_s": impulse, "peak_force_n": float((sign * f_b[j0:j1 + 1]).max())})
    free = ~not_free
    for r in rows:  # (the flights end where the mass crossed the gap, if before the force)
        r["before"] = _flight(free, _free_near(free, r["j0"] - 1, -1, merge),
                              -1) & (t >= r["t_start_s"] - FLIGHT_FIT_S)
        r["after"] = _flight(free, _free_near(free, r["j1"] + 1, 1, merge),
                             1) & (t <= r["t_end_s"] + FLIGHT_FIT_S)
    # the velocities: each flight's b first, then every flight again with their median (b is an
    # accelerometer's offset: one for the stretch; fitting it per flight costs the slope 4x its noise)
    a_rel = a_abs - a_table
    bs = [_velocity_at(t, d_raw, a_rel, r[k], r[at])[1] for r in rows
          for k, at in (("before", "t_start_s"), ("after", "t_end_s"))]
    b_all = float(np.nanmedian(bs)) if np.isfinite(bs).any() else None
    for r in rows:
        r["v_in_m_s"] = _velocity_at(t, d_raw, a_rel, r.pop("before"), r["t_start_s"], b_all)[0]
        r["v_out_m_s"] = _velocity_at(t, d_raw, a_rel, r.pop("after"), r["t_end_s"], b_all)[0]
    return _finish(rows, mass_kg), unconfirmed
