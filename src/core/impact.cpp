#include "impact.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "isolator.hpp"
#include "laws.hpp"
#include "impact_parts.hpp"
#include "run_parts.hpp"

namespace pounding::run_parts {

void state_accelerations(const double* st, const System& sy, const Sticking& stk, const double* ag, double* q,
                         double* row, std::vector<double>& au, std::vector<double>& a) {
    const int n = sy.n;
    outputs(st, sy, q, row);
    au.resize(static_cast<size_t>(n));
    a.resize(static_cast<size_t>(n));
    for (int k = 0; k < n; ++k) {
        au[static_cast<size_t>(k)] = row[1 + 2 * n + k] - ag[k];
        a[static_cast<size_t>(k)] = au[static_cast<size_t>(k)];
    }
    if (stk.rings) {  // (a ring held: its row and bias at this state's displacements and velocities)
        static thread_local Sticking fresh;
        fresh = stk;
        fresh.refresh(st + sy.lay.x, st + sy.lay.v);
        fresh.hold(sy.mass, a.data());
        return;
    }
    stk.hold(sy.mass, a.data());
}

namespace {

constexpr int MIN_CHATTER = 3;  // impacts: a shorter sequence followed by a flight is no chatter

void push_chatter(Rows& chatters, int c, double t_first, double t_end, double count, bool accumulated) {
    double* r = chatters.push();
    r[0] = static_cast<double>(c);
    r[1] = t_first;
    r[2] = t_end;
    r[3] = count;
    r[4] = accumulated ? 1.0 : 0.0;
}

// a free rigid stop's running sequence in its accumulators: first impact, impacts, last impact
inline double& seq_first(double* st, const Layout& L, int c) { return st[L.acc_at(c) + A_TSTART]; }
inline double& seq_count(double* st, const Layout& L, int c) { return st[L.acc_at(c) + A_DSTART]; }
inline double& seq_last(double* st, const Layout& L, int c) { return st[L.acc_at(c) + A_PEAK]; }

// the struck pair's sides' masses (a group's, infinite where it cannot move; on the line) and its inverse mass
// with the holds (1/kg: 0 where neither end can move)
struct Struck {
    double mi = INF, mj = INF, inv = 0.0;
    std::vector<double> row;  // (a ring's: its compression's gradient at the impact, its normal's; a line's: empty)
};
Struck struck(const Sticking& stk, const System& sy, const Contact& ct, const double* x) {
    Struck s;
    if (ct.radial.on) {  // (a ring's: always general mode, System::lever_holds)
        s.row.assign(static_cast<size_t>(sy.n), 0.0);
        push_contact(s.row.data(), ct, x, 1.0);
        s.inv = stk.inverse_mass_row(sy.mass, s.row.data());
        return s;
    }
    if (stk.general) {
        s.inv = stk.inverse_mass(sy.mass, ct);
        return s;
    }
    s.mi = stk.side_mass(sy.mass, ct.i);
    s.mj = stk.side_mass(sy.mass, ct.j);
    s.inv = (s.mi < INF ? 1.0 / s.mi : 0.0) + (s.mj < INF ? 1.0 / s.mj : 0.0);
    return s;
}

// an impulse p on contact ct (pushing its dofs by -sign p w) into the velocities v (or, scaled, displacements)
void kick(const Sticking& stk, const System& sy, const Contact& ct, const Struck& s, double* v, double p) {
    if (!s.row.empty()) {
        stk.impulse_row(sy.mass, v, s.row.data(), -p);
        return;
    }
    if (stk.general) {
        stk.impulse(sy.mass, v, ct, -ct.sign * p);
        return;
    }
    if (s.mi < INF) stk.add_velocity(v, ct.i, -ct.sign * p / s.mi);
    if (s.mj < INF) stk.add_velocity(v, ct.j, ct.sign * p / s.mj);
}

// the push of contact c shut (its relative acceleration towards compression, m/s^2) in the state
double push_of(const double* st, const System& sy, const Sticking& stk, int c, const double* ag, double* q, double* row,
               std::vector<double>& au, std::vector<double>& a) {
    const Contact& ct = sy.contact[static_cast<size_t>(c)];
    state_accelerations(st, sy, stk, ag, q, row, au, a);
    return compression(ct, st + sy.lay.x, st + sy.lay.v, a.data()).da;
}

// a ring's push's rates along the held motion (held_push_rates' for a line): P = n . a_s + kappa (a_s the
// accelerations with the other holds, kappa the centripetal term), its first rate n' . a_s + n . a_s' + kappa'
// along the held motion's velocities and accelerations (a_h), a_s' the free accelerations' rate with the other
// holds' projection (jerk: exact where those are lines'); its higher rates left 0 (the chatter's remainder then
// its first order: a chatter's reported end, the state held at its impact either way)
void ring_push_rates(const std::vector<double>& s0, const System& sy, const Sticking& stk, int c, const double* ag,
                     double* q, double* row, const std::vector<double>& jerk, const std::vector<double>& a_h,
                     int order, double* rates) {
    const Layout& L = sy.lay;
    const Contact& ct = sy.contact[static_cast<size_t>(c)];
    static thread_local std::vector<double> au, a_s;
    state_accelerations(s0.data(), sy, stk, ag, q, row, au, a_s);
    rates[0] = ring_push_rate(ct, s0.data() + L.x, s0.data() + L.v, a_s.data(), a_h.data(), jerk.data());
    for (int k = 1; k < order; ++k) rates[k] = 0.0;
}

// the push of contact c's rates in time, d^k P / dt^k for k = 1..order (m/s^(2+k)), along the motion held at
// the stop from the state s0 (at rest against it), into rates[0..order-1]: the free accelerations' derivatives
// -M^-1 (K x^(k) + C x^(k+1)) - a_g^(k), with the other held stops' constraint, x^(k) the held motion's (the same
// with contact c held too: its velocities, accelerations and their rates)
void held_push_rates(std::vector<double>& s0, const System& sy, const Phase& ph, double tau, const Sticking& stk,
                     int c, const double* ag, double* q, double* row, int order, double* rates) {
    const Layout& L = sy.lay;
    const Contact& ct = sy.contact[static_cast<size_t>(c)];
    const int n = sy.n;
    static thread_local std::vector<double> au, a, xs, rate_u;
    static thread_local Sticking held;
    const double in = s0[static_cast<size_t>(L.in_at(c))];
    s0[static_cast<size_t>(L.in_at(c))] = 1.0;
    held.build(sy, s0.data());
    state_accelerations(s0.data(), sy, held, ag, q, row, au, a);
    s0[static_cast<size_t>(L.in_at(c))] = in;
    // the held motion's derivatives x^(k), k = 1..order + 1 (row k - 1 of xs)
    xs.resize(static_cast<size_t>((order + 1) * n));
    std::copy(s0.data() + L.v, s0.data() + L.v + n, xs.begin());
    std::copy(a.begin(), a.end(), xs.begin() + n);
    rate_u.resize(static_cast<size_t>(n));
    const double angle = ph.w * tau + ph.phi;
    const double sn = (ph.axh != 0.0 && order > 1) || !ph.plain ? std::sin(angle) : 0.0, cs = std::cos(angle);
    const double turn[4] = {sn, cs, -sn, -cs};  // (sin's derivatives at the angle)
    const double turn_c[4] = {cs, -sn, -cs, sn};  // (cos's)
    double wk = ph.w;  // (w^k)
    const int loop_order = ct.radial.on ? 1 : order;  // (a ring's: its first rate, ring_push_rates)
    for (int k = 1; k <= loop_order; ++k, wk *= ph.w) {
        // the table's k-th rate: ax1 (k = 1) and the harmonic's, axh w^k sin^(k) (and its second component's)
        const double ag_k = (k == 1 ? ph.ax1 : 0.0) + ph.axh * wk * turn[k % 4];
        const double bg_k = ph.plain ? 0.0 : (k == 1 ? ph.bx1 : 0.0) + wk * (ph.bs * turn[k % 4] + ph.bc * turn_c[k % 4]);
        const double* x = &xs[static_cast<size_t>((k - 1) * n)];
        const double* x1 = &xs[static_cast<size_t>(k * n)];
        for (int i = 0; i < n; ++i) {
            double s = 0.0;
            for (int j = 0; j < n; ++j)
                s += ph.K[static_cast<size_t>(i * n + j)] * x[j] + ph.C[static_cast<size_t>(i * n + j)] * x1[j];
            rate_u[static_cast<size_t>(i)] = -ph.minv[static_cast<size_t>(i)] * s - ph.on(i, ag_k, bg_k);
        }
        if (k < loop_order) {  // (the held motion's next derivative: the same with c held)
            double* next = &xs[static_cast<size_t>((k + 1) * n)];
            std::copy(rate_u.begin(), rate_u.end(), next);
            held.project(sy.mass, next);
        }
        stk.project(sy.mass, rate_u.data());
        rates[k - 1] = ct.sign * rel(rate_u.data(), ct);
    }
    if (ct.radial.on) ring_push_rates(s0, sy, stk, c, ag, q, row, rate_u, a, order, rates);  // (rate_u: k = 1's)
}

// the rate in time of the push of contact c (m/s^3) along the motion held at the stop from the state s0
double held_push_rate(std::vector<double>& s0, const System& sy, const Phase& ph, double tau, const Sticking& stk,
                      int c, const double* ag, double* q, double* row) {
    double rate;
    held_push_rates(s0, sy, ph, tau, stk, c, ag, q, row, 1, &rate);
    return rate;
}

constexpr int PUSH_RATES = 8;  // the push's rates in time the chatter's local model takes

// The chatter's local model: the pair's opening y (m) off the stop, from the impact on (time s), flies as
//     y'' = -(P(s) + c y' + kappa y),   P(s) = sum_n p_n s^n  (n = 0..PUSH_RATES),
// P the push along the motion held at the stop (p_0 at rest against it, the rest its rates in time / n!), c its
// change with the opening's speed (a dashpot), kappa with the opening (a spring).  One mass on a linear isolator
// is this model exactly (a harmonic table's push to its PUSH_RATES-th rate, far below rounding over a chatter's
// remainder short against the table's period).
struct LocalChatter {
    double p[PUSH_RATES + 1];
    double c, kappa, e;
    // the push's Taylor coefficients at s (f[0..PUSH_RATES])
    void push_at(double s, double* f) const {
        std::copy(p, p + PUSH_RATES + 1, f);
        if (s == 0.0) return;
        for (int i = 0; i < PUSH_RATES; ++i)  // (the shift of the polynomial to s, by repeated synthetic division)
            for (int k = PUSH_RATES - 1; k >= i; --k) f[k] += s * f[k + 1];
    }
};

// The first-order sum of the remainder's flights from a rebound u at s: each flight lasts
// 2 u_k / P_k (1 - eps_c / 3 - 2 eps_J / 3) and returns at u_k (1 - 2 eps_c / 3 + 2 eps_J / 3), eps_c = c u_k / P,
// eps_J = J u_k / P^2, P_k the push at its start, J its rate:
// T = 2 u / P [1 / (1 - e) - (2 eps_c + 4 eps_J) e / (3 (1 - e) (1 - e^2)) - (eps_c + 2 eps_J) / (3 (1 - e^2))].
// neglected: its second order, T (eps / (1 - e))^2 with eps^2 the largest of eps_c^2, eps_J^2 and kappa u^2 / P^2
// (the spring's), and the push's change beyond its rate over T, T sum_(n >= 2) |p_n| T^n / P
double first_order_remainder(const LocalChatter& m, double s, double u, double& neglected) {
    double f[PUSH_RATES + 1];
    m.push_at(s, f);
    const double e = m.e, p = f[0], rate = f[1];
    const double eps_c = m.c * u / p, eps_j = rate * u / (p * p);
    const double e2 = 1.0 - e * e;
    const double t = 2.0 * u / p *
                     (1.0 / (1.0 - e) - (2.0 * eps_c + 4.0 * eps_j) * e / (3.0 * (1.0 - e) * e2) -
                      (eps_c + 2.0 * eps_j) / (3.0 * e2));
    const double eps2 = std::max({eps_c * eps_c, eps_j * eps_j, std::abs(m.kappa) * u * u / (p * p)});
    double beyond = 0.0, tn = std::abs(t);
    for (int k = 2; k <= PUSH_RATES; ++k) beyond += std::abs(f[k]) * (tn *= std::abs(t));
    neglected = std::abs(t) * (eps2 / ((1.0 - e) * (1.0 - e)) + beyond / std::abs(p));
    return t;
}

// One flight of the local model from the stop at s with speed u away: its length and the speed it comes back
// with, by the Taylor series of the exact solution, y = sum y_n tau^n (its root that of y / tau, by Newton's
// steps kept inside a bracket).  False when the model's pair does not come back (the push let go).
bool local_flight(const LocalChatter& m, double s, double u, double& tau, double& back) {
    constexpr int TERMS = 64;
    double y[TERMS + 1], f[PUSH_RATES + 1];
    m.push_at(s, f);  // (the push's coefficients in tau)
    if (!(f[0] > 0.0)) return false;
    y[0] = 0.0;
    y[1] = u;
    for (int k = 0; k + 2 <= TERMS; ++k) {
        const double push = k <= PUSH_RATES ? f[k] : 0.0;
        y[k + 2] = -(m.c * (k + 1) * y[k + 1] + m.kappa * y[k] + push) / ((k + 2.0) * (k + 1.0));
    }
    // y(tau) / tau and its derivative, the terms taken while they matter
    int used = TERMS;
    auto over = [&](double x, double& d) {
        double v = 0.0, dv = 0.0;
        for (int k = used; k >= 1; --k) {
            dv = dv * x + v;
            v = v * x + y[k];
        }
        d = dv;
        return v;
    };
    auto terms_for = [&](double x) {  // (the last term above the rounding of u at x)
        double xk = 1.0;
        int last = 1;
        for (int k = 1; k <= TERMS; ++k, xk *= x)
            if (std::abs(y[k]) * xk > 0.25 * EPS * u) last = k;
        return std::min(TERMS, last + 1);
    };
    // a bracket: y > 0 at lo, y < 0 at hi (from the first-order length, 2 u / P)
    double hi = 2.0 * u / f[0], lo = 0.0, d;
    used = terms_for(hi);
    for (int grow = 0; over(hi, d) >= 0.0; ++grow) {
        if (grow == 60) return false;
        lo = hi;
        hi *= 2.0;
        used = terms_for(hi);
    }
    if (used == TERMS && std::abs(y[TERMS]) * std::pow(hi, TERMS - 1) > EPS * u) return false;  // (too long)
    // from the first order's length, 2 u / P (1 - eps_c / 3 - 2 eps_J / 3)
    double x = 2.0 * u / f[0] * (1.0 - m.c * u / (3.0 * f[0]) - 2.0 * f[1] * u / (3.0 * f[0] * f[0]));
    if (!(lo < x && x < hi)) x = 0.5 * (lo + hi);
    for (int it = 0; it < 100; ++it) {
        const double v = over(x, d);
        if (v > 0.0) lo = x; else hi = x;
        double next = d < 0.0 ? x - v / d : 0.5 * (lo + hi);
        if (!(lo < next && next < hi)) next = 0.5 * (lo + hi);
        const bool done = std::abs(next - x) <= 2.0 * EPS * x || hi - lo <= 2.0 * EPS * hi;
        x = next;
        if (done) break;
    }
    tau = x;
    double dy = 0.0;  // y'(tau)
    for (int k = used; k >= 1; --k) dy = dy * tau + k * y[k];
    back = -dy;
    return back > 0.0;
}

// The time from the impact to the accumulation of a chatter that rebounded at u (sides: the struck pair's)
// under the local model above.  While the first-order sum of the rest would neglect more than the rounding of
// the accumulation's instant t + T (its rebounds still a sizeable share of the flight's velocity scales, P / c,
// P^2 / J, P / sqrt(kappa)), the model's flights are taken one by one (exactly, by their series); the rest is
// then summed to first order.  (The switch to the remainder, at a rebound below the run's length resolution,
// can come while the rebounds are still large against those scales: the first order alone missed its second,
// T eps^2 / (1 - e)^2, there.)
double accumulation(const double* st, const System& sy, const Phase& ph, double tau, const Sticking& stk, int c,
                    const double* ag, double u, const Struck& sides, double* q, double* row) {
    const Layout& L = sy.lay;
    const Contact& ct = sy.contact[static_cast<size_t>(c)];
    const double e = law_restitution(ct.p);
    static thread_local std::vector<double> s0, au, a;
    // the state at rest against the stop: the relative velocity brought to zero
    s0.assign(st, st + L.size);
    double* v = s0.data() + L.v;
    const double mu = 1.0 / sides.inv;
    kick(stk, sy, ct, sides, v, -(mu * u));
    const double p_rest = push_of(s0.data(), sy, stk, c, ag, q, row, au, a);
    const double p_out = push_of(st, sy, stk, c, ag, q, row, au, a);
    // the push at the stop opened by dx at rest (the sides moved apart as the impulse moves them)
    double* x = s0.data() + L.x;
    const double dx = 1e-6 * ph.xrun;
    kick(stk, sy, ct, sides, x, mu * dx);
    const double p_open = push_of(s0.data(), sy, stk, c, ag, q, row, au, a);
    std::copy(st + L.x, st + L.x + sy.n, x);
    LocalChatter m;
    held_push_rates(s0, sy, ph, tau, stk, c, ag, q, row, PUSH_RATES, m.p + 1);
    m.p[0] = p_rest;
    double factorial = 1.0;  // (the rates over n!: the push's Taylor coefficients)
    for (int k = 2; k <= PUSH_RATES; ++k) m.p[k] /= (factorial *= k);
    m.c = (p_out - p_rest) / u;
    m.kappa = dx > 0.0 ? (p_open - p_rest) / dx : 0.0;
    m.e = e;
    double neglected;
    const double first = first_order_remainder(m, 0.0, u, neglected);
    if (neglected <= EPS * std::abs(st[T] + first)) return first;  // (the usual case: a cheap closed form)
    constexpr int MAX_FLIGHTS = 1 << 20;
    double s = 0.0, rebound = u;
    for (int k = 0; k < MAX_FLIGHTS; ++k) {
        double flight, back;
        if (!local_flight(m, s, rebound, flight, back)) return first;  // (the model lets go: its first order)
        s += flight;
        rebound = e * back;
        const double rest = first_order_remainder(m, s, rebound, neglected);
        if (neglected <= EPS * std::abs(st[T] + s + rest)) return s + rest;
    }
    return s + first_order_remainder(m, s, rebound, neglected);
}

}  // namespace

void count_impact(double* st, const Layout& L, int c, double t, double window_s, Rows& chatters) {
    if (!(seq_count(st, L, c) > 0.0 && t - seq_last(st, L, c) <= window_s)) {
        if (seq_count(st, L, c) >= MIN_CHATTER)
            push_chatter(chatters, c, seq_first(st, L, c), seq_last(st, L, c), seq_count(st, L, c), false);
        seq_first(st, L, c) = t;
        seq_count(st, L, c) = 0.0;
    }
    seq_count(st, L, c) += 1.0;
    seq_last(st, L, c) = t;
}

void end_sequence(double* st, const Layout& L, int c, double t, Rows& chatters) {
    if (seq_count(st, L, c) >= MIN_CHATTER)
        push_chatter(chatters, c, seq_first(st, L, c), t, seq_count(st, L, c), false);
}

void settle_holds(double* st, const System& sy, const Sticking& stk, double* ledger) {
    if (!stk.general || !stk.any) return;
    double* v = st + sy.lay.v;
    static thread_local std::vector<double> before;
    before.assign(v, v + sy.n);
    stk.project(sy.mass, v);
    double loss = 0.0;  // (P is the mass's orthogonal projection: the energy taken is the change's own)
    for (int k = 0; k < sy.n; ++k) {
        const double dv = before[static_cast<size_t>(k)] - v[k];
        loss += 0.5 * sy.mass[static_cast<size_t>(k)] * dv * dv;
    }
    ledger[L_BUMPER_LOSS] += loss;
}

// After a velocity jump: the springs a hysteretic element slips and the turns of a deformable bumper's law
// follow the new velocities (their reversal events watch a velocity crossing zero, which a jump steps over)
void after_velocity_jump(double* st, const System& sy) {
    const Layout& L = sy.lay;
    const double* v = st + L.v;
    for (int e = 0; e < sy.n_h(); ++e) {
        const Hysteretic& h = sy.hyst[static_cast<size_t>(e)];
        if (h.rule != RULE_KINEMATIC) continue;
        double dir = 0.0;
        for (int i = 0; i < h.n_springs(); ++i)
            if (st[L.base + L.n_sp + h.first + i] != 0.0) dir = st[L.base + L.n_sp + h.first + i];
        if (dir != 0.0 && dir * rel(v, h) <= 0.0) iso_transition(sy, st, ACT_REVERSAL, e, 0.0);
    }
    for (int c = 0; c < sy.nc(); ++c) {
        const Contact& ct = sy.contact[static_cast<size_t>(c)];
        if (st[L.in_at(c)] == 0.0 || law_is_rigid(ct.law)) continue;
        const double turn = law_turn_sign(ct.law, ct.p, st + L.z_at(c));
        if (turn != 0.0 && turn * ct.sign * rel(v, ct) <= 0.0)
            law_after_event(ct.law, ct.p, st + L.z_at(c), st[L.def_at(c)], 0.0);
    }
}

namespace {

// the impulse each held stop of the struck groups would carry were the impulse J (on contact c, Newton's, along
// its normal) to move them as one: P_h = sign_h sum_(its side) side_k m_k (dv_k alone - dv of k's group); the
// first that would pull (P_h < 0), or -1
int tensile_hold(const System& sy, const Sticking& stk, int c, double impulse, const Struck& sides) {
    const Contact& ct = sy.contact[static_cast<size_t>(c)];
    const int n = sy.n;
    const double mi = sides.mi, mj = sides.mj;
    static thread_local std::vector<double> alone, group;
    alone.assign(static_cast<size_t>(n), 0.0);
    group.assign(static_cast<size_t>(n), 0.0);
    if (!sides.row.empty()) {  // (a ring's row)
        for (int k = 0; k < n; ++k) alone[static_cast<size_t>(k)] -= impulse * sides.row[static_cast<size_t>(k)] / sy.mass[static_cast<size_t>(k)];
        kick(stk, sy, ct, sides, group.data(), impulse);
    } else if (stk.general) {  // (alone: M^-1 w's; with the holds: P M^-1 w's)
        int d[4];
        double w[4];
        const int m = ct.entries(d, w);
        for (int q = 0; q < m; ++q) alone[static_cast<size_t>(d[q])] -= ct.sign * impulse * w[q] / sy.mass[static_cast<size_t>(d[q])];
        kick(stk, sy, ct, sides, group.data(), impulse);
    } else {
        alone[static_cast<size_t>(ct.i)] -= ct.sign * impulse / sy.mass[static_cast<size_t>(ct.i)];
        if (ct.j >= 0) alone[static_cast<size_t>(ct.j)] += ct.sign * impulse / sy.mass[static_cast<size_t>(ct.j)];
        stk.add_velocity(group.data(), ct.i, mi < INF ? -ct.sign * impulse / mi : 0.0);
        if (ct.j >= 0) stk.add_velocity(group.data(), ct.j, mj < INF ? ct.sign * impulse / mj : 0.0);
    }
    for (size_t h = 0; h < stk.held.size(); ++h) {
        if (is_tie(stk, static_cast<int>(h))) continue;  // (a system with a friction rule has no rigid stop)
        const double* side = &stk.side[h * static_cast<size_t>(n)];
        double p = 0.0, scale = 0.0;
        for (int k = 0; k < n; ++k) {
            if (side[k] == 0.0) continue;
            const double m = side[k] * sy.mass[static_cast<size_t>(k)];
            p += m * (alone[static_cast<size_t>(k)] - group[static_cast<size_t>(k)]);
            scale += std::abs(m) * (std::abs(alone[static_cast<size_t>(k)]) + std::abs(group[static_cast<size_t>(k)]));
        }
        if (sy.contact[static_cast<size_t>(stk.held[h])].sign * p < -ROUNDING * scale) return stk.held[h];
    }
    return -1;
}

// the held stops' forces (N) in the state: those that would pull let go (after a velocity jump, which changes a
// dashpot's share of a hold's force at once), but contact c's own
void release_pulling(double* st, const System& sy, Sticking& stk, int c, const double* ag, double* q, double* row,
                     Rows& contacts) {
    static thread_local std::vector<double> au, a;
    for (int pass = 0; pass < sy.nc(); ++pass) {
        stk.build(sy, st);
        if (!stk.any) return;
        state_accelerations(st, sy, stk, ag, q, row, au, a);
        int pulls = -1;
        for (size_t h = 0; h < stk.held.size() && pulls < 0; ++h) {
            if (is_tie(stk, static_cast<int>(h))) continue;
            const Contact& ct = sy.contact[static_cast<size_t>(stk.held[h])];
            const double f = stk.force(ct.sign, static_cast<int>(h), sy.mass, au.data(), a.data());
            double scale = 0.0;
            for (int k = 0; k < sy.n; ++k)
                scale += sy.mass[static_cast<size_t>(k)] * (std::abs(au[static_cast<size_t>(k)]) + std::abs(ag[k]));
            if (stk.held[h] != c && f < -ROUNDING * scale) pulls = stk.held[h];
        }
        if (pulls < 0) return;
        rigid_release(st, sy, pulls, contacts);
    }
}

// before an impact on contact c: the holds its impulse would have to pull through let go (their rows); a
// meeting slower than v_res lets none go (its impulse is the rounding's: the motion's forces decide, after it)
void release_tensile(double* st, const System& sy, Sticking& stk, int c, double v_res, Rows& contacts) {
    const Layout& L = sy.lay;
    const Contact& ct = sy.contact[static_cast<size_t>(c)];
    for (int pass = 0; pass < sy.nc(); ++pass) {
        stk.build(sy, st);
        if (!stk.any) return;
        const double vn = compression(ct, st + L.x, st + L.v).dv;
        if (!(vn > v_res)) return;
        const Struck sides = struck(stk, sy, ct, st + L.x);
        const double inv = sides.inv;
        if (inv == 0.0) return;
        const double impulse = (1.0 + law_restitution(ct.p)) * vn / inv;
        const int h = tensile_hold(sy, stk, c, impulse, sides);
        if (h < 0) return;
        rigid_release(st, sy, h, contacts);
    }
}

// the impact itself (rigid_contact without the release of the holds that would pull after it)
bool rigid_contact_(double* st, const System& sy, const Phase& ph, double tau, Sticking& stk, int c, const double* ag,
                    const ImpactScales& sc, double* ledger, Rows& contacts, Rows& chatters, double* q, double* row,
                    double& flight);

}  // namespace

bool rigid_contact(double* st, const System& sy, const Phase& ph, double tau, Sticking& stk, int c, const double* ag,
                   const ImpactScales& sc, double* ledger, Rows& contacts, Rows& chatters, double* q, double* row,
                   double& flight) {
    if (others_touch(st, sy, c, sc.h_min) &&
        impacts_at_once(st, sy, ph, tau, stk, c, ag, sc, ledger, contacts, chatters, q, row)) {
        flight = INF;
        stk.build(sy, st);  // (the holds, if any: most impacts have none to release)
        if (stk.any) release_pulling(st, sy, stk, -1, ag, q, row, contacts);
        return true;
    }
    const Contact& ct = sy.contact[static_cast<size_t>(c)];
    const bool jump = compression(ct, st + sy.lay.x, st + sy.lay.v).dv > 0.0;  // (an impulse to come: velocities jump)
    const bool was_held = st[sy.lay.in_at(c)] != 0.0;
    const bool resolved = rigid_contact_(st, sy, ph, tau, stk, c, ag, sc, ledger, contacts, chatters, q, row, flight);
    // (and where it is newly held: on levers a new hold's constraint changes every other hold's force)
    if (jump || (sy.lever_holds && !was_held && st[sy.lay.in_at(c)] != 0.0)) {
        stk.build(sy, st);
        if (stk.any) release_pulling(st, sy, stk, c, ag, q, row, contacts);
    }
    return resolved;
}

namespace {

bool rigid_contact_(double* st, const System& sy, const Phase& ph, double tau, Sticking& stk, int c, const double* ag,
                    const ImpactScales& sc, double* ledger, Rows& contacts, Rows& chatters, double* q, double* row,
                    double& flight) {
    flight = INF;
    const Layout& L = sy.lay;
    const Contact& ct = sy.contact[static_cast<size_t>(c)];
    const double t = st[T];
    const double e = law_restitution(ct.p);
    double* v = st + L.v;
    release_tensile(st, sy, stk, c, sc.v_res, contacts);  // (a hold the impulse would pull through lets go)
    stk.build(sy, st);
    const Struck sides = struck(stk, sy, ct, st + L.x);
    const double inv = sides.inv;
    if (inv == 0.0) return false;  // (both ends immovable)
    const double mu = 1.0 / inv;
    // the sequence this impact belongs to
    count_impact(st, L, c, t, sc.window_s, chatters);
    // Newton's impact: the normal velocity from vn to -e vn
    const double vn = compression(ct, st + L.x, v).dv;
    const double v_in = ct.radial.on ? vn : rel(v, ct);  // (a ring's: its normal's, jump.cpp's contact_speed)
    double u = 0.0, impulse = 0.0, loss = 0.0;  // the rebound's speed, the impulse, the energy lost
    if (vn > 0.0) {
        impulse = mu * (1.0 + e) * vn;
        kick(stk, sy, ct, sides, v, impulse);
        u = e * vn;
        after_velocity_jump(st, sy);
        loss = 0.5 * mu * (1.0 - e * e) * vn * vn;
        ledger[L_BUMPER_LOSS] += loss;
    }
    if (vn > sc.v_res) {  // (a touch slower than the resolution: computed, not listed)
        double* r = contacts.push();
        r[CC_CONTACT] = static_cast<double>(c);
        r[CC_T_START] = t;
        r[CC_T_END] = t;
        r[CC_V_IN] = v_in;
        r[CC_V_OUT] = ct.radial.on ? compression(ct, st + L.x, v).dv : rel(v, ct);
        r[CC_IMPULSE] = impulse;
        r[CC_PEAK_FORCE] = NaN;  // (an impulse has no peak force)
        r[CC_MAX_COMPRESSION] = 0.0;
        r[CC_DISSIPATION] = loss;
    }
    // does the motion push the stop shut?  (the accelerations with the stops already held)
    struct Scratch { std::vector<double> au, a, s0; };
    static thread_local Scratch scratch;  // (one thread-local lookup)
    std::vector<double>& au = scratch.au;
    std::vector<double>& a = scratch.a;
    std::vector<double>& s0 = scratch.s0;
    state_accelerations(st, sy, stk, ag, q, row, au, a);
    double push = compression(ct, st + L.x, v, a.data()).da;
    double round = ROUNDING * (std::abs(ag[ct.i]) + std::abs(au[static_cast<size_t>(ct.i)]) +
                               (ct.j >= 0 ? std::abs(au[static_cast<size_t>(ct.j)]) : 0.0));
    if (ct.radial.on) {  // (a ring's: every dof of its row's, by its weight, and its centripetal term)
        double s = 0.0;
        for (int k = 0; k < sy.n; ++k)
            s += std::abs(sides.row[static_cast<size_t>(k)]) * (std::abs(ag[k]) + std::abs(au[static_cast<size_t>(k)]));
        round = ROUNDING * (s + std::abs(ring_bend(ct, st + L.x, v)));
    } else if (ct.levered()) {  // (every dof of its pair's, by its weight)
        int d[4];
        double w[4];
        const int m = ct.entries(d, w);
        double s = 0.0;
        for (int k = 0; k < m; ++k) s += std::abs(w[k]) * (std::abs(ag[d[k]]) + std::abs(au[static_cast<size_t>(d[k])]));
        round = ROUNDING * s;
    }
    if (u == 0.0 && std::abs(push) <= round) {  // (no push to rounding, met at rest: the push's rate decides)
        s0.assign(st, st + L.size);
        // (a rate of 0 too, met at rest: the push grows at a higher order, the motion went into the stop)
        push = held_push_rate(s0, sy, ph, tau, stk, c, ag, q, row) >= 0.0 ? round + MIN_NORMAL : -1.0;
    }
    if (!(push > 0.0)) return u > 0.0 || vn > sc.v_res;  // (it flies off, or leaves it at rest: a touch)
    const double remainder = e < 1.0 ? 2.0 * u / (push * (1.0 - e)) : INF;
    const bool hold = u == 0.0 || u * u <= 2.0 * push * sc.h_min || remainder <= sc.local_s;
    if (!hold) {
        flight = 2.0 * u / push;
        return true;
    }
    if (sticking_closes_loop(sy, st, c)) return u > 0.0;  // (a loop of held stops: it bounces instead)
    // (e = 1: a rebound below the resolution never accumulates; it is held at once)
    const double t_acc = u > 0.0 && e < 1.0 ? t + accumulation(st, sy, ph, tau, stk, c, ag, u, sides, q, row) : t;
    if (u > 0.0) {  // the chatter's remainder at once: the relative velocity to rest (in the chatter's row)
        const double impulse = mu * u;
        kick(stk, sy, ct, sides, v, -impulse);
        const double loss = 0.5 * mu * u * u;
        ledger[L_BUMPER_LOSS] += loss;
    }
    if (!stk.general && ct.j < 0 && stk.grp[static_cast<size_t>(ct.i)] < 0) {  // on the stop exactly, at rest on it
        st[L.x + ct.i] = ct.sign * ct.gap;
        v[ct.i] = 0.0;
    }
    after_velocity_jump(st, sy);
    const bool accumulated = u > 0.0;
    if (accumulated || seq_count(st, L, c) >= MIN_CHATTER)
        push_chatter(chatters, c, seq_first(st, L, c), t_acc, seq_count(st, L, c), accumulated);
    // held: its accumulators now the hold's (start, impulse, peak force)
    const int acc = L.acc_at(c);
    st[L.in_at(c)] = 1.0;
    st[L.def_at(c)] = 0.0;
    for (int k = 0; k < N_ACC; ++k) st[acc + k] = 0.0;
    st[acc + A_TSTART] = t;
    stk.build(sy, st);
    settle_holds(st, sy, stk, ledger);
    return true;
}

}  // namespace

void rigid_release(double* st, const System& sy, int c, Rows& contacts) {
    const Layout& L = sy.lay;
    const int acc = L.acc_at(c);
    st[L.in_at(c)] = 0.0;
    double* r = contacts.push();
    r[CC_CONTACT] = static_cast<double>(c);
    r[CC_T_START] = st[acc + A_TSTART];
    r[CC_T_END] = st[T];
    r[CC_V_IN] = 0.0;
    r[CC_V_OUT] = 0.0;
    r[CC_IMPULSE] = st[acc + A_IMPULSE];
    r[CC_PEAK_FORCE] = st[acc + A_PEAK];
    r[CC_MAX_COMPRESSION] = 0.0;
    r[CC_DISSIPATION] = 0.0;
    for (int k = 0; k < N_ACC; ++k) st[acc + k] = 0.0;  // (no sequence running)
}

void close_chatters(const double* st, const System& sy, Rows& chatters) {
    const Layout& L = sy.lay;
    for (int c = 0; c < sy.nc(); ++c) {
        if (!sy.has_b || !law_is_rigid(sy.contact[static_cast<size_t>(c)].law) || st[L.in_at(c)] != 0.0) continue;
        const int acc = L.acc_at(c);
        if (st[acc + A_DSTART] >= MIN_CHATTER)
            push_chatter(chatters, c, st[acc + A_TSTART], st[acc + A_PEAK], st[acc + A_DSTART], false);
    }
}

void held_outputs(const double* st, const System& sy, Sticking& stk, const double* ag, double* row) {
    stk.build(sy, st);
    if (!stk.any) return;
    const int n = sy.n;
    static thread_local std::vector<double> au, a;
    au.resize(static_cast<size_t>(n));
    a.resize(static_cast<size_t>(n));
    for (int k = 0; k < n; ++k) au[static_cast<size_t>(k)] = a[static_cast<size_t>(k)] = row[1 + 2 * n + k] - ag[k];
    stk.hold(sy.mass, a.data());
    for (int k = 0; k < n; ++k) row[1 + 2 * n + k] = a[static_cast<size_t>(k)] + ag[k];
    double* fe = row + 1 + 3 * n;  // (each element's force, then each contact's)
    for (size_t h = 0; h < stk.held.size(); ++h) {
        const int b = stk.held[h];
        const double f = stk.force(stk.end_sign[h], static_cast<int>(h), sy.mass, au.data(), a.data());
        if (is_tie(stk, static_cast<int>(h))) fe[b - sy.nc()] += f;  // (a sticking element: its friction force)
        else fe[sy.n_h() + b] = f;
    }
}

double tie_force(double* st, const System& sy, int e, Sticking& stk, const double* ag, double* q, double* row) {
    static thread_local std::vector<double> au, a;
    double& slip = iso_slip_slot(sy, e, st);
    const double was = slip;
    slip = 0.0;
    stk.build(sy, st);
    state_accelerations(st, sy, stk, ag, q, row, au, a);
    const int h = stk.held_of[static_cast<size_t>(sy.nc() + e)];
    const double f = stk.force(1.0, h, sy.mass, au.data(), a.data());
    slip = was;
    return f;
}

}  // namespace pounding::run_parts
