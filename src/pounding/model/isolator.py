"""The isolator: a symmetric multi-linear backbone, a hysteresis rule and a linear dashpot."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, ClassVar, Literal, Optional

import numpy as np

from .._checks import at_most, backbone, non_negative, one_of, plausible, positive, real
from .._errors import InputError, Problem, renamed_fields
from ._toml import renamed_keys

HYSTERESIS_RULES = ("kinematic", "elastic")
# magnitudes beyond any real isolator (refused: the engine's numbers would overflow)
MAX_STIFFNESS_N_M = 1e15
MAX_DAMPING_N_S_M = 1e15
MAX_BREAKPOINT_M = 1e3
MAX_BW_EXPONENT = 100.0  # (n = 100: the elastic-perfectly-plastic spring to 1e-4)
MAX_BW_Z = 1e3  # |z| saturates at (a / (beta + gamma))^(1/n): beyond this the parameters mean something else
BW_PARAMS = 6  # the kernels' Bouc-Wen array: force scale k u_y (N), u_y (m), A, beta, gamma, n


@renamed_fields({"stiffness": "stiffness_n_m", "yield_displacement": "yield_displacement_m"})
@dataclass(frozen=True)
class BoucWen:
    """A Bouc-Wen hysteretic spring, in parallel with the isolator's backbone and dashpot: the
    rate-independent hysteresis of high-damping rubber, whose damping depends on the amplitude.

    Its force is ``stiffness_n_m * yield_displacement_m * z`` with the dimensionless ``z`` following::

        dz/dt = (dD/dt / yield_displacement_m) (a - |z|^n (beta sgn(z dD/dt) + gamma))

    (Wen 1976).  From ``z = 0`` it starts with stiffness ``a * stiffness`` and saturates at
    ``|z| = (a / (beta + gamma))^(1/n)``: with the defaults at the yield force
    ``stiffness_n_m * yield_displacement_m``; the larger ``n``, the sharper the yield (``n`` to
    infinity: an elastic-perfectly-plastic spring).  Integrated numerically inside the engine,
    every phase of motion (its kinks, where ``dD/dt`` or ``z`` cross zero, are located as events).

    Parameters
    ----------
    stiffness_n_m : float
        N/m, > 0.
    yield_displacement_m : float
        m, > 0.
    a, beta, gamma : float
        ``a > 0``; ``beta >= |gamma|`` and ``beta + gamma > 0`` (so that every loop dissipates).
    n : float
        Sharpness, 1 to 100.

    (``stiffness`` and ``yield_displacement``, the names before, still work for one release, with a
    warning.)

    Examples
    --------
    A high-damping rubber bearing: a linear backbone with a Bouc-Wen spring that yields at 100 N,
    under 5 s of a 1 Hz, 0.1 g table motion:

    >>> import pounding
    >>> bw = pounding.BoucWen(stiffness_n_m=20_000.0, yield_displacement_m=0.005,
    ...                       n=2.0)
    >>> bw.yield_force_n  # N
    100.0
    >>> hdr = pounding.Oscillator(500.0, pounding.Isolator([18_000.0],
    ...                                                    damping_n_s_m=500.0,
    ...                                                    bouc_wen=bw))
    >>> run = pounding.simulate(hdr, pounding.Harmonic(a_g=0.1, freq_hz=1.0),
    ...                         duration=5.0)
    >>> f"{run.displacement_max:.3f} m, {run.energy.hysteretic:.0f} J by hysteresis"
    '0.104 m, 144 J by hysteresis'
    """

    stiffness_n_m: float
    yield_displacement_m: float
    a: float = 1.0
    beta: float = 0.5
    gamma: float = 0.5
    n: float = 1.0

    FIELDS: ClassVar[tuple[str, ...]] = ("stiffness_n_m", "yield_displacement_m", "a", "beta", "gamma", "n")

    def __post_init__(self) -> None:
        stiffness = positive("isolator.bouc_wen.stiffness_n_m", self.stiffness_n_m, "N/m")
        at_most("isolator.bouc_wen.stiffness_n_m", stiffness, MAX_STIFFNESS_N_M,
                " N/m, stiffer than any isolator", "give the stiffness in N/m")
        uy = positive("isolator.bouc_wen.yield_displacement_m", self.yield_displacement_m, "m")
        at_most("isolator.bouc_wen.yield_displacement_m", uy, MAX_BREAKPOINT_M, " m", "give it in m")
        plausible("isolator.bouc_wen.yield_displacement_m", uy, 0.0, 1.0,
                  "a displacement in m (5 mm is 0.005)")
        a = positive("isolator.bouc_wen.a", self.a, "")
        beta = real("isolator.bouc_wen.beta", self.beta)
        gamma = real("isolator.bouc_wen.gamma", self.gamma)
        if beta + gamma <= 0.0 or beta < abs(gamma):
            raise InputError(Problem.OUT_OF_RANGE, "isolator.bouc_wen.beta", beta,
                             range=f"beta >= |gamma| = {abs(gamma):g} with beta + gamma > 0",
                             hint=" (else a loop can return energy, or z never saturates; 0.5 and 0.5 are "
                                  "usual)")
        n = real("isolator.bouc_wen.n", self.n)
        if not 1.0 <= n <= MAX_BW_EXPONENT:
            raise InputError(Problem.OUT_OF_RANGE, "isolator.bouc_wen.n", n,
                             range=f"[1, {MAX_BW_EXPONENT:g}]", hint=" (1: a smooth yield; larger, sharper)")
        at_most("isolator.bouc_wen.a", a * stiffness, MAX_STIFFNESS_N_M,
                " N/m of initial stiffness a * stiffness_n_m, "
                "stiffer than any isolator", "give a of order 1 (it scales the initial stiffness)")
        z_max = (a / (beta + gamma)) ** (1.0 / n)
        if z_max > MAX_BW_Z:
            raise InputError(Problem.OUT_OF_RANGE, "isolator.bouc_wen.beta", beta,
                             range=f"values that keep z_max = (a / (beta + gamma))^(1/n) = {z_max:g} within "
                                   f"{MAX_BW_Z:g}",
                             hint=" (beta + gamma of the order of a: the force saturates near "
                                  "stiffness_n_m * yield_displacement_m)")
        for name, value in (("stiffness_n_m", stiffness), ("yield_displacement_m", uy), ("a", a),
                            ("beta", beta), ("gamma", gamma), ("n", n)):
            object.__setattr__(self, name, value)

    @property
    def z_max(self) -> float:
        """The largest ``|z|``: ``(a / (beta + gamma))^(1/n)``."""
        return float((self.a / (self.beta + self.gamma)) ** (1.0 / self.n))

    @property
    def yield_force_n(self) -> float:
        """The force it saturates at, N: ``stiffness_n_m * yield_displacement_m * z_max``."""
        return self.stiffness_n_m * self.yield_displacement_m * self.z_max

    def kernel_array(self) -> np.ndarray:
        """``(stiffness_n_m * yield_displacement_m, yield_displacement_m, a, beta, gamma, n)``, shape (6,)."""
        return np.array([self.stiffness_n_m * self.yield_displacement_m, self.yield_displacement_m, self.a,
                         self.beta, self.gamma, self.n])

    def to_dict(self) -> dict[str, Any]:
        """The constructor's fields as plain values (the TOML form: ``Oscillator.to_toml`` writes it)."""
        return {name: getattr(self, name) for name in self.FIELDS}


@renamed_fields({"slopes": "slopes_n_m", "breakpoints": "breakpoints_m", "damping": "damping_n_s_m"})
@dataclass(frozen=True)
class Isolator:
    """Isolator ("damper") of the paper: rate-independent force ``R_d`` plus ``C_d * dD/dt``.

    The backbone of ``R_d`` is symmetric and multi-linear: slope ``slopes_n_m[j]`` between
    breakpoints ``breakpoints_m[j-1]`` and ``breakpoints_m[j]`` (with ``breakpoints_m[-1] = 0`` and
    the last slope running to infinity).  Any number of branches; softening (decreasing
    slopes, the paper's case) or hardening (real rubber bearings at large drift).

    Parameters
    ----------
    slopes_n_m : sequence of float, shape (n,)
        Branch stiffnesses ``K_1 ... K_n`` in N/m.  The first must be > 0, the others >= 0.
    breakpoints_m : sequence of float, shape (n - 1,)
        Displacements ``0 < D_1 < ... < D_{n-1}`` in m where the slope changes.
    hysteresis : {"kinematic", "elastic"}
        ``"kinematic"``: Masing / kinematic hardening, built exactly as a spring of slope
        ``K_n`` in parallel with ``n - 1`` elastic-perfectly-plastic springs (spring ``i`` of
        stiffness ``K_i - K_{i+1}`` slips at ``D_i``), as SAP2000's multi-linear plastic link.
        ``"elastic"``: the force follows the backbone both ways (no hysteresis).
    damping_n_s_m : float
        Linear dashpot ``C_d`` in N s/m, >= 0.
    bouc_wen : BoucWen, optional
        A Bouc-Wen spring in parallel (high-damping rubber: damping that depends on the
        amplitude).  With it every phase is integrated numerically (about 30 times the cost of
        the paper's campaign).

    (``slopes``, ``breakpoints`` and ``damping``, the names before, still work for one release, with a
    warning.)

    Notes
    -----
    With a hardening backbone some of the parallel springs have negative stiffness; the
    construction stays exact (Masing loops) but such a spring returns energy while slipping,
    and strongly hardening backbones can give loops of negative area, as Masing's rule does.

    Examples
    --------
    The paper's tri-linear isolator (Sect. 5) with the ``C_d = 1 kN s/m`` of
    :func:`pounding.presets.paper_damped`:

    >>> import pounding
    >>> iso = pounding.Isolator(slopes_n_m=[38_000.0, 18_000.0, 2_000.0],
    ...                         breakpoints_m=[0.015, 0.040],
    ...                         hysteresis="kinematic", damping_n_s_m=1_000.0)
    >>> iso.n_branches, iso.yield_forces  # N at 15 and 40 mm
    (3, array([ 570., 1020.]))
    >>> float(iso.backbone(-0.05))  # N at -50 mm
    -1040.0
    """

    slopes_n_m: tuple[float, ...]
    breakpoints_m: tuple[float, ...] = ()
    hysteresis: Literal["kinematic", "elastic"] = "kinematic"
    damping_n_s_m: float = 0.0
    bouc_wen: Optional[BoucWen] = None

    FIELDS: ClassVar[tuple[str, ...]] = ("slopes_n_m", "breakpoints_m", "hysteresis", "damping_n_s_m",
                                         "bouc_wen")
    OPTIONAL: ClassVar[tuple[str, ...]] = ("bouc_wen",)

    def __post_init__(self) -> None:
        slopes, breakpoints = backbone("isolator", self.slopes_n_m, self.breakpoints_m, MAX_STIFFNESS_N_M,
                                       " N/m, stiffer than any isolator",
                                       "give the slopes in N/m (38 kN/m is 38000.0)", MAX_BREAKPOINT_M,
                                       "give the breakpoints in m", ("slopes_n_m", "breakpoints_m"))
        for j, d in enumerate(breakpoints):
            plausible(f"isolator.breakpoints_m[{j}]", d, 0.0, 1.0,
                      "breakpoints are displacements in m (15 mm is 0.015)")
        one_of("isolator.hysteresis", self.hysteresis, HYSTERESIS_RULES)
        damping = non_negative("isolator.damping_n_s_m", self.damping_n_s_m, "N s/m")
        at_most("isolator.damping_n_s_m", damping, MAX_DAMPING_N_S_M, " N s/m", "give the damping in N s/m")
        object.__setattr__(self, "slopes_n_m", slopes)
        object.__setattr__(self, "breakpoints_m", breakpoints)
        object.__setattr__(self, "damping_n_s_m", damping)
        if isinstance(self.bouc_wen, dict):  # (from TOML: a table)
            table = renamed_keys(self.bouc_wen, "isolator.bouc_wen.", BoucWen.RENAMED)
            object.__setattr__(self, "bouc_wen", table)
            unknown = sorted(set(self.bouc_wen) - set(BoucWen.FIELDS))
            if unknown:
                raise InputError(Problem.UNKNOWN_KEY, f"isolator.bouc_wen.{unknown[0]}",
                                 self.bouc_wen[unknown[0]], choices=", ".join(BoucWen.FIELDS))
            for key in ("stiffness_n_m", "yield_displacement_m"):
                if key not in self.bouc_wen:
                    raise InputError(Problem.MISSING_KEY, f"isolator.bouc_wen.{key}", None,
                                     choices=", ".join(BoucWen.FIELDS))
            object.__setattr__(self, "bouc_wen", BoucWen(**self.bouc_wen))
        if self.bouc_wen is not None and not isinstance(self.bouc_wen, BoucWen):
            raise InputError(Problem.WRONG_TYPE, "isolator.bouc_wen", self.bouc_wen,
                             got=type(self.bouc_wen).__name__, expected="BoucWen or None")

    @property
    def n_branches(self) -> int:
        """Number of backbone branches ``n``."""
        return len(self.slopes_n_m)

    @property
    def initial_stiffness_n_m(self) -> float:
        """Its stiffness from rest, N/m: the backbone's first slope, and its Bouc-Wen spring's ``a k``."""
        bw = self.bouc_wen
        return self.slopes_n_m[0] + (0.0 if bw is None else bw.a * bw.stiffness_n_m)

    @property
    def yield_forces(self) -> np.ndarray:
        """Backbone force at each breakpoint, N, shape (n - 1,) (the paper's "yielding forces")."""
        return self.backbone(np.asarray(self.breakpoints_m))

    def backbone(self, displacement: Any) -> np.ndarray:
        """Backbone force (N) at displacement(s) in m, any shape; odd in the displacement."""
        d = np.asarray(displacement, dtype=float)
        a = np.abs(d)
        force = self.slopes_n_m[0] * np.minimum(a, self.breakpoints_m[0] if self.breakpoints_m else np.inf)
        edges = (*self.breakpoints_m, np.inf)
        for j in range(1, self.n_branches):
            force = force + self.slopes_n_m[j] * np.clip(a - edges[j - 1], 0.0, edges[j] - edges[j - 1])
        return np.sign(d) * force

    def to_dict(self) -> dict[str, Any]:
        """The constructor's fields as plain values (the TOML form: ``Oscillator.to_toml`` writes it)."""
        out: dict[str, Any] = {"slopes_n_m": list(self.slopes_n_m), "breakpoints_m": list(self.breakpoints_m),
                               "hysteresis": self.hysteresis, "damping_n_s_m": self.damping_n_s_m}
        if self.bouc_wen is not None:
            out["bouc_wen"] = self.bouc_wen.to_dict()
        return out

    @property
    def kernel_friction(self) -> dict[str, float]:
        """The friction the engine's friction rule takes: none, a rubber bearing has none
        (:class:`FrictionIsolator`'s has)."""
        return {}

    def kernel_arrays(self) -> tuple[np.ndarray, np.ndarray, int, np.ndarray]:
        """``(slopes, breakpoints, rule, bouc_wen)`` as the compiled engine takes them (the last
        :meth:`BoucWen.kernel_array`, zeros without one)."""
        bw = self.bouc_wen.kernel_array() if self.bouc_wen is not None else np.zeros(BW_PARAMS)
        return (np.array(self.slopes_n_m, dtype=float), np.array(self.breakpoints_m, dtype=float),
                HYSTERESIS_RULES.index(self.hysteresis), bw)
