"""Hypothesis strategies: random systems and excitations covering the model's range."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
from hypothesis import strategies as st

import pounding as pd_


@st.composite
def isolators(draw, hysteresis=None):
    n = draw(st.integers(1, 4))
    slopes = [draw(st.floats(5e3, 8e4))]
    for _ in range(n - 1):
        slopes.append(slopes[-1] * draw(st.floats(0.05, 3.0)))  # softening or hardening
    breaks = sorted(draw(st.lists(st.floats(0.002, 0.06), min_size=n - 1, max_size=n - 1, unique=True)))
    if any(b - a < 1e-3 for a, b in zip(breaks, breaks[1:])):
        breaks = [0.004 * (j + 1) for j in range(n - 1)]
    rule = hysteresis or draw(st.sampled_from(["kinematic", "elastic"]))
    return pd_.Isolator(slopes, breaks, rule, draw(st.floats(1.0, 5000.0)))


@st.composite
def bouc_wens(draw, slope):
    """A Bouc-Wen spring of 0.2 to 2 times ``slope`` (N/m), yielding at 2 to 20 mm, smooth to sharp,
    the usual parameters or others that dissipate."""
    beta, gamma = draw(st.sampled_from([(0.5, 0.5), (0.75, 0.25), (0.25, 0.25), (0.6, -0.4)]))
    return pd_.BoucWen(slope * draw(st.floats(0.2, 2.0)), draw(st.floats(0.002, 0.02)),
                       draw(st.sampled_from([1.0, 0.8, 1.2])), beta, gamma,
                       draw(st.sampled_from([1.0, 1.5, 2.0, 4.0])))


@st.composite
def oscillators(draw, bumpers=True, hysteresis=None, gaps="open", law="kelvin_voigt", bouc_wen=False):
    """``gaps``: "open" (3 to 30 mm each side) or "zero" (0 on one side or both: the mass at
    rest touches that bumper).  ``law``: "kelvin_voigt", "multilinear", "multilinear_kinematic",
    "elastic_plastic",
    "hertzdamp" or "jankowski" (its effective mass the system's).  ``bouc_wen``: the isolator with a
    Bouc-Wen spring in parallel."""
    iso = draw(isolators(hysteresis))
    if bouc_wen:
        iso = replace(iso, bouc_wen=draw(bouc_wens(iso.slopes_n_m[0])))
    mass = draw(st.floats(100.0, 1500.0))
    b = None
    if bumpers:
        if law in ("multilinear", "multilinear_kinematic"):  # 2 to 4 branches, softer or stiffer
            n = draw(st.integers(2, 4))
            slopes = [draw(st.floats(1e5, 3e6))]
            for j in range(n - 1):
                if j < n - 2:  # a flat, soft or stiff branch inside
                    slopes.append(slopes[-1] * draw(st.sampled_from([0.0, 0.1, 0.5, 2.0, 5.0])))
                else:  # the last one stiffer than the first (a real bumper stiffens once compressed:
                    # a flat last branch let 100 kg through 24 cm, where the reference stalls)
                    slopes.append(max(slopes[-1], slopes[0]) * draw(st.sampled_from([2.0, 5.0])))
            breaks = sorted(draw(st.lists(st.floats(3e-4, 0.01), min_size=n - 1, max_size=n - 1,
                                          unique=True)))
            if any(b - a < 1e-4 for a, b in zip(breaks, breaks[1:])):
                breaks = [0.001 * (j + 1) for j in range(n - 1)]
            hysteresis = "elastic"
            if law == "multilinear_kinematic":  # the softenings no more than the first slope
                hysteresis = "kinematic"
                softening = 0.0
                for j in range(1, n):
                    step = slopes[j - 1] - slopes[j]
                    if step > 0.0 and softening + step > slopes[0]:
                        slopes[j] = slopes[j - 1]  # (this one not softer)
                    softening += max(slopes[j - 1] - slopes[j], 0.0)
            law = pd_.MultilinearBumper(slopes, breaks, draw(st.floats(1.0, 5000.0)), hysteresis)
        elif law == "elastic_plastic":  # yield from 0.3 to 5 mm, K2 from nearly flat to nearly K1
            k1 = draw(st.floats(1e5, 3e6))
            law = pd_.ElasticPlastic(k1, k1 * draw(st.sampled_from([0.01, 0.1, 0.3, 0.8])),
                                     draw(st.floats(3e-4, 5e-3)))
        elif law == "hertzdamp":  # restitution about 0.5 to 1
            law = pd_.Hertzdamp(draw(st.floats(1e7, 3e9)), draw(st.floats(0.0, 1.6)),
                                draw(st.floats(1.0, 2.0)))
        elif law == "jankowski":
            law = pd_.Jankowski(draw(st.floats(1e7, 3e9)), draw(st.floats(0.0, 1.0)), mass,
                                draw(st.floats(1.0, 2.0)))
        else:
            law = pd_.KelvinVoigt(draw(st.floats(1e5, 3e6)), draw(st.floats(1.0, 5000.0)))
        gap = st.floats(0.003, 0.03)
        left, right = draw(gap), draw(gap)
        if gaps == "zero":
            left, right = draw(st.sampled_from([(0.0, 0.0), (0.0, right), (left, 0.0)]))
        b = pd_.Bumpers(left, right, law)
    return pd_.Oscillator(mass, iso, b)


@st.composite
def harmonics(draw):
    return pd_.Harmonic(draw(st.floats(0.03, 0.4)), draw(st.floats(0.5, 5.0)), draw(st.floats(0.0, 6.28)))


LINEAR_LAWS = ("kelvin_voigt", "multilinear", "multilinear_kinematic")  # (the laws with closed-form phases)


@st.composite
def records(draw, duration_s=3.0):
    """A piecewise-linear record over ``duration_s``: a step of 2 to 60 ms (sub-intervals both
    shorter and longer than the phases' own), even or jittered, starting at 0 or later (the
    table still before it, then from 0), peaks of 0.5 to 8 m/s^2, white or smoothed."""
    dt = draw(st.floats(0.002, 0.06))
    start = draw(st.sampled_from([0.0, 0.0, 0.13]))
    n = int((duration_s - start) / dt) + 1
    seed = draw(st.integers(0, 2**32 - 1))
    rng = np.random.default_rng(seed)
    t = start + dt * np.arange(n)
    if draw(st.booleans()):  # uneven steps (the knots no longer a grid)
        t = start + np.concatenate([[0.0], np.cumsum(dt * rng.uniform(0.5, 1.5, n - 1))])
    accel = rng.normal(0.0, 1.0, n)
    if draw(st.booleans()):
        accel = np.convolve(accel, np.ones(5) / 5, mode="same")
    accel *= draw(st.floats(0.5, 8.0)) / max(np.abs(accel).max(), 1e-12)
    # from and back to rest: the table's acceleration is 0 before and after the record, and a
    # jump there is one the reference steps into with solve_ivp's "step size less than spacing"
    accel[-1] = 0.0
    if start > 0.0:
        accel[0] = 0.0
    return pd_.Record(t, accel)


@st.composite
def building_isolators(draw):
    kind = draw(st.sampled_from(["linear", "bilinear", "flat", "pendulum", "triple"]))
    if kind == "linear":
        return pd_.Isolator((draw(st.floats(2e4, 4e5)),), damping_n_s_m=draw(st.floats(0.0, 4e3)))
    if kind == "bilinear":
        k = draw(st.floats(1e5, 1e6))
        return pd_.Isolator((k, 0.1 * k), (draw(st.floats(0.005, 0.03)),),
                            damping_n_s_m=draw(st.floats(0.0, 2e3)))
    if kind == "triple":
        return pd_.TripleFrictionPendulum(radii_m=(2.1, 0.3, 0.3, 2.1), mu=(0.05, 0.02, 0.02, 0.08),
                                          capacities_m=(0.3, 0.05, 0.05, 0.3))
    return pd_.FrictionIsolator(mu=draw(st.floats(0.02, 0.15)),
                                radius_m=None if kind == "flat" else draw(st.floats(1.0, 4.0)),
                                damping_n_s_m=draw(st.sampled_from([0.0, 1e3])))


@st.composite
def buildings(draw, min_levels=1):
    """A random building of ``min_levels`` to 5 levels on a linear, bilinear or friction isolator, with a wall
    (a linear law's or a rigid stop's) at one of its levels, or none."""
    n = draw(st.integers(min_levels, 5))
    masses = [draw(st.floats(1e3, 2e4)) for _ in range(n)]
    storeys = [pd_.Storey(m, draw(st.floats(1e6, 1e8)), draw(st.floats(0.0, 1e5))) for m in masses[1:]]
    isolator = draw(building_isolators())
    walls = []
    if draw(st.booleans()):
        laws = [pd_.KelvinVoigt(draw(st.floats(1e6, 5e7)), draw(st.floats(0.0, 1e4))),
                pd_.MultilinearBumper((2e6, 2e7), (0.004,), damping=1e3)]
        if isinstance(isolator, pd_.Isolator):  # (a rigid stop beside friction is refused)
            laws.append(pd_.RigidStop(draw(st.floats(0.0, 0.9))))
        law = draw(st.sampled_from(laws))
        gaps = (draw(st.floats(0.005, 0.08)), draw(st.floats(0.005, 0.08)))
        walls = [pd_.Wall(draw(st.integers(0, n - 1)), *gaps, law)]
    return pd_.Structure(masses[0], isolator, storeys, walls)
