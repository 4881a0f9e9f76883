#include "isolator.hpp"

#include <algorithm>
#include <cmath>

#include "events.hpp"

namespace pounding {

double backbone_force_at_break(const System& sy, int j) {
    double f = sy.slopes[0] * sy.breaks[0];
    for (int i = 1; i <= j; ++i) f += sy.slopes[i] * (sy.breaks[i] - sy.breaks[i - 1]);
    return f;
}

IsoLinear iso_linear(const System& sy, const double* st) {
    const int n_sp = sy.n_springs();
    const int base = sy.lay.base;
    if (sy.rule == RULE_ELASTIC) {
        const int r = static_cast<int>(st[sy.lay.region]);
        const int a = std::abs(r);
        const double k = sy.slopes[a];
        if (a == 0) return {k, 0.0};
        const double off = backbone_force_at_break(sy, a - 1) - k * sy.breaks[a - 1];
        return {k, r > 0 ? off : -off};
    }
    double k = sy.slopes[n_sp];
    double r0 = 0.0, kmax = 0.0;
    for (int i = 0; i < n_sp + 1; ++i) kmax = std::max(kmax, std::abs(sy.slopes[i]));
    for (int i = 0; i < n_sp; ++i) {
        const double ki = sy.slopes[i] - sy.slopes[i + 1];
        const double s = st[base + n_sp + i];
        if (s == 0.0) {
            k += ki;
            r0 -= ki * st[base + i];
        } else {
            r0 += s * ki * sy.breaks[i];
        }
    }
    if (std::abs(k) < 1e-12 * kmax) k = 0.0;  // exactly plastic: keep the closed form's k = 0 branch exact
    return {k, r0};
}

double iso_energy(const System& sy, const double* st, double d) {
    const int n_sp = sy.n_springs();
    const int base = sy.lay.base;
    if (sy.rule == RULE_ELASTIC) {
        const double a = std::abs(d);
        double u = 0.0, lo = 0.0, f_lo = 0.0;
        for (int j = 0; j < n_sp + 1; ++j) {
            const double hi = j < n_sp ? sy.breaks[j] : a;
            const double top = std::min(a, hi);
            if (top > lo) u += f_lo * (top - lo) + 0.5 * sy.slopes[j] * (top - lo) * (top - lo);
            if (a <= hi) break;
            f_lo += sy.slopes[j] * (hi - lo);
            lo = hi;
        }
        return u;
    }
    double u = 0.5 * sy.slopes[n_sp] * d * d;
    for (int i = 0; i < n_sp; ++i) {
        const double e = d - st[base + i];
        u += 0.5 * (sy.slopes[i] - sy.slopes[i + 1]) * e * e;
    }
    return u;
}

namespace {
int add(const System& sy, EventRow* evs, int n, double alpha, double beta, double gamma, int action, int index,
        double direction) {
    EventRow& e = evs[n];
    e.kind = KIND_LINEAR;
    e.i = sy.iso_i;
    e.j = sy.iso_j;
    e.alpha = alpha;
    e.beta = beta;
    e.gamma = gamma;
    e.side = SIDE_NONE;
    e.action = action;
    e.index = index;
    e.dir = direction;
    return n + 1;
}
}  // namespace

int iso_events(const System& sy, const double* st, EventRow* evs, int n) {
    const int n_sp = sy.n_springs();
    const int base = sy.lay.base;
    if (n_sp == 0) return n;
    if (sy.rule == RULE_ELASTIC) {
        const int r = static_cast<int>(st[sy.lay.region]);
        const int a = std::abs(r);
        if (r >= 0) {
            if (a < n_sp) n = add(sy, evs, n, sy.breaks[a], -1.0, 0.0, ACT_REGION, 0, 1.0);
            const double lower = r > 0 ? sy.breaks[a - 1] : -sy.breaks[0];
            n = add(sy, evs, n, -lower, 1.0, 0.0, ACT_REGION, 0, -1.0);
        } else {
            n = add(sy, evs, n, -sy.breaks[a - 1], -1.0, 0.0, ACT_REGION, 0, 1.0);
            if (a < n_sp) n = add(sy, evs, n, sy.breaks[a], 1.0, 0.0, ACT_REGION, 0, -1.0);
        }
        return n;
    }
    double slip_dir = 0.0;
    for (int i = 0; i < n_sp; ++i) {
        const double s = st[base + n_sp + i];
        if (s == 0.0) {
            const double u = st[base + i];
            n = add(sy, evs, n, sy.breaks[i] + u, -1.0, 0.0, ACT_YIELD, i, 1.0);
            n = add(sy, evs, n, sy.breaks[i] - u, 1.0, 0.0, ACT_YIELD, i, -1.0);
        } else {
            slip_dir = s;
        }
    }
    if (slip_dir != 0.0) n = add(sy, evs, n, 0.0, 0.0, slip_dir, ACT_REVERSAL, 0, 0.0);
    return n;
}

double iso_advance(const System& sy, double* st, double d_start, double d_end) {
    const int n_sp = sy.n_springs();
    const int base = sy.lay.base;
    double work = 0.0;
    if (sy.rule == RULE_ELASTIC) return work;
    for (int i = 0; i < n_sp; ++i) {
        const double s = st[base + n_sp + i];
        if (s != 0.0) {
            work += (sy.slopes[i] - sy.slopes[i + 1]) * sy.breaks[i] * std::abs(d_end - d_start);
            st[base + i] = d_end - s * sy.breaks[i];
        }
    }
    return work;
}

void iso_transition(const System& sy, double* st, int action, int index, double direction) {
    const int n_sp = sy.n_springs();
    const int base = sy.lay.base;
    if (action == ACT_REGION) {
        st[sy.lay.region] += direction;
    } else if (action == ACT_YIELD) {
        st[base + n_sp + index] = direction;
        st[base + index] = iso_u(sy, st) - direction * sy.breaks[index];
    } else if (action == ACT_REVERSAL) {
        for (int i = 0; i < n_sp; ++i) st[base + n_sp + i] = 0.0;
    }
}

}  // namespace pounding
