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

int iso_element_of_spring(const System& sy, int index) {
    int e = 0;
    while (index >= sy.hyst[static_cast<size_t>(e)].first + sy.hyst[static_cast<size_t>(e)].n_springs()) ++e;
    return e;
}

namespace {
// a friction element's slip force in its linear phase, N: its friction, a velocity dependence's fast one
// (the rest, iso_rate_force, numerical)
double slip_friction(const Hysteretic& h) { return h.friction_rate != 0.0 ? h.friction_fast : h.friction; }

// ---------------------------------------------------------------- surfaces in series (the header's rule)

// a series's surfaces in the state: their displacements u_g (m) and states (0 held, +-1 slipping that way, +-2
// held at the rigid ring on that side, +-3 slipping that way on a stiff ring)
struct Surfaces {
    const Hysteretic& h;
    double* u;
    double* state;
    int n() const { return static_cast<int>(h.slopes.size()); }
    double ring(int g) const { return h.surface_ring.empty() ? 0.0 : h.surface_ring[static_cast<size_t>(g)]; }
    bool slips(int g, double s) const { return state[g] == s || state[g] == 3.0 * s; }
    bool slipping(int g) const { return std::abs(state[g]) == 1.0 || std::abs(state[g]) == 3.0; }
};
Surfaces surfaces(const System& sy, const Hysteretic& h, const double* st) {
    double* s = const_cast<double*>(st);  // (read-only where st is: the callers that write own it)
    return {h, s + sy.lay.base + h.first, s + sy.lay.base + sy.lay.n_sp + h.first};
}

// surface g's spring force at u (N): k_g u, and beyond its travel a stiff ring's k_r (|u| - d_g)
double spring_force(const Surfaces& sf, int g, double u) {
    const double beyond = std::abs(u) - sf.h.breaks[static_cast<size_t>(g)];
    const double ring = sf.ring(g) > 0.0 && beyond > 0.0 ? sf.ring(g) * beyond : 0.0;
    return sf.h.slopes[g] * u + (u > 0.0 ? ring : -ring);
}
// a surface slipping the way s: u_g = (F - s F_g + c) / k, its stiffness k and offset c (N) within its travel
// (k_g, 0) or on a stiff ring (k_g + k_r, k_r d_g sign(u_g))
struct SlipSpring { double k, c; };
SlipSpring slip_spring(const Surfaces& sf, int g, double s) {
    if (sf.state[g] != 3.0 * s) return {sf.h.slopes[g], 0.0};
    const double kr = sf.ring(g), d = sf.h.breaks[static_cast<size_t>(g)];
    return {sf.h.slopes[g] + kr, sf.u[g] > 0.0 ? kr * d : -kr * d};
}
// the state of surface g as it starts to slip the way s: on its stiff ring where it is there or beyond it on
// that side, or beyond its travel on the other side (it comes off at -s d_g); else within its travel
double slip_state(const Surfaces& sf, int g, double s) {
    if (sf.ring(g) == 0.0) return s;
    const double d = sf.h.breaks[static_cast<size_t>(g)], su = s * sf.u[g];
    return su >= d * (1.0 - 1e-12) || su < -d * (1.0 + 1e-12) ? 3.0 * s : s;
}

// the force at which surface g, held, slips the way s (N): its spring's force + s F_g (+-inf at its rigid
// ring that way)
double threshold(const Surfaces& sf, int g, double s) {
    if (sf.state[g] == 2.0 * s) return s * INF;
    return spring_force(sf, g, sf.u[g]) + s * sf.h.surface_friction[g];
}
// the force at which the series, held, slips the way s: the lowest threshold up, the highest down
double series_threshold(const Surfaces& sf, double s) {
    double best = s * INF;
    for (int g = 0; g < sf.n(); ++g) {
        const double t = threshold(sf, g, s);
        if (s * t < s * best) best = t;
    }
    return best;
}
// its force while it slips the way s with the surfaces that slip that way: k u + r0 (k 0 when none slips)
IsoLinear series_linear(const Surfaces& sf, double s) {
    double compliance = 0.0, held = 0.0, offset = 0.0;
    for (int g = 0; g < sf.n(); ++g) {
        if (sf.slips(g, s)) {
            const SlipSpring sp = slip_spring(sf, g, s);
            compliance += 1.0 / sp.k;
            offset += (s * sf.h.surface_friction[g] - sp.c) / sp.k;
        } else {
            held += sf.u[g];
        }
    }
    if (compliance == 0.0) return {0.0, 0.0};  // (its travel used up: the run stops)
    const double k = 1.0 / compliance;
    return {k, k * (offset - held)};
}
// the held surfaces whose threshold the way s is the force f (to rounding) slip that way
void slip_at(const Surfaces& sf, double s, double f) {
    double scale = std::abs(f);
    for (int g = 0; g < sf.n(); ++g) scale += sf.h.surface_friction[g];
    for (int g = 0; g < sf.n(); ++g)
        if (!sf.slipping(g) && std::abs(threshold(sf, g, s) - f) <= 1e-9 * scale) sf.state[g] = slip_state(sf, g, s);
}
// the slipping surfaces held where they are (a stick)
void hold(const Surfaces& sf) {
    for (int g = 0; g < sf.n(); ++g)
        if (sf.slipping(g)) sf.state[g] = 0.0;
}
}  // namespace

IsoLinear iso_linear(const System& sy, int e, const double* st) {
    const Hysteretic& h = sy.hyst[static_cast<size_t>(e)];
    const int n_sp = h.n_springs();
    if (h.series()) {  // (held: the tie takes all of its force)
        const double s = st[sy.lay.region + e];
        return s != 0.0 ? series_linear(surfaces(sy, h, st), s) : IsoLinear{0.0, 0.0};
    }
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
    if (h.series()) {  // (each surface's spring; a slipping one's displacement from the force at d)
        const Surfaces sf = surfaces(sy, h, st);
        const double s = st[sy.lay.region + e];
        const IsoLinear il = iso_linear(sy, e, st);
        const double f = il.k * d + il.r0;
        double w = 0.0;
        for (int g = 0; g < sf.n(); ++g) {
            double ug = sf.u[g];
            if (s != 0.0 && sf.slips(g, s)) {
                const SlipSpring sp = slip_spring(sf, g, s);
                ug = (f - s * h.surface_friction[g] + sp.c) / sp.k;
            }
            const double beyond = std::max(std::abs(ug) - h.breaks[static_cast<size_t>(g)], 0.0);
            w += 0.5 * h.slopes[g] * ug * ug + 0.5 * sf.ring(g) * beyond * beyond;
        }
        return w;
    }
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
    static_cast<Pair&>(r) = h;
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

namespace {
// a series's event rows: slipping, its slip's end and each surface's threshold or ring (at a value of u);
// held, the tie's force reaching its thresholds
int series_events(const System& sy, const double* st, int e, EventRow* evs, int n) {
    const Hysteretic& h = sy.hyst[static_cast<size_t>(e)];
    const Surfaces sf = surfaces(sy, h, st);
    const double s = st[sy.lay.region + e];
    if (s == 0.0) {
        const int bond = sy.nc() + e;
        const double up = series_threshold(sf, 1.0), down = series_threshold(sf, -1.0);
        if (std::isfinite(up)) n = add(h, evs, n, up, -1.0, 0.0, ACT_SLIP, e, 1.0, KIND_STICK, bond);
        if (std::isfinite(down)) n = add(h, evs, n, -down, 1.0, 0.0, ACT_SLIP, e, -1.0, KIND_STICK, bond);
        return n;
    }
    n = add(h, evs, n, 0.0, 0.0, s, ACT_STICK, e, 0.0, KIND_LINEAR, SIDE_VELOCITY);
    const IsoLinear il = series_linear(sf, s);
    if (il.k == 0.0) return n;
    for (int g = 0; g < sf.n(); ++g) {
        double f;  // the force where it happens: a held surface's threshold, a slipping one's ring
        int action;
        if (sf.state[g] == s) {
            if (!std::isfinite(h.breaks[static_cast<size_t>(g)])) continue;
            f = s * (h.slopes[g] * h.breaks[g] + h.surface_friction[g]);
            action = ACT_RING;
        } else if (sf.state[g] == 3.0 * s) {  // on a stiff ring: off it where it comes back inside its travel
            if (s * sf.u[g] > 0.0) continue;  // (pressing on into it)
            f = s * (h.surface_friction[g] - h.slopes[g] * h.breaks[g]);
            action = ACT_RING_OFF;
        } else {
            f = threshold(sf, g, s);
            if (!std::isfinite(f)) continue;
            action = ACT_SURFACE_SLIP;
        }
        const double u_at = (f - il.r0) / il.k;  // (the slip moves u the way s: g = s (u_at - u) >= 0 before)
        n = add(h, evs, n, s * u_at, -s, 0.0, action, h.first + g, s);
    }
    return n;
}
}  // namespace

int iso_events(const System& sy, const double* st, EventRow* evs, int n) {
    for (int e = 0; e < sy.n_h(); ++e) {
        const Hysteretic& h = sy.hyst[static_cast<size_t>(e)];
        const int n_sp = h.n_springs();
        if (h.series()) {
            n = series_events(sy, st, e, evs, n);
            continue;
        }
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
        const double d_start = rel(x_start, h), d_end = rel(x_end, h);
        if (h.series()) {  // (the slipping surfaces moved with the force, each doing its friction's work)
            const double s = st[sy.lay.region + e];
            if (s == 0.0) continue;
            const Surfaces sf = surfaces(sy, h, st);
            const IsoLinear il = series_linear(sf, s);
            const double f_start = il.k * d_start + il.r0, f_end = il.k * d_end + il.r0;
            for (int g = 0; g < sf.n(); ++g) {
                if (!sf.slips(g, s)) continue;
                const SlipSpring sp = slip_spring(sf, g, s);
                work += h.surface_friction[g] * std::abs(f_end - f_start) / sp.k;
                sf.u[g] = (f_end - s * h.surface_friction[g] + sp.c) / sp.k;
            }
            continue;
        }
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

bool iso_slips(const System& sy, const double* st) {
    for (int e = 0; e < sy.n_h(); ++e) {
        const Hysteretic& h = sy.hyst[static_cast<size_t>(e)];
        if (h.rule == RULE_ELASTIC) continue;
        if (h.series() || h.rule == RULE_FRICTION) {
            if (st[sy.lay.region + e] != 0.0) return true;
            continue;
        }
        const double* dir = st + sy.lay.base + sy.lay.n_sp + h.first;
        for (int i = 0; i < h.n_springs(); ++i)
            if (dir[i] != 0.0) return true;
    }
    return false;
}

void iso_transition(const System& sy, double* st, int action, int index, double direction) {
    const int base = sy.lay.base, n_sp = sy.lay.n_sp;
    if (action == ACT_CIRCLE_SLIP || action == ACT_CIRCLE_STICK) {  // (a plastic circle: both mates switch)
        const Hysteretic& h = sy.hyst[static_cast<size_t>(index)];
        const bool slip = action == ACT_CIRCLE_SLIP;
        st[sy.lay.region + index] = st[sy.lay.region + h.bw_mate] = slip ? 1.0 : 0.0;
        double& zq = st[sy.lay.zeta + h.bw_slot];
        double& zm = st[sy.lay.zeta + h.bw_mate_slot];
        const double size = std::hypot(zq, zm);
        if (slip && size > 0.0) zq /= size, zm /= size;  // (on the circle: |z| = 1, not its rounding)
        (void)direction;
        return;
    }
    if (action == ACT_REGION) {
        st[sy.lay.region + index] += direction;
    } else if (action == ACT_YIELD) {  // (index: the spring's among the system's)
        const int e = iso_element_of_spring(sy, index);
        const Hysteretic& h = sy.hyst[static_cast<size_t>(e)];
        st[base + n_sp + index] = direction;
        st[base + index] = iso_u(sy, e, st) - direction * h.breaks[index - h.first];
    } else if (action == ACT_REVERSAL) {
        const Hysteretic& h = sy.hyst[static_cast<size_t>(index)];
        if (h.series()) {  // (held, then slipping back from the lowest threshold that way)
            const double s = -st[sy.lay.region + index];
            const Surfaces sf = surfaces(sy, h, st);
            hold(sf);
            st[sy.lay.region + index] = s;
            slip_at(sf, s, series_threshold(sf, s));
            return;
        }
        if (h.rule == RULE_FRICTION) st[sy.lay.region + index] = -st[sy.lay.region + index];
        for (int i = 0; i < h.n_springs(); ++i) st[base + n_sp + h.first + i] = 0.0;
    } else if (action == ACT_SLIP) {
        st[sy.lay.region + index] = direction;
        const Hysteretic& h = sy.hyst[static_cast<size_t>(index)];
        if (h.series()) {  // (from rest: the surfaces of the lowest threshold that way)
            const Surfaces sf = surfaces(sy, h, st);
            hold(sf);
            slip_at(sf, direction, series_threshold(sf, direction));
        }
    } else if (action == ACT_STICK) {  // the pair's relative velocity zero (the ground's end: the dof's)
        const Hysteretic& h = sy.hyst[static_cast<size_t>(index)];
        st[sy.lay.region + index] = 0.0;
        st[sy.lay.v + h.i] = h.j >= 0 ? st[sy.lay.v + h.j] : 0.0;
        if (h.series()) hold(surfaces(sy, h, st));
    } else if (action == ACT_SURFACE_SLIP || action == ACT_RING || action == ACT_RING_OFF) {  // (index: its spring's)
        const int e = iso_element_of_spring(sy, index);
        const Hysteretic& h = sy.hyst[static_cast<size_t>(e)];
        const Surfaces sf = surfaces(sy, h, st);
        const int g = index - h.first;
        const double s = st[sy.lay.region + e];
        if (action == ACT_RING_OFF) {  // (back inside its travel, slipping on)
            sf.state[g] = s;
            sf.u[g] = -s * h.breaks[static_cast<size_t>(g)];
        } else if (action == ACT_RING && sf.ring(g) > 0.0) {  // (a stiff ring: it slides on against it)
            sf.state[g] = 3.0 * s;
            sf.u[g] = s * h.breaks[static_cast<size_t>(g)];
        } else if (action == ACT_RING) {
            sf.state[g] = 2.0 * s;
            sf.u[g] = s * h.breaks[static_cast<size_t>(g)];
            bool slipping = false;
            for (int q = 0; q < sf.n(); ++q) slipping = slipping || sf.slips(q, s);
            const double next = series_threshold(sf, s);
            // (none slips on: the series, rigid, takes at once the force that starts the next held one, a
            // jump in force at no displacement; none left: the travel is used up, iso_travel_used)
            if (!slipping && std::isfinite(next)) slip_at(sf, s, next);
        } else {
            const double f = threshold(sf, g, s);
            sf.state[g] = slip_state(sf, g, s);
            slip_at(sf, s, f);  // (with any other of the same threshold)
        }
    }
}

double friction_slip_way(const System& sy, const double* st, int e, double tie_force) {
    const Hysteretic& h = sy.hyst[static_cast<size_t>(e)];
    if (h.series()) {  // (every surface held where it is)
        const Surfaces sf = surfaces(sy, h, st);
        if (tie_force > series_threshold(sf, 1.0)) return 1.0;
        return tie_force < series_threshold(sf, -1.0) ? -1.0 : 0.0;
    }
    if (std::abs(tie_force) <= h.friction) return 0.0;
    return tie_force > 0.0 ? 1.0 : -1.0;  // (the way D pushes: the way the pair accelerates)
}

double friction_threshold_way(const System& sy, const double* st, int e, double tie_force) {
    const Hysteretic& h = sy.hyst[static_cast<size_t>(e)];
    double up = h.friction, down = -h.friction;
    if (h.series()) {
        const Surfaces sf = surfaces(sy, h, st);
        up = series_threshold(sf, 1.0);
        down = series_threshold(sf, -1.0);
    }
    return std::abs(tie_force - up) <= std::abs(tie_force - down) ? 1.0 : -1.0;
}

bool iso_travel_used(const System& sy, const double* st, int e) {
    const Hysteretic& h = sy.hyst[static_cast<size_t>(e)];
    const double s = st[sy.lay.region + e];
    if (!h.series() || s == 0.0) return false;
    const Surfaces sf = surfaces(sy, h, st);
    for (int g = 0; g < sf.n(); ++g)
        if (sf.slips(g, s)) return false;
    return true;
}

int friction_decision(const System& sy, double* st, int e, double tie_force) {
    const double s = st[sy.lay.region + e];
    const double on = friction_slip_way(sy, st, e, tie_force);
    if (on == 0.0) {
        iso_transition(sy, st, ACT_STICK, e, 0.0);
        return ACT_STICK;
    }
    iso_transition(sy, st, ACT_SLIP, e, on);
    return on == -s ? ACT_REVERSAL : ACT_SLIP;
}

IsoLinear iso_linear_in_slips(const System& sy, int e, const double* st, double* d_slip, double* follows) {
    const Hysteretic& h = sy.hyst[static_cast<size_t>(e)];
    IsoLinear il = iso_linear(sy, e, st);
    std::fill(d_slip, d_slip + h.n_springs(), 0.0);
    std::fill(follows, follows + h.n_springs(), 0.0);
    if (h.series()) {  // (slipping: F = k (u - the held surfaces' u_h) + k offset, the slipping ones following)
        const Surfaces sf = surfaces(sy, h, st);
        const double s = st[sy.lay.region + e];
        if (s == 0.0 || il.k == 0.0) return il;  // (held: the tie takes its force, every surface a constant)
        for (int g = 0; g < sf.n(); ++g) {
            if (sf.slips(g, s)) {
                follows[g] = il.k / slip_spring(sf, g, s).k;  // (u_g' = F' / K_g)
            } else {
                d_slip[g] = -il.k;
                il.r0 += il.k * sf.u[g];
            }
        }
        return il;
    }
    if (h.rule != RULE_KINEMATIC) return il;  // (a single friction surface: no slips)
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

IsoGuard series_guard(const System& sy, int action, int index, const double* st, double* d_surface) {
    const int e = iso_element_of_spring(sy, index);
    const Hysteretic& h = sy.hyst[static_cast<size_t>(e)];
    const Surfaces sf = surfaces(sy, h, st);
    const double s = st[sy.lay.region + e];
    std::vector<double> follows(static_cast<size_t>(sf.n()));
    const IsoLinear il = iso_linear_in_slips(sy, e, st, d_surface, follows.data());
    if (action == ACT_SURFACE_SLIP) {  // (less its threshold: its spring's force, a stiff ring's past its travel)
        const int g = index - h.first;
        const bool beyond = std::abs(sf.u[g]) > h.breaks[static_cast<size_t>(g)];
        d_surface[g] -= h.slopes[g] + (beyond ? sf.ring(g) : 0.0);
    }
    return {e, il.k, 0.0, -1, s};
}

IsoGuard iso_guard(const System& sy, int action, int index, const double* st, const double* v, const double* acc) {
    if (action == ACT_YIELD) {  // the spring's strain u - slip at +-its break
        const int e = iso_element_of_spring(sy, index);
        return {e, 1.0, 0.0, index, sgn(iso_u(sy, e, st) - st[sy.lay.base + index])};
    }
    if (action == ACT_REVERSAL) return {index, 0.0, 1.0, -1, 0.0};  // the slipping springs stop: u' = 0
    const Hysteretic& h = sy.hyst[static_cast<size_t>(index)];  // ACT_REGION: u at a break
    const double u_rate = rel(v, h);
    const double heading = u_rate != 0.0 ? u_rate : rel(acc, h);
    return {index, 1.0, 0.0, -1, heading > 0.0 ? 1.0 : -1.0};
}

}  // namespace pounding
