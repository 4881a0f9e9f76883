// A certified screen of a sub-interval's extrema, from its ends alone (screen.hpp).
#include "screen.hpp"

#include <algorithm>
#include <cmath>

namespace pounding {

namespace {
constexpr double RELATIVE_MARGIN = 1e-9;  // of the values' sizes: far above the series' and the cubic's rounding
constexpr double SCALE_MARGIN = 1e-12;    // of the run's and the ends' scales (the series' rounding is of them)
}  // namespace

void screen_phase(ExtremaScreen& sc, const Phase& ph) {
    const int n = ph.n;
    sc.tau = -1.0;
    sc.on = !ph.numeric && ph.axh == 0.0 && (ph.plain || (ph.bs == 0.0 && ph.bc == 0.0));
    if (!sc.on) return;
    sc.kr.assign(static_cast<size_t>(n), 0.0);
    sc.cr.assign(static_cast<size_t>(n), 0.0);
    sc.jerk.assign(static_cast<size_t>(n), 0.0);
    double kmax = 0.0;
    for (int i = 0; i < n; ++i) {
        double k = 0.0, c = 0.0;
        for (int j = 0; j < n; ++j) {
            k += std::abs(ph.K[static_cast<size_t>(i * n + j)]);
            c += std::abs(ph.C[static_cast<size_t>(i * n + j)]);
        }
        sc.kr[static_cast<size_t>(i)] = ph.minv[static_cast<size_t>(i)] * k;
        sc.cr[static_cast<size_t>(i)] = ph.minv[static_cast<size_t>(i)] * c;
        kmax = std::max(kmax, sc.kr[static_cast<size_t>(i)]);
        sc.on = sc.on && std::isfinite(sc.kr[static_cast<size_t>(i)]) && std::isfinite(sc.cr[static_cast<size_t>(i)]);
    }
    sc.s = std::sqrt(kmax);
    sc.beta = 0.0;
    for (int i = 0; i < n; ++i) {
        const double row = (sc.s > 0.0 ? sc.kr[static_cast<size_t>(i)] / sc.s : 0.0) + sc.cr[static_cast<size_t>(i)];
        sc.beta = std::max(sc.beta, row);
    }
    sc.alpha = std::max(sc.s, sc.beta);
    sc.on = sc.on && std::isfinite(sc.alpha);
}

void screen_interval(ExtremaScreen& sc, const Phase& ph, const double* y0, const double* a0, const double* y1,
                     double tau) {
    const int n = ph.n;
    // the jerk at the start: the equation of motion differentiated, -M^-1 (K v + C a) less the table's rate,
    // projected by the held stops
    double* jerk = sc.jerk.data();
    for (int i = 0; i < n; ++i) {
        const double* rk = &ph.K[static_cast<size_t>(i * n)];
        const double* rc = &ph.C[static_cast<size_t>(i * n)];
        double q = 0.0;
        for (int j = 0; j < n; ++j) q += rk[j] * y0[n + j] + rc[j] * a0[j];
        jerk[i] = -ph.minv[static_cast<size_t>(i)] * q - ph.on(i, ph.ax1, ph.bx1);
    }
    ph.stk.project(ph.mass, jerk);
    double norm = 0.0;
    double xs = ph.xrun, vs = ph.vrun;
    for (int i = 0; i < n; ++i) {
        norm = std::max({norm, sc.s * std::abs(a0[i]), std::abs(jerk[i])});
        xs = std::max({xs, std::abs(y0[i]), std::abs(y1[i])});
        vs = std::max({vs, std::abs(y0[n + i]), std::abs(y1[n + i])});
    }
    sc.tau = tau;
    sc.z = (1.0 + RELATIVE_MARGIN) * std::exp(sc.alpha * tau) * norm;
    sc.xscale = std::max(xs, tau * vs);
    sc.vscale = vs;
}

Range hermite_range(double f0, double d0, double f1, double d1, double h, double f4) {
    // the cubic Hermite interpolant c0 + c1 s + c2 s^2 + c3 s^3 on s = t / h in [0, 1]
    const double c0 = f0, c1 = h * d0;
    const double c2 = 3.0 * (f1 - f0) - 2.0 * h * d0 - h * d1;
    const double c3 = 2.0 * (f0 - f1) + h * d0 + h * d1;
    double top = std::max(f0, f1), bottom = std::min(f0, f1);
    // its stationary points inside: c1 + 2 c2 s + 3 c3 s^2 = 0
    const double qa = 3.0 * c3, qb = 2.0 * c2, qc = c1;
    double roots[2];
    int n_roots = 0;
    if (qa == 0.0) {
        if (qb != 0.0) roots[n_roots++] = -qc / qb;
    } else {
        const double disc = qb * qb - 4.0 * qa * qc;
        if (disc >= 0.0) {
            const double q = -0.5 * (qb + std::copysign(std::sqrt(disc), qb));
            roots[n_roots++] = q / qa;
            if (q != 0.0) roots[n_roots++] = qc / q;
        }
    }
    for (int k = 0; k < n_roots; ++k) {
        const double x = roots[k];
        if (!(0.0 < x && x < 1.0)) continue;
        const double v = c0 + x * (c1 + x * (c2 + x * c3));
        top = std::max(top, v);
        bottom = std::min(bottom, v);
    }
    const double h2 = h * h;
    const double err = h2 * h2 / 384.0 * f4;
    return {bottom - err, top + err, std::abs(f0) + std::abs(f1) + h * (std::abs(d0) + std::abs(d1)) + err};
}

bool surely_within(double f0, double d0, double f1, double d1, double h, double f4, double lo, double hi,
                   double scale) {
    if (!(h > 0.0) || !std::isfinite(f4)) return false;
    return surely_within(hermite_range(f0, d0, f1, d1, h, f4), lo, hi, scale);
}

bool surely_within(const Range& r, double lo, double hi, double scale) {
    if (!std::isfinite(r.lo) || !std::isfinite(r.hi)) return false;
    const double margin = RELATIVE_MARGIN * r.size + SCALE_MARGIN * scale;
    return r.hi + margin <= hi && r.lo - margin >= lo;
}

void audit_value(ExtremaScreen& sc, const Range& r, double off, double scale, double value) {
    // (the exact path's own rounding: of the values' size, and of the scales the series' rounding is of)
    constexpr double ROUNDED = 1e-12;
    const double tol = off + ROUNDED * r.size + SCALE_MARGIN * scale;
    sc.audited += 1;
    if (value > r.hi + tol || value < r.lo - tol) sc.escapes += 1;
}

}  // namespace pounding
