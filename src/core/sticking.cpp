#include "sticking.hpp"

#include <cmath>
#include <numeric>

#include "isolator.hpp"
#include "laws.hpp"
#include "compression.hpp"
#include "linalg.hpp"

namespace pounding {

namespace {

// union-find over the dofs and the ground (node n), on a buffer of the caller's
struct Sets {
    std::vector<int>& up;
    Sets(std::vector<int>& buf, int size) : up(buf) {
        up.resize(static_cast<size_t>(size));
        std::iota(up.begin(), up.end(), 0);
    }
    int find(int a) {
        while (up[static_cast<size_t>(a)] != a) a = up[static_cast<size_t>(a)] = up[static_cast<size_t>(up[static_cast<size_t>(a)])];
        return a;
    }
    bool join(int a, int b) {  // false when they were already one
        a = find(a);
        b = find(b);
        if (a == b) return false;
        up[static_cast<size_t>(a)] = b;
        return true;
    }
};

inline int node(const Contact& ct, int n) { return ct.j >= 0 ? ct.j : n; }

bool is_held(const System& sy, const double* st, int c) {
    return sy.has_b && st[sy.lay.in_at(c)] != 0.0 && law_is_rigid(sy.contact[static_cast<size_t>(c)].law);
}

bool sticks(const System& sy, const double* st, int e) { return iso_slip(sy, e, st) == 0.0; }

// the bonds held in the state, with their pairs and signs: the rigid stops held shut, then the ties
template <class Visit>
void each_held(const System& sy, const double* st, Visit&& visit) {
    for (int c = 0; c < sy.nc(); ++c)
        if (is_held(sy, st, c)) {
            const Contact& ct = sy.contact[static_cast<size_t>(c)];
            visit(c, ct.i, ct.j, ct.sign);
        }
    for (const int e : sy.ties)
        if (sticks(sy, st, e)) {
            const Hysteretic& h = sy.hyst[static_cast<size_t>(e)];
            visit(sy.nc() + e, h.i, h.j, 1.0);
        }
}

// bond b's pair: contact b's, or (b >= nc) element b - nc's
const Pair& bond_pair(const System& sy, int b) {
    if (b < sy.nc()) return sy.contact[static_cast<size_t>(b)];
    return sy.hyst[static_cast<size_t>(b - sy.nc())];
}

// is bond b a ring's (a rigid stop on a circular moat's wall: its row the normal's, turning as the point moves)?
bool ring_bond(const System& sy, int b) { return b < sy.nc() && sy.contact[static_cast<size_t>(b)].radial.on; }

// the rows w of the bonds (W, nb x n) at the displacements x and X = A^-1 W M^-1, A = W M^-1 W^T; false when
// the rows are dependent (A singular to 1e-12 of its largest diagonal: a loop).  A ring's row is its
// compression's gradient at x (compression.hpp); with a ring among them (Ainv not null) A^-1 (nb x nb) too.
bool constraint_rows(const System& sy, const double* x, const int* bonds, int nb, std::vector<double>& W,
                     std::vector<double>& X, std::vector<double>* Ainv = nullptr) {
    const int n = sy.n;
    W.assign(static_cast<size_t>(nb * n), 0.0);
    for (int h = 0; h < nb; ++h) {
        if (ring_bond(sy, bonds[h])) push_contact(&W[static_cast<size_t>(h * n)], sy.contact[static_cast<size_t>(bonds[h])], x, 1.0);
        else push_pair(&W[static_cast<size_t>(h * n)], bond_pair(sy, bonds[h]), 1.0);
    }
    const int extra = Ainv != nullptr ? nb : 0;  // (the identity's columns beside: A^-1)
    Mat A(nb, nb), R(nb, n + extra);
    double top = 0.0;
    for (int h = 0; h < nb; ++h) {
        for (int g = 0; g < nb; ++g) {
            double s = 0.0;
            for (int k = 0; k < n; ++k)
                s += W[static_cast<size_t>(h * n + k)] * W[static_cast<size_t>(g * n + k)] / sy.mass[static_cast<size_t>(k)];
            A(h, g) = s;
        }
        top = std::max(top, A(h, h));
        for (int k = 0; k < n; ++k) R(h, k) = W[static_cast<size_t>(h * n + k)] / sy.mass[static_cast<size_t>(k)];
        for (int g = 0; g < extra; ++g) R(h, n + g) = h == g ? 1.0 : 0.0;
    }
    if (!solve_checked(A, R, 1e-12 * top)) return false;
    X.resize(static_cast<size_t>(nb * n));
    for (int h = 0; h < nb; ++h)
        for (int k = 0; k < n; ++k) X[static_cast<size_t>(h * n + k)] = R(h, k);
    if (Ainv != nullptr) {
        Ainv->resize(static_cast<size_t>(nb * nb));
        for (int h = 0; h < nb; ++h)
            for (int g = 0; g < nb; ++g) (*Ainv)[static_cast<size_t>(h * nb + g)] = R(h, n + g);
    }
    return true;
}

}  // namespace

bool Sticking::build(const System& sy, const double* st) {
    general = sy.lever_holds;
    sys = &sy;
    if (!any && n == sy.n && held_of.size() == static_cast<size_t>(sy.nc() + sy.n_h()) &&
        grp.size() == static_cast<size_t>(sy.n)) {
        bool none = true;
        if (sy.has_b)
            for (const int c : sy.rigid) none = none && st[sy.lay.in_at(c)] == 0.0;
        for (const int e : sy.ties) none = none && !sticks(sy, st, e);
        if (none) return true;  // (nothing held, as before: the tables stand)
    }
    n = sy.n;
    nc = sy.nc();
    held.clear();
    end_i.clear();
    end_j.clear();
    end_sign.clear();
    held_of.assign(static_cast<size_t>(sy.nc() + sy.n_h()), -1);
    any = false;
    rings = false;
    each_held(sy, st, [&](int b, int i, int j, double sign) {
        held_of[static_cast<size_t>(b)] = static_cast<int>(held.size());
        held.push_back(b);
        end_i.push_back(i);
        end_j.push_back(j);
        end_sign.push_back(sign);
    });
    grp.assign(static_cast<size_t>(n), -1);
    grounded.clear();
    gmass.clear();
    ngrp = 0;
    if (held.empty()) return true;
    any = true;
    if (general) {  // (the holds as constraints: one group of the dofs they touch, never grounded)
        const int nh = static_cast<int>(held.size());
        rings = false;
        for (int h = 0; h < nh; ++h) rings = rings || ring_bond(sy, held[static_cast<size_t>(h)]);
        const bool independent = general_rows(sy, st + sy.lay.x, st + sy.lay.v);
        ngrp = 1;
        grounded.assign(1, 0);
        gmass.assign(1, 0.0);
        for (int k = 0; k < n; ++k) {
            bool touched = false;
            for (int h = 0; h < nh; ++h) touched = touched || wrow[static_cast<size_t>(h * n + k)] != 0.0;
            if (!touched) continue;
            grp[static_cast<size_t>(k)] = 0;
            gmass[0] += sy.mass[static_cast<size_t>(k)];
        }
        return independent;
    }
    Sets sets(up, n + 1);
    const int nh = static_cast<int>(held.size());
    auto node_j = [&](int h) { return end_j[static_cast<size_t>(h)] >= 0 ? end_j[static_cast<size_t>(h)] : n; };
    bool tree = true;
    for (int h = 0; h < nh; ++h) tree = sets.join(end_i[static_cast<size_t>(h)], node_j(h)) && tree;
    std::vector<int>& root_grp = roots;  // (scratch kept between builds: no allocation a build)
    root_grp.assign(static_cast<size_t>(n + 1), -1);
    auto group_of_root = [&](int r) {
        if (root_grp[static_cast<size_t>(r)] < 0) {
            root_grp[static_cast<size_t>(r)] = ngrp++;
            grounded.push_back(0);
            gmass.push_back(0.0);
        }
        return root_grp[static_cast<size_t>(r)];
    };
    for (int h = 0; h < nh; ++h) {  // the dofs bound by a held bond
        const int g = group_of_root(sets.find(end_i[static_cast<size_t>(h)]));
        if (end_j[static_cast<size_t>(h)] < 0) grounded[static_cast<size_t>(g)] = 1;
    }
    for (int k = 0; k < n; ++k) {
        const int r = sets.find(k);
        if (root_grp[static_cast<size_t>(r)] < 0) continue;
        const int g = root_grp[static_cast<size_t>(r)];
        grp[static_cast<size_t>(k)] = g;
        gmass[static_cast<size_t>(g)] += sy.mass[static_cast<size_t>(k)];
    }
    // each held bond's side: the dofs one of its ends reaches through the other held bonds, the ground left out:
    // its first end's (+1), unless another held bond ties those to the ground, then its second end's (-1)
    side.assign(static_cast<size_t>(nh * n), 0.0);
    std::vector<int>& stack = stack_;
    for (int h = 0; h < nh; ++h) {
        double* s = &side[static_cast<size_t>(h * n)];
        const int own_i = end_i[static_cast<size_t>(h)], own_j = end_j[static_cast<size_t>(h)];
        for (const int end : {own_i, own_j}) {
            if (end < 0) break;  // (the second end the ground: the first's side never reaches it)
            const double mark = end == own_i ? 1.0 : -1.0;
            std::fill(s, s + n, 0.0);
            bool grounded_side = false;
            stack.assign(1, end);
            s[end] = mark;
            while (!stack.empty()) {
                const int k = stack.back();
                stack.pop_back();
                for (int q = 0; q < nh; ++q) {
                    if (q == h) continue;
                    const int qi = end_i[static_cast<size_t>(q)], qj = end_j[static_cast<size_t>(q)];
                    int other = -2;
                    if (qi == k) other = qj;
                    else if (qj == k) other = qi;
                    if (other == GROUND) grounded_side = true;
                    if (other >= 0 && s[other] == 0.0) {
                        s[other] = mark;
                        stack.push_back(other);
                    }
                }
            }
            if (!grounded_side) break;
        }
    }
    return tree;
}

bool Sticking::general_rows(const System& sy, const double* x, const double* v) {
    const int nh = static_cast<int>(held.size());
    std::vector<double>* inv = rings ? &ainv : nullptr;
    const bool independent = constraint_rows(sy, x, held.data(), nh, wrow, side, inv);
    if (!independent) {  // (a loop: the holds of the largest independent rows in order, the others idle)
        static thread_local std::vector<int> kept;
        static thread_local std::vector<double> W, X, I;
        kept.clear();
        for (int h = 0; h < nh; ++h) {
            kept.push_back(held[static_cast<size_t>(h)]);
            if (!constraint_rows(sy, x, kept.data(), static_cast<int>(kept.size()), W, X)) kept.pop_back();
        }
        const int nk = static_cast<int>(kept.size());
        constraint_rows(sy, x, kept.data(), nk, W, X, rings ? &I : nullptr);
        side.assign(static_cast<size_t>(nh * n), 0.0);
        if (rings) ainv.assign(static_cast<size_t>(nh * nh), 0.0);
        for (int q = 0; q < nk; ++q) {
            const int h = held_of[static_cast<size_t>(kept[static_cast<size_t>(q)])];
            std::copy(X.begin() + static_cast<std::ptrdiff_t>(q * n), X.begin() + static_cast<std::ptrdiff_t>((q + 1) * n),
                      side.begin() + static_cast<std::ptrdiff_t>(h * n));
            if (!rings) continue;
            for (int r = 0; r < nk; ++r) {
                const int g = held_of[static_cast<size_t>(kept[static_cast<size_t>(r)])];
                ainv[static_cast<size_t>(h * nh + g)] = I[static_cast<size_t>(q * nk + r)];
            }
        }
    }
    bias.assign(static_cast<size_t>(nh), 0.0);
    if (!rings) return independent;
    // the rings' centripetal terms kappa (a held point's compression's second derivative at zero acceleration):
    // the holds keep W a = -kappa, a bias A^-1 kappa on each hold's multiplier
    bend.assign(static_cast<size_t>(nh), 0.0);
    for (int g = 0; g < nh; ++g)
        if (ring_bond(sy, held[static_cast<size_t>(g)]))
            bend[static_cast<size_t>(g)] = ring_bend(sy.contact[static_cast<size_t>(held[static_cast<size_t>(g)])], x, v);
    for (int h = 0; h < nh; ++h) {
        double s = 0.0;
        for (int g = 0; g < nh; ++g) s += ainv[static_cast<size_t>(h * nh + g)] * bend[static_cast<size_t>(g)];
        bias[static_cast<size_t>(h)] = s;
    }
    return independent;
}

void Sticking::refresh(const double* x, const double* v) {
    if (rings) general_rows(*sys, x, v);
}

void Sticking::hold(const std::vector<double>& mass, double* a) const {
    if (!rings) return project(mass, a);
    const int nh = static_cast<int>(held.size());
    static thread_local std::vector<double> t;  // (X M a + A^-1 kappa: a held bond's each)
    t.resize(static_cast<size_t>(nh));
    for (int h = 0; h < nh; ++h) {
        const double* x = &side[static_cast<size_t>(h * n)];
        double s = 0.0;
        for (int k = 0; k < n; ++k) s += x[k] * mass[static_cast<size_t>(k)] * a[k];
        t[static_cast<size_t>(h)] = s + bias[static_cast<size_t>(h)];
    }
    for (int k = 0; k < n; ++k) {
        double s = 0.0;
        for (int h = 0; h < nh; ++h) s += wrow[static_cast<size_t>(h * n + k)] * t[static_cast<size_t>(h)];
        a[k] -= s / mass[static_cast<size_t>(k)];
    }
}

double Sticking::ring_rate(int h, const double* x, const double* v, const double* au, const double* a) const {
    // d/dt A^-1 (W au + kappa) less A^-1 W au' (the lines' part, from the free accelerations' rate):
    // A^-1 (W' a - W M^-1 W'^T lam + kappa'), lam = A^-1 (W au + kappa) = X M (au - a) the multipliers
    // (with W a = -kappa: sticking.hpp), W' a ring's row's rate (its normal's turn n' = (P' - n (n . P')) / |P|)
    const System& sy = *sys;
    const int nh = static_cast<int>(held.size());
    static thread_local std::vector<double> lam, turn, c;
    lam.assign(static_cast<size_t>(nh), 0.0);
    turn.assign(static_cast<size_t>(n), 0.0);
    c.assign(static_cast<size_t>(nh), 0.0);
    for (int g = 0; g < nh; ++g) {
        const double* xs = &side[static_cast<size_t>(g * n)];
        double s = 0.0;
        for (int k = 0; k < n; ++k) s += xs[k] * sy.mass[static_cast<size_t>(k)] * (au[k] - a[k]);
        lam[static_cast<size_t>(g)] = s;
    }
    for (int g = 0; g < nh; ++g) {
        if (!ring_bond(sy, held[static_cast<size_t>(g)])) continue;
        const Contact& ct = sy.contact[static_cast<size_t>(held[static_cast<size_t>(g)])];
        const RingTurn t = ring_turn(ct, x, v, a);
        const double tx = t.tx, ty = t.ty;
        c[static_cast<size_t>(g)] += tx * rel(a, ct) + ty * rel(a, ct.radial.y) + t.bend_rate;
        push_pair(turn.data(), ct, lam[static_cast<size_t>(g)] * tx);  // (W'^T lam)
        push_pair(turn.data(), ct.radial.y, lam[static_cast<size_t>(g)] * ty);
    }
    for (int g = 0; g < nh; ++g) {
        const double* w = &wrow[static_cast<size_t>(g * n)];
        double s = 0.0;
        for (int k = 0; k < n; ++k) s += w[k] * turn[static_cast<size_t>(k)] / sy.mass[static_cast<size_t>(k)];
        c[static_cast<size_t>(g)] -= s;
    }
    double out = 0.0;
    for (int g = 0; g < nh; ++g) out += ainv[static_cast<size_t>(h * nh + g)] * c[static_cast<size_t>(g)];
    return out;
}

void Sticking::project(const std::vector<double>& mass, double* a) const {
    if (!any) return;
    if (general) {  // a -= M^-1 W^T (X M a)
        const int nh = static_cast<int>(held.size());
        static thread_local std::vector<double> t;  // (X M a: a held bond's each)
        t.resize(static_cast<size_t>(nh));
        for (int h = 0; h < nh; ++h) {
            const double* x = &side[static_cast<size_t>(h * n)];
            double s = 0.0;
            for (int k = 0; k < n; ++k) s += x[k] * mass[static_cast<size_t>(k)] * a[k];
            t[static_cast<size_t>(h)] = s;
        }
        for (int k = 0; k < n; ++k) {
            double s = 0.0;
            for (int h = 0; h < nh; ++h) s += wrow[static_cast<size_t>(h * n + k)] * t[static_cast<size_t>(h)];
            a[k] -= s / mass[static_cast<size_t>(k)];
        }
        return;
    }
    for (int g = 0; g < ngrp; ++g) {
        double mean = 0.0;
        if (!grounded[static_cast<size_t>(g)]) {
            double s = 0.0;
            for (int k = 0; k < n; ++k)
                if (grp[static_cast<size_t>(k)] == g) s += mass[static_cast<size_t>(k)] * a[k];
            mean = s / gmass[static_cast<size_t>(g)];
        }
        for (int k = 0; k < n; ++k)
            if (grp[static_cast<size_t>(k)] == g) a[k] = mean;
    }
}

double Sticking::force(double sign, int h, const std::vector<double>& mass, const double* au,
                       const double* a) const {
    const double* s = &side[static_cast<size_t>(h * n)];
    double f = 0.0;
    for (int k = 0; k < n; ++k)
        if (s[k] != 0.0) f += s[k] * mass[static_cast<size_t>(k)] * (au[k] - a[k]);
    return sign * f;
}

double Sticking::side_mass(const std::vector<double>& mass, int k) const {
    if (k < 0) return INF;
    const int g = any ? grp[static_cast<size_t>(k)] : -1;
    if (g < 0) return mass[static_cast<size_t>(k)];
    return grounded[static_cast<size_t>(g)] ? INF : gmass[static_cast<size_t>(g)];
}

void Sticking::add_velocity(double* v, int k, double dv) const {
    if (k < 0) return;
    const int g = any ? grp[static_cast<size_t>(k)] : -1;
    if (g < 0) {
        v[k] += dv;
        return;
    }
    if (grounded[static_cast<size_t>(g)]) return;
    for (int q = 0; q < n; ++q)
        if (grp[static_cast<size_t>(q)] == g) v[q] += dv;
}

double Sticking::inverse_mass(const std::vector<double>& mass, const Pair& p) const {
    int d[4];
    double w[4];
    const int m = p.entries(d, w);
    double inv = 0.0;
    for (int q = 0; q < m; ++q) inv += w[q] * w[q] / mass[static_cast<size_t>(d[q])];
    if (!any) return inv;
    const double alone = inv;
    for (size_t h = 0; h < held.size(); ++h) {  // - (W M^-1 w)_h (X w)_h
        double wm = 0.0, xw = 0.0;
        for (int q = 0; q < m; ++q) {
            wm += wrow[h * static_cast<size_t>(n) + static_cast<size_t>(d[q])] * w[q] / mass[static_cast<size_t>(d[q])];
            xw += side[h * static_cast<size_t>(n) + static_cast<size_t>(d[q])] * w[q];
        }
        inv -= wm * xw;
    }
    return inv > 64.0 * EPS * alone ? inv : 0.0;  // (the holds keep it from moving, to the rounding)
}

void Sticking::impulse(const std::vector<double>& mass, double* v, const Pair& p, double s) const {
    int d[4];
    double w[4];
    const int m = p.entries(d, w);
    for (int q = 0; q < m; ++q) v[d[q]] += s * w[q] / mass[static_cast<size_t>(d[q])];
    if (!any) return;
    for (size_t h = 0; h < held.size(); ++h) {  // - M^-1 W^T (X w) s
        double xw = 0.0;
        for (int q = 0; q < m; ++q) xw += side[h * static_cast<size_t>(n) + static_cast<size_t>(d[q])] * w[q];
        if (xw == 0.0) continue;
        for (int k = 0; k < n; ++k)
            v[k] -= s * wrow[h * static_cast<size_t>(n) + static_cast<size_t>(k)] * xw / mass[static_cast<size_t>(k)];
    }
}

double Sticking::inverse_mass_row(const std::vector<double>& mass, const double* w) const {
    double inv = 0.0;
    for (int k = 0; k < n; ++k)
        if (w[k] != 0.0) inv += w[k] * w[k] / mass[static_cast<size_t>(k)];
    if (!any) return inv;
    const double alone = inv;
    for (size_t h = 0; h < held.size(); ++h) {  // - (W M^-1 w)_h (X w)_h
        double wm = 0.0, xw = 0.0;
        for (int k = 0; k < n; ++k) {
            if (w[k] == 0.0) continue;
            wm += wrow[h * static_cast<size_t>(n) + static_cast<size_t>(k)] * w[k] / mass[static_cast<size_t>(k)];
            xw += side[h * static_cast<size_t>(n) + static_cast<size_t>(k)] * w[k];
        }
        inv -= wm * xw;
    }
    return inv > 64.0 * EPS * alone ? inv : 0.0;
}

void Sticking::impulse_row(const std::vector<double>& mass, double* v, const double* w, double s) const {
    for (int k = 0; k < n; ++k) v[k] += s * w[k] / mass[static_cast<size_t>(k)];
    if (!any) return;
    for (size_t h = 0; h < held.size(); ++h) {
        double xw = 0.0;
        for (int k = 0; k < n; ++k) xw += side[h * static_cast<size_t>(n) + static_cast<size_t>(k)] * w[k];
        if (xw == 0.0) continue;
        for (int k = 0; k < n; ++k)
            v[k] -= s * wrow[h * static_cast<size_t>(n) + static_cast<size_t>(k)] * xw / mass[static_cast<size_t>(k)];
    }
}

double Sticking::projector(const std::vector<double>& mass, int i, int k) const {
    double s = 0.0;
    for (size_t h = 0; h < held.size(); ++h)
        s += wrow[h * static_cast<size_t>(n) + static_cast<size_t>(i)] * side[h * static_cast<size_t>(n) + static_cast<size_t>(k)];
    return (i == k ? 1.0 : 0.0) - s * mass[static_cast<size_t>(k)] / mass[static_cast<size_t>(i)];
}

bool sticking_closes_loop(const System& sy, const double* st, int c) {
    if (sy.lever_holds) {  // (the rows of the held bonds and c's dependent)
        static thread_local std::vector<int> bonds;
        static thread_local std::vector<double> W, X;
        bonds.clear();
        each_held(sy, st, [&](int b, int, int, double) {
            if (b != c) bonds.push_back(b);
        });
        bonds.push_back(c);
        return !constraint_rows(sy, st + sy.lay.x, bonds.data(), static_cast<int>(bonds.size()), W, X);
    }
    static thread_local std::vector<int> buf;
    Sets sets(buf, sy.n + 1);
    each_held(sy, st, [&](int b, int i, int j, double) {
        if (b != c) sets.join(i, j >= 0 ? j : sy.n);
    });
    const Contact& ct = sy.contact[static_cast<size_t>(c)];
    return !sets.join(ct.i, node(ct, sy.n));
}

}  // namespace pounding
