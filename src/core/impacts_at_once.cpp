// Impacts at one instant on rigid stops that share a dof (impact_parts.hpp): Moreau's impact law over the
// touching contacts, a linear complementarity problem solved over its active sets.
#include <algorithm>
#include <cmath>
#include <vector>

#include "impact_parts.hpp"
#include "isolator.hpp"
#include "laws.hpp"
#include "linalg.hpp"

namespace pounding::run_parts {

namespace {

constexpr int MAX_AT_ONCE = 12;  // contacts: beyond this many the impacts are taken one after the other

int bits(int s) {  // (the members of a set)
    int count = 0;
    for (; s != 0; s &= s - 1) ++count;
    return count;
}

// a rigid stop at its stop (held, or within h of it)
bool touching(const double* st, const System& sy, int d, double h) {
    const Contact& ct = sy.contact[static_cast<size_t>(d)];
    if (!law_is_rigid(ct.law)) return false;
    if (st[sy.lay.in_at(d)] != 0.0) return true;
    return compression_of(ct, st + sy.lay.x) >= -h;
}

// the touching rigid stops that reach contact c through shared dofs (c first)
std::vector<int> cluster_of(const double* st, const System& sy, int c, double h) {
    std::vector<int> out{c};
    std::vector<char> dof(static_cast<size_t>(sy.n), 0), in(static_cast<size_t>(sy.nc()), 0);
    in[static_cast<size_t>(c)] = 1;
    int d4[4];
    double w4[4];
    auto mark = [&](const Contact& ct) {  // (a ring's second pair too)
        for (const Pair* p : {static_cast<const Pair*>(&ct), ct.radial.on ? &ct.radial.y : nullptr}) {
            if (p == nullptr) continue;
            const int m = p->entries(d4, w4);
            for (int q = 0; q < m; ++q) dof[static_cast<size_t>(d4[q])] = 1;
        }
    };
    auto shares = [&](const Contact& ct) {
        for (const Pair* p : {static_cast<const Pair*>(&ct), ct.radial.on ? &ct.radial.y : nullptr}) {
            if (p == nullptr) continue;
            const int m = p->entries(d4, w4);
            for (int q = 0; q < m; ++q)
                if (dof[static_cast<size_t>(d4[q])]) return true;
        }
        return false;
    };
    mark(sy.contact[static_cast<size_t>(c)]);
    for (bool grew = true; grew;) {
        grew = false;
        for (int d = 0; d < sy.nc(); ++d) {
            if (in[static_cast<size_t>(d)] || !touching(st, sy, d, h)) continue;
            const Contact& ct = sy.contact[static_cast<size_t>(d)];
            if (!shares(ct)) continue;
            in[static_cast<size_t>(d)] = 1;
            out.push_back(d);
            mark(ct);
            grew = true;
        }
    }
    return out;
}

// w = W lam - b >= 0, lam >= 0, lam . w = 0 (W k x k, symmetric positive semidefinite), over the active
// sets in order of size; false where none is found to the rounding
bool solve_lcp(const std::vector<double>& W, const std::vector<double>& b, int k, std::vector<double>& lam) {
    double scale = 0.0, wmax = 0.0;
    for (int a = 0; a < k; ++a) {
        scale = std::max(scale, std::abs(b[static_cast<size_t>(a)]));
        wmax = std::max(wmax, W[static_cast<size_t>(a * k + a)]);
    }
    const double tol = 1e-12 * scale;
    std::vector<int> sets;
    for (int s = 0; s < (1 << k); ++s) sets.push_back(s);
    std::stable_sort(sets.begin(), sets.end(), [](int x, int y) { return bits(x) < bits(y); });
    std::vector<int> idx;
    for (const int s : sets) {
        idx.clear();
        for (int a = 0; a < k; ++a)
            if (s & (1 << a)) idx.push_back(a);
        const int m = static_cast<int>(idx.size());
        Mat A(m, m), r(m, 1);  // (every entry set below)
        for (int p = 0; p < m; ++p) {
            r(p, 0) = b[static_cast<size_t>(idx[static_cast<size_t>(p)])];
            for (int q = 0; q < m; ++q)
                A(p, q) = W[static_cast<size_t>(idx[static_cast<size_t>(p)] * k + idx[static_cast<size_t>(q)])];
        }
        bool ok = m == 0 || solve_checked(A, r, 1e-12 * wmax);  // (a singular active set: the next one)
        if (!ok) continue;
        lam.assign(static_cast<size_t>(k), 0.0);
        for (int p = 0; p < m; ++p) {
            if (r(p, 0) < -tol / std::max(wmax, MIN_NORMAL)) ok = false;
            lam[static_cast<size_t>(idx[static_cast<size_t>(p)])] = std::max(r(p, 0), 0.0);
        }
        for (int a = 0; a < k && ok; ++a) {
            if (s & (1 << a)) continue;
            double w = -b[static_cast<size_t>(a)];
            for (int q = 0; q < k; ++q) w += W[static_cast<size_t>(a * k + q)] * lam[static_cast<size_t>(q)];
            if (w < -tol) ok = false;
        }
        if (ok) return true;
    }
    return false;
}

}  // namespace

bool impacts_at_once(double* st, const System& sy, const Phase& ph, double tau, Sticking& stk, int c, const double* ag,
                     const ImpactScales& sc, double* ledger, Rows& contacts, Rows& chatters, double* q,
                     double* row) {
    const Layout& L = sy.lay;
    const std::vector<int> set = cluster_of(st, sy, c, sc.h_min);
    const int k = static_cast<int>(set.size());
    bool other_free = false, bodies = false;
    for (int a = 0; a < k; ++a) {
        const int d = set[static_cast<size_t>(a)];
        if (a > 0) other_free = other_free || st[L.in_at(d)] == 0.0;
        // (a stop on a lever, a moat's wall struck at a floor's corner, moves a floor's two dofs: a body's)
        bodies = bodies || sy.contact[static_cast<size_t>(d)].j >= 0 || sy.contact[static_cast<size_t>(d)].levered();
    }
    // (one contact, or the held groups' masses do; or one dof between stops on the ground: it is clamped,
    // one stop after the other)
    if (k < 2 || k > MAX_AT_ONCE || !other_free || !bodies) return false;
    const int n = sy.n;
    double* v = st + L.v;
    // each contact's row of J (its compression rate J v) and W = J M^-1 J^T
    std::vector<double> J(static_cast<size_t>(k * n), 0.0), W(static_cast<size_t>(k * k), 0.0);
    std::vector<double> u0(static_cast<size_t>(k)), b(static_cast<size_t>(k)), lam;
    for (int a = 0; a < k; ++a) {
        const Contact& ct = sy.contact[static_cast<size_t>(set[static_cast<size_t>(a)])];
        push_contact(&J[static_cast<size_t>(a * n)], ct, st + L.x, 1.0);  // (its weights w, signed; a ring's normal)
    }
    for (int a = 0; a < k; ++a) {
        double u = 0.0;
        for (int i = 0; i < n; ++i) u += J[static_cast<size_t>(a * n + i)] * v[i];
        u0[static_cast<size_t>(a)] = u;
        const double e = law_restitution(sy.contact[static_cast<size_t>(set[static_cast<size_t>(a)])].p);
        // Moreau's law: each separates at least e times its closing speed (none at rest), pushing only
        b[static_cast<size_t>(a)] = u + e * std::max(u, 0.0);
        for (int d = 0; d < k; ++d) {
            double s = 0.0;
            for (int i = 0; i < n; ++i)
                s += J[static_cast<size_t>(a * n + i)] * J[static_cast<size_t>(d * n + i)] / sy.mass[static_cast<size_t>(i)];
            W[static_cast<size_t>(a * k + d)] = s;
        }
    }
    if (!solve_lcp(W, b, k, lam)) return false;  // (taken one after the other)
    const double t = st[T];
    std::vector<double> v_in(static_cast<size_t>(k));
    for (int a = 0; a < k; ++a) {
        const Contact& ct = sy.contact[static_cast<size_t>(set[static_cast<size_t>(a)])];
        v_in[static_cast<size_t>(a)] = ct.radial.on ? u0[static_cast<size_t>(a)] : rel(v, ct);
    }
    for (int a = 0; a < k; ++a)
        for (int i = 0; i < n; ++i)
            v[i] -= J[static_cast<size_t>(a * n + i)] * lam[static_cast<size_t>(a)] / sy.mass[static_cast<size_t>(i)];
    after_velocity_jump(st, sy);
    std::vector<int> rest;  // (free contacts left at rest against their stops: held where pushed)
    for (int a = 0; a < k; ++a) {
        const int d = set[static_cast<size_t>(a)];
        const Contact& ct = sy.contact[static_cast<size_t>(d)];
        const int acc = L.acc_at(d);
        double u1 = 0.0;
        for (int i = 0; i < n; ++i) u1 += J[static_cast<size_t>(a * n + i)] * v[i];
        const double la = lam[static_cast<size_t>(a)], u = u0[static_cast<size_t>(a)];
        const double loss = 0.5 * la * (u + u1);  // (its share of the kinetic energy lost: they sum to it)
        ledger[L_BUMPER_LOSS] += loss;
        if (st[L.in_at(d)] != 0.0) {  // held: it carries the impulse, or lets go where the pair moves apart
            st[acc + A_IMPULSE] += la;
            if (u1 < -sc.v_res) rigid_release(st, sy, d, contacts);
            continue;
        }
        if (u > sc.v_res || la * W[static_cast<size_t>(a * k + a)] > sc.v_res) {  // (an impulse that shows)
            count_impact(st, L, d, t, sc.window_s, chatters);
            double* r = contacts.push();
            r[CC_CONTACT] = static_cast<double>(d);
            r[CC_T_START] = t;
            r[CC_T_END] = t;
            r[CC_V_IN] = v_in[static_cast<size_t>(a)];
            r[CC_V_OUT] = ct.radial.on ? u1 : rel(v, ct);
            r[CC_IMPULSE] = la;
            r[CC_PEAK_FORCE] = NaN;
            r[CC_MAX_COMPRESSION] = 0.0;
            r[CC_DISSIPATION] = loss;
        }
        if (std::abs(u1) <= sc.v_res) rest.push_back(d);
    }
    // those at rest held where the motion pushes them shut: the smallest set whose holds all push and
    // with which none of the others is pushed shut (each set tried, the smallest first: where nothing
    // pushes, to the rounding, nothing is held)
    const int nr = static_cast<int>(rest.size());
    static thread_local std::vector<double> au, a, ju, jh;
    auto hold = [&](int s) {
        for (int p = 0; p < nr; ++p) st[L.in_at(rest[static_cast<size_t>(p)])] = (s >> p) & 1 ? 1.0 : 0.0;
    };
    // (a force or push zero to the rounding: its rate decides, along the motion with the holds, whose
    // accelerations' rate is -M^-1 (K v + C a) - a_g')
    const double ang = ph.w * tau + ph.phi;
    const double ag_rate = ph.ax1 + ph.axh * ph.w * std::cos(ang);
    const double bg_rate = ph.plain ? 0.0 : ph.bx1 + ph.w * (ph.bs * std::cos(ang) - ph.bc * std::sin(ang));
    auto consistent = [&](int s) {
        hold(s);
        if (!stk.build(sy, st)) return false;  // (a loop of holds)
        state_accelerations(st, sy, stk, ag, q, row, au, a);
        ju.assign(static_cast<size_t>(n), 0.0);
        for (int i = 0; i < n; ++i) {
            double f = 0.0;
            for (int j = 0; j < n; ++j)
                f += ph.K[static_cast<size_t>(i * n + j)] * v[j] + ph.C[static_cast<size_t>(i * n + j)] * a[static_cast<size_t>(j)];
            ju[static_cast<size_t>(i)] = -ph.minv[static_cast<size_t>(i)] * f - ph.on(i, ag_rate, bg_rate);
        }
        jh = ju;
        stk.project(sy.mass, jh.data());
        // (the rounding of accelerations and their rates: against the run's scales as well as the instant's,
        // where every force is passing through zero)
        double round = std::abs(ph.ax0) + std::abs(ph.axh) + ph.xrun * ph.rate * ph.rate;
        double round_rate = std::abs(ph.ax1) + std::abs(ph.axh * ph.w) + ph.xrun * ph.rate * ph.rate * ph.rate;
        if (!ph.plain) {
            round += std::abs(ph.bx0) + std::abs(ph.bs) + std::abs(ph.bc);
            round_rate += std::abs(ph.bx1) + (std::abs(ph.bs) + std::abs(ph.bc)) * ph.w;
        }
        double mass = 0.0;
        for (int i = 0; i < n; ++i) {
            round += std::abs(au[static_cast<size_t>(i)]) + std::abs(ag[i]);
            round_rate += std::abs(ju[static_cast<size_t>(i)]) + std::abs(ph.on(i, ag_rate, bg_rate));
            mass += sy.mass[static_cast<size_t>(i)];
        }
        round *= ROUNDING;
        round_rate *= ROUNDING;
        for (int p = 0; p < nr; ++p) {
            const int d = rest[static_cast<size_t>(p)];
            const Contact& ct = sy.contact[static_cast<size_t>(d)];
            if ((s >> p) & 1) {  // held: it pushes, or is about to
                const int h = stk.held_of[static_cast<size_t>(d)];
                const double f = stk.force(ct.sign, h, sy.mass, au.data(), a.data());
                if (f < -mass * round) return false;
                if (f <= mass * round && stk.force(ct.sign, h, sy.mass, ju.data(), jh.data()) < -mass * round_rate)
                    return false;
            } else {  // free: the motion does not push it shut, nor is about to
                auto closing = [&](const std::vector<double>& x) { return ct.sign * rel(x.data(), ct); };
                // (a ring's: its compression's second derivative and that's rate, its normal turning)
                const double push = ct.radial.on ? compression(ct, st + L.x, v, a.data()).da : closing(a);
                const double rate = ct.radial.on ? ring_push_rate(ct, st + L.x, v, a.data(), a.data(), jh.data())
                                                 : closing(jh);
                if (push > round || (push >= -round && rate > round_rate)) return false;
                // (contact c's own event found its free motion closing it, at a higher order where these
                // are zero to the rounding: it is held)
                if (d == c && push >= -round && rate >= -round_rate) return false;
            }
        }
        return true;
    };
    int chosen = -1, fallback = 0;  // (none consistent: the largest set of holds that closes no loop)
    for (int size = 0; size <= nr && chosen < 0; ++size)
        for (int s = 0; s < (1 << nr) && chosen < 0; ++s) {
            if (bits(s) != size) continue;
            if (consistent(s)) chosen = s;
            else if (stk.build(sy, st)) fallback = s;  // (consistent() left set s in st)
        }
    hold(chosen >= 0 ? chosen : fallback);
    for (const int d : rest) {
        if (st[L.in_at(d)] == 0.0) continue;
        const int acc = L.acc_at(d);
        end_sequence(st, L, d, t, chatters);
        const Contact& ct = sy.contact[static_cast<size_t>(d)];
        if (ct.j < 0 && !ct.levered() && !ct.radial.on) {  // (on the stop exactly, at rest on it)
            st[L.x + ct.i] = ct.sign * ct.gap;
            v[ct.i] = 0.0;
        }
        st[L.def_at(d)] = 0.0;
        for (int z = 0; z < N_ACC; ++z) st[acc + z] = 0.0;
        st[acc + A_TSTART] = t;
    }
    stk.build(sy, st);
    settle_holds(st, sy, stk, ledger);
    return true;
}

}  // namespace pounding::run_parts
