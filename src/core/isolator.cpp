#include "isolator.hpp"

#include <algorithm>
#include <cmath>

#include "events.hpp"

namespace pounding {

double backbone_force_at_break(const Hysteretic& h, int j) {
    double f = h.slopes[0] * h.breaks[0];
    for (int i = 1; i <= j; ++i) f += h.slopes[i] * (h.breaks[i] - h.breaks[i - 1]);
    return f;
}

bool iso_is_friction(const Hysteretic& h) { return h.rule == RULE_FRICTION; }

namespace {
// a friction element's slip force in its linear phase, N: its friction, a velocity dependence's fast one
// (the rest, iso_rate_force, numerical)
double slip_friction(const Hysteretic& h) { return h.friction_rate != 0.0 ? h.friction_fast : h.friction; }
}  // namespace

IsoLinear iso_linear(const System& sy, int e, const double* st) {
    const Hysteretic& h = sy.hyst[static_cast<size_t>(e)];
    const int n_sp = h.n_springs();
    if (h.rule == RULE_FRICTION) return {h.slopes[0], st[sy.lay.region + e] * slip_friction(h)};  // (0: sticks)
    if (h.rule == RULE_ELASTIC) {
        const int r = static_cast<int>(st[sy.lay.region + e]);
        const int a = std::abs(r);
        const double k = h.slopes[a];
        if (a == 0) return {k, 0.0};
        const double off = backbone_force_at_break(h, a - 1) - k * h.breaks[a - 1];
        return {k, r > 0 ? off : -off};
    }
    const double* slip = st + sy.lay.base + h.first;
    const double* dir = st + sy.lay.base + sy.lay.n_sp + h.first;
    double k = h.slopes[n_sp];
    double r0 = 0.0, kmax = 0.0;
    for (int i = 0; i < n_sp + 1; ++i) kmax = std::max(kmax, std::abs(h.slopes[i]));
    for (int i = 0; i < n_sp; ++i) {
        const double ki = h.slopes[i] - h.slopes[i + 1];
        if (dir[i] == 0.0) {
            k += ki;
            r0 -= ki * slip[i];
        } else {
            r0 += dir[i] * ki * h.breaks[i];
        }
    }
    if (std::abs(k) < 1e-12 * kmax) k = 0.0;  // exactly plastic: keep the closed form's k = 0 branch exact
    return {k, r0};
}

double iso_energy(const System& sy, int e, const double* st, double d) {
    const Hysteretic& h = sy.hyst[static_cast<size_t>(e)];
    const int n_sp = h.n_springs();
    if (h.rule == RULE_FRICTION) return 0.5 * h.slopes[0] * d * d;
    if (h.rule == RULE_ELASTIC) {
        const double a = std::abs(d);
        double u = 0.0, lo = 0.0, f_lo = 0.0;
        for (int j = 0; j < n_sp + 1; ++j) {
            const double hi = j < n_sp ? h.breaks[j] : a;
            const double top = std::min(a, hi);
            if (top > lo) u += f_lo * (top - lo) + 0.5 * h.slopes[j] * (top - lo) * (top - lo);
            if (a <= hi) break;
            f_lo += h.slopes[j] * (hi - lo);
            lo = hi;
        }
        return u;
    }
    const double* slip = st + sy.lay.base + h.first;
    double u = 0.5 * h.slopes[n_sp] * d * d;
    for (int i = 0; i < n_sp; ++i) {
        const double q = d - slip[i];
        u += 0.5 * (h.slopes[i] - h.slopes[i + 1]) * q * q;
    }
    return u;
}

namespace {
int add(const Hysteretic& h, EventRow* evs, int n, double alpha, double beta, double gamma, int action, int index,
        double direction, int kind = KIND_LINEAR, int side = SIDE_NONE) {
    EventRow& r = evs[n];
    r.kind = kind;
    r.i = h.i;
    r.j = h.j;
    r.alpha = alpha;
    r.beta = beta;
    r.gamma = gamma;
    r.side = side;
    r.action = action;
    r.index = index;
    r.dir = direction;
    return n + 1;
}
}  // namespace

int iso_events(const System& sy, const double* st, EventRow* evs, int n) {
    for (int e = 0; e < sy.n_h(); ++e) {
        const Hysteretic& h = sy.hyst[static_cast<size_t>(e)];
        const int n_sp = h.n_springs();
        if (h.rule == RULE_FRICTION) {
            const double s = st[sy.lay.region + e];
            if (s != 0.0) {  // slipping: until s u' comes to zero
                n = add(h, evs, n, 0.0, 0.0, s, ACT_STICK, e, 0.0, KIND_LINEAR, SIDE_VELOCITY);
            } else {  // sticking: until the tie's force D reaches +F (then slips up) or -F (down)
                const int bond = sy.nc() + e;
                n = add(h, evs, n, h.friction, -1.0, 0.0, ACT_SLIP, e, 1.0, KIND_STICK, bond);
                n = add(h, evs, n, h.friction, 1.0, 0.0, ACT_SLIP, e, -1.0, KIND_STICK, bond);
            }
            continue;
        }
        if (n_sp == 0) continue;
        if (h.rule == RULE_ELASTIC) {
            const int r = static_cast<int>(st[sy.lay.region + e]);
            const int a = std::abs(r);
            if (r >= 0) {
                if (a < n_sp) n = add(h, evs, n, h.breaks[a], -1.0, 0.0, ACT_REGION, e, 1.0);
                const double lower = r > 0 ? h.breaks[a - 1] : -h.breaks[0];
                n = add(h, evs, n, -lower, 1.0, 0.0, ACT_REGION, e, -1.0);
            } else {
                n = add(h, evs, n, -h.breaks[a - 1], -1.0, 0.0, ACT_REGION, e, 1.0);
                if (a < n_sp) n = add(h, evs, n, h.breaks[a], 1.0, 0.0, ACT_REGION, e, -1.0);
            }
            continue;
        }
        const double* slip = st + sy.lay.base + h.first;
        const double* dir = st + sy.lay.base + sy.lay.n_sp + h.first;
        double slip_dir = 0.0;
        for (int i = 0; i < n_sp; ++i) {
            if (dir[i] == 0.0) {
                const double u = slip[i];
                n = add(h, evs, n, h.breaks[i] + u, -1.0, 0.0, ACT_YIELD, h.first + i, 1.0);
                n = add(h, evs, n, h.breaks[i] - u, 1.0, 0.0, ACT_YIELD, h.first + i, -1.0);
            } else {
                slip_dir = dir[i];
            }
        }
        if (slip_dir != 0.0) n = add(h, evs, n, 0.0, 0.0, slip_dir, ACT_REVERSAL, e, 0.0);
    }
    return n;
}

double iso_advance(const System& sy, double* st, const double* x_start, const double* x_end) {
    double work = 0.0;
    for (int e = 0; e < sy.n_h(); ++e) {
        const Hysteretic& h = sy.hyst[static_cast<size_t>(e)];
        if (h.rule == RULE_ELASTIC) continue;
        const int n_sp = h.n_springs();
        const double d_start = rel(x_start, h.i, h.j), d_end = rel(x_end, h.i, h.j);
        if (h.rule == RULE_FRICTION) {  // (a slip never turns inside a sub-interval: its end is an event)
            if (st[sy.lay.region + e] != 0.0)  // (a velocity dependence's rest: numeric_contributions)
                work += slip_friction(h) * std::abs(d_end - d_start);
            continue;
        }
        double* slip = st + sy.lay.base + h.first;
        const double* dir = st + sy.lay.base + sy.lay.n_sp + h.first;
        for (int i = 0; i < n_sp; ++i) {
            if (dir[i] != 0.0) {
                work += (h.slopes[i] - h.slopes[i + 1]) * h.breaks[i] * std::abs(d_end - d_start);
                slip[i] = d_end - dir[i] * h.breaks[i];
            }
        }
    }
    return work;
}

void iso_transition(const System& sy, double* st, int action, int index, double direction) {
    const int base = sy.lay.base, n_sp = sy.lay.n_sp;
    if (action == ACT_REGION) {
        st[sy.lay.region + index] += direction;
    } else if (action == ACT_YIELD) {  // (index: the spring's among the system's)
        int e = 0;
        while (index >= sy.hyst[static_cast<size_t>(e)].first + sy.hyst[static_cast<size_t>(e)].n_springs()) ++e;
        const Hysteretic& h = sy.hyst[static_cast<size_t>(e)];
        st[base + n_sp + index] = direction;
        st[base + index] = iso_u(sy, e, st) - direction * h.breaks[index - h.first];
    } else if (action == ACT_REVERSAL) {
        const Hysteretic& h = sy.hyst[static_cast<size_t>(index)];
        if (h.rule == RULE_FRICTION) st[sy.lay.region + index] = -st[sy.lay.region + index];
        for (int i = 0; i < h.n_springs(); ++i) st[base + n_sp + h.first + i] = 0.0;
    } else if (action == ACT_SLIP) {
        st[sy.lay.region + index] = direction;
    } else if (action == ACT_STICK) {  // the pair's relative velocity zero (the ground's end: the dof's)
        const Hysteretic& h = sy.hyst[static_cast<size_t>(index)];
        st[sy.lay.region + index] = 0.0;
        st[sy.lay.v + h.i] = h.j >= 0 ? st[sy.lay.v + h.j] : 0.0;
    }
}

int friction_decision(const System& sy, double* st, int e, double tie_force) {
    const Hysteretic& h = sy.hyst[static_cast<size_t>(e)];
    const double s = st[sy.lay.region + e];
    if (std::abs(tie_force) <= h.friction) {
        iso_transition(sy, st, ACT_STICK, e, 0.0);
        return ACT_STICK;
    }
    const double on = tie_force > 0.0 ? 1.0 : -1.0;  // (the way D pushes: the way the pair accelerates)
    iso_transition(sy, st, ACT_SLIP, e, on);
    return on == -s ? ACT_REVERSAL : ACT_SLIP;
}

IsoLinear iso_linear_in_slips(const System& sy, int e, const double* st, double* d_slip, double* follows) {
    const Hysteretic& h = sy.hyst[static_cast<size_t>(e)];
    IsoLinear il = iso_linear(sy, e, st);
    std::fill(d_slip, d_slip + h.n_springs(), 0.0);
    std::fill(follows, follows + h.n_springs(), 0.0);
    if (h.rule != RULE_KINEMATIC) return il;  // (friction: no exact monodromy yet, Python refuses it)  // (its slips are not used: constants of the monodromy)
    const double* slip = st + sy.lay.base + h.first;
    const double* dir = st + sy.lay.base + sy.lay.n_sp + h.first;
    for (int i = 0; i < h.n_springs(); ++i) {
        const bool sticks = dir[i] == 0.0;
        d_slip[i] = sticks ? -(h.slopes[i] - h.slopes[i + 1]) : 0.0;
        follows[i] = sticks ? 0.0 : 1.0;
        il.r0 -= d_slip[i] * slip[i];
    }
    return il;
}

IsoGuard iso_guard(const System& sy, int action, int index, const double* st, const double* v, const double* acc) {
    if (action == ACT_YIELD) {  // the spring's strain u - slip at +-its break
        int e = 0;
        while (index >= sy.hyst[static_cast<size_t>(e)].first + sy.hyst[static_cast<size_t>(e)].n_springs()) ++e;
        return {e, 1.0, 0.0, index, sgn(iso_u(sy, e, st) - st[sy.lay.base + index])};
    }
    if (action == ACT_REVERSAL) return {index, 0.0, 1.0, -1, 0.0};  // the slipping springs stop: u' = 0
    const Hysteretic& h = sy.hyst[static_cast<size_t>(index)];  // ACT_REGION: u at a break
    const double u_rate = rel(v, h.i, h.j);
    const double heading = u_rate != 0.0 ? u_rate : rel(acc, h.i, h.j);
    return {index, 1.0, 0.0, -1, heading > 0.0 ? 1.0 : -1.0};
}

}  // namespace pounding
