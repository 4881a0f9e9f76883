// The outputs at an instant and what a sub-interval adds to a run: energy integrals, contact statistics,
// extrema (run_parts.hpp).
#include "run_parts.hpp"

#include <algorithm>
#include <cmath>

#include "events.hpp"
#include "isolator.hpp"
#include "laws.hpp"
#include "phase.hpp"
#include "screen.hpp"

namespace pounding::run_parts {

// ---------------------------------------------------------------- outputs at an instant

// element e's force on its pair (k u + r0 + c_d u', and its Bouc-Wen spring's)
double iso_force(const System& sy, int e, const double* st) {
    const Hysteretic& h = sy.hyst[static_cast<size_t>(e)];
    const IsoLinear iso = iso_linear(sy, e, st);
    const Layout& L = sy.lay;
    const double u = rel(st + L.x, h), du = rel(st + L.v, h);
    return iso.k * u + iso.r0 + h.c_d * du +
           (h.has_bw() ? h.bw[0] * st[L.zeta + h.bw_slot] * circle_factor(sy, e, st) : 0.0) +
           iso_rate_force(h, iso_rate_slip(sy, e, st), du);
}

// a sample row (or the absolute accelerations and forces) from the state, outside a phase
void outputs(const double* st, const System& sy, double* q, double* row) {
    const Layout& L = sy.lay;
    const int n = sy.n;
    const double* x = st + L.x;
    const double* v = st + L.v;
    for (int i = 0; i < n; ++i) {  // the structure's own springs and dashpots (not the isolator's)
        double s = 0.0;
        for (int j = 0; j < n; ++j)
            s += sy.k0[static_cast<size_t>(i * n + j)] * x[j] + sy.c0[static_cast<size_t>(i * n + j)] * v[j];
        q[i] = s;
    }
    for (int e = 0; e < sy.n_h(); ++e) {
        const Hysteretic& h = sy.hyst[static_cast<size_t>(e)];
        const double f = iso_force(sy, e, st);
        push_pair(q, h, f);
        row[1 + 3 * n + e] = f;
    }
    double* fc = row + 1 + 3 * n + sy.n_h();
    for (int c = 0; c < sy.nc(); ++c) {
        fc[c] = 0.0;
        if (st[L.in_at(c)] == 0.0) continue;
        const Contact& ct = sy.contact[static_cast<size_t>(c)];
        const Compression cp = compression(ct, x, v);
        const double f = law_force(ct.law, ct.p, cp.d, cp.dv, st + L.z_at(c)).f;
        fc[c] = f;
        push_contact(q, ct, x, f);
    }
    row[0] = st[T];
    for (int i = 0; i < n; ++i) {
        row[1 + i] = x[i];
        row[1 + n + i] = v[i];
        row[1 + 2 * n + i] = -q[i] / sy.mass[static_cast<size_t>(i)];
    }
}

void outputs_in_phase(Phase& ph, const System& sy, double t, double tau, const double* y, const double* a,
                      double* row) {
    const int n = ph.n;
    const double ag = table_acceleration(ph, tau), bg = table_b(ph, tau);
    row[0] = t;
    for (int i = 0; i < n; ++i) {
        row[1 + i] = y[i];
        row[1 + n + i] = y[n + i];
        row[1 + 2 * n + i] = a[i] + ph.on(i, ag, bg);
    }
    const double* z = phase_zeta(ph, tau, y);
    for (int e = 0; e < sy.n_h(); ++e) {  // each element's force, its Bouc-Wen spring's with its own
        const Hysteretic& h = sy.hyst[static_cast<size_t>(e)];
        double f = ph.el_k[static_cast<size_t>(e)] * rel(y, h) + ph.el_r[static_cast<size_t>(e)] +
                   h.c_d * rel(y + n, h);
        if (h.has_bw())  // (a friction circle's velocity dependence: isolator.hpp)
            f += h.friction_rate != 0.0 ? h.bw[0] * z[h.bw_slot] * circle_scale(ph, h.bw_slot, y + n, z).f
                                        : h.bw[0] * z[h.bw_slot];
        f += iso_rate_force(h, ph.el_s[static_cast<size_t>(e)], rel(y + n, h));
        if (ph.stk.any && ph.stk.held_of[static_cast<size_t>(ph.nc + e)] >= 0)  // (sticking: its friction)
            f += held_force(ph, ph.nc + e, tau, y, a).g;
        row[1 + 3 * n + e] = f;
    }
    double* fc = row + 1 + 3 * n + sy.n_h();
    for (int c = 0; c < ph.nc; ++c) {
        const bool held = ph.stk.any && ph.stk.held_of[static_cast<size_t>(c)] >= 0;  // (a rigid stop held shut)
        fc[c] = held ? held_force(ph, c, tau, y, a).g : ph.ct[static_cast<size_t>(c)].in ? contact_force(ph, c, y, a).f : 0.0;
    }
}

void energies(const double* st, const System& sy, double& kin, double& iso, double& bmp) {
    const Layout& L = sy.lay;
    const int n = sy.n;
    const double* x = st + L.x;
    const double* v = st + L.v;
    kin = 0.0;
    for (int i = 0; i < n; ++i) kin += 0.5 * sy.mass[static_cast<size_t>(i)] * v[i] * v[i];
    // (element e's Bouc-Wen spring's energy)
    auto e_bw = [&](int e) {
        const Hysteretic& h = sy.hyst[static_cast<size_t>(e)];
        if (!h.has_bw()) return 0.0;
        const double z = st[L.zeta + h.bw_slot];
        return 0.5 * h.bw[0] * h.bw[1] * z * z / h.bw[2];
    };
    double e_k0 = 0.0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) e_k0 += 0.5 * x[i] * sy.k0[static_cast<size_t>(i * n + j)] * x[j];
    iso = (sy.n_h() > 0 ? iso_energy(sy, 0, st, iso_u(sy, 0, st)) + e_bw(0) : 0.0) + e_k0;
    for (int e = 1; e < sy.n_h(); ++e) iso += iso_energy(sy, e, st, iso_u(sy, e, st)) + e_bw(e);
    bmp = 0.0;
    for (int c = 0; c < sy.nc(); ++c) {
        const Contact& ct = sy.contact[static_cast<size_t>(c)];
        bmp += law_energy(ct.law, ct.p, st[L.def_at(c)], st + L.z_at(c));
    }
}

void track_abs_acceleration(double* ex, double t, double a) {
    if (std::abs(a) > ex[EX_A_ABS_MAX]) {
        ex[EX_A_ABS_MAX] = std::abs(a);
        ex[EX_A_ABS_MAX_T] = t;
        ex[EX_A_AT_MAX] = a;
    }
}

void track_displacement(double* ex, double t, double d) {
    static_assert(int(PX_MAX) == int(EX_D_MAX) && int(PX_MAX_T) == int(EX_D_MAX_T) &&
                      int(PX_MIN) == int(EX_D_MIN) && int(PX_MIN_T) == int(EX_D_MIN_T),
                  "a dof's displacement extrema and a pair's share their places");
    if (d > ex[EX_D_MAX]) {
        ex[EX_D_MAX] = d;
        ex[EX_D_MAX_T] = t;
    }
    if (d < ex[EX_D_MIN]) {
        ex[EX_D_MIN] = d;
        ex[EX_D_MIN_T] = t;
    }
}

// ---------------------------------------------------------------- absolute accelerations of a linear phase

namespace {

// the held rigid stops' impulse and peak force over the sub-interval: exactly on a linear phase's polynomial,
// by Gauss-Lobatto on a numerical one
void held_statistics(Phase& ph, const Layout& L, double* st, double tau, const Ends& e, bool linear, Buffers& b);

}  // namespace

// ---------------------------------------------------------------- what a sub-interval adds

// 7-point Gauss-Lobatto on [0, 1] (nonlinear phases' integrals)
constexpr int N_LOBATTO = 7;
constexpr double LOBATTO_X[N_LOBATTO] = {0.0, 0.08488805186071696, 0.2655756032646429, 0.4999999999999999,
                                         0.7344243967353572, 0.9151119481392831, 1.0};
constexpr double LOBATTO_W[N_LOBATTO] = {0.02380952380952377, 0.1384130236807831, 0.21587269060493133,
                                         0.2438095238095238, 0.2158726906049313, 0.13841302368078298,
                                         0.02380952380952377};

namespace {

// a linear phase's energy integrals (dashpots, forcing) and each contact in progress's impulse, work and loss,
// in closed form (or as a kept transition's forms: ``given``)
void linear_contributions(Phase& ph, const System& sy, double* st, double tau, const Ends& e, double* ledger,
                          Buffers& b, bool with_energy, const Given& given) {
    const Layout& L = sy.lay;
    double vcv = given.vcv, gv = given.gv;
    if (!given.have)
        linear_integrals(ph, sy.c_lin, sy.mass, tau, e.y0, e.a0, e.s0, e.c0, e.y1, e.a1, e.s1, e.c1,
                         with_energy, vcv, gv, b.du.data(), b.dvv.data());
    ledger[L_INPUT] -= gv;
    ledger[L_VISCOUS] += vcv;
    for (int c = 0; c < ph.nc; ++c) {
        const ContactPhase& k = ph.ct[static_cast<size_t>(c)];
        if (!k.in) continue;
        const double sg = k.sign, gap = k.gap;
        const int acc = L.acc_at(c);
        const double x0 = sg * rel(e.y0, k) - gap, x1 = sg * rel(e.y1, k) - gap;
        st[acc + A_IMPULSE] += k.kb * (sg * b.du[c] - gap * tau) + k.rb * tau + k.cb * (x1 - x0);
        st[acc + A_WORK] += 0.5 * k.kb * (x1 * x1 - x0 * x0) + k.rb * (x1 - x0) + k.cb * b.dvv[c];
        ledger[L_BUMPER_LOSS] += k.cb * b.dvv[c] + law_branch_loss(k.law, k.p, k.jb, x0, x1, k.lz);
    }
}

// a nonlinear phase's: the same by 7-point Gauss-Lobatto, with the Bouc-Wen springs' hysteresis and a linear
// law's branch loss
void numeric_contributions(Phase& ph, const System& sy, double* st, double tau, const Ends& e, double* ledger,
                           Buffers& b) {
    const int n = ph.n;
    const Layout& L = sy.lay;
    double* y = b.ym.data();
    double* a = b.am.data();
    for (int qn = 0; qn < N_LOBATTO; ++qn) {
        const double tq = tau * LOBATTO_X[qn];
        const double wq = tau * LOBATTO_W[qn];
        if (qn == 0) {
            std::copy(e.y0, e.y0 + 2 * n, y);
            std::copy(e.a0, e.a0 + n, a);
        } else if (qn == N_LOBATTO - 1) {
            std::copy(e.y1, e.y1 + 2 * n, y);
            std::copy(e.a1, e.a1 + n, a);
        } else {
            phase_eval(ph, tq, y, a);
        }
        const double* v = y + n;
        const double ag = table_acceleration(ph, tq), bg = table_b(ph, tq);
        double mv = 0.0, mvb = 0.0, vcv = 0.0;  // (m . v, each component's influence weighted so)
        for (int i = 0; i < n; ++i) {
            if (ph.plain) {
                mv += sy.mass[static_cast<size_t>(i)] * v[i];
            } else {
                mv += sy.mass[static_cast<size_t>(i)] * ph.rA[static_cast<size_t>(i)] * v[i];
                mvb += sy.mass[static_cast<size_t>(i)] * ph.rB[static_cast<size_t>(i)] * v[i];
            }
            double s = 0.0;
            for (int j = 0; j < n; ++j) s += sy.c_lin[static_cast<size_t>(i * n + j)] * v[j];
            vcv += v[i] * s;
        }
        ledger[L_INPUT] -= ph.plain ? wq * ag * mv : wq * (ag * mv + bg * mvb);
        ledger[L_VISCOUS] += wq * vcv;
        if (ph.nbw > 0) {
            const double* z = phase_zeta(ph, tq, y);
            for (int q = 0; q < ph.nbw; ++q) {
                const Hysteretic& h = *ph.bw[static_cast<size_t>(q)];
                if (h.friction_rate != 0.0)  // (a friction circle's velocity dependence)
                    ledger[L_HYSTERETIC] += wq * h.bw[0] * z[q] * circle_scale(ph, q, v, z).f * rel(v, h);
                else
                    ledger[L_HYSTERETIC] += wq * h.bw[0] * z[q] * rel(v, h);
            }
        }
        for (const Phase::RateFriction& r : ph.rate_fr) {  // (a velocity-dependent friction's rest)
            const double du = rel(v, *r.h);
            ledger[L_HYSTERETIC] += wq * iso_rate_force(*r.h, r.s, du) * du;
        }
        for (int c = 0; c < ph.nc; ++c) {
            if (!ph.ct[static_cast<size_t>(c)].in) continue;
            const ContactForce f = contact_force(ph, c, y, a);
            const int acc = L.acc_at(c);
            st[acc + A_IMPULSE] += wq * f.f;
            st[acc + A_WORK] += wq * f.f * f.dx;
            ledger[L_BUMPER_LOSS] += wq * (f.f - f.elastic) * f.dx;
        }
    }
    if (ph.nbw > 0)
        ledger[L_HYSTERETIC] -= bouc_wen_energy(ph, phase_zeta(ph, tau, e.y1)) - bouc_wen_energy(ph, ph.zeta0.data());
    for (int c = 0; c < ph.nc; ++c) {  // a linear law's branch in a numerical phase: its spring's loss
        const ContactPhase& k = ph.ct[static_cast<size_t>(c)];
        if (k.in && law_is_linear(k.law)) {
            ledger[L_BUMPER_LOSS] += law_branch_loss(k.law, k.p, k.jb, compression_of(k, e.y0),
                                                     compression_of(k, e.y1), k.lz);
        }
    }
}

// the screen's bound over [0, tau], made when first asked for in the sub-interval (accumulate resets it)
const ExtremaScreen& ready(ExtremaScreen& sc, const Phase& ph, const Ends& e, double tau) {
    if (sc.tau != tau) screen_interval(sc, ph, e.y0, e.a0, e.y1, tau);
    return sc;
}

// a pair's displacement's range on [0, tau] from the screen (a displacement's fourth derivative is an
// acceleration's second: at most beta Z, a pair's sum |w| times that), and how far y1's shift moves it (off)
struct Screened { Range r; double off; };
Screened displacement_range(const ExtremaScreen& s, const Phase& ph, const Ends& e, double tau, const Pair& pr) {
    const int n = ph.n;
    const double times = pr.weight();
    // (y1 the motion at tau give or take the shift: f1 off by at most |d1| shift + |f''| shift^2 / 2 and d1
    // by |f''| shift, f'' within |a1| + times Z shift there; the cubic moves by the first and 4 tau / 27 of
    // the second, counted twice)
    const double d1 = rel(e.y1 + n, pr);
    const double f2 = std::abs(rel(e.a1, pr)) + times * s.z * s.shift;
    const double off = s.shift == 0.0 ? 0.0 : 2.0 * s.shift * (std::abs(d1) + f2 * (s.shift + 0.15 * tau));
    return {hermite_range(rel(e.y0, pr), rel(e.y0 + n, pr), rel(e.y1, pr), d1, tau, times * s.beta * s.z), off};
}

// whether the range stays within [lo, hi] beyond any doubt of rounding (screen.hpp's surely_within)
bool range_within(const Screened& sr, double lo, double hi, double scale) {
    return surely_within(sr.r, lo + sr.off, hi - sr.off, scale);
}

// a free dof's absolute acceleration's range on [0, tau] from the screen (its fourth derivative:
// -(M^-1 (K a'' + C a^(3)))_i, screen.hpp), from its values aa and rates r at the ends; and its scale
struct ScreenedAcc { Screened sr; double scale; };
ScreenedAcc abs_acceleration_range(const ExtremaScreen& s, const Phase& ph, double tau, int i, double aa0, double r0,
                                   double aa1, double r1) {
    const double kr = s.kr[static_cast<size_t>(i)], cr = s.cr[static_cast<size_t>(i)];
    const double a4 = (kr + cr * s.alpha) * s.beta * s.z;
    const double scale = kr * s.xscale + cr * s.vscale + std::abs(ph.minv[static_cast<size_t>(i)] * ph.R0[static_cast<size_t>(i)]);
    // (y1 off by the shift: the acceleration's second derivative at most (kr / s + cr) Z, and the end's rate
    // read with the table's value at tau, off by its slope over the shift through C)
    const double f2 = ((s.s > 0.0 ? kr / s.s : 0.0) + cr) * s.z + cr * std::abs(ph.ax1);
    const double off = s.shift == 0.0 ? 0.0 : 2.0 * s.shift * (std::abs(r1) + f2 * (s.shift + 0.15 * tau));
    return {{hermite_range(aa0, r0, aa1, r1, tau, a4), off}, scale};
}

// tracked vector q's length (two tracked pairs its components: a bearing's displacement in plan), its largest
// into ex: at the ends, and inside where u . u' crosses zero downwards (u . u' of one sign at the ends and
// turning back inside: both its zeros, found on its rate's); looked for inside only where each component's own
// largest magnitude on the sub-interval (its ends and its velocity's zeros) could make it longer than the
// longest so far
[[gnu::noinline]] void norm_extrema(Phase& ph, const System& sy, int q, double t0, double tau, const Ends& e, double* ex,
                  bool inside) {
    const int n = ph.n;
    const Pair& pp = sy.track[static_cast<size_t>(sy.norm_p[static_cast<size_t>(q)])];
    const Pair& pq = sy.track[static_cast<size_t>(sy.norm_q[static_cast<size_t>(q)])];
    const double op = sy.norm_at[static_cast<size_t>(2 * q)], oq = sy.norm_at[static_cast<size_t>(2 * q + 1)];
    // (u, w: the components' displacements; the length is the offset's plus theirs)
    auto at = [&](double t, double u, double w) {
        const double r = std::hypot(op + u, oq + w);
        if (r > ex[NX_MAX]) {
            ex[NX_MAX] = r;
            ex[NX_MAX_T] = t;
            ex[NX_AT_P] = u;
            ex[NX_AT_Q] = w;
        }
    };
    const double u0 = rel(e.y0, pp), w0 = rel(e.y0, pq), u1 = rel(e.y1, pp), w1 = rel(e.y1, pq);
    at(t0, u0, w0);
    at(t0 + tau, u1, w1);
    if (!inside) return;
    auto largest = [&](const Pair& pr, double o, double f0, double f1) {
        double m = std::max(std::abs(o + f0), std::abs(o + f1));
        const Phase::Zeros& z = velocity_zeros(ph, pr);
        for (int k = 0; k < z.count; ++k)
            if (z.t[k] < tau) m = std::max(m, std::abs(o + z.x[k]));
        return m;
    };
    if (std::hypot(largest(pp, op, u0, u1), largest(pq, oq, w0, w1)) <= ex[NX_MAX]) return;
    const double vp0 = rel(e.y0 + n, pp), vq0 = rel(e.y0 + n, pq), vp1 = rel(e.y1 + n, pp), vq1 = rel(e.y1 + n, pq);
    const double U0 = op + u0, W0 = oq + w0, U1 = op + u1, W1 = oq + w1;
    const double g0 = U0 * vp0 + W0 * vq0, g1 = U1 * vp1 + W1 * vq1;
    const double b0 = vp0 * vp0 + vq0 * vq0 + U0 * rel(e.a0, pp) + W0 * rel(e.a0, pq);
    const double b1 = vp1 * vp1 + vq1 * vq1 + U1 * rel(e.a1, pp) + W1 * rel(e.a1, pq);
    Fn fg;
    fg.kind = FN_NORM_RATE;
    fg.pair = &pp;
    fg.second = &pq;
    fg.at[0] = op;
    fg.at[1] = oq;
    auto length_at = [&](double t) {
        if (!(0.0 < t && t < tau)) return;
        phase_eval(ph, t, ph.ye.data(), ph.ae.data());
        at(t0 + t, rel(ph.ye.data(), pp), rel(ph.ye.data(), pq));
    };
    if (g0 > 0.0 && g1 < 0.0) {
        length_at(find_root(fg, ph, 0.0, tau, g0, g1, b0, b1, XTOL_EXTREMUM_S));
    } else if (g0 * g1 > 0.0 && b0 * b1 < 0.0 && may_turn_back(tau, g0, g1, b0, b1)) {
        Fn fb = fg;
        fb.kind = FN_NORM_BEND;
        const double t_b = find_root(fb, ph, 0.0, tau, b0, b1, NaN, NaN, XTOL_EXTREMUM_S);
        double g_b, b_b;
        fn_eval(fg, ph, t_b, g_b, b_b);
        if (0.0 < t_b && t_b < tau && g_b * g0 < 0.0) {
            length_at(find_root(fg, ph, 0.0, t_b, g0, g_b, b0, b_b, XTOL_EXTREMUM_S));
            length_at(find_root(fg, ph, t_b, tau, g_b, g1, b_b, b1, XTOL_EXTREMUM_S));
        }
    }
}

// a ring's contact (core.hpp's Radial) in progress: its compression's largest inside (0, tau) into mc, where
// its rate crosses zero (once, or twice where it turns back inside)
void deepest_on_ring(Phase& ph, int c, double tau, const Ends& e, double& mc) {
    const int n = ph.n;
    const ContactPhase& k = ph.ct[static_cast<size_t>(c)];
    const Compression c0 = compression(k, e.y0, e.y0 + n, e.a0), c1 = compression(k, e.y1, e.y1 + n, e.a1);
    Fn fr;
    fr.kind = FN_COMPRESSION_RATE;
    fr.idx = c;
    auto deepest_at = [&](double t) {
        phase_eval(ph, t, ph.ye.data(), ph.ae.data());
        mc = std::max(mc, compression_of(k, ph.ye.data()));
    };
    if (c0.dv * c1.dv < 0.0) {
        deepest_at(find_root(fr, ph, 0.0, tau, c0.dv, c1.dv, c0.da, c1.da, XTOL_S));
    } else if (c0.dv * c1.dv > 0.0 && c0.da * c1.da < 0.0 && may_turn_back(tau, c0.dv, c1.dv, c0.da, c1.da)) {
        Fn fb;
        fb.kind = FN_COMPRESSION_BEND;
        fb.idx = c;
        const double t_b = find_root(fb, ph, 0.0, tau, c0.da, c1.da, NaN, NaN, XTOL_EXTREMUM_S);
        double v_b, a_b;
        fn_eval(fr, ph, t_b, v_b, a_b);
        if (0.0 < t_b && t_b < tau && v_b * c0.dv < 0.0) {
            deepest_at(find_root(fr, ph, 0.0, t_b, c0.dv, v_b, c0.da, a_b, XTOL_S));
            deepest_at(find_root(fr, ph, t_b, tau, v_b, c1.dv, a_b, c1.da, XTOL_S));
        }
    }
}

// each dof's displacement extrema and each tracked pair's (a storey's drift), at the velocity's zeros and the
// ends (none inside where the screen clears it); each tracked vector's longest; each contact in progress's
// deepest compression
void displacement_extrema(Phase& ph, const System& sy, double* st, double t0, double tau, const Ends& e,
                          double* extrema, ExtremaScreen* sc, bool inside) {
    const int n = ph.n;
    const Layout& L = sy.lay;
    // whether a pair may be extreme inside: its velocity may cross zero there (where no event of the
    // sub-interval asked for a velocity's zeros, none is kept that could say otherwise), and the screen does
    // not clear it (a displacement's fourth derivative is an acceleration's second: at most beta Z, a pair's
    // sum |w| times that)
    const bool none_kept = ph.zeros.empty();
    auto may_be_extreme = [&](const Pair& pr, const double* ex) {
        const bool may_cross = velocity_may_cross(ph, pr);
        if (!may_cross) return !none_kept;
        if (sc == nullptr) return true;
        const ExtremaScreen& s = ready(*sc, ph, e, tau);
        const Screened sr = displacement_range(s, ph, e, tau, pr);
        if (!range_within(sr, ex[EX_D_MIN], ex[EX_D_MAX], s.xscale)) return true;
        if (sc->audit) {  // (found all the same, and held against the bound)
            const Phase::Zeros& z = velocity_zeros(ph, pr);
            for (int k = 0; k < z.count; ++k)
                if (z.t[k] < tau) audit_value(*sc, sr.r, sr.off, s.xscale, z.x[k]);
        }
        return false;
    };
    // displacement extrema of each dof, at its velocity's zeros and the ends (none inside where the screen
    // clears it: within the largest and smallest so far)
    for (int i = 0; i < n; ++i) {
        double* ex = extrema + DOF_EXTREMA * i;
        track_displacement(ex, t0, e.y0[i]);
        track_displacement(ex, t0 + tau, e.y1[i]);
        const Pair& own = sy.dof_pair[static_cast<size_t>(i)];
        if (!inside || !may_be_extreme(own, ex)) continue;
        const Phase::Zeros& z = velocity_zeros(ph, own);
        for (int k = 0; k < z.count; ++k)
            if (z.t[k] < tau) track_displacement(ex, t0 + z.t[k], z.x[k]);
    }
    // the tracked pairs' relative displacement (a storey's drift): the same, on the pair
    for (int p = 0; p < sy.n_track(); ++p) {
        double* ex = extrema + DOF_EXTREMA * n + PAIR_EXTREMA * p;
        const Pair& pr = sy.track[static_cast<size_t>(p)];
        track_displacement(ex, t0, rel(e.y0, pr));
        track_displacement(ex, t0 + tau, rel(e.y1, pr));
        if (!inside || !may_be_extreme(pr, ex)) continue;
        const Phase::Zeros& z = velocity_zeros(ph, pr);
        for (int k = 0; k < z.count; ++k)
            if (z.t[k] < tau) track_displacement(ex, t0 + z.t[k], z.x[k]);
    }
    for (int q = 0; q < sy.n_norm(); ++q)
        norm_extrema(ph, sy, q, t0, tau, e, extrema + sy.norm_extrema_at() + NORM_EXTREMA * q, inside);
    // the contacts' deepest compression: the ends and the pair's velocity zeros
    for (int c = 0; c < ph.nc; ++c) {
        const ContactPhase& k = ph.ct[static_cast<size_t>(c)];
        if (!k.in) continue;
        double& mc = st[L.acc_at(c) + A_MAXCOMP];
        mc = std::max(mc, compression_of(k, e.y0));
        mc = std::max(mc, compression_of(k, e.y1));
        if (k.radial.on) {  // (a ring's: where its compression's rate is zero inside)
            deepest_on_ring(ph, c, tau, e, mc);
            continue;
        }
        const Phase::Zeros& z = velocity_zeros(ph, k);
        for (int q = 0; q < z.count; ++q)
            if (z.t[q] < tau) mc = std::max(mc, k.sign * z.x[q] - k.gap);
    }
}

// an absolute acceleration's polynomial fa's extremum inside [0, tau], where its rate (fr) changes sign
void extreme_inside(Phase& ph, Fn& fa, Fn& fr, double* ex, double t0, double tau) {
    poly_deriv(fa.q, fr.q);
    fr.kind = FN_POLY;
    const double r0 = poly_val(fr.q, 0.0), r1 = poly_val(fr.q, tau);
    ph.poly_evaluations += 2;
    if (r0 * r1 < 0.0) {
        const double tm = find_root(fr, ph, 0.0, tau, r0, r1, NaN, NaN, XTOL_EXTREMUM_S);
        ph.poly_evaluations += 1;
        track_abs_acceleration(ex, t0 + tm, poly_val(fa.q, tm));
    }
}

// a held dof's absolute acceleration extrema: its group's motion (on the ground: the table's crests inside)
void held_abs_acceleration(Phase& ph, int i, double* ex, double t0, double tau, const Ends& e, bool linear) {
    const int n = ph.n;
    track_abs_acceleration(ex, t0, e.a0[i] + table_on(ph, i, 0.0));
    track_abs_acceleration(ex, t0 + tau, e.a1[i] + table_on(ph, i, tau));
    const int g = ph.stk.grp[static_cast<size_t>(i)];
    // (the table on dof i: a line a0 + a1 s and a harmonic amp sin(w s + phi + lead); a plain table's the
    // first component's)
    double a1 = ph.ax1, amp = ph.axh, lead = 0.0;
    if (!ph.plain) {
        const double ri = ph.rA[static_cast<size_t>(i)], qi = ph.rB[static_cast<size_t>(i)];
        const double S = ri * ph.axh + qi * ph.bs, C = qi * ph.bc;
        a1 = ri * ph.ax1 + qi * ph.bx1;
        amp = std::hypot(S, C);
        lead = std::atan2(C, S);
    }
    if (ph.stk.grounded[static_cast<size_t>(g)] && amp != 0.0 && ph.w > 0.0) {
        // held on the ground it moves with the table: the table's crests inside, where
        // a1 + amp w cos(w s + phi + lead) = 0
        const double c = -a1 / (amp * ph.w);
        if (std::abs(c) <= 1.0) {
            const double theta = std::acos(c);
            for (const double target : {theta, -theta}) {
                double s = std::fmod(target - (ph.phi + lead), TWO_PI);
                if (s < 0.0) s += TWO_PI;
                s /= ph.w;
                if (0.0 < s && s < tau) track_abs_acceleration(ex, t0 + s, table_on(ph, i, s));
            }
        }
    } else if (linear && ph.stk.general) {
        // held by constraints (sticking.hpp's general mode): its relative acceleration the projection of the
        // free ones, a_i = sum_k P_ik (aa_k - table_k), aa_k = -(K x + C v + R0)_k / m_k, then its own table
        Fn fa, fr, fk;
        abs_acc_poly(ph, i, fk.q);  // (its degree: the series', the table's with it where P's row is all 0)
        fa.q.deg = fk.q.deg;
        std::fill(fa.q.c, fa.q.c + fa.q.deg + 1, 0.0);
        double ra = ph.plain ? 1.0 : ph.rA[static_cast<size_t>(i)], rb = ph.plain ? 0.0 : ph.rB[static_cast<size_t>(i)];
        for (int k = 0; k < n; ++k) {
            const double w = ph.stk.projector(ph.mass, i, k);
            if (w == 0.0) continue;
            abs_acc_poly(ph, k, fk.q);
            for (int m = fa.q.deg + 1; m <= fk.q.deg; ++m) fa.q.c[m] = 0.0;
            fa.q.deg = std::max(fa.q.deg, fk.q.deg);
            for (int m = 0; m <= fk.q.deg; ++m) fa.q.c[m] += w * fk.q.c[m];
            ra -= w * (ph.plain ? 1.0 : ph.rA[static_cast<size_t>(k)]);
            rb -= w * (ph.plain ? 0.0 : ph.rB[static_cast<size_t>(k)]);
        }
        double ga[MAX_TERMS + 1], gb[MAX_TERMS + 1];
        table_series(ph, fa.q.deg, ga, gb);
        for (int m = 0; m <= fa.q.deg; ++m) fa.q.c[m] += ra * ga[m] + rb * gb[m];
        extreme_inside(ph, fa, fr, ex, t0, tau);
    } else if (linear && !ph.stk.grounded[static_cast<size_t>(g)]) {
        // a group moving as one: its absolute acceleration the mass-weighted mean of its dofs' free
        // ones, -(K x + C v + R0)_k / M (the holds' forces inside it cancel), extreme where its rate
        // changes sign
        Fn fa, fr, fk;
        fa.q.deg = 0;
        fa.q.c[0] = 0.0;
        const double share = 1.0 / ph.stk.gmass[static_cast<size_t>(g)];
        for (int k = 0; k < n; ++k) {
            if (ph.stk.grp[static_cast<size_t>(k)] != g) continue;
            abs_acc_poly(ph, k, fk.q);
            const double w = ph.mass[static_cast<size_t>(k)] * share;
            for (int m = fa.q.deg + 1; m <= fk.q.deg; ++m) fa.q.c[m] = 0.0;
            fa.q.deg = std::max(fa.q.deg, fk.q.deg);
            for (int m = 0; m <= fk.q.deg; ++m) fa.q.c[m] += w * fk.q.c[m];
        }
        if (!ph.plain) {
            // (the group's mean of its dofs' free absolute accelerations is its relative acceleration and the
            // mean of their tables; dof i's own table differs from that mean where the influences differ)
            double ra = ph.rA[static_cast<size_t>(i)], rb = ph.rB[static_cast<size_t>(i)];
            for (int k = 0; k < n; ++k) {
                if (ph.stk.grp[static_cast<size_t>(k)] != g) continue;
                const double w = ph.mass[static_cast<size_t>(k)] * share;
                ra -= w * ph.rA[static_cast<size_t>(k)];
                rb -= w * ph.rB[static_cast<size_t>(k)];
            }
            double ga[MAX_TERMS + 1], gb[MAX_TERMS + 1];
            table_series(ph, fa.q.deg, ga, gb);
            for (int m = 0; m <= fa.q.deg; ++m) fa.q.c[m] += ra * ga[m] + rb * gb[m];
        }
        extreme_inside(ph, fa, fr, ex, t0, tau);
    }
}

// a free dof's: a linear phase's at the ends and where its polynomial's rate changes sign (skipped when the
// polynomial's bound is below the largest so far), a nonlinear one's where the numerical rate does
void free_abs_acceleration(Phase& ph, int i, double* ex, double t0, double tau, const Ends& e, bool linear,
                           Buffers& b, ExtremaScreen* sc, bool inside) {
    if (linear) {
        // a linear phase's absolute acceleration -(K x + C v + R0)_i / m_i and its rate at the ends; the
        // polynomial only where the rate changes sign
        // (the start's is the last sub-interval's end's where the same phase went on from it: the same numbers)
        double& kept = b.aa_end[static_cast<size_t>(i)];
        const double aa0 = b.went_on ? kept : abs_acc_linear(ph, i, e.y0), aa1 = abs_acc_linear(ph, i, e.y1);
        kept = aa1;
        track_abs_acceleration(ex, t0, aa0);
        track_abs_acceleration(ex, t0 + tau, aa1);
        if (!inside) return;
        const double r0 = abs_acc_rate_linear(ph, i, e.y0, e.a0), r1 = abs_acc_rate_linear(ph, i, e.y1, e.a1);
        if (r0 * r1 < 0.0) {
            if (sc != nullptr) {
                const ExtremaScreen& s = ready(*sc, ph, e, tau);
                const ScreenedAcc sa = abs_acceleration_range(s, ph, tau, i, aa0, r0, aa1, r1);
                if (range_within(sa.sr, -ex[EX_A_ABS_MAX], ex[EX_A_ABS_MAX], sa.scale)) {
                    if (sc->audit) {  // (found all the same, and held against the bound)
                        Fn fa, fr;
                        abs_acc_poly(ph, i, fa.q);
                        poly_deriv(fa.q, fr.q);
                        fr.kind = FN_POLY;
                        const double tm = find_root(fr, ph, 0.0, tau, r0, r1, NaN, NaN, XTOL_EXTREMUM_S);
                        audit_value(*sc, sa.sr.r, sa.sr.off, sa.scale, poly_val(fa.q, tm));
                    }
                    return;
                }
            }
            Fn fa, fr;
            abs_acc_poly(ph, i, fa.q);
            // (its bound over the sub-interval, sum |c_k| tau^k, below the largest so far: no new extremum)
            double bound = 0.0;
            for (int k = fa.q.deg; k >= 0; --k) bound = bound * tau + std::abs(fa.q.c[k]);
            if (bound <= ex[EX_A_ABS_MAX]) return;
            poly_deriv(fa.q, fr.q);
            fr.kind = FN_POLY;
            const double tm = find_root(fr, ph, 0.0, tau, r0, r1, NaN, NaN, XTOL_EXTREMUM_S);
            ph.poly_evaluations += 1;
            track_abs_acceleration(ex, t0 + tm, poly_val(fa.q, tm));
        }
    } else {
        Fn fr;
        fr.kind = FN_AABS_RATE;
        fr.idx = i;
        double r0, r1, unused;
        track_abs_acceleration(ex, t0, e.a0[i] + table_on(ph, i, 0.0));
        track_abs_acceleration(ex, t0 + tau, e.a1[i] + table_on(ph, i, tau));
        fn_eval(fr, ph, 0.0, r0, unused);
        fn_eval(fr, ph, tau, r1, unused);
        if (r0 * r1 < 0.0) {
            const double tm = find_root(fr, ph, 0.0, tau, r0, r1, NaN, NaN, XTOL_EXTREMUM_S);
            phase_eval(ph, tm, b.ym.data(), b.am.data());
            track_abs_acceleration(ex, t0 + tm, b.am[static_cast<size_t>(i)] + table_on(ph, i, tm));
        }
    }
}

// each contact in progress's peak force: the ends, and where its rate changes sign
void peak_contact_forces(Phase& ph, const Layout& L, double* st, double tau, const Ends& e, bool linear,
                         Buffers& b) {
    for (int c = 0; c < ph.nc; ++c) {
        const ContactPhase& k = ph.ct[static_cast<size_t>(c)];
        if (!k.in) continue;
        const int acc = L.acc_at(c);
        const ContactForce fa = contact_force(ph, c, e.y0, e.a0);
        const ContactForce fb = contact_force(ph, c, e.y1, e.a1);
        double peak = std::max(fa.f, fb.f);
        if (fa.rate * fb.rate < 0.0) {
            if (linear) {
                Fn ff, fr;
                pair_poly(ph, k, k.rb - k.kb * k.gap, k.kb * k.sign, k.cb * k.sign, 0.0, ff.q);
                poly_deriv(ff.q, fr.q);
                fr.kind = FN_POLY;
                const double tm = find_root(fr, ph, 0.0, tau, fa.rate, fb.rate, NaN, NaN, XTOL_EXTREMUM_S);
                ph.poly_evaluations += 1;
                peak = std::max(peak, poly_val(ff.q, tm));
            } else {
                Fn fr;
                fr.kind = FN_FORCE_RATE;
                fr.idx = c;
                const double tm = find_root(fr, ph, 0.0, tau, fa.rate, fb.rate, NaN, NaN, XTOL_EXTREMUM_S);
                phase_eval(ph, tm, b.ym.data(), b.am.data());
                peak = std::max(peak, contact_force(ph, c, b.ym.data(), b.am.data()).f);
            }
        }
        st[acc + A_PEAK] = std::max(st[acc + A_PEAK], peak);
    }
}

}  // namespace

// whether no extremum accumulate looks for can lie inside [0, tau] beyond those at its ends (a record's whole
// step, run.cpp): each dof's displacement and each tracked pair's within the largest and smallest so far and at
// the ends, or its velocity of one sign throughout (its fourth derivative an acceleration's third: at most
// beta alpha Z, a pair's sum |w| times that); each free dof's absolute acceleration within the largest so far and at
// the ends; a held dof on the ground (the table a line: its ends).  Not cleared: a contact in progress, a
// held rigid stop, a group held off the ground (their extrema are found on the phase's polynomials)
bool extrema_surely_inside(const Phase& ph, const System& sy, double tau, const Ends& e, const double* extrema,
                           ExtremaScreen& sc) {
    const int n = ph.n;
    if (!sc.on || !(tau > 0.0) || !(sc.s > 0.0)) return false;
    if (sy.n_norm() > 0) return false;  // (a tracked vector's length: no bound of its own here yet)
    for (const ContactPhase& k : ph.ct)
        if (k.in) return false;
    if (ph.stk.any)
        for (const int c : ph.stk.held)
            if (c < ph.stk.nc) return false;
    const ExtremaScreen& s = ready(sc, ph, e, tau);
    auto pair_inside = [&](const Pair& pr, const double* ex) {
        // its velocity of one sign throughout (y1's shift moves v1 by |a1| shift and more, a1 by |v''| shift,
        // |v''| at most times Z), looked at first where its ends' are of one sign
        const double v0 = rel(e.y0 + n, pr), v1 = rel(e.y1 + n, pr);
        if (v0 * v1 > 0.0) {
            const double times = pr.weight();
            const double a0 = rel(e.a0, pr), a1 = rel(e.a1, pr);
            // (a1 read with the table at tau: off by its slope over the shift, for a level against the ground)
            const double slope = pr.levered() ? std::abs(table_slope_on(ph, pr)) : pr.j >= 0 ? 0.0 : std::abs(ph.ax1);
            const double off =
                s.shift == 0.0 ? 0.0 : 2.0 * s.shift * (std::abs(a1) + (times * s.z + slope) * (s.shift + 0.15 * tau));
            const Screened sv{hermite_range(v0, a0, v1, a1, tau, times * s.beta * s.alpha * s.z), off};
            if (v0 > 0.0 ? range_within(sv, 0.0, INF, s.vscale) : range_within(sv, -INF, 0.0, s.vscale)) return true;
        }
        const double f0 = rel(e.y0, pr), f1 = rel(e.y1, pr);
        return range_within(displacement_range(s, ph, e, tau, pr), std::min({ex[EX_D_MIN], f0, f1}),
                            std::max({ex[EX_D_MAX], f0, f1}), s.xscale);
    };
    for (int i = 0; i < n; ++i) {
        const double* ex = extrema + DOF_EXTREMA * i;
        if (ph.stk.any && ph.stk.grp[static_cast<size_t>(i)] >= 0) {  // (held on the ground: it stays)
            if (!ph.stk.grounded[static_cast<size_t>(ph.stk.grp[static_cast<size_t>(i)])]) return false;
            continue;
        }
        if (!pair_inside(sy.dof_pair[static_cast<size_t>(i)], ex)) return false;
        const double aa0 = abs_acc_linear(ph, i, e.y0), aa1 = abs_acc_linear(ph, i, e.y1);
        const double r0 = abs_acc_rate_linear(ph, i, e.y0, e.a0), r1 = abs_acc_rate_linear(ph, i, e.y1, e.a1);
        const double top = std::max({ex[EX_A_ABS_MAX], std::abs(aa0), std::abs(aa1)});
        const ScreenedAcc sa = abs_acceleration_range(s, ph, tau, i, aa0, r0, aa1, r1);
        if (!range_within(sa.sr, -top, top, sa.scale)) return false;
    }
    for (int p = 0; p < sy.n_track(); ++p)
        if (!pair_inside(sy.track[static_cast<size_t>(p)], extrema + DOF_EXTREMA * n + PAIR_EXTREMA * p))
            return false;
    return true;
}

// what a sub-interval adds: the energy integrals and contact statistics, the held stops' impulses, then the
// extrema (displacements, drifts, compressions, absolute accelerations, contact forces)
void accumulate(Phase& ph, const System& sy, double* st, double t0, double tau, const Ends& e, double* ledger,
                double* extrema, Buffers& b, bool with_energy, const Given& given, ExtremaScreen* screen,
                bool ends_only) {
    bool any_in = false;
    for (const ContactPhase& k : ph.ct) any_in = any_in || k.in;
    const bool linear = !ph.numeric;
    if (tau > 0.0 && linear && (with_energy || any_in))
        linear_contributions(ph, sy, st, tau, e, ledger, b, with_energy, given);
    else if (tau > 0.0 && (with_energy || any_in))
        numeric_contributions(ph, sy, st, tau, e, ledger, b);
    if (ph.stk.any && tau > 0.0) held_statistics(ph, sy.lay, st, tau, e, linear, b);
    ExtremaScreen* sc = nullptr;  // (the screen of what is extreme inside: a record's linear phase)
    if (screen != nullptr && screen->on && linear && tau > 0.0) {
        screen->tau = -1.0;  // (its bound made when first asked for: ready)
        sc = screen;
    }
    // (a whole step the screen cleared, ends_only: its extrema at its ends, if anywhere)
    const bool inside = !(ends_only && linear);
    displacement_extrema(ph, sy, st, t0, tau, e, extrema, sc, inside);
    for (int i = 0; i < ph.n; ++i) {
        double* ex = extrema + DOF_EXTREMA * i;
        if (ph.stk.any && ph.stk.grp[static_cast<size_t>(i)] >= 0)
            held_abs_acceleration(ph, i, ex, t0, tau, e, linear);
        else
            free_abs_acceleration(ph, i, ex, t0, tau, e, linear, b, sc, inside);
    }
    peak_contact_forces(ph, sy.lay, st, tau, e, linear, b);
}

namespace {

void held_statistics(Phase& ph, const Layout& L, double* st, double tau, const Ends& e, bool linear, Buffers& b) {
    for (const int c : ph.stk.held) {
        if (c >= ph.stk.nc) continue;  // (a sticking friction element's tie: its force is the element's)
        const int acc = L.acc_at(c);
        double impulse = 0.0, peak = st[acc + A_PEAK];
        if (linear) {
            Fn ff, fr;
            held_force_poly(ph, c, ff.q);
            double tk = tau;
            for (int k = 0; k <= ff.q.deg; ++k) {
                impulse += ff.q.c[k] * tk / (k + 1);
                tk *= tau;
            }
            peak = std::max({peak, poly_val(ff.q, 0.0), poly_val(ff.q, tau)});
            poly_deriv(ff.q, fr.q);
            fr.kind = FN_POLY;
            const double r0 = poly_val(fr.q, 0.0), r1 = poly_val(fr.q, tau);
            ph.poly_evaluations += 4;
            if (r0 > 0.0 && r1 < 0.0) {
                const double tm = find_root(fr, ph, 0.0, tau, r0, r1, NaN, NaN, XTOL_EXTREMUM_S);
                peak = std::max(peak, poly_val(ff.q, tm));
            }
        } else {
            double* y = b.ym.data();
            double* a = b.am.data();
            for (int qn = 0; qn < N_LOBATTO; ++qn) {
                const double tq = tau * LOBATTO_X[qn];
                if (qn == 0) {
                    std::copy(e.y0, e.y0 + 2 * ph.n, y);
                    std::copy(e.a0, e.a0 + ph.n, a);
                } else if (qn == N_LOBATTO - 1) {
                    std::copy(e.y1, e.y1 + 2 * ph.n, y);
                    std::copy(e.a1, e.a1 + ph.n, a);
                } else {
                    phase_eval(ph, tq, y, a);
                }
                const double f = held_force(ph, c, tq, y, a).g;
                impulse += tau * LOBATTO_W[qn] * f;
                peak = std::max(peak, f);
            }
        }
        st[acc + A_IMPULSE] += impulse;
        st[acc + A_PEAK] = peak;
    }
}

}  // namespace

}  // namespace pounding::run_parts
