#include "phase.hpp"

#include "isolator.hpp"

#include <algorithm>

namespace pounding {

namespace {
constexpr double SERIES_TAIL = 1e-18;  // a series' next terms, against the motion's scale
constexpr int HERMITE_ORDER = 8;
// int_0^T f = sum_k c_k T^(k+1) (f^(k)(0) + (-1)^k f^(k)(T)):
// c_k of the rule of order p (exact to degree 2 p + 1): (1/2) p! (2p + 1 - k)! / ((2p + 1)! (p - k)! (k + 1)!)
struct HermiteTable {
    double c[HERMITE_ORDER + 1][HERMITE_ORDER + 1];
    constexpr HermiteTable() : c() {
        for (int p = 0; p <= HERMITE_ORDER; ++p)
            for (int k = 0; k <= p; ++k) {
                double v = 0.5;  // the ratio of factorials, built as a product of ratios
                for (int f = 2 * p + 1 - k + 1; f <= 2 * p + 1; ++f) v /= f;           // (2p+1-k)! / (2p+1)!
                for (int f = p - k + 1; f <= p; ++f) v *= f;                         // p! / (p-k)!
                for (int f = 2; f <= k + 1; ++f) v /= f;                             // 1 / (k+1)!
                c[p][k] = v;
            }
    }
};
constexpr HermiteTable HERMITE;
// the rule's order for a sub-interval of x = tau times the fastest rate of the integrands: the lowest whose
// error bound x^(2p+2) / (2p+2)! is below 1e-18 (the full order at a whole sub-interval)
int hermite_order(double x) {
    double term = x * x / 2.0;  // x^(2p+2) / (2p+2)! at p = 0
    for (int p = 0; p < HERMITE_ORDER; ++p) {
        if (term <= 1e-18) return std::max(p, 2);
        term *= x * x / ((2.0 * p + 3.0) * (2.0 * p + 4.0));
    }
    return HERMITE_ORDER;
}

// binom(k, j), and binom(k, j) (1 if 2 j = k, else 2): sum_j binom(k, j) a_j b_(k-j) for a = b in half the terms
constexpr double SYM[HERMITE_ORDER + 1][HERMITE_ORDER / 2 + 1] = {
    {1, 0, 0, 0, 0}, {2, 0, 0, 0, 0}, {2, 2, 0, 0, 0}, {2, 6, 0, 0, 0}, {2, 8, 6, 0, 0}, {2, 10, 20, 0, 0},
    {2, 12, 30, 20, 0}, {2, 14, 42, 70, 0}, {2, 16, 56, 112, 70}};
constexpr double BINOM[HERMITE_ORDER + 1][HERMITE_ORDER + 1] = {
    {1, 0, 0, 0, 0, 0, 0, 0, 0},       {1, 1, 0, 0, 0, 0, 0, 0, 0},        {1, 2, 1, 0, 0, 0, 0, 0, 0},
    {1, 3, 3, 1, 0, 0, 0, 0, 0},       {1, 4, 6, 4, 1, 0, 0, 0, 0},        {1, 5, 10, 10, 5, 1, 0, 0, 0},
    {1, 6, 15, 20, 15, 6, 1, 0, 0},    {1, 7, 21, 35, 35, 21, 7, 1, 0},    {1, 8, 28, 56, 70, 56, 28, 8, 1}};

// out = M^-1 (A x + B v), n x n row-major A and B
inline void minv_ab(const Phase& ph, const std::vector<double>& A, const double* x, const std::vector<double>& B,
                    const double* v, double* out) {
    const int n = ph.n;
    with_rows(ph, [&](const auto& row) {
        for (int i = 0; i < n; ++i) {
            const double* ra = &A[static_cast<size_t>(i * n)];
            const double* rb = &B[static_cast<size_t>(i * n)];
            double s = 0.0;
            row(i, [&](int j) { s += ra[j] * x[j] + rb[j] * v[j]; });
            out[i] = ph.minv[static_cast<size_t>(i)] * s;
        }
    });
}

// the displacements' derivatives D_0..D_9 (each n) at one end, from x, v, a there and the table acceleration's
// derivatives G_1..G_7: D_(k+2) = -M^-1 (K D_k + C D_(k+1)) - G_k 1
void end_derivatives(const Phase& ph, int order, const double* y, const double* a, const double* g, const double* gb,
                     double* D) {
    const int n = ph.n;
    for (int i = 0; i < n; ++i) {
        D[i] = y[i];
        D[n + i] = y[n + i];
        D[2 * n + i] = a[i];
    }
    for (int k = 1; k + 2 <= order + 1; ++k) {
        double* out = D + (k + 2) * n;
        minv_ab(ph, ph.K, D + k * n, ph.C, D + (k + 1) * n, out);
        if (ph.plain)
            for (int i = 0; i < n; ++i) out[i] = -out[i] - g[k];
        else
            for (int i = 0; i < n; ++i) out[i] = -out[i] - ph.on(i, g[k], gb[k]);
        ph.stk.project(ph.mass, out);
    }
}

// one end's share of the integrals: sum_k c_k T^(k+1) sgn^k f^(k), f the integrands (D: the displacements'
// derivatives D_0..D_9 there, g: the table acceleration's G_0..G_8)
void hermite_end(Phase& ph, int order, const std::vector<double>& c_lin, const std::vector<double>& mass,
                 const double* D, const double* g, const double* gb, double big_t, double sgn, bool energy,
                 double& vcv, double& gv, double* du, double* dvv) {
    const int n = ph.n;
    double q[HERMITE_ORDER + 1];
    double t = big_t;
    for (int k = 0; k <= order; ++k) {
        q[k] = HERMITE.c[order][k] * t * ((k % 2) ? sgn : 1.0);
        t *= big_t;
    }
    if (energy && n == 1 && ph.plain) {  // (one mass: scalars)
        const double c = c_lin[0], m = mass[0];
        double CD[HERMITE_ORDER + 2], P[HERMITE_ORDER + 1];
        for (int k = 1; k <= order + 1; ++k) CD[k] = c * D[k];
        for (int k = 0; k <= order; ++k) P[k] = m * D[k + 1];
        for (int k = 0; k <= order; ++k) {
            double s_vcv = 0.0, s_gv = 0.0;
            for (int j = 0; j <= k / 2; ++j) s_vcv += SYM[k][j] * (D[j + 1] * CD[k - j + 1]);
            for (int j = 0; j <= k; ++j) s_gv += BINOM[k][j] * g[j] * P[k - j];
            vcv += q[k] * s_vcv;
            gv += q[k] * s_gv;
        }
    } else if (energy) {
        // int v^T C v: f^(k) = sum_j binom(k, j) D_(j+1) . (C D_(k-j+1)); int a_g (m . v): sum_j binom G_j P_(k-j)
        double* CD = ph.work.data() + ph.w_q;  // C D_m, m = 1..9 (9 n)
        double P[HERMITE_ORDER + 1], PB[HERMITE_ORDER + 1];
        for (int m = 1; m <= order + 1; ++m) {
            const double* d = D + m * n;
            double* out = CD + (m - 1) * n;
            with_rows(ph, [&](const auto& row) {  // (c_lin's nonzeros are within K's and C's pattern)
                for (int i = 0; i < n; ++i) {
                    const double* r = &c_lin[static_cast<size_t>(i * n)];
                    double s = 0.0;
                    row(i, [&](int j) { s += r[j] * d[j]; });
                    out[i] = s;
                }
            });
        }
        // (m . v, or each component's influence weighted so: a_g's power is sum_i m_i (rA_i a_g + rB_i b_g) v_i)
        for (int k = 0; k <= order; ++k) {
            const double* d = D + (k + 1) * n;
            double s = 0.0, sb = 0.0;
            if (ph.plain) {
                for (int i = 0; i < n; ++i) s += mass[static_cast<size_t>(i)] * d[i];
            } else {
                for (int i = 0; i < n; ++i) {
                    s += mass[static_cast<size_t>(i)] * ph.rA[static_cast<size_t>(i)] * d[i];
                    sb += mass[static_cast<size_t>(i)] * ph.rB[static_cast<size_t>(i)] * d[i];
                }
            }
            P[k] = s;
            PB[k] = sb;
        }
        for (int k = 0; k <= order; ++k) {
            double s_vcv = 0.0;
            for (int j = 0; j <= k / 2; ++j) {
                const double* a = D + (j + 1) * n;
                const double* b = CD + (k - j) * n;
                double dot = 0.0;
                for (int i = 0; i < n; ++i) dot += a[i] * b[i];
                s_vcv += SYM[k][j] * dot;
            }
            double s_gv = 0.0;
            for (int j = 0; j <= k; ++j) s_gv += BINOM[k][j] * g[j] * P[k - j];
            if (!ph.plain)
                for (int j = 0; j <= k; ++j) s_gv += BINOM[k][j] * gb[j] * PB[k - j];
            vcv += q[k] * s_vcv;
            gv += q[k] * s_gv;
        }
    }
    for (int c = 0; c < ph.nc; ++c) {  // the contacts in contact with a linear law: their pair's motion
        const ContactPhase& ct = ph.ct[static_cast<size_t>(c)];
        if (!ct.in || ct.nl) continue;
        double W[HERMITE_ORDER + 2];
        for (int m = 0; m <= order + 1; ++m) W[m] = rel(D + m * n, ct);
        double s_u = 0.0, s_vv = 0.0;
        for (int k = 0; k <= order; ++k) {
            double f = 0.0;
            for (int j = 0; j <= k / 2; ++j) f += SYM[k][j] * W[j + 1] * W[k - j + 1];
            s_vv += q[k] * f;
            s_u += q[k] * W[k];
        }
        du[c] += s_u;
        dvv[c] += s_vv;
    }
}

// Dormand-Prince 5(4) tableau
constexpr double C2 = 1.0 / 5.0, C3 = 3.0 / 10.0, C4 = 4.0 / 5.0, C5 = 8.0 / 9.0;
constexpr double A21 = 1.0 / 5.0;
constexpr double A31 = 3.0 / 40.0, A32 = 9.0 / 40.0;
constexpr double A41 = 44.0 / 45.0, A42 = -56.0 / 15.0, A43 = 32.0 / 9.0;
constexpr double A51 = 19372.0 / 6561.0, A52 = -25360.0 / 2187.0, A53 = 64448.0 / 6561.0, A54 = -212.0 / 729.0;
constexpr double A61 = 9017.0 / 3168.0, A62 = -355.0 / 33.0, A63 = 46732.0 / 5247.0, A64 = 49.0 / 176.0,
                 A65 = -5103.0 / 18656.0;
constexpr double B1 = 35.0 / 384.0, B3 = 500.0 / 1113.0, B4 = 125.0 / 192.0, B5 = -2187.0 / 6784.0,
                 B6 = 11.0 / 84.0;
constexpr double E1 = 71.0 / 57600.0, E3 = -71.0 / 16695.0, E4 = 71.0 / 1920.0, E5 = -17253.0 / 339200.0,
                 E6 = 22.0 / 525.0, E7 = -1.0 / 40.0;
}  // namespace

// ---------------------------------------------------------------- the series

// 1 / k, k = 1..MAX_TERMS + 1
struct Inverses {
    double v[MAX_TERMS + 2];
    constexpr Inverses() : v() {
        for (int k = 1; k < MAX_TERMS + 2; ++k) v[k] = 1.0 / k;
    }
};
constexpr Inverses INV;

int series_terms(double r) {
    // the terms the eigenvalue bound asks for: (r^k / k!) below the tail's bound, and three more (a nearly
    // defective phase's terms carry a factor k)
    double term = 1.0;
    for (int k = 1; k < MAX_TERMS - 3; ++k) {
        term *= r / k;
        if (k >= 3 && term <= SERIES_TAIL) return k + 3;
    }
    return MAX_TERMS;
}

namespace {
// the second component's series coefficient k (wk: w^k / k!; sp, cp: the sine and cosine of the angle at 0)
inline double table_b_term(const Phase& ph, int k, double wk, double sp, double cp) {
    const int m4 = k & 3;
    double g = wk * (ph.bs * (m4 == 0 ? sp : m4 == 1 ? cp : m4 == 2 ? -sp : -cp) +
                     ph.bc * (m4 == 0 ? cp : m4 == 1 ? -sp : m4 == 2 ? -cp : sp));
    if (k == 0) g += ph.bx0;
    if (k == 1) g += ph.bx1;
    return g;
}

// series() for one mass: scalars, the same sums (Plain: a line's table, no second component to add: a few
// instructions a term, so the test is made once, at compile time)
template <bool Plain>
int series_one(const Phase& ph, const double* y0, const double* r, double a0, double a1, double amp, double sp,
               double cp, double h, double* t, int need, double scale, bool held) {
    const double w = ph.w, kk = ph.K[0], cc = ph.C[0], mi = ph.minv[0];
    const double phase[4] = {sp, cp, -sp, -cp};  // sin(w tau + phi)'s k-th derivative at 0, by k mod 4
    double x = y0[0], v = y0[1];
    double wk = 1.0;  // w^k / k!
    double hk = 1.0;  // h^k
    for (int k = 0;; ++k) {
        // the table acceleration's series: a0 + a1 tau + amp sin(w tau + phi)
        double g = amp * wk * phase[k & 3];
        if (k == 0) g += a0;
        if (k == 1) g += a1;
        if (!Plain) g = ph.on(0, g, table_b_term(ph, k, wk, sp, cp));
        const double inv = INV.v[k + 1];
        wk *= w * inv;
        double f = mi * (kk * x + cc * v);
        if (k == 0 && r != nullptr) f += r[0];
        const double vn = held ? 0.0 : (-f - g) * inv;
        const double xn = v * inv;
        t[2 * (k + 1)] = xn;
        t[2 * (k + 1) + 1] = vn;
        const int m = k + 1;  // the term just computed
        hk *= h;
        if (m + 1 >= need) {
            // its size and the last one's, as lengths over [0, h]: both below the tail bound, done
            const double hp = hk / (h > 0.0 ? h : 1.0);
            const double e_m = std::max(0.0, hk * (std::abs(xn) + h * std::abs(vn)));  // (NaN: 0, as series')
            const double e_p = std::max(0.0, hp * (std::abs(x) + h * std::abs(v)));
            if ((e_m <= SERIES_TAIL * scale && e_p <= 1e3 * SERIES_TAIL * scale) || m + 1 >= MAX_TERMS || h == 0.0)
                return m + 1;
        }
        x = xn;
        v = vn;
    }
}
}  // namespace

int series(const Phase& ph, const double* y0, const double* r, double a0, double a1, double amp, double sp,
           double cp, double h, double* t) {
    const int n = ph.n, ny = ph.ny;
    for (int q = 0; q < ny; ++q) t[q] = y0[q];
    const int need = series_terms(std::max(ph.rate, std::abs(ph.w)) * h);
    double scale = ph.xrun;
    for (int i = 0; i < n; ++i) scale = std::max({scale, std::abs(t[i]), h * std::abs(t[n + i])});
    const double w = ph.w;
    const double* K = ph.K.data();
    const double* C = ph.C.data();
    const double* minv = ph.minv.data();
    const bool held = ph.stk.any;  // (held masses do not move)
    const bool plain = ph.plain;
    const double* rA = ph.rA.data();
    const double* rB = ph.rB.data();
    if (n == 1)
        return plain ? series_one<true>(ph, y0, r, a0, a1, amp, sp, cp, h, t, need, scale, held)
                     : series_one<false>(ph, y0, r, a0, a1, amp, sp, cp, h, t, need, scale, held);
    return with_rows(ph, [&](const auto& row) -> int {  // (the loop once for each way to walk a row)
        double wk = 1.0;  // w^k / k!
        double hk = 1.0;  // h^k
        for (int k = 0;; ++k) {
            const int m4 = k % 4;
            // the table acceleration's series: a0 + a1 tau + amp sin(w tau + phi) (and its second component's)
            double g = amp * wk * (m4 == 0 ? sp : m4 == 1 ? cp : m4 == 2 ? -sp : -cp);
            if (k == 0) g += a0;
            if (k == 1) g += a1;
            const double gb = ph.plain ? 0.0 : table_b_term(ph, k, wk, sp, cp);
            const double inv = INV.v[k + 1];
            wk *= w * inv;
            const double* Xk = t + k * ny;
            const double* Vk = Xk + n;
            double* Xn = t + (k + 1) * ny;
            double* Vn = Xn + n;
            for (int i = 0; i < n; ++i) {
                const double* rk = K + i * n;
                const double* rc = C + i * n;
                double s = 0.0;
                row(i, [&](int j) { s += rk[j] * Xk[j] + rc[j] * Vk[j]; });
                double f = minv[i] * s;
                if (k == 0 && r != nullptr) f += r[i];
                Vn[i] = (-f - (plain ? g : rA[i] * g + rB[i] * gb)) * inv;
                Xn[i] = Vk[i] * inv;
            }
            if (held) ph.stk.project(ph.mass, Vn);
            const int m = k + 1;  // the term just computed
            hk *= h;
            if (m + 1 >= need) {
                // its size and the last one's, as lengths over [0, h]: both below the tail bound, done
                double e_m = 0.0, e_p = 0.0;
                const double hp = hk / (h > 0.0 ? h : 1.0);
                for (int i = 0; i < n; ++i) {
                    e_m = std::max(e_m, hk * (std::abs(Xn[i]) + h * std::abs(Vn[i])));
                    e_p = std::max(e_p, hp * (std::abs(Xk[i]) + h * std::abs(Vk[i])));
                }
                if ((e_m <= SERIES_TAIL * scale && e_p <= 1e3 * SERIES_TAIL * scale) || m + 1 >= MAX_TERMS || h == 0.0)
                    return m + 1;
            }
        }
    });
}

void taylor(const Phase& ph, double h) {
    ph.series_made += 1;
    // the restoring force's constant part, as accelerations: M^-1 R0
    double* r = ph.rbuf.data();
    for (int i = 0; i < ph.n; ++i) r[i] = ph.minv[static_cast<size_t>(i)] * ph.R0[static_cast<size_t>(i)];
    ph.nt = series(ph, ph.y0.data(), r, ph.ax0, ph.ax1, ph.axh, ph.sphi, ph.cphi, h, ph.tc.data());
    ph.tc_ok = true;
}

void lin_eval(const Phase& ph, double tau, double* y, double* a) {
    ph.evaluations += 1;
    ensure_series(ph);
    const int n = ph.n, ny = ph.ny, nt = ph.nt;
    const double* t = ph.tc.data();
    if (n == 1) {  // (one mass: scalars, the same sums)
        double x = t[(nt - 1) * 2], v = t[(nt - 1) * 2 + 1], acc = (nt - 1) * v;
        for (int k = nt - 2; k >= 1; --k) {
            x = x * tau + t[2 * k];
            v = v * tau + t[2 * k + 1];
            acc = acc * tau + k * t[2 * k + 1];
        }
        if (nt >= 2) {
            x = x * tau + t[0];
            v = v * tau + t[1];
        }
        y[0] = x;
        y[1] = v;
        a[0] = acc;
        return;
    }
    for (int q = 0; q < ny; ++q) y[q] = t[(nt - 1) * ny + q];
    for (int i = 0; i < n; ++i) a[i] = (nt - 1) * t[(nt - 1) * ny + n + i];
    for (int k = nt - 2; k >= 0; --k) {
        const double* Yk = t + k * ny;
        for (int q = 0; q < ny; ++q) y[q] = y[q] * tau + Yk[q];
        if (k >= 1)
            for (int i = 0; i < n; ++i) a[i] = a[i] * tau + k * Yk[n + i];
    }
}

void table_series(const Phase& ph, int m, double* ga, double* gb) {
    double wk = 1.0;  // w^k / k!
    for (int k = 0; k <= m; ++k) {
        const int m4 = k & 3;
        double g = ph.axh * wk * (m4 == 0 ? ph.sphi : m4 == 1 ? ph.cphi : m4 == 2 ? -ph.sphi : -ph.cphi);
        if (k == 0) g += ph.ax0;
        if (k == 1) g += ph.ax1;
        ga[k] = g;
        gb[k] = table_b_term(ph, k, wk, ph.sphi, ph.cphi);
        wk *= ph.w / (k + 1);
    }
}

void table_derivatives(const Phase& ph, double tau, double s, double c, int m, double* g, double* gb) {
    const double w = ph.w, amp = ph.axh;
    g[0] = ph.ax0 + ph.ax1 * tau + amp * s;
    if (m >= 1) g[1] = ph.ax1 + amp * w * c;
    double wk = w;
    for (int k = 2; k <= m; ++k) {
        wk *= w;
        const int m4 = k % 4;
        g[k] = amp * wk * (m4 == 0 ? s : m4 == 1 ? c : m4 == 2 ? -s : -c);
    }
    if (gb == nullptr) return;
    double wj = 1.0;
    for (int k = 0; k <= m; ++k, wj *= w) {  // (bs sin + bc cos's k-th derivatives, then the line's)
        const int m4 = k % 4;
        gb[k] = wj * (ph.bs * (m4 == 0 ? s : m4 == 1 ? c : m4 == 2 ? -s : -c) +
                      ph.bc * (m4 == 0 ? c : m4 == 1 ? -s : m4 == 2 ? -c : s));
    }
    gb[0] += ph.bx0 + ph.bx1 * tau;
    if (m >= 1) gb[1] += ph.bx1;
}

void pair_poly(const Phase& ph, const Pair& pr, double alpha, double beta, double gamma, double delta, Poly& q) {
    ensure_series(ph);
    const int n = ph.n, ny = ph.ny, nt = ph.nt;
    const double* t = ph.tc.data();
    const int i = pr.i, j = pr.j;
    q.deg = nt - 1;
    if (pr.levered()) {
        for (int k = 0; k < nt; ++k) {
            const double* Yk = t + k * ny;
            q.c[k] = beta * rel(Yk, pr) + gamma * rel(Yk + n, pr);
        }
        if (delta != 0.0)
            for (int k = 0; k + 1 < nt; ++k) q.c[k] += delta * (k + 1) * rel(t + (k + 1) * ny + n, pr);
    } else if (j < 0) {
        const double* xi = t + i;
        const double* vi = t + n + i;
        for (int k = 0; k < nt; ++k) q.c[k] = beta * xi[k * ny] + gamma * vi[k * ny];
        if (delta != 0.0)
            for (int k = 0; k + 1 < nt; ++k) q.c[k] += delta * (k + 1) * vi[(k + 1) * ny];
    } else {
        for (int k = 0; k < nt; ++k) {
            const double* Yk = t + k * ny;
            q.c[k] = beta * (Yk[i] - Yk[j]) + gamma * (Yk[n + i] - Yk[n + j]);
        }
        if (delta != 0.0)
            for (int k = 0; k + 1 < nt; ++k) {
                const double* Yk = t + (k + 1) * ny + n;
                q.c[k] += delta * (k + 1) * (Yk[i] - Yk[j]);
            }
    }
    q.c[0] += alpha;
}

double pair_x(const Phase& ph, const Pair& pr, double tau) {
    ensure_series(ph);
    const int ny = ph.ny;
    const double* t = ph.tc.data();
    const int i = pr.i, j = pr.j;
    double f = 0.0;
    if (pr.levered()) {
        for (int k = ph.nt - 1; k >= 0; --k) f = f * tau + rel(t + k * ny, pr);
    } else if (j < 0) {
        for (int k = ph.nt - 1; k >= 0; --k) f = f * tau + t[k * ny + i];
    } else {
        for (int k = ph.nt - 1; k >= 0; --k) f = f * tau + (t[k * ny + i] - t[k * ny + j]);
    }
    return f;
}

void abs_acc_poly(const Phase& ph, int i, Poly& q) {
    ensure_series(ph);
    const int n = ph.n, ny = ph.ny, nt = ph.nt;
    const double* t = ph.tc.data();
    const double* rk = &ph.K[static_cast<size_t>(i * n)];
    const double* rc = &ph.C[static_cast<size_t>(i * n)];
    const double mi = ph.minv[static_cast<size_t>(i)];
    q.deg = nt - 1;
    for (int k = 0; k < nt; ++k) {
        const double* Yk = t + k * ny;
        double s = 0.0;
        for (int j = 0; j < n; ++j) s += rk[j] * Yk[j] + rc[j] * Yk[n + j];
        q.c[k] = -mi * s;
    }
    q.c[0] -= mi * ph.R0[static_cast<size_t>(i)];
}

void poly_deriv(const Poly& q, Poly& out) {
    out.deg = std::max(q.deg - 1, 0);
    if (q.deg <= 0) {
        out.c[0] = 0.0;
        return;
    }
    for (int k = 1; k <= q.deg; ++k) out.c[k - 1] = k * q.c[k];
}

namespace {
// linear_integrals for one mass that is not held, both ends at once: scalars, and int v^2 once for the
// viscous loss and the contacts'
void one_mass_integrals(const Phase& ph, int order, double c, double m, double tau, const double* y0,
                        const double* a0, double s0, double c0, const double* y1, const double* a1, double s1,
                        double c1, bool energy, double& vcv, double& gv, double* du, double* dvv) {
    double g0[HERMITE_ORDER + 1], g1[HERMITE_ORDER + 1];
    double D0[HERMITE_ORDER + 2], D1[HERMITE_ORDER + 2];
    table_derivatives(ph, 0.0, s0, c0, order, g0);
    table_derivatives(ph, tau, s1, c1, order, g1);
    const double kk = ph.K[0], cc = ph.C[0], mi = ph.minv[0];
    D0[0] = y0[0];
    D0[1] = y0[1];
    D0[2] = a0[0];
    D1[0] = y1[0];
    D1[1] = y1[1];
    D1[2] = a1[0];
    for (int k = 1; k + 2 <= order + 1; ++k) {
        D0[k + 2] = -(mi * (kk * D0[k] + cc * D0[k + 1])) - g0[k];
        D1[k + 2] = -(mi * (kk * D1[k] + cc * D1[k + 1])) - g1[k];
    }
    // sum_k c_k T^(k+1) (f^(k)(0) + (-1)^k f^(k)(T)) for f = v^2, a_g v, x
    double s_vv = 0.0, s_gv = 0.0, s_u = 0.0;
    const double* hc = HERMITE.c[order];
    double t = tau;
    for (int k = 0; k <= order; ++k) {
        const double sg = (k & 1) ? -1.0 : 1.0;
        const double q = hc[k] * t;
        t *= tau;
        double f0 = 0.0, f1 = 0.0;
        for (int j = 0; j <= k / 2; ++j) {
            f0 += SYM[k][j] * (D0[j + 1] * D0[k - j + 1]);
            f1 += SYM[k][j] * (D1[j + 1] * D1[k - j + 1]);
        }
        s_vv += q * (f0 + sg * f1);
        s_u += q * (D0[k] + sg * D1[k]);
        if (energy) {
            double e0 = 0.0, e1 = 0.0;
            for (int j = 0; j <= k; ++j) {
                e0 += BINOM[k][j] * (g0[j] * D0[k - j + 1]);
                e1 += BINOM[k][j] * (g1[j] * D1[k - j + 1]);
            }
            s_gv += q * (e0 + sg * e1);
        }
    }
    if (energy) {
        vcv = c * s_vv;
        gv = m * s_gv;
    }
    for (int k = 0; k < ph.nc; ++k) {  // the contacts in contact with a linear law (the mass against the ground)
        const ContactPhase& ct = ph.ct[static_cast<size_t>(k)];
        if (!ct.in || ct.nl) continue;
        du[k] = s_u;
        dvv[k] = s_vv;
    }
}
}  // namespace

void linear_integrals(Phase& ph, const std::vector<double>& c_lin, const std::vector<double>& mass, double tau,
                      const double* y0, const double* a0, double s0, double c0, const double* y1, const double* a1,
                      double s1, double c1, bool energy, double& vcv, double& gv, double* du, double* dvv) {
    const int n = ph.n;
    double* D = ph.work.data() + ph.w_D;  // (HERMITE_ORDER + 2) n
    double* g = ph.work.data() + ph.w_g;  // HERMITE_ORDER + 1
    double* gb = ph.plain ? nullptr : ph.work.data() + ph.w_gb;  // HERMITE_ORDER + 1 (a second component's)
    vcv = 0.0;
    gv = 0.0;
    for (int c = 0; c < ph.nc; ++c) {
        du[c] = 0.0;
        dvv[c] = 0.0;
    }
    // (the integrands' fastest rate: a product of two motions, each at most the phase's or the forcing's)
    const int order = hermite_order(2.0 * std::max(ph.rate, std::abs(ph.w)) * tau);
    if (n == 1 && !ph.stk.any && ph.plain) {
        one_mass_integrals(ph, order, c_lin[0], mass[0], tau, y0, a0, s0, c0, y1, a1, s1, c1, energy, vcv, gv, du, dvv);
        return;
    }
    table_derivatives(ph, 0.0, s0, c0, order, g, gb);
    end_derivatives(ph, order, y0, a0, g, gb, D);
    hermite_end(ph, order, c_lin, mass, D, g, gb, tau, 1.0, energy, vcv, gv, du, dvv);
    table_derivatives(ph, tau, s1, c1, order, g, gb);
    end_derivatives(ph, order, y1, a1, g, gb, D);
    hermite_end(ph, order, c_lin, mass, D, g, gb, tau, -1.0, energy, vcv, gv, du, dvv);
    (void)n;
}

// ---------------------------------------------------------------- the numerical phase

double zeta_rate(const Phase& ph, int q, const double* v, const double* z) {
    const Hysteretic& h = *ph.bw[static_cast<size_t>(q)];
    const double a = h.bw[2], beta = h.bw[3], gamma = h.bw[4], nexp = h.bw[5];
    const double du = rel(v, h), zq = z[q];
    if (h.bw_mate_slot < 0) {  // (along its line: u' / u_y (a - |z|^n (gamma + beta sgn(u' z))))
        const double az = std::abs(zq);
        const double zn = nexp == 1.0 ? az : std::pow(az, nexp);
        const double s = du * zq > 0.0 ? beta : -beta;
        return du / h.bw[1] * (a - zn * (s + gamma));
    }
    // bidirectional (Park, Wen and Ang, any n): z_q' = (a u'_q - |z|^(n-2) z_q sum_k u'_k z_k (gamma + beta
    // sgn(u'_k z_k))) / u_y over its two components k: yielding under the resultant, |z| <= (a / (beta +
    // gamma))^(1/n), and dissipating (k u_y / a) |z|^n sum_k |u'_k z_k| (beta + gamma sgn(u'_k z_k)) >= 0
    const int m = h.bw_mate_slot;
    const double dm = rel(v, *ph.bw[static_cast<size_t>(m)]), zm = z[m];
    if (h.bw_plastic) {  // (the plastic circle: elastic inside it; on it, slipping, z turns with u''s tangent)
        if (!ph.bw_slip[static_cast<size_t>(q)]) return du / h.bw[1];
        return (du - zq * (du * zq + dm * zm)) / h.bw[1];
    }
    const double pq = du * zq, pm = dm * zm;
    const double sum = pq * (gamma + (pq > 0.0 ? beta : -beta)) + pm * (gamma + (pm > 0.0 ? beta : -beta));
    const double size = std::hypot(zq, zm);
    const double lead = size == 0.0 ? 0.0 : nexp == 2.0 ? 1.0 : std::pow(size, nexp - 2.0);
    return (a * du - lead * zq * sum) / h.bw[1];
}

CircleScale circle_scale(const Phase& ph, int q, const double* v, const double* z, const double* acc,
                         double* rate) {
    const Hysteretic& h = *ph.bw[static_cast<size_t>(q)];
    if (rate) *rate = 0.0;
    const bool slipping = ph.bw_slip[static_cast<size_t>(q)] != 0;
    if (h.friction_rate == 0.0 || h.bw_mate_slot < 0 || (h.bw_plastic && !slipping)) return {1.0, 0.0};
    const int m = h.bw_mate_slot;
    const Hysteretic& hm = *ph.bw[static_cast<size_t>(m)];
    const double du = rel(v, h), dm = rel(v, hm);
    const double s = circle_speed(h, slipping, du, dm, z[q], z[m]);
    if (rate && acc && s > 0.0) {  // (s': z' . u' + z . u'' slipping on a plastic circle, u' . u'' / |u'| on
        const double aq = rel(acc, h), am = rel(acc, hm);  // Bouc-Wen's; none where s is held at 0)
        *rate = h.bw_plastic ? zeta_rate(ph, q, v, z) * du + zeta_rate(ph, m, v, z) * dm + z[q] * aq + z[m] * am
                             : (du * aq + dm * am) / s;
    }
    return circle_scale(h, s);
}

void phase_rhs(Phase& ph, double tau, const double* y, const double* z, double* a, bool held) {
    // dof i: (-R0_i - m_i a_g(tau) - (C v)_i - (K x)_i - the Bouc-Wen spring's - the nonlinear contacts') / m_i,
    // summed in that order (a one-mass system's numbers as the engine has always summed them)
    const int n = ph.n;
    const double* x = y;
    const double* v = y + n;
    const double sn = std::sin(ph.w * tau + ph.phi);
    const double ga = ph.plain ? 0.0 : table_acceleration(ph, tau), gb = table_b(ph, tau);
    with_rows(ph, [&](const auto& row) {
        for (int i = 0; i < n; ++i) {
            const double m = ph.mass[static_cast<size_t>(i)];
            const double* rk = &ph.K[static_cast<size_t>(i * n)];
            const double* rc = &ph.C[static_cast<size_t>(i * n)];
            double f = ph.plain ? (-ph.R0[static_cast<size_t>(i)] - m * ph.ax0) + (-m * ph.ax1) * tau + (-m * ph.axh) * sn
                                : -ph.R0[static_cast<size_t>(i)] - m * ph.on(i, ga, gb);
            row(i, [&](int j) { f -= rc[j] * v[j]; });
            row(i, [&](int j) { f -= rk[j] * x[j]; });
            a[i] = f;
        }
    });
    for (int q = 0; q < ph.nbw; ++q) {
        if (ph.bw_lin[static_cast<size_t>(q)]) continue;  // (a plastic circle inside: in K and R0)
        const Hysteretic& h = *ph.bw[static_cast<size_t>(q)];
        if (h.friction_rate != 0.0) {  // (a friction circle's velocity dependence: isolator.hpp)
            push_pair(a, h, -(h.bw[0] * z[q] * circle_scale(ph, q, v, z).f));
            continue;
        }
        push_pair(a, h, -(h.bw[0] * z[q]));
    }
    for (const Phase::RateFriction& r : ph.rate_fr) {  // (a velocity-dependent friction's rest, isolator.hpp)
        const double f = iso_rate_force(*r.h, r.s, rel(v, *r.h));
        push_pair(a, *r.h, -f);
    }
    for (int c = ph.nc - 1; c >= 0; --c) {
        const ContactPhase& k = ph.ct[static_cast<size_t>(c)];
        if (!k.nl) continue;
        const Compression cp = compression(k, x, v);
        // (a ring's linear law: its phase's branch, as its events and outputs take it)
        const double f = law_is_linear(k.law) ? k.kb * cp.d + k.rb + k.cb * cp.dv
                                              : law_force(k.law, k.p, cp.d, cp.dv, k.lz).f;
        push_contact(a, k, x, -f);
    }
    for (int i = 0; i < n; ++i) a[i] /= ph.mass[static_cast<size_t>(i)];
    if (ph.stk.rings) ph.stk.refresh(x, v);  // (a ring's hold: its row and bias at this state)
    if (held) ph.stk.hold(ph.mass, a);
}

void free_acceleration(Phase& ph, double tau, const double* y, const double* zeta, double* au) {
    phase_rhs(ph, tau, y, zeta, au, false);
}

void held_force_poly(const Phase& ph, int c, Poly& q) {
    ensure_series(ph);
    const int n = ph.n, ny = ph.ny, nt = ph.nt;
    const double* t = ph.tc.data();
    const Sticking& st = ph.stk;
    const int h = st.held_of[static_cast<size_t>(c)];
    const double* side = &st.side[static_cast<size_t>(h * n)];
    const double sign = st.end_sign[static_cast<size_t>(h)];
    q.deg = nt - 1;
    double ga[MAX_TERMS + 1], gb[MAX_TERMS + 1];  // (the table's series, each component's)
    table_series(ph, nt - 1, ga, gb);
    for (int k = 0; k < nt; ++k) {
        const double g = ga[k];
        const double* Yk = t + k * ny;
        double f = 0.0;
        for (int i = 0; i < n; ++i) {
            if (!side[i]) continue;
            const double* rk = &ph.K[static_cast<size_t>(i * n)];
            const double* rc = &ph.C[static_cast<size_t>(i * n)];
            double s = k == 0 ? ph.R0[static_cast<size_t>(i)] : 0.0;
            for (int j = 0; j < n; ++j) s += rk[j] * Yk[j] + rc[j] * Yk[n + j];
            const double a_held = k + 1 < nt ? (k + 1) * t[(k + 1) * ny + n + i] : 0.0;
            f += side[i] * (-s - ph.mass[static_cast<size_t>(i)] * (ph.on(i, g, gb[k]) + a_held));
        }
        q.c[k] = sign * f;
    }
}

Dp5 dp5_step(Phase& ph, double h) {
    const int n = ph.n, ny = ph.ny, nb = ph.nbw;
    double* out = ph.dp5.data();  // y (ny), a (n), ey (ny), z (nb), ez (nb)
    const Dp5 res{out, out + ny, out + ny + n, out + 2 * ny + n, out + 2 * ny + n + nb};
    if (ph.dp5_h == h) return res;
    ph.evaluations += 1;
    const int w = ny + nb;  // a stage's slope: (v, a, z')
    double* ks = ph.work.data() + ph.w_stage;  // 7 stages
    double* yt = ks + 7 * w;                        // a stage's state (ny + nb)
    const double* y0 = ph.y0.data();
    const double* z0 = ph.zeta0.data();
    auto slope = [&](double tau, const double* y, const double* z, double* k) {
        for (int i = 0; i < n; ++i) k[i] = y[n + i];
        phase_rhs(ph, tau, y, z, k + n);
        for (int q = 0; q < nb; ++q) k[ny + q] = zeta_rate(ph, q, y + n, z);
    };
    auto stage = [&](const double* coef, int m) {  // yt = y0 + h sum_j coef_j k_j
        for (int q = 0; q < w; ++q) {
            const double start = q < ny ? y0[q] : z0[q - ny];
            if (m == 1) {  // (h a21 k1, associated as the engine always has)
                yt[q] = start + h * coef[0] * ks[q];
                continue;
            }
            double s = coef[0] * ks[q];
            for (int j = 1; j < m; ++j)
                if (coef[j] != 0.0) s += coef[j] * ks[j * w + q];
            yt[q] = start + h * s;
        }
    };
    slope(0.0, y0, z0, ks);
    const double a2[1] = {A21}, a3[2] = {A31, A32}, a4[3] = {A41, A42, A43}, a5[4] = {A51, A52, A53, A54};
    const double a6[5] = {A61, A62, A63, A64, A65}, b[6] = {B1, 0.0, B3, B4, B5, B6};
    stage(a2, 1);
    slope(C2 * h, yt, yt + ny, ks + w);
    stage(a3, 2);
    slope(C3 * h, yt, yt + ny, ks + 2 * w);
    stage(a4, 3);
    slope(C4 * h, yt, yt + ny, ks + 3 * w);
    stage(a5, 4);
    slope(C5 * h, yt, yt + ny, ks + 4 * w);
    stage(a6, 5);
    slope(h, yt, yt + ny, ks + 5 * w);
    stage(b, 6);
    slope(h, yt, yt + ny, ks + 6 * w);
    const double e[7] = {E1, 0.0, E3, E4, E5, E6, E7};
    for (int q = 0; q < ny; ++q) out[q] = yt[q];
    for (int i = 0; i < n; ++i) out[ny + i] = ks[6 * w + n + i];
    for (int q = 0; q < w; ++q) {
        double s = e[0] * ks[q];
        for (int j = 2; j < 7; ++j) s += e[j] * ks[j * w + q];
        if (q < ny) out[ny + n + q] = h * s;
        else out[2 * ny + n + nb + (q - ny)] = h * s;
    }
    for (int q = 0; q < nb; ++q) out[2 * ny + n + q] = yt[ny + q];
    ph.dp5_h = h;
    return res;
}

void phase_eval(Phase& ph, double tau, double* y, double* a) {
    if (!ph.numeric) {
        lin_eval(ph, tau, y, a);
        return;
    }
    if (tau == 0.0) {
        for (int q = 0; q < ph.ny; ++q) y[q] = ph.y0[static_cast<size_t>(q)];
        phase_rhs(ph, 0.0, y, ph.zeta0.data(), a);
        return;
    }
    const Dp5 r = dp5_step(ph, tau);
    for (int q = 0; q < ph.ny; ++q) y[q] = r.y[q];
    for (int i = 0; i < ph.n; ++i) a[i] = r.a[i];
}

const double* phase_zeta(Phase& ph, double tau, const double* x) {
    if (ph.nbw == 0) return nullptr;
    if (!ph.numeric) {  // (every spring a plastic circle inside: z = zoff + u / u_y, through the sub-intervals)
        for (int q = 0; q < ph.nbw; ++q) {
            const Hysteretic& h = *ph.bw[static_cast<size_t>(q)];
            ph.zlin[static_cast<size_t>(q)] = ph.zoff[static_cast<size_t>(q)] + rel(x, h) / h.bw[1];
        }
        return ph.zlin.data();
    }
    if (tau == 0.0) return ph.zeta0.data();
    return dp5_step(ph, tau).z;
}

}  // namespace pounding
