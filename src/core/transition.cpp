#include "transition.hpp"

#include <algorithm>
#include <cmath>

namespace pounding {

namespace {
constexpr int N_CACHE = 16;  // transitions kept (a steady motion goes through a few phases)
constexpr int N_GAUSS = 12;
constexpr double GAUSS_X[N_GAUSS] = {0.009219682876640378, 0.0479413718147626,  0.11504866290284765,
                                     0.20634102285669126,  0.31608425050090994, 0.43738329574426554,
                                     0.5626167042557344,   0.6839157494990901,  0.7936589771433087,
                                     0.8849513370971523,   0.9520586281852375,  0.9907803171233596};
constexpr double GAUSS_W[N_GAUSS] = {0.023587668193255706, 0.05346966299765953, 0.08003916427167321,
                                     0.10158371336153287,  0.1167462682691773,  0.12457352290670134,
                                     0.12457352290670134,  0.1167462682691773,  0.10158371336153287,
                                     0.08003916427167321,  0.05346966299765953, 0.023587668193255706};

bool same(const std::vector<double>& a, const std::vector<double>& b) {
    for (size_t i = 0; i < a.size(); ++i)
        if (a[i] != b[i]) return false;
    return true;
}

// y at tau of a series of nt terms (coefficient k at t[k ny]); NY the state's length fixed at compile time
// (0: ny_run, known at run time)
template <int NY>
void series_at(const double* t, int nt, int ny_run, double tau, double* y) {
    const int ny = NY > 0 ? NY : ny_run;
    for (int q = 0; q < ny; ++q) y[q] = t[(nt - 1) * ny + q];
    for (int k = nt - 2; k >= 0; --k)
        for (int q = 0; q < ny; ++q) y[q] = y[q] * tau + t[k * ny + q];
}

// the transition's numbers (T, Q, R, L, Qp) for the phase over h, from each input's unit response; NF the
// masses fixed at compile time (0: ph.n, known at run time): one source, the same sums in the same order
template <int NF>
void make(Transition& e, const Phase& ph, const System& sy, double h, const std::vector<Pair>& pairs,
          std::vector<double>& scratch) {
    const int n = NF > 0 ? NF : ph.n, ny = 2 * n, dim = 3 * n + 4, np = static_cast<int>(pairs.size());
    e.T.assign(static_cast<size_t>(ny * dim), 0.0);
    e.Q.assign(static_cast<size_t>(dim * dim), 0.0);
    e.R.assign(static_cast<size_t>(4 * dim), 0.0);
    e.L.assign(static_cast<size_t>(np * dim), 0.0);
    e.Qp.assign(static_cast<size_t>(np * dim * dim), 0.0);
    // each input's unit response: its series, then at h and at the Gauss nodes
    const size_t series_len = static_cast<size_t>((MAX_TERMS + 1) * ny);
    scratch.assign(series_len + static_cast<size_t>(ny + n) + static_cast<size_t>((N_GAUSS + 1) * ny * dim), 0.0);
    double* t = scratch.data();
    double* unit = t + series_len;      // y0 (ny) then r (n)
    double* at = unit + ny + n;         // (N_GAUSS + 1) responses of ny each, per column: at[(node * dim + col) * ny]
    for (int col = 0; col < dim; ++col) {
        std::fill(unit, unit + ny + n, 0.0);
        double a0 = 0.0, a1 = 0.0, amp = 0.0, sp = 0.0, cp = 0.0;
        const double* r = nullptr;
        if (col < ny) {
            unit[col] = 1.0;
        } else if (col < ny + n) {
            unit[ny + (col - ny)] = 1.0;
            r = unit + ny;
        } else if (col == ny + n) {
            a0 = 1.0;
        } else if (col == ny + n + 1) {
            a1 = 1.0;
        } else if (col == ny + n + 2) {  // sin(w tau)
            amp = 1.0;
            cp = 1.0;
        } else {                          // cos(w tau)
            amp = 1.0;
            sp = 1.0;
        }
        const int nt = series(ph, unit, r, a0, a1, amp, sp, cp, h, t);
        for (int q = 0; q < N_GAUSS; ++q) series_at<2 * NF>(t, nt, ny, h * GAUSS_X[q], at + (q * dim + col) * ny);
        series_at<2 * NF>(t, nt, ny, h, at + (N_GAUSS * dim + col) * ny);
    }
    for (int q = 0; q < ny; ++q)
        for (int col = 0; col < dim; ++col) e.T[static_cast<size_t>(q * dim + col)] = at[(N_GAUSS * dim + col) * ny + q];
    // the integrals over the nodes
    std::vector<double> cv(static_cast<size_t>(n * dim)), mv(static_cast<size_t>(dim)), dv(static_cast<size_t>(dim));
    for (int q = 0; q < N_GAUSS; ++q) {
        const double wq = h * GAUSS_W[q], tq = h * GAUSS_X[q];
        const double* node = at + q * dim * ny;  // column col: node[col * ny + ...]
        auto V = [&](int i, int col) { return node[col * ny + n + i]; };
        auto X = [&](int i, int col) { return node[col * ny + i]; };
        // C_lin Mv (n, dim) and m . Mv (dim)
        for (int i = 0; i < n; ++i)
            for (int col = 0; col < dim; ++col) {
                double s = 0.0;
                for (int j = 0; j < n; ++j) s += sy.c_lin[static_cast<size_t>(i * n + j)] * V(j, col);
                cv[static_cast<size_t>(i * dim + col)] = s;
            }
        for (int col = 0; col < dim; ++col) {
            double s = 0.0;
            for (int i = 0; i < n; ++i) s += sy.mass[static_cast<size_t>(i)] * V(i, col);
            mv[static_cast<size_t>(col)] = s;
        }
        for (int a = 0; a < dim; ++a)
            for (int b = 0; b < dim; ++b) {
                double s = 0.0;
                for (int i = 0; i < n; ++i) s += V(i, a) * cv[static_cast<size_t>(i * dim + b)];
                e.Q[static_cast<size_t>(a * dim + b)] += wq * s;
            }
        const double basis[4] = {1.0, tq, std::sin(ph.w * tq), std::cos(ph.w * tq)};
        for (int k = 0; k < 4; ++k)
            for (int col = 0; col < dim; ++col) e.R[static_cast<size_t>(k * dim + col)] += wq * basis[k] * mv[static_cast<size_t>(col)];
        for (int p = 0; p < np; ++p) {
            const Pair& pr = pairs[static_cast<size_t>(p)];
            const int i = pr.i, j = pr.j;
            int d[4];
            double w[4];
            const int m = pr.entries(d, w);
            for (int col = 0; col < dim; ++col) {
                double dx, dvc;
                if (pr.levered()) {  // (w . X's column, w . V's)
                    dx = 0.0;
                    dvc = 0.0;
                    for (int r = 0; r < m; ++r) {
                        dx += w[r] * X(d[r], col);
                        dvc += w[r] * V(d[r], col);
                    }
                } else {
                    dx = j >= 0 ? X(i, col) - X(j, col) : X(i, col);
                    dvc = j >= 0 ? V(i, col) - V(j, col) : V(i, col);
                }
                dv[static_cast<size_t>(col)] = dvc;
                e.L[static_cast<size_t>(p * dim + col)] += wq * dx;
            }
            double* qp = &e.Qp[static_cast<size_t>(p * dim * dim)];
            for (int a = 0; a < dim; ++a)
                for (int b = 0; b < dim; ++b) qp[a * dim + b] += wq * dv[static_cast<size_t>(a)] * dv[static_cast<size_t>(b)];
        }
    }
}
}  // namespace

void TransitionCache::setup(const System& sy) {
    entries.assign(N_CACHE, Transition());
    next = 0;
    recent[0] = recent[1] = Recent();
    pairs.clear();
    pair_of.assign(static_cast<size_t>(sy.nc()), 0);
    for (int c = 0; c < sy.nc(); ++c) {
        const Contact& ct = sy.contact[static_cast<size_t>(c)];
        int p = 0;
        while (p < static_cast<int>(pairs.size()) && !same_pair(pairs[static_cast<size_t>(p)], ct)) ++p;
        if (p == static_cast<int>(pairs.size())) pairs.push_back(ct);
        pair_of[static_cast<size_t>(c)] = p;
    }
}

const Transition* TransitionCache::get(const Phase& ph, const System& sy, double h, uint64_t phase) {
    // (found for this phase and h before, and not made over since: the same entry the search finds, as an
    // entry is made only where none has its key)
    for (const Recent& r : recent)
        if (r.phase == phase && r.h == h && entries[static_cast<size_t>(r.idx)].made == r.made) {
            entries[static_cast<size_t>(r.idx)].uses += 1;
            return &entries[static_cast<size_t>(r.idx)];
        }
    auto remember = [&](int idx) {
        recent[1] = recent[0];
        recent[0] = Recent{phase, entries[static_cast<size_t>(idx)].made, h, idx};
    };
    for (int idx = 0; idx < N_CACHE; ++idx) {
        Transition& e = entries[static_cast<size_t>(idx)];
        if (e.h == h && e.w == ph.w && e.xrun == ph.xrun && e.vrun == ph.vrun && same(e.K, ph.K) &&
            same(e.C, ph.C) && e.grp == ph.stk.grp && e.grounded == ph.stk.grounded &&
            (!ph.stk.general || e.held == ph.stk.held)) {
            e.uses += 1;
            remember(idx);
            return &e;
        }
    }
    const int idx = next;
    Transition& e = entries[static_cast<size_t>(next)];
    next = (next + 1) % N_CACHE;
    e.made = ++made;
    remember(idx);
    e.K = ph.K;
    e.C = ph.C;
    e.grp = ph.stk.grp;
    e.grounded = ph.stk.grounded;
    e.held = ph.stk.held;
    e.h = h;
    e.w = ph.w;
    e.xrun = ph.xrun;
    e.vrun = ph.vrun;
    e.dim = 3 * ph.n + 4;
    e.uses = 1;
    sized(ph.n, [&](auto N) { make<decltype(N)::value>(e, ph, sy, h, pairs, scratch); });
    return &e;
}

}  // namespace pounding
