"""The elastic-plastic impact law, compiled: its branches, state changes and stored energy.

Parameters at ``p[o:o + N_LAW_PARAMS]`` as :meth:`ElasticPlastic.params` lays them out:
``k1`` (elastic stiffness, N/m), ``k2`` (post-yield stiffness, N/m, 0 < k2 < k1), ``dy``
(yield compression, m).  The force lies between two lines of slope ``k2``: the yield line
``k1 dy + k2 (d - dy)`` above, the unloading line ``k2 d`` below; in between it moves
elastically, ``k1 (d - z)`` with ``z`` the plastic offset (OpenSees' ``ImpactMaterial``).

The law's state ``z`` (one number per bumper, kept in the engine's state vector):

* ``z >= 0``: on the elastic branch, plastic offset ``z`` (m);
* ``EP_YIELD`` (-1): on the yield line, loading;
* ``EP_UNLOAD`` (-2): on the unloading line, coming back.

It changes only at events: the elastic branch reaching a line (``z`` becomes the line's code),
and the compression rate turning on a line (back to elastic, with the offset where it turned).
"""

from __future__ import annotations

from .._jit import jit

EP_ELASTIC = 0    # branch indices, as law_linear_branch reports them
EP_YIELD_BRANCH = 1
EP_UNLOAD_BRANCH = 2
EP_YIELD = -1.0   # the state on those lines
EP_UNLOAD = -2.0


@jit
def ep_line(p, o, z):
    """The branch of state ``z``: ``(slope N/m, offset N, branch index)``, force = slope d + offset."""
    k1, k2 = p[o], p[o + 1]
    if z == EP_YIELD:
        return k2, (k1 - k2) * p[o + 2], EP_YIELD_BRANCH
    if z == EP_UNLOAD:
        return k2, 0.0, EP_UNLOAD_BRANCH
    return k1, -k1 * z, EP_ELASTIC


@jit
def ep_edges(p, o, z):
    """Compressions (m) where the elastic branch of offset ``z`` meets the unloading line
    (below; -1.0 for none: at ``z = 0`` that is 0, where the contact ends) and the yield line
    (above); ``(-1.0, -1.0)`` on a line (it is left where the compression rate turns)."""
    if z < 0.0:
        return -1.0, -1.0
    k1, k2 = p[o], p[o + 1]
    s = k1 * z / (k1 - k2)
    return (s if z > 0.0 else -1.0), p[o + 2] + s


@jit
def ep_turn_sign(z):
    """On a line, the sign of the compression rate there (+1 loading on the yield line, -1
    unloading): the line is left where the rate crosses zero.  0 on the elastic branch."""
    if z == EP_YIELD:
        return 1.0
    if z == EP_UNLOAD:
        return -1.0
    return 0.0


@jit
def ep_after_event(p, o, z, d, code):
    """The state after an event of the law at compression ``d``: on a line, the compression rate
    turned (back to elastic, the offset where the force is); on the elastic branch, a line was
    reached (``code``, that line's state)."""
    k1, k2 = p[o], p[o + 1]
    if z == EP_YIELD:
        f = k2 * d + (k1 - k2) * p[o + 2]
        return max(d - f / k1, 0.0)
    if z == EP_UNLOAD:
        return max(d * (1.0 - k2 / k1), 0.0)
    return code


@jit
def ep_force(p, o, d, z):
    """Force (N) at compression ``d`` (m) in state ``z``, never below 0."""
    k, r, _ = ep_line(p, o, z)
    return max(k * d + r, 0.0)


@jit
def ep_energy(p, o, d, z):
    """Energy (J) the bumper gives back when unloaded from compression ``d`` in state ``z``:
    elastically down to the unloading line, then along it, ``F^2 / (2 k1) + k1 k2 z^2 / (2 (k1 - k2))``
    with ``z`` the plastic offset (the rest of the work done on it was dissipated)."""
    k1, k2 = p[o], p[o + 1]
    f = ep_force(p, o, d, z)
    dp = z if z >= 0.0 else max(d - f / k1, 0.0)
    return 0.5 * f * f / k1 + 0.5 * k1 * k2 * dp * dp / (k1 - k2)


@jit
def ep_force_path(p, o, d, out):
    """Forces (N) along a path of compressions ``d`` (shape (n,), m) from the unloaded state, by
    return mapping: an elastic step, held between the two lines (exact for a path sampled
    finely enough that no step crosses a line and turns back within it).  A compression at or
    below 0 is out of contact and resets the state."""
    k1, k2, dy = p[o], p[o + 1], p[o + 2]
    f = 0.0
    prev = 0.0
    for i in range(d.size):
        x = d[i]
        if x <= 0.0:
            f = 0.0
            prev = 0.0
            out[i] = 0.0
            continue
        f = f + k1 * (x - prev)
        f = min(max(f, k2 * x), k1 * dy + k2 * (x - dy))
        prev = x
        out[i] = f
