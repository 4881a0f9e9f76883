// The elastic response of a record, exact: the peaks of u, u' and a_abs over time, for each oscillator.
//
// Between two samples the record is A = g0 + g1 tau and the motion has the closed form
// u = exp(-sigma tau) (C cos wd tau + S sin wd tau) + p0 + p1 tau.  Its peaks between samples are found, not
// sampled: every quantity f here (u, u', a_abs) is a damped sinusoid plus a straight line, so f'' is a pure
// damped sinusoid whose zeros are known in closed form; between them f' is monotone with one root at most.
#include "spectrum.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace pounding {

namespace {
constexpr int NEWTON_ITERATIONS = 100;
constexpr int64_t RESORT_EVERY = 32;
constexpr int64_t STOP_POLL = 1024;  // (intervals of a pair's period between two looks at the stop flag)  // (intervals searched between two sorts of the directions by their peaks)
constexpr double PI = 3.141592653589793;

double value(double a, double b, double d0, double d1, double sig, double wd, double tau) {
    return std::exp(-sig * tau) * (a * std::cos(wd * tau) + b * std::sin(wd * tau)) + d0 + d1 * tau;
}
double deriv_a(double a, double b, double sig, double wd) { return -sig * a + wd * b; }
double deriv_b(double a, double b, double sig, double wd) { return -wd * a - sig * b; }

double root(double a1, double b1, double d1, double a2, double b2, double sig, double wd, double lo, double hi,
            double f_lo) {
    double x = 0.5 * (lo + hi);
    for (int it = 0; it < NEWTON_ITERATIONS; ++it) {
        const double fx = value(a1, b1, d1, 0.0, sig, wd, x);
        if (fx == 0.0) return x;
        if ((fx < 0.0) == (f_lo < 0.0)) {
            lo = x;
            f_lo = fx;
        } else {
            hi = x;
        }
        const double dfx = value(a2, b2, 0.0, 0.0, sig, wd, x);
        const double step = dfx != 0.0 ? fx / dfx : 0.0;
        double nx = x - step;
        if (!(lo < nx && nx < hi) || dfx == 0.0) nx = 0.5 * (lo + hi);
        if (std::abs(nx - x) <= 1e-15 * (1.0 + std::abs(x)) || hi - lo <= 1e-15 * (1.0 + std::abs(x))) return nx;
        x = nx;
    }
    return x;
}

// the peak of |f| inside (0, h), f = exp(-sig tau) (a cos + b sin) + d0 + d1 tau; (e, c, s) = exp(-sig h),
// cos(wd h), sin(wd h): the end's factors, known to the caller (the same numbers as computed here)
double interior_peak(double a, double b, double d0, double d1, double sig, double wd, double h, double e, double c,
                     double s) {
    const double a1 = deriv_a(a, b, sig, wd), b1 = deriv_b(a, b, sig, wd);
    const double a2 = deriv_a(a1, b1, sig, wd), b2 = deriv_b(a1, b1, sig, wd);
    double peak = 0.0;
    const double phi = std::atan2(a2, b2);
    double k = std::floor(phi / PI) + 1.0;
    double lo = 0.0;
    double f_lo = a1 + d1;  // (its rate at the start)
    while (true) {
        double cut = (k * PI - phi) / wd;
        const bool last = cut >= h;
        if (last) cut = h;
        const double f_hi = last ? e * (a1 * c + b1 * s) + d1 : value(a1, b1, d1, 0.0, sig, wd, cut);
        if (f_hi == 0.0 && !last) {
            peak = std::max(peak, std::abs(value(a, b, d0, d1, sig, wd, cut)));
        } else if ((f_lo < 0.0) != (f_hi < 0.0) && f_lo != 0.0 && f_hi != 0.0) {
            const double x = root(a1, b1, d1, a2, b2, sig, wd, lo, cut, f_lo);
            peak = std::max(peak, std::abs(value(a, b, d0, d1, sig, wd, x)));
        }
        if (last) break;
        lo = cut;
        f_lo = f_hi;
        k += 1.0;
    }
    return peak;
}
}  // namespace

int spectrum_kernel(const double* t, const double* acc, int64_t n, const double* omegas, int64_t n_omega, double zeta,
                    double* out, int64_t* ctl) {
    const double rt = std::sqrt(1.0 - zeta * zeta);
    for (int64_t j = 0; j < n_omega; ++j) {
        const Control control{ctl};
        if (control.stop()) return INTERRUPTED;
        const double w = omegas[j];
        if (control.add_work(n - 1 + static_cast<int64_t>(w * rt * (t[n - 1] - t[0]) / PI)) < 0) return BUDGET;
        const double w2 = w * w, sig = zeta * w, wd = w * rt;
        double u = 0.0, v = 0.0, u_max = 0.0, v_max = 0.0, a_max = 0.0, h_prev = -1.0, e = 0.0, c = 0.0, s = 0.0;
        for (int64_t k = 0; k < n - 1; ++k) {
            const double h = t[k + 1] - t[k];
            const double g0 = acc[k];
            const double g1 = (acc[k + 1] - g0) / h;
            const double p1 = -g1 / w2;
            const double p0 = (-g0 - 2.0 * sig * p1) / w2;
            const double cu = u - p0;
            const double su = (v - p1 + sig * cu) / wd;
            if (h != h_prev) {
                e = std::exp(-sig * h);
                c = std::cos(wd * h);
                s = std::sin(wd * h);
                h_prev = h;
            }
            const double cv = deriv_a(cu, su, sig, wd), sv = deriv_b(cu, su, sig, wd);
            const double ca = deriv_a(cv, sv, sig, wd), sa = deriv_b(cv, sv, sig, wd);
            const double cj = deriv_a(ca, sa, sig, wd), sj = deriv_b(ca, sa, sig, wd);
            const double cs = deriv_a(cj, sj, sig, wd), ss = deriv_b(cj, sj, sig, wd);
            const double u1 = e * (cu * c + su * s) + p0 + p1 * h;
            const double v1 = e * (cv * c + sv * s) + p1;
            const double acc0 = -2.0 * sig * v - w2 * u;
            const double acc1 = -2.0 * sig * v1 - w2 * u1;
            const bool lng = wd * h >= PI;
            const double ddu0 = acc0 - g0, ddu1 = acc1 - acc[k + 1];
            const bool bend = (ddu0 < 0.0) != (ddu1 < 0.0);
            if (lng || bend || ((v < 0.0) != (v1 < 0.0))) u_max = std::max(u_max, interior_peak(cu, su, p0, p1, sig, wd, h, e, c, s));
            if (lng || bend) v_max = std::max(v_max, interior_peak(cv, sv, p1, 0.0, sig, wd, h, e, c, s));
            const double j0 = cj + g1, j1 = e * (cj * c + sj * s) + g1;
            const double q0 = cs, q1 = e * (cs * c + ss * s);
            if (lng || ((j0 < 0.0) != (j1 < 0.0)) || ((q0 < 0.0) != (q1 < 0.0)))
                a_max = std::max(a_max, interior_peak(ca, sa, g0, g1, sig, wd, h, e, c, s));
            u_max = std::max(u_max, std::abs(u1));
            v_max = std::max(v_max, std::abs(v1));
            a_max = std::max(a_max, std::abs(acc1));
            u = u1;
            v = v1;
        }
        out[3 * j] = u_max;
        out[3 * j + 1] = v_max;
        out[3 * j + 2] = a_max;
    }
    return SUCCESS;
}

namespace {
// one component's interval: its closed form (C, S, p0, p1), its end state and its relative acceleration u'' at both
// ends (a pure damped sinusoid: one zero at most in an interval shorter than half a damped period)
struct Piece {
    // (ca, sa: u'' = exp(-sigma tau) (ca cos + sa sin); cj, sj: its rate's)
    double cu, su, p0, p1, u1, v1, ddu0, ddu1, ca, sa, cj, sj;
};
Piece piece(double u, double v, double g0, double g_end, double h, double w2, double sig, double wd, double e,
            double c, double s) {
    Piece q;
    const double g1 = (g_end - g0) / h;
    q.p1 = -g1 / w2;
    q.p0 = (-g0 - 2.0 * sig * q.p1) / w2;
    q.cu = u - q.p0;
    q.su = (v - q.p1 + sig * q.cu) / wd;
    const double cv = deriv_a(q.cu, q.su, sig, wd), sv = deriv_b(q.cu, q.su, sig, wd);
    q.ca = deriv_a(cv, sv, sig, wd);
    q.sa = deriv_b(cv, sv, sig, wd);
    q.cj = deriv_a(q.ca, q.sa, sig, wd);
    q.sj = deriv_b(q.ca, q.sa, sig, wd);
    q.u1 = e * (q.cu * c + q.su * s) + q.p0 + q.p1 * h;
    q.v1 = e * (cv * c + sv * s) + q.p1;
    q.ddu0 = -2.0 * sig * v - w2 * u - g0;
    q.ddu1 = -2.0 * sig * q.v1 - w2 * q.u1 - g_end;
    return q;
}
}  // namespace

int spectrum_pair_kernel(const double* t, const double* ax, const double* ay, int64_t n, const double* omegas,
                         int64_t n_omega, double zeta, const double* cos_a, const double* sin_a, int64_t n_angle,
                         double* out, int64_t* ctl) {
    const double rt = std::sqrt(1.0 - zeta * zeta);
    std::vector<int64_t> order(static_cast<size_t>(n_angle));
    std::vector<double> snap(static_cast<size_t>(n_angle));
    for (int64_t j = 0; j < n_omega; ++j) {
        const Control control{ctl};
        if (control.stop()) return INTERRUPTED;
        const double w = omegas[j];
        // (each interval searched in a share of the directions; each direction searched for its peaks between
        // the half periods inside an interval, at about four intervals' cost each)
        if (control.add_work((n - 1) * (1 + n_angle / 8) +
                             static_cast<int64_t>(w * rt * (t[n - 1] - t[0]) / PI) * 4 * (1 + n_angle)) < 0)
            return BUDGET;
        const double w2 = w * w, sig = zeta * w, wd = w * rt;
        double* peak = out + j * n_angle;
        std::fill(peak, peak + n_angle, 0.0);
        // the directions in increasing order of their peaks as last sorted (each snapshot <= its peak now, the
        // peaks only grow): an interval is searched in the directions whose snapshot its bound reaches
        for (int64_t q = 0; q < n_angle; ++q) order[static_cast<size_t>(q)] = q;
        std::fill(snap.begin(), snap.end(), 0.0);
        int64_t since = 0;
        double ux = 0.0, vx = 0.0, uy = 0.0, vy = 0.0, h_prev = -1.0, e = 0.0, c = 0.0, s = 0.0;
        for (int64_t k = 0; k < n - 1; ++k) {
            if ((k & (STOP_POLL - 1)) == STOP_POLL - 1 && control.stop()) return INTERRUPTED;
            const double h = t[k + 1] - t[k];
            if (h != h_prev) {
                e = std::exp(-sig * h);
                c = std::cos(wd * h);
                s = std::sin(wd * h);
                h_prev = h;
            }
            const Piece px = piece(ux, vx, ax[k], ax[k + 1], h, w2, sig, wd, e, c, s);
            const Piece py = piece(uy, vy, ay[k], ay[k + 1], h, w2, sig, wd, e, c, s);
            const double h2_8 = h * h / 8.0;
            // |u(tau)| <= |(C cos + S sin)| + |p0 + p1 tau| <= sqrt(|C|^2 + |S|^2) + the line's larger end, and
            // <= the chord's larger end + max |u''| h^2 / 8, max |u''| <= sqrt(|ca|^2 + |sa|^2)
            const double bound = std::min(
                std::sqrt(px.cu * px.cu + py.cu * py.cu + px.su * px.su + py.su * py.su) +
                    std::max(std::hypot(px.p0, py.p0), std::hypot(px.p0 + px.p1 * h, py.p0 + py.p1 * h)),
                std::max(std::hypot(ux, uy), std::hypot(px.u1, py.u1)) +
                    h2_8 * std::sqrt(px.ca * px.ca + py.ca * py.ca + px.sa * px.sa + py.sa * py.sa));
            const bool lng = wd * h >= PI;
            bool searched = false;
            for (int64_t r = 0; r < n_angle && snap[static_cast<size_t>(r)] <= bound; ++r) {
                const int64_t q = order[static_cast<size_t>(r)];  // each direction: n.u, the same closed form
                searched = true;
                const double ca = cos_a[q], sa = sin_a[q];
                const double nc = ca * px.cu + sa * py.cu, ns = ca * px.su + sa * py.su;
                const double n0 = ca * px.p0 + sa * py.p0, n1 = ca * px.p1 + sa * py.p1;
                // (nothing to find below this direction's peak: |n.u| is within |n.(C cos + S sin)| of the
                // line, and within |n.u''| h^2 / 8 of the chord)
                const double room = peak[q] - std::max(std::abs(n0), std::abs(n0 + n1 * h));
                if (room >= 0.0 && nc * nc + ns * ns <= room * room) continue;
                const double e1 = ca * px.u1 + sa * py.u1;
                const double chord = peak[q] - std::max(std::abs(ca * ux + sa * uy), std::abs(e1));
                const double na = ca * px.ca + sa * py.ca, nb = ca * px.sa + sa * py.sa;
                if (chord >= 0.0 && (na * na + nb * nb) * h2_8 * h2_8 <= chord * chord) continue;
                const double v0 = ca * vx + sa * vy, v1 = ca * px.v1 + sa * py.v1;
                const double d0 = ca * px.ddu0 + sa * py.ddu0, d1 = ca * px.ddu1 + sa * py.ddu1;
                double p = std::abs(e1);
                bool inside = lng || ((v0 < 0.0) != (v1 < 0.0));
                if (!inside && ((d0 < 0.0) != (d1 < 0.0))) {
                    // (a bend: the velocity, of one sign at both ends, crosses zero twice only by straying from
                    // its chord further than the largest rate of u'' times h^2 / 8)
                    const double ja = ca * px.cj + sa * py.cj, jb = ca * px.sj + sa * py.sj;
                    const double least = std::min(std::abs(v0), std::abs(v1));
                    inside = !(least * least > (ja * ja + jb * jb) * h2_8 * h2_8);
                }
                if (inside) p = std::max(p, interior_peak(nc, ns, n0, n1, sig, wd, h, e, c, s));
                peak[q] = std::max(peak[q], p);
            }
            if (searched && ++since >= RESORT_EVERY) {  // (the snapshot taken again, in order)
                std::sort(order.begin(), order.end(), [peak](int64_t a, int64_t b) { return peak[a] < peak[b]; });
                for (int64_t r = 0; r < n_angle; ++r) snap[static_cast<size_t>(r)] = peak[order[static_cast<size_t>(r)]];
                since = 0;
            }
            ux = px.u1;
            vx = px.v1;
            uy = py.u1;
            vy = py.v1;
        }
    }
    return SUCCESS;
}

}  // namespace pounding
