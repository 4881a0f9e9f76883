#include "sticking.hpp"

#include <numeric>

#include "isolator.hpp"
#include "laws.hpp"

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

}  // namespace

bool Sticking::build(const System& sy, const double* st) {
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
    side.assign(static_cast<size_t>(nh * n), 0);
    std::vector<int>& stack = stack_;
    for (int h = 0; h < nh; ++h) {
        char* s = &side[static_cast<size_t>(h * n)];
        const int own_i = end_i[static_cast<size_t>(h)], own_j = end_j[static_cast<size_t>(h)];
        for (const int end : {own_i, own_j}) {
            if (end < 0) break;  // (the second end the ground: the first's side never reaches it)
            const char mark = end == own_i ? 1 : -1;
            std::fill(s, s + n, 0);
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
                    if (other >= 0 && !s[other]) {
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

void Sticking::project(const std::vector<double>& mass, double* a) const {
    if (!any) return;
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
    const char* s = &side[static_cast<size_t>(h * n)];
    double f = 0.0;
    for (int k = 0; k < n; ++k)
        if (s[k]) f += s[k] * mass[static_cast<size_t>(k)] * (au[k] - a[k]);
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

bool sticking_closes_loop(const System& sy, const double* st, int c) {
    static thread_local std::vector<int> buf;
    Sets sets(buf, sy.n + 1);
    each_held(sy, st, [&](int b, int i, int j, double) {
        if (b != c) sets.join(i, j >= 0 ? j : sy.n);
    });
    const Contact& ct = sy.contact[static_cast<size_t>(c)];
    return !sets.join(ct.i, node(ct, sy.n));
}

}  // namespace pounding
