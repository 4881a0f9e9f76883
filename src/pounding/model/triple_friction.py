"""The triple friction pendulum: four concave sliding surfaces in one bearing, with exact stick and slip on
each and restraining rings (rigid or stiff), modelled as Fenz and Constantinou's series of single pendulums.

Its engine form is the isolator's element with the friction rule's surfaces in series (the core's
``RULE_FRICTION`` with ``surface_friction_n``, isolator.hpp): four springs ``W / R_i`` each in parallel with a
friction force ``mu_i W``, one after another without mass between them, each held at its ring once it gets
there (or, against a stiff ring, sliding on with the ring's stiffness added).  The series' radii and
capacities are the bearing's own, modified so that it retraces the bearing's five stages (Fenz and
Constantinou, 2008): the outer surfaces' radii less the inner ones' beside them, and the travels to the rings
measured as the series' elements move.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, ClassVar, Optional

import numpy as np

from .._checks import at_most, non_negative, plausible, positive, real_tuple
from .._errors import InputError, Problem
from .._units import GRAVITY_M_S2
from .friction import MAX_MU, RULE_FRICTION, CarriesWeight
from .isolator import BW_PARAMS, MAX_DAMPING_N_S_M, MAX_STIFFNESS_N_M

SURFACES = 4


def _four(field: str, values: Any, unit: str) -> tuple[float, ...]:
    out = real_tuple(field, values)
    if len(out) != SURFACES:
        raise InputError(Problem.WRONG_CONFIGURATION, field, values, got=f"{len(out)} numbers",
                         fix=f"give {SURFACES}, one for each surface (1 the bottom concave plate, 2 and 3 "
                             "the inner slider's lower and upper surfaces, 4 the top concave plate)")
    for i, v in enumerate(out):
        positive(f"{field}[{i}]", v, unit)
    return out


def slide(k: Any, f: Any, cap: Any, ring: float, to_m: float = math.inf) -> tuple:
    """A series of friction surfaces pushed slowly from rest, centred, to ``to_m`` (m; inf: as far as it
    goes): the surfaces slip in the order their thresholds come, each held at its rigid ring or sliding on
    against its stiff one (``ring``, N/m; 0: rigid).

    Parameters
    ----------
    k, f, cap : sequence of floats, each of length n
        Each surface's stiffness (N/m), friction (N) and travel to its ring (m).
    ring : float
        Each ring's stiffness, N/m (0: rigid).
    to_m : float
        Where the push stops, m (its sign the push's way).

    Returns
    -------
    us, fs : ndarray, shape (m,)
        The slide's vertices (m, N), from (0, 0), up to where it stops (a positive push's).
    last : float
        The stiffness past the last vertex, N/m (0: rigid rings, none past the travel).
    u_g : ndarray, shape (n,)
        Where each surface is when the push stops, m (signed as the push).
    state : ndarray, shape (n,)
        Each one's state there, held: 0, or +-2 at its rigid ring (the core's).
    """
    k, f, cap = (np.array(x, dtype=float) for x in (k, f, cap))
    n, way, reach = k.size, (-1.0 if to_m < 0.0 else 1.0), abs(to_m)
    ug, state = np.zeros(n), np.zeros(n)  # (0 held, 1 slipping, 2 at its rigid ring, 3 on its stiff one)
    us, fs = [0.0], [0.0]
    force, u = 0.0, 0.0
    for _ in range(3 * n):
        if not ((state == 1) | (state == 3) | (state == 0)).any() or u >= reach:
            break  # (every surface at its rigid ring: the travel; or the push's end)
        if not ((state == 1) | (state == 3)).any():  # (none slips on: the force jumps to the next one)
            force = max(force, float(np.where(state == 0, k * ug + f, np.inf).min()))
            us.append(u)
            fs.append(force)
        state[(state == 0) & (k * ug + f <= force * (1 + 1e-12))] = 1
        slipping = (state == 1) | (state == 3)
        stiffness = np.where(state == 3, k + ring, k)
        thresholds = np.where(state == 0, k * ug + f, np.inf)
        rings = np.where(state == 1, k * cap + f, np.inf)
        nxt = float(min(thresholds.min(), rings.min()))
        compliance = float(np.sum(1.0 / stiffness[slipping]))
        if u + (nxt - force) * compliance > reach:  # (the push ends inside this stage)
            nxt = force + (reach - u) / compliance
            ug[slipping] += (nxt - force) / stiffness[slipping]
            us.append(reach)
            fs.append(nxt)
            u, force = reach, nxt
            break
        if not math.isfinite(nxt):
            break  # (every surface slipping on its stiff ring: the last stage, without end)
        u += (nxt - force) * compliance
        ug[slipping] += (nxt - force) / stiffness[slipping]
        force = nxt
        reached = (state == 1) & (rings <= nxt * (1 + 1e-12))
        state[reached] = 3 if ring > 0.0 else 2
        ug[reached] = cap[reached]
        us.append(u)
        fs.append(force)
    slipping = (state == 1) | (state == 3)
    compliance = float(np.sum(1.0 / np.where(state == 3, k + ring, k)[slipping]))
    last = 1.0 / compliance if ring > 0.0 and compliance > 0.0 else 0.0  # (a push of 0: none slid)
    held = np.where(state == 2, 2.0, 0.0)  # (a slow push's end: every surface held where it is)
    return np.array(us), np.array(fs), last, way * ug, way * held


@dataclass(frozen=True)
class TripleFrictionPendulum(CarriesWeight):
    """A triple friction pendulum bearing (TFP): four spherical sliding surfaces, each with its friction
    and its restraining ring, whose stiffness and damping change with the amplitude (stages I to V).

    Surface 1 is the bottom concave plate's, 4 the top one's, 2 and 3 the inner slider's (lower and upper).
    The usual bearing has ``mu[1], mu[2] < mu[0] <= mu[3]`` and ``radii_m[0] = radii_m[3]`` much larger than
    ``radii_m[1] = radii_m[2]``.  Its stages follow from where each surface sticks or slips, found as
    events on the exact trajectory: I, sliding on 2 and 3 (stiffness ``W / (R2 + R3)``); II, on 1 and 3
    from ``mu_1 W``; III, on 1 and 4 from ``mu_4 W``; IV, 1 at its ring, on 2 and 4; V, 4 at its ring too,
    on 2 and 3 again (stiffening).  Where 2 and 3 reach theirs, the bearing's travel is used up: with rigid
    rings the run stops there with :attr:`Status.CAPACITY <pounding.Status>`; with stiff rings
    (``ring_stiffness_n_m``) each surface slides on against its ring, stiffer, and comes off it on the way
    back (the events ``ring`` and ``ring_off``).  The force on the base while it slips is
    linear in its displacement in every stage, so every phase is exact; while every surface sticks, the
    base is held.

    It is modelled as Fenz and Constantinou's (2008) series of four single pendulums, which retraces the
    bearing's five stages: radii ``(R1 - R2, R2, R3, R4 - R3)``, frictions ``mu``, and travels to the rings
    ``(d1 (R1 - R2) / R1, d2 + d1 R2 / R1, d3 + d4 R3 / R4, d4 (R4 - R3) / R4)`` (:attr:`series_radii_m`,
    :attr:`series_capacities_m`).  Outside ``max(mu2, mu3) < min(mu1, mu4)`` the stages come in another
    order, which the series does not retrace: refused.

    Parameters
    ----------
    radii_m : sequence of 4 floats
        Each surface's effective radius ``R_i - h_i``, m, > 0, with ``R1 > R2`` and ``R4 > R3``.
    mu : sequence of 4 floats
        Each surface's friction coefficient, > 0 and at most 1, with ``max(mu2, mu3) < min(mu1, mu4)``.
    capacities_m : sequence of 4 floats
        Each surface's displacement capacity ``d_i`` (its effective one, ``d_i (R_i - h_i) / R_i``), m, > 0:
        how far it slides before its ring stops it.
    damping_n_s_m : float
        A linear dashpot in parallel, N s/m, >= 0.
    weight_n : float, optional
        The weight it carries, N.  None: the system's weight, set when it is put into one (``weight_carried``
        then True).
    ring_stiffness_n_m : float, optional
        Each ring's stiffness, N/m, > 0: a surface past its travel (its series displacement beyond
        :attr:`series_capacities_m`) slides on with this stiffness added to its spring ``W / R``.  None: rigid
        rings.
    weight_carried : bool
        Whether ``weight_n`` is the system's (set by the system; not written to TOML).

    Examples
    --------
    A 4-level building on a TFP of the usual proportions, shaken at 0.25 g and 0.5 Hz: each half cycle
    slides on the inner surfaces from rest, then on 1 (stage II) and 4 (III), the surfaces' slips among
    the run's events (their index the surface's, from 0).

    >>> import pounding
    >>> tfp = pounding.TripleFrictionPendulum(radii_m=(2.1, 0.3, 0.3, 2.1),
    ...                                       mu=(0.05, 0.02, 0.02, 0.08),
    ...                                       capacities_m=(0.35, 0.05, 0.05, 0.35))
    >>> storeys = [pounding.Storey(30_000.0, 6.0e7, 1.0e5)] * 3
    >>> building = pounding.Structure(40_000.0, tfp, storeys, [])
    >>> round(building.isolator.travel_m, 3)  # m: every surface at its ring
    0.8
    >>> run = pounding.simulate(building, pounding.Harmonic(a_g=0.25, freq_hz=0.5),
    ...                         duration=8.0)
    >>> kinds = run.events["kind"].value_counts()
    >>> kinds[["slip", "surface_slip", "reversal"]].tolist()
    [1, 16, 7]
    >>> f"{run.summary()['displacement_max_m']:.3f} m"
    '0.629 m'
    """

    radii_m: tuple[float, ...]
    mu: tuple[float, ...]
    capacities_m: tuple[float, ...]
    damping_n_s_m: float = 0.0
    weight_n: Optional[float] = None
    weight_carried: bool = False
    ring_stiffness_n_m: Optional[float] = None

    FIELDS: ClassVar[tuple[str, ...]] = ("radii_m", "mu", "capacities_m", "damping_n_s_m", "weight_n",
                                         "ring_stiffness_n_m")
    OPTIONAL: ClassVar[tuple[str, ...]] = ("damping_n_s_m", "weight_n", "ring_stiffness_n_m")
    RENAMED: ClassVar[dict[str, str]] = {}
    bouc_wen: ClassVar[None] = None  # (no Bouc-Wen spring: what readers of any isolator ask)
    preslip_m: ClassVar[float] = 0.0  # (a rigid stick on every surface)
    mu_fast: ClassVar[None] = None  # (Coulomb's constant friction on every surface)
    rate_s_m: ClassVar[float] = 0.0

    def __post_init__(self) -> None:
        radii = _four("isolator.radii_m", self.radii_m, "m")
        mu = _four("isolator.mu", self.mu, "")
        caps = _four("isolator.capacities_m", self.capacities_m, "m")
        for i in range(SURFACES):
            at_most(f"isolator.radii_m[{i}]", radii[i], 1e4, " m", "give the radius in m")
            at_most(f"isolator.mu[{i}]", mu[i], MAX_MU, "", "give the friction coefficient (0.05 is 5 %)")
            at_most(f"isolator.capacities_m[{i}]", caps[i], 100.0, " m", "give the capacity in m")
            plausible(f"isolator.mu[{i}]", mu[i], 0.005, 0.3, "a sliding surface's friction coefficient "
                                                              "(usually 0.01 to 0.12)")
            plausible(f"isolator.capacities_m[{i}]", caps[i], 0.005, 2.0, "a surface's displacement "
                                                                          "capacity in m")
        for outer, inner in ((0, 1), (3, 2)):
            if not radii[outer] > radii[inner]:
                raise InputError(Problem.WRONG_CONFIGURATION, f"isolator.radii_m[{outer}]", radii[outer],
                                 got=f"not larger than the inner surface's beside it ({radii[inner]:g} m)",
                                 fix="give the outer concave plates' radii (surfaces 1 and 4) larger than "
                                     "the inner slider's (2 and 3), as a triple friction pendulum has them")
        if not max(mu[1], mu[2]) < min(mu[0], mu[3]):
            raise InputError(Problem.WRONG_CONFIGURATION, "isolator.mu", self.mu,
                             got="an inner surface's friction not below both outer ones'",
                             fix="give mu[1] and mu[2] (the inner slider's) below mu[0] and mu[3]: the "
                                 "series model retraces the bearing only in that order of stages")
        object.__setattr__(self, "radii_m", radii)
        object.__setattr__(self, "mu", mu)
        object.__setattr__(self, "capacities_m", caps)
        damping = non_negative("isolator.damping_n_s_m", self.damping_n_s_m, "N s/m")
        at_most("isolator.damping_n_s_m", damping, MAX_DAMPING_N_S_M, " N s/m", "give the damping in N s/m")
        object.__setattr__(self, "damping_n_s_m", damping)
        if self.ring_stiffness_n_m is not None:
            ring = positive("isolator.ring_stiffness_n_m", self.ring_stiffness_n_m,
                            "N/m (leave it out: rigid)")
            at_most("isolator.ring_stiffness_n_m", ring, MAX_STIFFNESS_N_M, " N/m",
                    "give the stiffness in N/m, or leave it out for rigid rings")
            object.__setattr__(self, "ring_stiffness_n_m", ring)
        weight = self._check_weight()
        if weight is not None:
            r_min = min(self.series_radii_m)
            if weight / r_min > MAX_STIFFNESS_N_M:
                raise InputError(Problem.TOO_SMALL, "isolator.radii_m", self.radii_m,
                                 minimum=weight / MAX_STIFFNESS_N_M,
                                 hint=f" m for each series radius under the weight {weight:g} N")

    # ---------------------------------------------------------------- its numbers

    @property
    def series_radii_m(self) -> tuple[float, ...]:
        """The series model's radii, m: ``(R1 - R2, R2, R3, R4 - R3)``."""
        r = self.radii_m
        return (r[0] - r[1], r[1], r[2], r[3] - r[2])

    @property
    def series_capacities_m(self) -> tuple[float, ...]:
        """The series model's travels to the rings, m: ``(d1 (R1 - R2) / R1, d2 + d1 R2 / R1,
        d3 + d4 R3 / R4, d4 (R4 - R3) / R4)``."""
        r, d = self.radii_m, self.capacities_m
        return (d[0] * (r[0] - r[1]) / r[0], d[1] + d[0] * r[1] / r[0], d[2] + d[3] * r[2] / r[3],
                d[3] * (r[3] - r[2]) / r[3])

    @property
    def travel_m(self) -> float:
        """The bearing's whole travel, m: where every surface is at its ring (the series' travels summed)."""
        return float(sum(self.series_capacities_m))

    @property
    def friction_forces_n(self) -> tuple[float, ...]:
        """``mu_i W``, N, each surface's."""
        w = self._weight()
        return tuple(m * w for m in self.mu)

    @property
    def friction_force_n(self) -> float:
        """The force at which it starts to slide from rest, N: ``min(mu2, mu3) W``."""
        return min(self.mu[1], self.mu[2]) * self._weight()

    @property
    def restoring_stiffness_n_m(self) -> float:
        """Its first stage's stiffness from rest, N/m: ``W / (R2 + R3)`` where ``mu2 = mu3``."""
        return self.slopes_n_m[0]

    @property
    def period_s(self) -> float:
        """Its sliding period in stage III (on the outer surfaces, ``2 pi sqrt((R1 + R4) / g)``), s."""
        return 2.0 * math.pi * math.sqrt((self.radii_m[0] + self.radii_m[3]) / GRAVITY_M_S2)

    @property
    def hysteresis(self) -> str:
        """``"friction"``: a rigid stick on every surface."""
        return "friction"

    @property
    def slopes_n_m(self) -> tuple[float, ...]:
        """Its stages' stiffnesses from rest, N/m, in the order a monotonic slide meets them (with stiff
        rings, the last: every surface on its ring, without end)."""
        u, f, last = self._backbone_points()
        du, df = np.diff(u), np.diff(f)
        return tuple(float(x) for x in df[du > 0.0] / du[du > 0.0]) + ((last,) if last > 0.0 else ())

    @property
    def breakpoints_m(self) -> tuple[float, ...]:
        """The displacements where a monotonic slide from rest changes stage, m (with rigid rings the last
        is the travel, where it ends)."""
        u, _, _ = self._backbone_points()
        return tuple(float(x) for x in u[1:][np.diff(u) > 0.0])

    @property
    def n_branches(self) -> int:
        """Its stages met by a monotonic slide from rest."""
        return len(self.slopes_n_m)

    @property
    def yield_forces(self) -> np.ndarray:
        """The force where it starts to slide from rest, N, shape (1,)."""
        return np.array([self.friction_force_n])

    def _backbone_points(self) -> tuple[np.ndarray, np.ndarray, float]:
        """The vertices ``(u, F)`` of a monotonic slide from rest (m, N) and the last stage's stiffness
        beyond the last vertex, N/m (0: rigid rings, none beyond the travel); see :func:`slide`."""
        w = self._weight()
        us, fs, last, _, _ = slide([w / r for r in self.series_radii_m], self.friction_forces_n,
                                   self.series_capacities_m, self.ring_stiffness_n_m or 0.0)
        return us, fs, last

    def backbone(self, displacement: Any) -> np.ndarray:
        """The force of a monotonic slide from rest (N) at displacement(s) in m, any shape: piecewise
        linear through the stages, odd in the displacement; NaN beyond the travel with rigid rings, its
        last stage's stiffness on with stiff ones."""
        d = np.asarray(displacement, dtype=float)
        a = np.abs(d)
        u, f, last = self._backbone_points()
        out = np.interp(a, u[1:], f[1:])
        out = np.where(a > 0.0, out, 0.0)
        beyond = f[-1] + last * (a - u[-1]) if last > 0.0 else np.nan
        return np.sign(d) * np.where(a <= u[-1] * (1 + 1e-12), out, beyond)

    def to_dict(self) -> dict[str, Any]:
        """The constructor's fields as plain values, the unset ones left out (the TOML form)."""
        out: dict[str, Any] = {"radii_m": list(self.radii_m), "mu": list(self.mu),
                               "capacities_m": list(self.capacities_m), "damping_n_s_m": self.damping_n_s_m}
        if self.weight_n is not None and not self.weight_carried:
            out["weight_n"] = self.weight_n
        if self.ring_stiffness_n_m is not None:
            out["ring_stiffness_n_m"] = self.ring_stiffness_n_m
        return out

    # ---------------------------------------------------------------- the engine's form

    def kernel_arrays(self) -> tuple[np.ndarray, np.ndarray, int, np.ndarray]:
        """``(slopes, breakpoints, rule, bouc_wen)`` as the compiled engine takes them: the series'
        stiffnesses ``W / R`` (N/m) and travels (m), the friction rule (2), no Bouc-Wen spring."""
        w = self._weight()
        return (np.array([w / r for r in self.series_radii_m]), np.array(self.series_capacities_m),
                RULE_FRICTION, np.zeros(BW_PARAMS))

    @property
    def kernel_friction(self) -> dict[str, Any]:
        """The friction the engine's friction rule takes: each surface's, ``surface_friction_n`` (N), and
        its ring's stiffness, ``surface_ring_n_m`` (N/m; none: rigid)."""
        rings = [] if self.ring_stiffness_n_m is None else [self.ring_stiffness_n_m] * SURFACES
        return {"surface_friction_n": list(self.friction_forces_n), "surface_ring_n_m": rings}
