#include "events.hpp"

#include <algorithm>
#include <cmath>

namespace pounding {

namespace {

// the phase's contact slot of an event row
inline const ContactPhase& slot(const Phase& ph, int c) { return ph.ct[static_cast<size_t>(c)]; }

// the internal force's rate on dof i in a numerical phase: (K v + C a)_i and the nonlinear forces' rates
double abs_acceleration_rate(Phase& ph, int i, double tau, const double* y, const double* a) {
    const int n = ph.n;
    const double* v = y + n;
    const double* rk = &ph.K[static_cast<size_t>(i * n)];
    const double* rc = &ph.C[static_cast<size_t>(i * n)];
    double q = 0.0;
    for (int j = 0; j < n; ++j) q += rk[j] * v[j] + rc[j] * a[j];
    // (each force along its pair's w: dof i takes its weight there, +-1 on a plain pair, exact)
    for (int c = 0; c < ph.nc; ++c) {
        const ContactPhase& k = slot(ph, c);
        if (k.radial.on) {  // (its normal turns: its force's direction has a rate too)
            if (!k.nl) continue;  // (out of contact: no force)
            const ContactForce f = contact_force(ph, c, y, a);
            q += push_contact_rate(k, i, y, y + n, f.f, f.rate);
            continue;
        }
        const double w = k.nl ? weight_on(k, i) : 0.0;
        if (w != 0.0) q += w * (k.sign * contact_force(ph, c, y, a).rate);
    }
    if (ph.nbw > 0) {
        const double* z = phase_zeta(ph, tau, y);
        for (int b = 0; b < ph.nbw; ++b) {
            if (ph.bw_lin[static_cast<size_t>(b)]) continue;  // (a plastic circle inside: its rate in K v)
            const Hysteretic& h = *ph.bw[static_cast<size_t>(b)];
            const double w_b = weight_on(h, i);
            if (w_b == 0.0) continue;
            if (h.friction_rate != 0.0) {  // (a circle's velocity dependence: bw[0] (f z' + z f' s'))
                double s_rate = 0.0;
                const CircleScale f = circle_scale(ph, b, v, z, a, &s_rate);
                q += w_b * (h.bw[0] * (f.f * zeta_rate(ph, b, v, z) + z[b] * f.df * s_rate));
                continue;
            }
            q += w_b * (h.bw[0] * zeta_rate(ph, b, v, z));
        }
    }
    for (const Phase::RateFriction& r : ph.rate_fr) {  // (a velocity-dependent friction's rest, isolator.hpp)
        const double w_r = weight_on(*r.h, i);
        if (w_r != 0.0) q += w_r * iso_rate_force_rate(*r.h, r.s, rel(v, *r.h), rel(a, *r.h));
    }
    return -ph.minv[static_cast<size_t>(i)] * q;
}

// a plastic circle's switch (core.hpp's bw_plastic), z slot q's with its mate's: inside it, 1 - |z|^2 (zero where
// it is reached); slipping on it, z . u' (zero where the slip turns back inside)
EventValue circle_value(Phase& ph, int q, double tau, const double* y, const double* a) {
    const Hysteretic& h = *ph.bw[static_cast<size_t>(q)];
    const int m = h.bw_mate_slot;
    const Hysteretic& hm = *ph.bw[static_cast<size_t>(m)];
    const double* z = phase_zeta(ph, tau, y);
    const double* v = y + ph.n;
    const double du = rel(v, h), dm = rel(v, hm), uy = h.bw[1];
    if (!ph.bw_slip[static_cast<size_t>(q)]) {  // (rounded as z's terms: z0 + u / u_y on a linear phase)
        const double terms = ph.numeric ? 1.0 : 1.0 + 2.0 * (std::abs(ph.zoff[static_cast<size_t>(q)]) +
                                                             std::abs(ph.zoff[static_cast<size_t>(m)]));
        return {1.0 - (z[q] * z[q] + z[m] * z[m]), -2.0 * (z[q] * du + z[m] * dm) / uy, terms};
    }
    const double p = z[q] * du + z[m] * dm;
    const double rq = (du - z[q] * p) / uy, rm = (dm - z[m] * p) / uy;  // (z's rates)
    return {p, rq * du + rm * dm + z[q] * rel(a, h) + z[m] * rel(a, hm), std::hypot(du, dm) + ph.vround};
}

// the accuracy of a plastic circle's slip rate z . u' in a numerical phase, m/s: the step's tolerance of the velocities
// v it is made of (phase.hpp's NUMERIC_V_FLOOR_M_S), weighted by both mates' pairs (|z| <= 1)
double circle_rate_accuracy(const Phase& ph, int q, const double* v) {
    const Hysteretic& h = *ph.bw[static_cast<size_t>(q)];
    double s = 0.0;
    for (const Hysteretic* e : {&h, ph.bw[static_cast<size_t>(h.bw_mate_slot)]}) {
        int d[4];
        double w[4];
        const int m = e->entries(d, w);
        for (int r = 0; r < m; ++r) s += std::abs(w[r]) * ph.rtol * (NUMERIC_V_FLOOR_M_S + std::abs(v[d[r]]));
    }
    return s;
}

}  // namespace

EventValue held_force(Phase& ph, int c, double tau, const double* y, const double* a) {
    const int n = ph.n;
    const Sticking& st = ph.stk;
    const int h = st.held_of[static_cast<size_t>(c)];
    const double* side = &st.side[static_cast<size_t>(h * n)];
    const int g_c = st.grp[static_cast<size_t>(st.end_i[static_cast<size_t>(h)])];
    double* au = ph.au.data();
    double* aur = ph.aur.data();
    free_acceleration(ph, tau, y, phase_zeta(ph, tau, y), au);
    // the table acceleration and its rate
    const double ang = ph.w * tau + ph.phi;
    const double ag = ph.ax0 + ph.ax1 * tau + ph.axh * std::sin(ang);
    const double agr = ph.ax1 + ph.axh * ph.w * std::cos(ang);
    // (the second component's and its rate)
    const double bg = table_b(ph, tau);
    const double bgr = ph.plain ? 0.0 : ph.bx1 + ph.w * (ph.bs * std::cos(ang) - ph.bc * std::sin(ang));
    double mean_rate = 0.0;  // the group's acceleration rate (0 on the ground)
    static thread_local std::vector<double> held_rate;  // (general mode: every dof's, the holds' projection's)
    if (st.general) {
        held_rate.resize(static_cast<size_t>(n));
        for (int k = 0; k < n; ++k) {
            aur[k] = abs_acceleration_rate(ph, k, tau, y, a) - ph.on(k, agr, bgr);
            held_rate[static_cast<size_t>(k)] = aur[k];
        }
        st.project(ph.mass, held_rate.data());
    } else {
        for (int k = 0; k < n; ++k) {
            if (st.grp[static_cast<size_t>(k)] != g_c) continue;
            aur[k] = abs_acceleration_rate(ph, k, tau, y, a) - ph.on(k, agr, bgr);
            mean_rate += ph.mass[static_cast<size_t>(k)] * aur[k];
        }
        mean_rate = st.grounded[static_cast<size_t>(g_c)] ? 0.0 : mean_rate / st.gmass[static_cast<size_t>(g_c)];
    }
    double f = 0.0, rate = 0.0, scale = 0.0;
    for (int k = 0; k < n; ++k) {
        if (!side[k]) continue;
        const double m = side[k] * ph.mass[static_cast<size_t>(k)];
        f += m * (au[k] - a[k]);
        rate += m * (aur[k] - (st.general ? held_rate[static_cast<size_t>(k)] : mean_rate));
        double s = std::abs(ph.R0[static_cast<size_t>(k)]) + std::abs(m) * (std::abs(ph.on(k, ag, bg)) + std::abs(a[k]));
        for (int j = 0; j < n; ++j)
            s += std::abs(ph.K[static_cast<size_t>(k * n + j)] * y[j]) + std::abs(ph.C[static_cast<size_t>(k * n + j)] * y[n + j]);
        scale += s;
    }
    if (st.rings) rate += st.ring_rate(h, y, y + n, au, a);  // (a ring held: its rows turn)
    const double sign = st.end_sign[static_cast<size_t>(h)];
    return {sign * f, sign * rate, scale};
}

ForceTurn held_force_turn(Phase& ph, int c, double tau, const double* y, const double* a) {
    const int n = ph.n;
    const Sticking& st = ph.stk;
    const int h = st.held_of[static_cast<size_t>(c)];
    const double* side = &st.side[static_cast<size_t>(h * n)];
    const double* v = y + n;
    double* jerk = ph.au.data();
    double* snap = ph.aur.data();
    // the table's first and second derivatives there, each component's
    const double ang = ph.w * tau + ph.phi;
    double g[3], gb[3];
    table_derivatives(ph, tau, std::sin(ang), std::cos(ang), 2, g, gb);
    // the motion's jerk and snap with the holds: the free ones' (the equation of motion differentiated once
    // more from the two derivatives below, d1 and d2, and the table's k-th) projected as the accelerations are
    auto differentiated = [&](const double* d1, const double* d2, int k, double* out) {
        for (int i = 0; i < n; ++i) {
            const double* rk = &ph.K[static_cast<size_t>(i * n)];
            const double* rc = &ph.C[static_cast<size_t>(i * n)];
            double q = 0.0;
            for (int j = 0; j < n; ++j) q += rk[j] * d1[j] + rc[j] * d2[j];
            out[i] = -ph.minv[static_cast<size_t>(i)] * q - ph.on(i, g[k], gb[k]);
        }
        st.project(ph.mass, out);
    };
    differentiated(v, a, 1, jerk);
    differentiated(a, jerk, 2, snap);
    // the force's rate and bend: sign sum over its side of -(K x + C v + R0)_i - m_i (table_i + a_i),
    // differentiated once and twice; each with the size of its terms, the table's by its amplitude (at a crest
    // its derivative's value is the rounding of its sine and cosine, not a size)
    const double w = ph.w;
    const double amp1 = std::abs(ph.ax1) + std::abs(ph.axh) * w, amp2 = std::abs(ph.axh) * w * w;
    const double bmp1 = std::abs(ph.bx1) + (std::abs(ph.bs) + std::abs(ph.bc)) * w;
    const double bmp2 = (std::abs(ph.bs) + std::abs(ph.bc)) * w * w;
    ForceTurn out{0.0, 0.0, 0.0, 0.0};
    for (int i = 0; i < n; ++i) {
        if (!side[i]) continue;
        const double* rk = &ph.K[static_cast<size_t>(i * n)];
        const double* rc = &ph.C[static_cast<size_t>(i * n)];
        const double m = side[i] * ph.mass[static_cast<size_t>(i)];
        double r = 0.0, b = 0.0, rs = 0.0, bs = 0.0;
        for (int j = 0; j < n; ++j) {
            r += rk[j] * v[j] + rc[j] * a[j];
            b += rk[j] * a[j] + rc[j] * jerk[j];
            rs += std::abs(rk[j] * v[j]) + std::abs(rc[j] * a[j]);
            bs += std::abs(rk[j] * a[j]) + std::abs(rc[j] * jerk[j]);
        }
        const double t1 = ph.on(i, g[1], gb[1]) + jerk[i], t2 = ph.on(i, g[2], gb[2]) + snap[i];
        out.rate += -side[i] * r - m * t1;
        out.bend += -side[i] * b - m * t2;
        const double table1 = std::abs(ph.on(i, amp1, 0.0)) + std::abs(ph.on(i, 0.0, bmp1));
        const double table2 = std::abs(ph.on(i, amp2, 0.0)) + std::abs(ph.on(i, 0.0, bmp2));
        out.rate_scale += rs + std::abs(m) * (table1 + std::abs(jerk[i]));
        out.bend_scale += bs + std::abs(m) * (table2 + std::abs(snap[i]));
    }
    const double sign = st.end_sign[static_cast<size_t>(h)];
    out.rate *= sign;
    out.bend *= sign;
    return out;
}

EventValue stick_value(const EventRow& e, const EventValue& d) {
    return {e.alpha + e.beta * d.g, e.beta * d.gp, std::abs(e.alpha) + d.scale};
}

void circle_turn(Phase& ph, int q, double tau, const double* y, const double* a, double& rate, double& bend) {
    const Hysteretic &h = *ph.bw[static_cast<size_t>(q)], &hm = *ph.bw[static_cast<size_t>(h.bw_mate_slot)];
    const double* z = phase_zeta(ph, tau, y);
    const double zq = z[q], zm = z[h.bw_mate_slot], uy = h.bw[1];
    const double dq = rel(y + ph.n, h), dm = rel(y + ph.n, hm);
    rate = 2.0 * (zq * dq + zm * dm) / uy;
    bend = 2.0 * ((dq * dq + dm * dm) / uy + zq * rel(a, h) + zm * rel(a, hm)) / uy;
}

EventValue event_value_of(const EventRow& e, Phase& ph, double tau, const double* y, const double* a) {
    const int n = ph.n;
    if (e.kind == KIND_ZETA) {  // (alpha: minus z's sign at the phase start; side: its z's slot)
        const double* z = phase_zeta(ph, tau, y);
        return {-e.alpha * z[e.side], -e.alpha * zeta_rate(ph, e.side, y + n, z), 1.0};
    }
    if (e.kind == KIND_CIRCLE) return circle_value(ph, e.side, tau, y, a);
    if (e.kind == KIND_HELD) return held_force(ph, e.side, tau, y, a);
    if (e.kind == KIND_STICK) return stick_value(e, held_force(ph, e.side, tau, y, a));
    if (e.kind == KIND_RADIAL) {  // (alpha + beta x + gamma x', x the compression: rounded against the
                                  // ring's radius and the run's lengths, its rate against the run's speeds)
        const ContactPhase& k = slot(ph, e.side);
        const Compression cp = compression(k, y, y + n, a);
        const double g = e.alpha + e.beta * cp.d + e.gamma * cp.dv, gp = e.beta * cp.dv + e.gamma * cp.da;
        const double scale = std::abs(e.alpha) + std::abs(e.beta) * (k.radial.radius + ph.xround) +
                             std::abs(e.gamma) * (std::abs(cp.dv) + ph.vround);
        if (e.action != ACT_CONTACT || !(k.def0 > 0.0)) return {g, gp, scale};
        // (its start against the wall's relaxing surface: the compression reaches what is left of it)
        const Relaxed r = law_relax(k.law, k.p, k.def0, tau, k.lz);
        return {g + r.d, gp + r.rate, scale + r.d};
    }
    const double dx = rel(y, e), dv = rel(y + n, e), da = rel(a, e);
    if (e.kind == KIND_LINEAR) {  // (a contact's start against its relaxing surface: event_value's others)
        const double g = e.alpha + e.beta * dx + e.gamma * dv;
        const double gp = e.beta * dv + e.gamma * da;
        const double scale = std::abs(e.alpha) + std::abs(e.beta * dx) + std::abs(e.gamma * dv) + ph.xround;
        const ContactPhase& k = slot(ph, e.side);
        const Relaxed r = law_relax(k.law, k.p, k.def0, tau, k.lz);
        return {g + r.d, gp + r.rate, scale + r.d};
    }
    const ContactPhase& k = slot(ph, e.side);
    const double sg = k.sign;
    double dd = sg * dx - k.gap, ddv = sg * dv, dda = sg * da;
    if (k.radial.on) {
        const Compression cp = compression(k, y, y + n, a);
        dd = cp.d, ddv = cp.dv, dda = cp.da;
    }
    double g, gp;
    if (law_is_linear(k.law)) {
        // the phase's own branch, not the one the compression is in: at a breakpoint, the slope the motion
        // heads into
        g = k.kb * dd + k.rb + k.cb * ddv;
        gp = k.kb * ddv + k.cb * dda;
    } else {
        const Relaxed r = law_release(k.law, k.p, dd, ddv, dda, k.lz);
        g = r.d;
        gp = r.rate;
    }
    const double scale =
        law_release(k.law, k.p, std::abs(dd) + ph.xround, std::abs(ddv) + ph.vround, 0.0, k.lz).d;
    return {g, gp, scale};
}

void fn_eval(const Fn& fn, Phase& ph, double tau, double& f, double& fp) {
    if (fn.kind == FN_POLY || fn.kind == FN_POLY_RELAX) {
        ph.poly_evaluations += 1;
        const Poly& q = fn.q;
        f = q.c[q.deg];
        fp = 0.0;
        for (int k = q.deg - 1; k >= 0; --k) {
            fp = fp * tau + f;
            f = f * tau + q.c[k];
        }
        if (fn.kind == FN_POLY_RELAX) {
            const ContactPhase& k = slot(ph, fn.idx);
            const Relaxed r = law_relax(k.law, k.p, k.def0, tau, k.lz);
            f += r.d;
            fp += r.rate;
        }
        return;
    }
    double* y = ph.ye.data();
    double* a = ph.ae.data();
    phase_eval(ph, tau, y, a);
    const int n = ph.n;
    switch (fn.kind) {
        case FN_EVENT: {
            const EventValue ev = event_value(fn.evs[fn.idx], ph, tau, y, a);
            f = ev.g;
            fp = ev.gp;
            return;
        }
        case FN_EVENT_RATE:
            f = event_value(fn.evs[fn.idx], ph, tau, y, a).gp;
            fp = NaN;
            return;
        case FN_PAIR_V:
            f = rel(y + n, *fn.pair);
            fp = rel(a, *fn.pair);
            return;
        case FN_PAIR_A:
            f = rel(a, *fn.pair);
            fp = NaN;
            return;
        case FN_AABS_RATE:
            f = abs_acceleration_rate(ph, fn.idx, tau, y, a);
            fp = NaN;
            return;
        case FN_NORM_RATE:
        case FN_NORM_BEND: {
            const Pair &p = *fn.pair, &q = *fn.second;
            const double up = fn.at[0] + rel(y, p), uq = fn.at[1] + rel(y, q);
            const double vp = rel(y + n, p), vq = rel(y + n, q);
            const double bend = vp * vp + vq * vq + up * rel(a, p) + uq * rel(a, q);
            f = fn.kind == FN_NORM_RATE ? up * vp + uq * vq : bend;
            fp = fn.kind == FN_NORM_RATE ? bend : NaN;
            return;
        }
        case FN_CIRCLE_RATE:
        case FN_CIRCLE_BEND: {
            double rate, bend;
            circle_turn(ph, fn.idx, tau, y, a, rate, bend);
            f = fn.kind == FN_CIRCLE_RATE ? rate : bend;
            fp = fn.kind == FN_CIRCLE_RATE ? bend : NaN;
            return;
        }
        case FN_COMPRESSION_RATE:
        case FN_COMPRESSION_BEND: {
            const Compression cp = compression(slot(ph, fn.idx), y, y + n, a);
            f = fn.kind == FN_COMPRESSION_RATE ? cp.dv : cp.da;
            fp = fn.kind == FN_COMPRESSION_RATE ? cp.da : NaN;
            return;
        }
        default:  // FN_FORCE_RATE
            f = contact_force(ph, fn.idx, y, a).rate;
            fp = NaN;
            return;
    }
}

double root_guess(double fa, double fb, double sa, double sb) {
    const double df = fb - fa;
    const double x = -fa / df;  // the secant's root
    const double ra = df / sa, rb = df / sb;
    if (!(ra > 0.0 && rb > 0.0)) return x;  // (False for NaN)
    const double x2 = x * x;
    const double t = x2 * (3.0 - 2.0 * x) + ra * x * (1.0 - x) * (1.0 - x) + rb * x2 * (x - 1.0);
    if (0.0 < t && t < 1.0) return t;
    return x;
}

namespace {

// Halley's method on a polynomial, kept in the bracket (bisection where a step would leave it)
double halley(const Fn& fn, Phase& ph, double xa, double xb, double fa, double fb, double ra, double rb,
              double xtol) {
    double lo = fa < 0.0 ? xa : xb, hi = fa < 0.0 ? xb : xa;  // f(lo) < 0 < f(hi)
    double x = xa + (xb - xa) * root_guess(fa, fb, ra * (xb - xa), rb * (xb - xa));
    if (!(std::min(xa, xb) < x && x < std::max(xa, xb))) x = 0.5 * (xa + xb);
    for (int it = 0; it < 100; ++it) {
        double f, f1, f2;
        ph.poly_evaluations += 1;
        poly_val3(fn.q, x, f, f1, f2);
        if (f == 0.0) return x;
        if (f < 0.0) lo = x;
        else hi = x;
        double step = NaN;
        if (f1 != 0.0) {
            const double newton = f / f1;
            const double den = 1.0 - 0.5 * newton * f2 / f1;
            step = (den > 0.5 && den < 2.0) ? newton / den : newton;
        }
        double x_new = x - step;
        const bool inside = (x_new - lo) * (x_new - hi) < 0.0;  // (False for NaN)
        if (!inside) {
            x_new = 0.5 * (lo + hi);
            step = x - x_new;
        }
        const double tol = xtol + 4.0 * EPS * std::abs(x_new);
        x = x_new;
        if (std::abs(step) < tol) break;
    }
    return x;
}

// Newton's method kept in the bracket (rtsafe), for a function with a rate
double rtsafe(const Fn& fn, Phase& ph, double xa, double xb, double fa, double fb, double ra, double rb,
              double xtol) {
    double lo = fa < 0.0 ? xa : xb, hi = fa < 0.0 ? xb : xa;  // f(lo) < 0 < f(hi)
    double x = xa + (xb - xa) * root_guess(fa, fb, ra * (xb - xa), rb * (xb - xa));
    double dx_old = std::abs(xb - xa), dx = dx_old;
    double prev_newton = 0.0;
    for (int it = 0; it < 100; ++it) {
        double f, fp;
        fn_eval(fn, ph, x, f, fp);
        if (f == 0.0) break;
        if (f < 0.0) lo = x;
        else hi = x;
        bool newton_ok = fp != 0.0 && !std::isnan(fp);
        double step = 0.0, x_new = 0.0;
        if (newton_ok) {
            step = f / fp;
            x_new = x - step;
            newton_ok = ((x_new - lo) * (x_new - hi) < 0.0) && std::abs(2.0 * step) <= dx_old;
        }
        dx_old = dx;
        double tol;
        if (newton_ok) {
            dx = std::abs(step);
            x = x_new;
            tol = xtol + 4.0 * EPS * std::abs(x);
            // converging quadratically, the next step would be dx^3 / prev^2: below the tolerance, done
            if (dx < prev_newton && dx * dx * dx < tol * prev_newton * prev_newton) break;
            prev_newton = dx;
        } else {
            x_new = 0.5 * (lo + hi);
            dx = std::abs(x_new - x);
            x = x_new;
            tol = xtol + 4.0 * EPS * std::abs(x);
            prev_newton = 0.0;
        }
        if (dx < tol) break;
    }
    return x;
}

double brent(const Fn& fn, Phase& ph, double xa, double xb, double fa, double fb, double xtol) {
    double xpre = xa, xcur = xb, fpre = fa, fcur = fb;
    double xblk = xpre, fblk = fpre, spre = 0.0, scur = 0.0;
    for (int it = 0; it < 200; ++it) {
        if (fpre != 0.0 && fcur != 0.0 && ((fpre < 0.0) != (fcur < 0.0))) {
            xblk = xpre;
            fblk = fpre;
            spre = scur = xcur - xpre;
        }
        if (std::abs(fblk) < std::abs(fcur)) {
            xpre = xcur;
            xcur = xblk;
            xblk = xpre;
            fpre = fcur;
            fcur = fblk;
            fblk = fpre;
        }
        const double delta = 0.5 * (xtol + 4.0 * EPS * std::abs(xcur));
        const double sbis = 0.5 * (xblk - xcur);
        if (fcur == 0.0 || std::abs(sbis) < delta) break;
        if (std::abs(spre) > delta && std::abs(fcur) < std::abs(fpre)) {
            double stry;
            if (xpre == xblk) {
                stry = -fcur * (xcur - xpre) / (fcur - fpre);
            } else {
                const double dpre = (fpre - fcur) / (xpre - xcur);
                const double dblk = (fblk - fcur) / (xblk - xcur);
                stry = -fcur * (fblk * dblk - fpre * dpre) / (dblk * dpre * (fblk - fpre));
            }
            if (2.0 * std::abs(stry) < std::min(std::abs(spre), 3.0 * std::abs(sbis) - delta)) {
                spre = scur;
                scur = stry;
            } else {
                spre = sbis;
                scur = sbis;
            }
        } else {
            spre = sbis;
            scur = sbis;
        }
        xpre = xcur;
        fpre = fcur;
        if (std::abs(scur) > delta) xcur += scur;
        else xcur += sbis > 0.0 ? delta : -delta;
        double fp;
        fn_eval(fn, ph, xcur, fcur, fp);
    }
    return xcur;
}

}  // namespace

double find_root(const Fn& fn, Phase& ph, double xa, double xb, double fa, double fb, double ra, double rb,
                 double xtol) {
    if (fa == 0.0) return xa;
    if (fb == 0.0) return xb;
    if (fn.kind == FN_POLY) return halley(fn, ph, xa, xb, fa, fb, ra, rb, xtol);
    if (fn.kind == FN_POLY_RELAX || fn.kind == FN_EVENT || fn.kind == FN_PAIR_V || fn.kind == FN_COMPRESSION_RATE ||
        fn.kind == FN_CIRCLE_RATE)
        return rtsafe(fn, ph, xa, xb, fa, fb, ra, rb, xtol);
    return brent(fn, ph, xa, xb, fa, fb, xtol);
}

namespace {
// the kind of event function event_fn makes
int event_fn_kind(const EventRow& e, const Phase& ph) {
    if (ph.numeric || e.kind == KIND_ZETA || e.kind == KIND_RADIAL || e.kind == KIND_CIRCLE) return FN_EVENT;
    if (e.kind == KIND_LINEAR && e.action == ACT_CONTACT && slot(ph, e.side).def0 > 0.0) return FN_POLY_RELAX;
    return FN_POLY;
}
}  // namespace

void event_fn(const EventRow* evs, int i, Phase& ph, Fn& fn) {
    const EventRow& e = evs[i];
    fn.evs = evs;
    fn.idx = i;
    fn.pair = &e;
    fn.kind = event_fn_kind(e, ph);
    if (fn.kind == FN_EVENT) return;
    if (e.kind == KIND_HELD) {  // a held rigid stop's force: a polynomial of the series
        held_force_poly(ph, e.side, fn.q);
        return;
    }
    if (e.kind == KIND_STICK) {  // alpha + beta D, D a sticking friction element's tie's force
        held_force_poly(ph, e.side, fn.q);
        for (int k = 0; k <= fn.q.deg; ++k) fn.q.c[k] *= e.beta;
        fn.q.c[0] += e.alpha;
        return;
    }
    if (e.kind == KIND_LINEAR) {
        pair_poly(ph, e, e.alpha, e.beta, e.gamma, 0.0, fn.q);
        if (fn.kind == FN_POLY_RELAX) fn.idx = e.side;  // (against a relaxing surface)
        return;
    }
    // a linear law's release: its branch's force kb x + rb + cb x' with x = sign (x_i - x_j) - gap
    const ContactPhase& k = slot(ph, e.side);
    pair_poly(ph, e, k.rb - k.kb * k.gap, k.kb * k.sign, k.cb * k.sign, 0.0, fn.q);
}

namespace {
// the rate of event i's function: the polynomial's derivative, or the event's rate on the trajectory
void rate_fn(const Fn& fn, Fn& out) {
    out.evs = fn.evs;
    out.idx = fn.idx;
    out.pair = fn.pair;
    if (fn.kind == FN_POLY) {
        poly_deriv(fn.q, out.q);
        out.kind = FN_POLY;
        return;
    }
    out.kind = FN_EVENT_RATE;
}
}  // namespace

bool may_turn_back(double h, double v0, double v1, double a0, double a1) {
    const double s0 = h * a0, s1 = h * a1;
    const double c2 = 3.0 * (v1 - v0) - 2.0 * s0 - s1;
    const double c3 = 2.0 * (v0 - v1) + s0 + s1;
    const double disc = std::max(c2 * c2 - 3.0 * c3 * s0, 0.0);
    const double q = -(c2 + std::copysign(std::sqrt(disc), c2));
    double x = q != 0.0 ? s0 / q : 0.5;
    if (!(0.0 <= x && x <= 1.0) && c3 != 0.0) x = q / (3.0 * c3);
    x = std::min(std::max(x, 0.0), 1.0);
    const double v_c = v0 + x * (s0 + x * (c2 + x * c3));
    const double margin = 0.25 * std::max(std::abs(s0), std::abs(s1));
    return !(v_c * v0 > 0.0 && std::abs(v_c) > margin);
}

const Phase::Zeros& velocity_zeros(Phase& ph, const Pair& pr) {
    const double h = ph.e_h;
    for (const Phase::Zeros& z : ph.zeros)
        if (same_pair(z, pr) && z.h >= h) return z;  // (found on this sub-interval, up to h or beyond)
    Phase::Zeros z{pr, h, 0, {0.0, 0.0}, {0.0, 0.0}};
    const int n = ph.n;
    const double v0 = rel(ph.e_y0 + n, pr), v1 = rel(ph.e_y1 + n, pr);
    const double a0 = rel(ph.e_a0, pr), a1 = rel(ph.e_a1, pr);
    Fn fv, fa;
    const bool poly = !ph.numeric;
    auto velocity_fn = [&]() {  // (made only where a zero may be: the polynomial needs the phase's series)
        if (poly) {
            pair_poly(ph, pr, 0.0, 0.0, 1.0, 0.0, fv.q);
            fv.kind = FN_POLY;
        } else {
            fv.kind = FN_PAIR_V;
            fv.pair = &pr;
        }
    };
    if (h > 0.0 && v0 * v1 < 0.0) {
        velocity_fn();
        double lo = 0.0, v_lo = v0, a_lo = a0;
        if (std::abs(v0) <= TINY_SPEED) {
            // a start at rest: its velocity is zero at the start, the zero sought is the one it comes back
            // through.  Where its acceleration there is zero but for the rounding (a friction slip from rest),
            // the polynomial also crosses zero right at the start: the bracket begins where it already moves
            // the way it starts
            for (double tp = 0.5 * h; tp > 1e-12 * h; tp *= 0.5) {
                double vp, ap;
                fn_eval(fv, ph, tp, vp, ap);
                if (vp != 0.0 && (vp < 0.0) == (v0 < 0.0)) {  // (signs: the product of two tiny ones underflows)
                    lo = tp;
                    v_lo = vp;
                    a_lo = ap;
                    break;
                }
            }
        }
        z.t[0] = find_root(fv, ph, lo, h, v_lo, v1, a_lo, a1, XTOL_S);
        z.count = 1;
    } else if (h > 0.0 && v0 * v1 > 0.0 && a0 * a1 < 0.0 && may_turn_back(h, v0, v1, a0, a1)) {
        velocity_fn();
        if (poly) {
            poly_deriv(fv.q, fa.q);
            fa.kind = FN_POLY;
        } else {
            fa.kind = FN_PAIR_A;
            fa.pair = &pr;
        }
        const double t_a = find_root(fa, ph, 0.0, h, a0, a1, NaN, NaN, XTOL_EXTREMUM_S);
        double vm, am;
        fn_eval(fv, ph, t_a, vm, am);
        if (0.0 < t_a && t_a < h && vm * v0 < 0.0) {
            z.t[0] = find_root(fv, ph, 0.0, t_a, v0, vm, a0, am, XTOL_S);
            z.t[1] = find_root(fv, ph, t_a, h, vm, v1, am, a1, XTOL_S);
            z.count = 2;
        }
    }
    for (int k = 0; k < z.count; ++k) {  // the relative displacement there
        if (poly) {
            ph.poly_evaluations += 1;
            z.x[k] = pair_x(ph, pr, z.t[k]);
        } else {
            phase_eval(ph, z.t[k], ph.ye.data(), ph.ae.data());
            z.x[k] = rel(ph.ye.data(), pr);
        }
    }
    ph.zeros.push_back(z);
    return ph.zeros.back();
}

double locate_event(const EventRow* evs, int i, Phase& ph, double h, double g0, double gp0, double tol0, double g1,
                    double gp1, double tol1, double xtol) {
    double* y = ph.ye.data();
    double* a = ph.ae.data();
    // a slip's end, the slip from rest: its velocity starts at zero the way it slips (g0's sign), its
    // acceleration zero but for the rounding (its force at the threshold), whose sign says nothing.  Where
    // that rounding points back, the polynomial dips right at the start, and where the run's velocity scale is
    // below the dip (a free vibration, a table of next to nothing) the dip would be taken for the slip's end
    // at once.  The sub-interval is then looked at from where its velocity already has the slip's sign
    // (velocity_zeros does the same), moving: no longer at the boundary
    double t_lo = 0.0;
    const EventRow& row = evs[i];
    if (row.side == SIDE_VELOCITY && row.kind == KIND_LINEAR && row.gamma != 0.0 && g0 != 0.0 &&
        gp0 * g0 <= 0.0 && rel(ph.y0.data() + ph.n, row) == 0.0) {
        for (double tp = 0.5 * h; tp > 1e-12 * h; tp *= 0.5) {
            phase_eval(ph, tp, y, a);
            const EventValue ev = event_value(row, ph, tp, y, a);
            if (ev.g != 0.0 && (ev.g < 0.0) == (g0 < 0.0)) {
                t_lo = tp;
                g0 = ev.g;
                gp0 = ev.gp;
                tol0 = 0.0;
                break;
            }
        }
    }
    const bool crosses = g0 > tol0 && g1 <= 0.0;
    const bool leaves = g0 <= tol0 && g1 < -tol1;
    if (!crosses && !leaves && !(gp0 < 0.0 && gp1 > 0.0)) return -1.0;  // (at zero, moving away: nothing)
    // the event's function and its rate, made when first asked for (a polynomial needs the series' terms)
    const int kind = event_fn_kind(evs[i], ph);
    Fn fn, rate;
    bool made_fn = false, made_rate = false;
    auto the_fn = [&]() -> const Fn& {
        if (!made_fn) event_fn(evs, i, ph, fn);
        made_fn = true;
        return fn;
    };
    auto the_rate = [&]() -> const Fn& {
        if (!made_rate) {
            rate_fn(the_fn(), rate);
            if (kind == FN_POLY_RELAX) rate.idx = i;  // (the event's rate on the trajectory)
        }
        made_rate = true;
        return rate;
    };
    // its minimum inside, when it falls at the start and rises at the end: (time, value, scale).  A function of
    // the pair's displacement alone has it where the pair's velocity is zero (found once for every such event
    // of the sub-interval)
    auto minimum = [&](double& tm, double& gm, double& sc) {
        const EventRow& e = evs[i];
        // (a ring's or a circle's own pair's zeros say nothing of its function's: not looked for)
        static const Phase::Zeros none{};
        const Phase::Zeros& z = e.kind == KIND_RADIAL || e.kind == KIND_CIRCLE ? none : velocity_zeros(ph, e);
        if (kind == FN_POLY && e.kind == KIND_LINEAR && e.gamma == 0.0 && e.beta != 0.0 && z.count == 1 &&
            z.t[0] < h) {
            tm = z.t[0];
            gm = e.alpha + e.beta * z.x[0];
            sc = std::abs(e.alpha) + std::abs(e.beta * z.x[0]) + (e.side == SIDE_NONE ? 0.0 : ph.xround);
        } else {
            tm = find_root(the_rate(), ph, t_lo, h, gp0, gp1, NaN, NaN, xtol);
            phase_eval(ph, tm, y, a);
            const EventValue ev = event_value(e, ph, tm, y, a);
            gm = ev.g;
            sc = ev.scale;
        }
    };
    if (crosses) {
        // down and back up to zero by the end (its end within the rounding of zero, on its way up): the bracket
        // over the whole sub-interval holds two crossings, the first before the minimum
        if (gp0 < 0.0 && gp1 > 0.0 && g1 >= -tol1) {
            double tm, gm, sc;
            minimum(tm, gm, sc);
            if (gm < 0.0 && tm > t_lo) return find_root(the_fn(), ph, t_lo, tm, g0, gm, gp0, 0.0, xtol);
        }
        return find_root(the_fn(), ph, t_lo, h, g0, g1, gp0, gp1, xtol);
    }
    if (leaves && kind == FN_POLY && gp0 > 0.0 && gp1 < 0.0 && evs[i].action == ACT_CONTACT &&
        law_is_rigid(slot(ph, evs[i].side).law)) {
        // a rebound off a rigid stop, rising first: where it turns (the pair's velocity zero, found once for
        // the sub-interval), then its root beyond (or there, when the rise is below the rounding)
        const EventRow& e = evs[i];
        const Phase::Zeros& z = velocity_zeros(ph, e);
        double tm, gm;
        if (e.kind == KIND_LINEAR && e.gamma == 0.0 && z.count == 1 && 0.0 < z.t[0] && z.t[0] < h) {
            tm = z.t[0];
            gm = e.alpha + e.beta * z.x[0];
        } else {
            double unused;
            tm = find_root(the_rate(), ph, t_lo, h, gp0, gp1, NaN, NaN, xtol);
            fn_eval(the_fn(), ph, tm, gm, unused);
        }
        if (gm <= tol0) return tm;
        return find_root(the_fn(), ph, tm, h, gm, g1, 0.0, gp1, xtol);
    }
    if (leaves && g0 < -tol0 && g1 >= g0 - tol1 && std::max(std::abs(gp0), std::abs(gp1)) <= ROUNDING * ph.vround &&
        evs[i].action == ACT_CONTACT && law_is_rigid(slot(ph, evs[i].side).law))
        // a free rigid stop past its stop by more than the rounding at the start, not moving at either end and
        // no deeper at the end: a corner its floor's holds keep still, 1e-10 m into its wall by the holds' own
        // rounding.  Nothing meets it (its impact could move nothing: the floor cannot move)
        return -1.0;
    if (leaves) {
        double tp = h;
        double t_up = -1.0, gp_up = 0.0;  // (the earliest instant looked at where it still moved away)
        double t_sure = -1.0, gp_sure = 0.0;  // (the latest where it moved away by more than the rounding)
        for (int it = 0; it < 60; ++it) {
            tp *= 0.5;
            phase_eval(ph, tp, y, a);
            const EventValue ev = event_value(evs[i], ph, tp, y, a);
            if (ev.g > ROUNDING * ev.scale) return find_root(the_fn(), ph, tp, h, ev.g, g1, ev.gp, gp1, xtol);
            if (ev.gp > 0.0) {
                t_up = tp;
                gp_up = ev.gp;
            }
            if (t_sure < 0.0 && ev.gp > ROUNDING * ph.vround) {
                t_sure = tp;
                gp_sure = ev.gp;
            }
        }
        // (near the start of a numerical phase its rate is the rounding of zero either way, a turn of its own
        // every few 1e-15 s: the turn sought is bracketed from where it surely moved away)
        if (t_sure > 0.0) {
            t_up = t_sure;
            gp_up = gp_sure;
        }
        // it first rose, by less than the rounding, and came back: where it turned.  Its rate at the start may
        // be the rounding of zero either way (a rigid stop left at rest by an impulse on a floor's corner, the
        // corner's rate summed from the floor's motions): where it still moved away soon after, it turned there
        if (gp0 > 0.0 && gp1 < 0.0) return find_root(the_rate(), ph, t_lo, h, gp0, gp1, NaN, NaN, xtol);
        if (gp1 < 0.0 && t_up > 0.0 && std::abs(gp0) <= ROUNDING * ph.vround && evs[i].action == ACT_CONTACT &&
            law_is_rigid(slot(ph, evs[i].side).law))
            return find_root(the_rate(), ph, t_up, h, gp_up, gp1, NaN, NaN, xtol);
        return 0.0;
    }
    if (!(gp0 < 0.0 && gp1 > 0.0)) return -1.0;
    // a local minimum inside: does it dip below zero?
    double tm, gm, sc;
    minimum(tm, gm, sc);
    // (a circle's slip rate in a numerical phase: each instant's value is a step of its own from the start, within
    // the step's tolerance of the velocities it is made of, not their rounding: a dip of 1e-11 m/s, within that
    // accuracy, taken for the slip's end on a floor at rest, stuck it and slipped it again at one instant, without end)
    double noise = ROUNDING * sc;
    if (evs[i].kind == KIND_CIRCLE && ph.numeric) noise = std::max(noise, circle_rate_accuracy(ph, evs[i].side, y + ph.n));
    if (gm >= -noise) return -1.0;
    if (g0 <= tol0) return 0.0;  // it leaves the boundary on the wrong side at once
    return find_root(the_fn(), ph, t_lo, tm, g0, gm, gp0, 0.0, xtol);
}

bool events_surely_absent(const EventRow* evs, int n_ev, Phase& ph, const ExtremaScreen& sc, double h,
                          const double* y0, const double* a0, const double* y1, const double* a1, double* ends) {
    const int n = ph.n;
    if (!(sc.tau == h) || !(sc.s > 0.0)) return false;
    const double z = sc.z, beta = sc.beta, alpha = sc.alpha;
    // (a tie's two thresholds share its held force and its bounds)
    int tie = -1;
    EventValue d0{}, d1{};
    double d2 = 0.0, d4 = 0.0, table = 0.0;  // (table: how fast the tie's force moves with the table's line)
    for (int i = 0; i < n_ev; ++i) {
        const EventRow& e = evs[i];
        EventValue e0, e1;
        double g2, g4;  // bounds of the function's second and fourth derivatives over [0, h]
        // (its end's value and rate read with the table at h, not at the instant y1 is the motion at: off by
        // these times the shift)
        double value_slope, rate_slope;
        if (e.kind == KIND_STICK) {
            if (e.side != tie) {
                tie = e.side;
                d0 = held_force(ph, tie, 0.0, y0, a0);
                d1 = held_force(ph, tie, h, y1, a1);
                // D = sum_k side_k m_k (au_k - a_k) (held_force), the table a line: au_k'' = -(M^-1 (K a + C a'))_k
                // and au_k'''' = -(M^-1 (K a'' + C a'''))_k; |a_k| <= Z / s, |a_k'| <= Z, |a_k''| <= beta Z,
                // |a_k'''| <= beta alpha Z, |a_k''''| <= beta alpha^2 Z (screen.hpp)
                const Sticking& stk = ph.stk;
                const double* side = &stk.side[static_cast<size_t>(stk.held_of[static_cast<size_t>(tie)] * n)];
                d2 = d4 = 0.0;
                table = 0.0;
                for (int k = 0; k < n; ++k) {
                    if (!side[k]) continue;
                    const double m = std::abs(side[k] * ph.mass[static_cast<size_t>(k)]);
                    const double kr = sc.kr[static_cast<size_t>(k)], cr = sc.cr[static_cast<size_t>(k)];
                    // (a dof held on the ground: a_k is zero throughout)
                    const int g = stk.grp[static_cast<size_t>(k)];
                    const bool still = g >= 0 && stk.grounded[static_cast<size_t>(g)];
                    d2 += m * ((kr / sc.s + cr) * z + (still ? 0.0 : beta * z));
                    d4 += m * ((kr + cr * alpha) * beta * z + (still ? 0.0 : beta * alpha * alpha * z));
                    table += m;
                }
                table *= std::abs(ph.ax1);
            }
            e0 = stick_value(e, d0);
            e1 = stick_value(e, d1);
            g2 = std::abs(e.beta) * d2;
            g4 = std::abs(e.beta) * d4;
            value_slope = std::abs(e.beta) * table;
            rate_slope = 0.0;
        } else if (e.kind == KIND_LINEAR && !(e.side >= 0 && e.action == ACT_CONTACT && slot(ph, e.side).def0 > 0.0)) {
            e0 = event_value(e, ph, 0.0, y0, a0);
            e1 = event_value(e, ph, h, y1, a1);
            const double times = e.weight();  // (|w . a| at most sum |w| max |a_k|)
            g2 = times * (std::abs(e.beta) / sc.s + std::abs(e.gamma)) * z;
            g4 = times * (std::abs(e.beta) + std::abs(e.gamma) * alpha) * beta * z;
            value_slope = 0.0;
            rate_slope = e.levered() ? std::abs(e.gamma * table_slope_on(ph, e))
                                     : e.j >= 0 ? 0.0 : std::abs(e.gamma * ph.ax1);
        } else {
            return false;
        }
        // (y1 the motion at h give or take the shift: as the extrema's, accumulate.cpp; the end's value and rate
        // read with the table at h, off by its slope over the shift)
        const double off = sc.shift == 0.0 ? 0.0
                                           : 2.0 * sc.shift * (std::abs(e1.gp) + value_slope +
                                                               (g2 + rate_slope) * (sc.shift + 0.15 * h));
        const double scale = e0.scale + e1.scale;
        if (!surely_within(e0.g, e0.gp, e1.g, e1.gp, h, g4, ROUNDING * scale + off, INF, scale)) return false;
        double* end = ends + 3 * i;
        end[0] = e1.g;
        end[1] = e1.gp;
        end[2] = e1.scale;
    }
    return true;
}

namespace {
// contact c's event row a + b x + g x' in its compression x (and its rate): on a line's pair alpha + beta u +
// gamma u' (x = sign u - gap), on a ring's its own kind (KIND_RADIAL: events.hpp); side: a line's rounding
// (a ring's is its own)
void contact_row(EventRow& r, const Contact& ct, int c, double a, double b, double g, int action, int side) {
    r = EventRow();
    static_cast<Pair&>(r) = ct;
    r.index = c;
    r.action = action;
    if (ct.radial.on) {
        r.kind = KIND_RADIAL;
        r.alpha = a, r.beta = b, r.gamma = g;
        r.side = c;
        return;
    }
    r.alpha = a - b * ct.gap;
    r.beta = b * ct.sign;
    r.gamma = g * ct.sign;
    r.side = side;
}
}  // namespace

int bumper_events(const double* st, const Phase& ph, const System& sy, EventRow* evs, int n) {
    if (!sy.has_b) return n;
    const Layout& L = sy.lay;
    for (int c = 0; c < sy.nc(); ++c) {
        const Contact& ct = sy.contact[static_cast<size_t>(c)];
        const bool in_contact = st[L.in_at(c)] != 0.0;
        if (in_contact && law_is_linear(ct.law)) {  // its branch's ends (in the compression x)
            const double* z = st + L.z_at(c);
            const Edges edges = law_branch_edges(ct.law, ct.p, slot(ph, c).jb, z);
            const double turn = law_turn_sign(ct.law, ct.p, z);
            if (turn != 0.0)  // the compression rate x' (of sign ``turn`` on the branch) crossing zero
                // (a velocity: rounded as the isolator's reversals are)
                contact_row(evs[n++], ct, c, 0.0, 0.0, turn, ACT_LAW_BRANCH, SIDE_NONE);
            for (int k = 0; k < 2; ++k) {
                const bool up = k == 1;
                const double edge = up ? edges.upper : edges.lower;
                if (edge < 0.0) continue;
                EventRow& r = evs[n++];  // upper - x, or x - lower
                contact_row(r, ct, c, up ? edge : -edge, up ? -1.0 : 1.0, 0.0, ACT_LAW_BRANCH, c);
                r.dir = up ? EDGE_UP_STATE : EDGE_DOWN_STATE;
            }
        }
        if (in_contact && law_is_rigid(ct.law)) {  // held shut: released when its force would pull
            contact_row(evs[n], ct, c, 0.0, 0.0, 0.0, ACT_RELEASE, c);
            evs[n++].kind = KIND_HELD;
            continue;
        }
        if (!in_contact) {  // its surface met (g = d(t) - x, d the relaxing compression)
            contact_row(evs[n++], ct, c, 0.0, -1.0, 0.0, ACT_CONTACT, c);
        } else {  // the compression back to zero, or the law's force-based release
            contact_row(evs[n++], ct, c, 0.0, 1.0, 0.0, ACT_RELEASE, c);
            evs[n] = evs[n - 1];
            evs[n].kind = KIND_RELEASE;
            n += 1;
        }
    }
    return n;
}

bool law_switches(const Phase& ph) {
    for (int c = 0; c < ph.nc; ++c)
        if (slot(ph, c).nl && law_switches_at_rest(slot(ph, c).law)) return true;
    return false;
}

double relax_horizon(const double* st, const System& sy) {
    const Layout& L = sy.lay;
    double out = INF;
    for (int c = 0; c < sy.nc(); ++c) {
        if (st[L.in_at(c)] == 0.0 && st[L.def_at(c)] > 0.0) {
            const Contact& ct = sy.contact[static_cast<size_t>(c)];
            out = std::min(out, law_relax_horizon(ct.law, ct.p, st[L.def_at(c)], st + L.z_at(c)));
        }
    }
    return out;
}

}  // namespace pounding
