"""A slow, obviously-correct reference for structures in plan: scipy's solve_ivp (DOP853) with events,
restarted at each of them.

The structure restated directly, sharing no code with the engine: n coordinates q (each floor's x, y and
rotation, relative to the ground), ``M q'' + C q' + K q + f_plastic + f_walls = -M R a_g(t)``, M diagonal (the
masses and the floors' rotational inertias), R the influence of the ground's two components (n, 2), a_g(t) the
pair of components linear between their samples. Every nonlinear force acts along a weight vector w (a
point of a floor: its displacement along an axis is w . q, e.g. ``x - y_c theta``) and pushes the coordinates
by its force times w:

* an elastic-perfectly-plastic spring (stiffness k_p, yield displacement D; a bilinear bearing is one beside
  a linear spring in K): stuck, its force is k_p (w . q - slip); it slips when w . q - slip reaches +-D and
  sticks again when w . q' turns back; with a velocity dependence (``plastic_fast``: a sliding bearing's
  pre-slip) its slip's force the way m is m k_p D (r - (r - 1) exp(-c m w . q')), r = mu_fast / mu;
* a Bouc-Wen spring (its force f_z z, z' = w . q' / u_y (a - |z|^n (gamma + beta sgn(w . q' z))), z one more
  state; the integration restarts where z and where w . q' cross zero, its law's kinks); two of them may be
  one bidirectional spring (Park, Wen and Ang's, of any n): with u'_k = w_k . q', the vector z = (z_1, z_2),
  z_k' = (a u'_k - |z|^(n-2) z_k sum_j u'_j z_j (gamma + beta sgn(u'_j z_j))) / u_y, yielding under the
  resultant (one spring along a line when the other's z and u' are 0); or one elastic-perfectly-plastic circle
  (a friction bearing's: its numbers' a = 1, its force still f_z z): inside |z| = 1, z' = u' / u_y (stuck,
  elastic); on it, while z . u' > 0, z' = (u' - (z . u') z) / u_y (slipping); the integration restarts where
  |z| reaches 1 (it slips) and where z . u' comes back to 0 (it sticks);
* a friction circle's velocity dependence (``fast``: a bidirectional spring's or a plastic circle's): its
  force f_z z times r - (r - 1) exp(-c s), r = mu_fast / mu, c the rate (s/m), at the slip's rate s: z . u'
  while a plastic circle slips (none while it sticks inside), |u'| on a bidirectional Bouc-Wen spring;
* a Kelvin-Voigt wall (stiffness k_b, dashpot c_b) behind a gap, on one side (sign +-1): in contact its force
  is k_b d + c_b d' (d = sign w . q - gap) until it would pull; out of contact its compression relaxes as
  d_r exp(-k_b (t - t_r) / c_b) from where it was released, and contact starts when the point meets that
  surface;
* a Kelvin-Voigt ring (a circular moat's wall, radius R) struck by a point at (p_x, p_y) from its centre that
  moves by (w_x . q, w_y . q): its compression d = |(p_x + w_x . q, p_y + w_y . q)| - R, its force
  k_b d + c_b d' along the ring's normal n there (pushing the coordinates by it times n_x w_x + n_y w_y), the
  same contact rules as a wall's; or a Jankowski ring (its entry's eighth number, the exponent n: its force
  k_b d^n + c_b d^((n-1)/2) d' while d' > 0, k_b d^n while it recovers, never pulling: the contact ends where
  d is back to 0, the integration restarting where d' crosses zero in contact, its dashpot's kink; no
  relaxing surface).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import minimize_scalar

from reference_ndof import TouchAtRest, _stepped_over


@dataclass
class PlanModel:
    mass: np.ndarray       # (n,): kg, kg m^2 for a rotation
    k: np.ndarray          # (n, n), N/m (the linear springs, the bearings' elastic part among them)
    c: np.ndarray          # (n, n), N s/m
    influence: np.ndarray  # (n, 2)
    record: tuple          # (t s, a_x m/s^2, a_y m/s^2): linear between the samples, zero outside
    # elastic-perfectly-plastic springs: (w (n,), k_p N/m, D m)
    plastic: list = field(default_factory=list)
    # their velocity dependence: {index into plastic: (mu_fast / mu, rate s/m)}
    plastic_fast: dict = field(default_factory=dict)
    # Kelvin-Voigt walls: (w (n,), sign +-1, gap m, k_b N/m, c_b N s/m)
    walls: list = field(default_factory=list)
    # Kelvin-Voigt rings, after the walls in the contacts' numbering: (w_x (n,), w_y (n,), p_x m, p_y m,
    # R m, k_b N/m, c_b N s/m), or Jankowski rings: the same and its exponent n (k_b N/m^n, c_b
    # N s/m^((n+1)/2))
    rings: list = field(default_factory=list)
    # Bouc-Wen springs: (w (n,), (f_z N, u_y m, a, beta, gamma, n)); their z start at 0
    bouc_wen: list = field(default_factory=list)
    # the bidirectional ones: pairs of indices into bouc_wen (the same numbers), each one spring in the plane
    bidirectional: list = field(default_factory=list)
    # the plastic circles: pairs of indices into bouc_wen (a = 1), each one elastic-perfectly-plastic circle
    circles: list = field(default_factory=list)
    # a velocity-dependent friction on a circle: {its first Bouc-Wen index: (mu_fast / mu, rate s/m)}
    fast: dict = field(default_factory=dict)
    # points whose displacement's extrema are found (w (n,) each: a bearing's along an axis, a corner's)
    tracked: list = field(default_factory=list)
    # vectors of two tracked points each (indices into tracked: a bearing's x and y), whose length's largest
    # is found
    vectors: list = field(default_factory=list)
    # each vector's offset (m, m; none given: zeros): its length is the offset's plus it (a corner's distance
    # from a ring's centre)
    vector_offsets: list = field(default_factory=list)


def record_pair(rng: np.random.Generator, duration_s: float, dt: float, pga: float) -> tuple:
    """A pair of smooth random components (m/s^2, each of peak ``pga``) on one time base: ``(t, a_x,
    a_y)``."""
    t = np.arange(0.0, duration_s + dt / 2, dt)
    comps = []
    for _ in range(2):
        a = np.convolve(rng.normal(0.0, 1.0, t.size), np.ones(7) / 7, "same")
        comps.append(pga * a / np.max(np.abs(a)))
    return t, comps[0], comps[1]


@dataclass
class PlanResult:
    yields: list = field(default_factory=list)          # (spring, t): began to slip
    sticks: list = field(default_factory=list)          # (spring, t): stuck again
    contact_starts: list = field(default_factory=list)  # (wall, t)
    contact_ends: list = field(default_factory=list)
    y: np.ndarray | None = None                         # the final (q, q')
    z: np.ndarray | None = None                         # the final Bouc-Wen z
    z_zeros: list = field(default_factory=list)         # (spring, t): its z back through zero
    circle_slips: list = field(default_factory=list)    # (circle, t): it reached its circle and slips
    circle_sticks: list = field(default_factory=list)   # (circle, t): it sticks again (inside)
    tracked_max: np.ndarray | None = None               # each tracked point's largest and smallest w . q, m
    tracked_min: np.ndarray | None = None
    vector_max: np.ndarray | None = None                # each vector's longest, m
    abs_acc_max: np.ndarray | None = None               # each coordinate's largest |absolute acceleration|


def reference(s: PlanModel, t_end: float, y0: np.ndarray, rtol: float = 1e-12, atol: float = 1e-15,
              steps_per_period: float = 100.0, track_acceleration: bool = False) -> PlanResult:
    n = s.mass.size
    inv_m = 1.0 / s.mass
    # every contact as its compression's value and rate, its gradient (what its force pushes along), k_b, c_b;
    # jankowski: each contact's exponent (None: Kelvin-Voigt's)
    contacts, jankowski = [], []
    for w, sg, gap, k_b, c_b in s.walls:
        w = np.asarray(w, dtype=float)
        contacts.append((lambda y, w=w, sg=sg, gap=gap: (sg * float(w @ y[:n]) - gap,
                                                         sg * float(w @ y[n:2 * n])),
                         lambda y, w=w, sg=sg: sg * w, k_b, c_b))
        jankowski.append(None)
    for wx, wy, px, py, radius, k_b, c_b, *law in s.rings:
        jankowski.append(law[0] if law else None)
        wx, wy = np.asarray(wx, dtype=float), np.asarray(wy, dtype=float)

        def normal(y, wx=wx, wy=wy, px=px, py=py):
            x, yy = px + float(wx @ y[:n]), py + float(wy @ y[:n])
            r = math.hypot(x, yy)
            return r, x / r, yy / r

        def depth(y, wx=wx, wy=wy, radius=radius, normal=normal):
            r, nx, ny = normal(y)
            return r - radius, nx * float(wx @ y[n:2 * n]) + ny * float(wy @ y[n:2 * n])
        contacts.append((depth, lambda y, wx=wx, wy=wy, normal=normal: normal(y)[1] * wx + normal(y)[2] * wy,
                         k_b, c_b))
    wp = [np.asarray(w, dtype=float) for w, *_ in s.plastic]
    wz = [np.asarray(w, dtype=float) for w, _ in s.bouc_wen]
    bws = [p for _, p in s.bouc_wen]
    z_max = [(a / (beta + gamma)) ** (1.0 / ne) for _, _, a, beta, gamma, ne in bws]
    nz = len(bws)
    mate = [-1] * nz
    for b1, b2 in [*s.bidirectional, *s.circles]:
        mate[b1], mate[b2] = b2, b1
    circle_of = {b: q for q, pair in enumerate(s.circles) for b in pair}
    on_circle = [False] * len(s.circles)  # (slipping on it)

    def longest_step(kk):  # (a hundredth of the fastest period: no dip of an event between two steps' signs)
        w_max = math.sqrt(max(float(np.max(np.linalg.eigvals(kk * inv_m[:, None]).real)), 0.0))
        return 2.0 * math.pi / w_max / steps_per_period if w_max > 0.0 else np.inf

    k_stuck = s.k + sum((k_p * np.outer(w, w) for w, (_, k_p, _) in zip(wp, s.plastic)), np.zeros((n, n)))
    k_stuck = k_stuck + sum((bws[b][0] / bws[b][1] * np.outer(wz[b], wz[b]) for b in circle_of),
                            np.zeros((n, n)))  # (a circle's elastic stiffness)
    k_in = k_stuck + sum((k_b * np.outer(w, w) for w, _, _, k_b, _ in s.walls), np.zeros((n, n)))
    k_in = k_in + sum((k_b * (np.outer(wx, wx) + np.outer(wy, wy)) for wx, wy, _, _, _, k_b, *_ in s.rings),
                      np.zeros((n, n)))
    step_in, step_out = longest_step(k_in), longest_step(k_stuck)

    inside = [False] * len(contacts)
    relax = [(0.0, 0.0)] * len(contacts)  # (compression at release, release time)
    slip = [0.0] * len(s.plastic)
    mode = [0] * len(s.plastic)  # 0 stuck, +-1 slipping that way
    # a spring just stuck from slipping that way (+-1; 0 none): its strain leaves that yield by less than the
    # rounding at first, so that yield is looked for only once the strain turns back towards it
    left = [0] * len(s.plastic)
    out = PlanResult()

    def along(y, w):  # (displacement, velocity) of a point along w
        return float(w @ y[:n]), float(w @ y[n:2 * n])

    def surface(c, t):
        d_r, t_r = relax[c]
        _, _, k_b, c_b = contacts[c]
        if d_r == 0.0 or c_b == 0.0 or jankowski[c] is not None:
            return 0.0
        return d_r * math.exp(-k_b * (t - t_r) / c_b)

    def nonlinear_forces(y):
        f = np.zeros(n)
        for q, (w, (_, k_p, d)) in enumerate(zip(wp, s.plastic)):
            if mode[q] == 0:
                f += k_p * (along(y, w)[0] - slip[q]) * w
                continue
            factor = 1.0
            if q in s.plastic_fast:  # (a velocity dependence at the slip's rate)
                ratio, rate = s.plastic_fast[q]
                factor = ratio - (ratio - 1.0) * math.exp(-rate * mode[q] * along(y, w)[1])
            f += mode[q] * k_p * d * factor * w
        for c, (depth, grad, k_b, c_b) in enumerate(contacts):
            if inside[c]:
                d, dd = depth(y)
                if jankowski[c] is None:
                    f += (k_b * d + c_b * dd) * grad(y)
                else:
                    ne, dp = jankowski[c], max(d, 0.0)
                    f += (k_b * dp**ne + (c_b * dp ** (0.5 * (ne - 1.0)) * dd if dd > 0.0 else 0.0)) * grad(y)
        for b, w in enumerate(wz):
            f += bws[b][0] * y[2 * n + b] * speed_factor(y, b) * w
        return f

    def speed_factor(y, b):  # (a circle's velocity dependence: 1 without one, or inside a plastic circle)
        pair = min(b, mate[b])
        if pair not in s.fast or (b in circle_of and not on_circle[circle_of[b]]):
            return 1.0
        ratio, rate = s.fast[pair]
        du, dm = float(wz[b] @ y[n:2 * n]), float(wz[mate[b]] @ y[n:2 * n])
        z, zm = float(y[2 * n + b]), float(y[2 * n + mate[b]])
        speed = max(du * z + dm * zm, 0.0) if b in circle_of else math.hypot(du, dm)
        return ratio - (ratio - 1.0) * math.exp(-rate * speed)

    def z_rates(y):
        out = np.zeros(nz)
        for b, (w, (_, u_y, a, beta, gamma, ne)) in enumerate(zip(wz, bws)):
            du, z = float(w @ y[n:2 * n]), float(y[2 * n + b])
            if b in circle_of:  # (a plastic circle: elastic inside, turning on it while it slips)
                zm, dm = float(y[2 * n + mate[b]]), float(wz[mate[b]] @ y[n:2 * n])
                out[b] = (du - z * (du * z + dm * zm) if on_circle[circle_of[b]] else du) / u_y
                continue
            if mate[b] < 0:
                # (|z| held at 2 z_max in the power: a rejected trial stage can leave |z| <= z_max)
                zn = min(abs(z), 2.0 * z_max[b]) ** ne
                out[b] = du / u_y * (a - zn * (beta * np.sign(du * z) + gamma))
                continue
            dm, zm = float(wz[mate[b]] @ y[n:2 * n]), float(y[2 * n + mate[b]])
            both = du * z * (gamma + beta * np.sign(du * z)) + dm * zm * (gamma + beta * np.sign(dm * zm))
            size = min(math.hypot(z, zm), 2.0 * z_max[b])
            out[b] = (a * du - (size ** (ne - 2.0) * z * both if size > 0.0 else 0.0)) / u_y
        return out

    a_lin = np.zeros((2 * n, 2 * n))
    a_lin[:n, n:] = np.eye(n)
    a_lin[n:, :n] = -inv_m[:, None] * s.k
    a_lin[n:, n:] = -inv_m[:, None] * s.c
    t_rec, ax, ay = (np.asarray(a, dtype=float) for a in s.record)

    def rhs(t, y):
        g = np.array([float(np.interp(t, t_rec, ax, left=0.0, right=0.0)),
                      float(np.interp(t, t_rec, ay, left=0.0, right=0.0))])
        dy = np.zeros(y.size)
        dy[:2 * n] = a_lin @ y[:2 * n]
        dy[n:2 * n] -= s.influence @ g + inv_m * nonlinear_forces(y)
        dy[2 * n:] = z_rates(y)
        return dy

    def make_events(quiet_contact=None):
        evs = []
        for c, (depth, _, k_b, c_b) in enumerate(contacts):
            if c == quiet_contact:
                continue
            if inside[c]:
                def release(t, y, depth=depth, k_b=k_b, c_b=c_b):
                    d, dd = depth(y)
                    return k_b * d + c_b * dd

                def emptied(t, y, depth=depth):  # (the compression back to 0: the contact ends too)
                    return depth(y)[0]
                emptied.terminal = True
                emptied.direction = -1.0
                emptied.contact = c
                evs.append(emptied)
                if jankowski[c] is not None:  # (it never pulls: it ends when emptied; its dashpot's kink)
                    # (signed to fall through zero next: at its zero, the way it leaves it, as a BW kink)
                    rate = depth(y)[1]
                    if abs(rate) <= 1e-12 * float(np.max(np.abs(y[n:2 * n]))):
                        rate = depth(y + 1e-9 * rhs(t, y))[1]
                    def rate_zero(t, y, depth=depth, sr=math.copysign(1.0, rate)):
                        return sr * depth(y)[1]
                    rate_zero.terminal = True
                    rate_zero.direction = -1.0
                    rate_zero.kink = (-1, False)
                    evs.append(rate_zero)
                    continue
            else:
                def release(t, y, c=c, depth=depth):
                    return surface(c, t) - depth(y)[0]
            release.terminal = True
            release.direction = -1.0
            release.contact = c
            evs.append(release)
        for q, (w, (_, _, d)) in enumerate(zip(wp, s.plastic)):
            for sg in (1.0, -1.0):
                if mode[q] == 0 and left[q] == sg:  # just stuck from this side: the strain turns back
                    def change(t, y, w=w, sg=sg):
                        return -sg * along(y, w)[1]
                    change.turn = True
                elif mode[q] == 0:  # stuck: the spring's strain reaches +-D
                    def change(t, y, q=q, w=w, sg=sg, d=d):
                        return d - sg * (along(y, w)[0] - slip[q])

                    def rate(t, y, w=w, sg=sg):  # (change's derivative: its minima are the strain's turns)
                        return -sg * along(y, w)[1]
                    change.rate = rate
                elif mode[q] == sg:  # slipping: its rate turns back
                    def change(t, y, w=w, sg=sg):
                        return sg * along(y, w)[1]
                else:
                    continue
                change.terminal = True
                change.direction = -1.0
                change.plastic = (q, sg)
                evs.append(change)
        if nz:
            dy = rhs(t, y)
        for q, (b1, b2) in enumerate(s.circles):  # (a circle reached; a slip's z . u' back to zero)
            def circle(t, y, q=q, b1=b1, b2=b2):
                z1, z2 = y[2 * n + b1], y[2 * n + b2]
                if on_circle[q]:
                    return z1 * float(wz[b1] @ y[n:2 * n]) + z2 * float(wz[b2] @ y[n:2 * n])
                return 1.0 - (z1 * z1 + z2 * z2)
            circle.terminal = True
            circle.direction = -1.0
            circle.circle = q
            evs.append(circle)
        for b, w in enumerate(wz):  # (a Bouc-Wen spring's kinks: its z and its rate w . q' through zero)
            if b in circle_of:
                continue
            # (z is set to 0 where it crosses zero, as the engine does: it has none while it is 0, and leaves
            # 0 with w . q''s sign; w . q' at rest heads where w . q'' does; from rest at rest, nowhere yet)
            z = y[2 * n + b]
            du, ddu = float(w @ y[n:2 * n]), float(w @ dy[n:2 * n])
            kinks = []
            if z != 0.0:
                def z_kink(t, y, b=b, sz=math.copysign(1.0, z)):
                    return sz * y[2 * n + b]
                kinks.append((z_kink, True))
            if abs(du) > 1e-13 or ddu != 0.0:
                def u_kink(t, y, w=w, su=math.copysign(1.0, du if abs(du) > 1e-13 else ddu)):
                    return su * float(w @ y[n:2 * n])
                kinks.append((u_kink, False))
            for f, zero in kinks:
                f.terminal = True
                f.direction = -1.0
                f.kink = (b, zero)
                evs.append(f)
        return evs

    t, y = 0.0, np.concatenate((np.asarray(y0, dtype=float), np.zeros(nz)))
    wt = [np.asarray(w, dtype=float) for w in s.tracked]
    top = np.array([along(y, w)[0] for w in wt])
    bottom = top.copy()

    def turn(w):  # (a tracked point's velocity: its zeros are its extrema; not terminal)
        def f(t, y):
            return float(w @ y[n:2 * n])
        f.terminal = False
        return f

    offsets = s.vector_offsets or [(0.0, 0.0)] * len(s.vectors)

    def length(y, p, q, o):
        return math.hypot(o[0] + along(y, wt[p])[0], o[1] + along(y, wt[q])[0])

    def lengthening(p, q, o):  # (u . u': its downward zeros are the vector's longest; not terminal)
        def f(t, y):
            (u, du), (w, dw) = along(y, wt[p]), along(y, wt[q])
            return (o[0] + u) * du + (o[1] + w) * dw
        f.terminal = False
        f.direction = -1.0
        return f

    longest = np.array([length(y, p, q, o) for (p, q), o in zip(s.vectors, offsets)])

    def abs_acc(t, y):  # (each coordinate's absolute acceleration: the relative one and the ground's)
        g = np.array([float(np.interp(t, t_rec, ax, left=0.0, right=0.0)),
                      float(np.interp(t, t_rec, ay, left=0.0, right=0.0))])
        return rhs(t, y)[n:2 * n] + s.influence @ g

    acc_top = np.abs(abs_acc(t, y))

    def acc_extrema(sol, t0, t1):  # (on a grid of the stretch, each largest refined on the dense output)
        grid = np.linspace(t0, t1, 65)
        values = np.abs(np.array([abs_acc(tg, sol.sol(tg)) for tg in grid]))
        for i in range(n):
            k = int(np.argmax(values[:, i]))
            best = values[k, i]
            if best > acc_top[i] * (1.0 - 1e-6):
                lo, hi = grid[max(k - 1, 0)], grid[min(k + 1, grid.size - 1)]
                r = minimize_scalar(lambda tt, i=i: -abs(abs_acc(tt, sol.sol(tt))[i]), bounds=(lo, hi),
                                    method="bounded", options={"xatol": 1e-14})
                best = max(best, -float(r.fun))
            acc_top[i] = max(acc_top[i], best)

    quiet = None  # (a wall just released, until when its start is not looked for)
    while t < t_end:
        quiet_now = quiet is not None and t < quiet[1]
        evs = make_events(quiet[0] if quiet_now else None)
        after = t_rec[t_rec > t * (1.0 + 1e-15) + 1e-15]  # (a record's kink: a stretch ends at the next)
        t_next = min(t_end, float(after[0])) if after.size else t_end
        if quiet_now:
            t_next = min(t_next, quiet[1])
        sol = solve_ivp(rhs, (t, t_next), y, method="DOP853", rtol=rtol, atol=atol,
                        events=evs + [turn(w) for w in wt] + [lengthening(p, q, o)
                                                               for (p, q), o in zip(s.vectors, offsets)],
                        dense_output=True,
                        max_step=step_in if any(inside) else step_out)
        if sol.status == -1:
            raise RuntimeError(sol.message)
        hits = [(float(te[0]), c) for c, te in enumerate(sol.t_events[:len(evs)])
                if te.size and te[0] > t + 1e-13]
        dip = _stepped_over(evs, sol, t)
        if dip is not None:
            hits.append(dip)
        t_stop = min(hits)[0] if hits else float(sol.t[-1])
        for q, w in enumerate(wt):  # (the extrema up to where this stretch stops: its turns and its end)
            turns = zip(sol.t_events[len(evs) + q], sol.y_events[len(evs) + q])
            xs = [along(sol.sol(t_stop), w)[0]] + [float(w @ ye[:n]) for te, ye in turns if te <= t_stop]
            top[q], bottom[q] = max(top[q], *xs), min(bottom[q], *xs)
        for k, ((p, q), o) in enumerate(zip(s.vectors, offsets)):
            at = len(evs) + len(wt) + k
            rs = [length(sol.sol(t_stop), p, q, o)] + [
                length(ye, p, q, o) for te, ye in zip(sol.t_events[at], sol.y_events[at]) if te <= t_stop]
            longest[k] = max(longest[k], *rs)
        if track_acceleration:
            acc_extrema(sol, t, t_stop)
        for q, (w, (_, _, d)) in enumerate(zip(wp, s.plastic)):  # (a stretch that slipped: the slip followed)
            if mode[q] != 0:
                end = sol.sol(min(hits)[0]) if hits else sol.y[:, -1]
                slip[q] = along(end, w)[0] - mode[q] * d
        if not hits:
            if sol.status != 0:
                fired = [evs[k] for k, te in enumerate(sol.t_events[:len(evs)]) if te.size]
                just = [f.contact for f in fired if hasattr(f, "contact") and not inside[f.contact]
                        and relax[f.contact][1] == t]
                if just and (quiet is None or quiet[1] <= t):  # (as reference_ndof: a release at rest)
                    quiet = (just[0], t + 1e-9)
                    continue
                raise TouchAtRest(f"an event fires again at its own instant, t = {t}")
            t, y = float(sol.t[-1]), sol.y[:, -1]
            if t_next < t_end:
                continue
            break
        t_hit = min(hits)[0]
        y = sol.sol(t_hit)
        t = t_hit
        # (every event at that instant, to 1e-12 s, once: solve_ivp's and a stepped-over dip may be the same)
        for c in sorted({c for t_c, c in hits if t_c <= t_hit + 1e-12}):
            if hasattr(evs[c], "circle"):  # (a circle's switch: slipping on it, |z| = 1; or inside)
                q = evs[c].circle
                on_circle[q] = not on_circle[q]
                (out.circle_slips if on_circle[q] else out.circle_sticks).append((q, t))
                if on_circle[q]:
                    at = [2 * n + b for b in s.circles[q]]
                    y[at] /= math.hypot(*y[at])
                continue
            if hasattr(evs[c], "kink"):  # (a Bouc-Wen kink: the integration restarts there)
                b, zero = evs[c].kink
                if zero:
                    out.z_zeros.append((b, t))
                    y[2 * n + b] = 0.0
                continue
            if hasattr(evs[c], "plastic"):
                q, sg = evs[c].plastic
                if hasattr(evs[c], "turn"):  # (its strain turned back: its yield is looked for again)
                    left[q] = 0
                elif mode[q] == 0:
                    mode[q], left[q] = int(sg), 0
                    out.yields.append((q, t))
                else:
                    mode[q] = 0
                    out.sticks.append((q, t))
                    # (it leaves the yield it stuck at where its strain's acceleration heads away from it)
                    left[q] = int(sg) if -sg * along(rhs(t, y), wp[q])[1] > 0.0 else 0
                continue
            c = evs[c].contact
            if inside[c]:
                inside[c] = False
                relax[c] = (max(contacts[c][0](y)[0], 0.0), t)
                out.contact_ends.append((c, t))
            else:
                inside[c] = True
                out.contact_starts.append((c, t))
    out.y, out.z = y[:2 * n], y[2 * n:]
    out.tracked_max, out.tracked_min = top, bottom
    out.vector_max = longest
    out.abs_acc_max = acc_top if track_acceleration else None
    return out
