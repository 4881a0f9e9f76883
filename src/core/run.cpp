// The event loop (run.hpp).  The run is cut into sub-intervals, each inside one phase of motion and short
// against its periods; on each, every event function is checked for a crossing or a graze and the earliest
// root is located; what the sub-interval adds to the run (energy integrals, extrema, contact statistics) is
// accumulated; then the state jumps at the event.
#include "run.hpp"

#include <algorithm>
#include <cmath>

#include "events.hpp"
#include "isolator.hpp"
#include "laws.hpp"
#include "phase.hpp"

namespace pounding {

namespace {

constexpr double SUBINTERVALS_PER_PERIOD = 8.0;
constexpr int ZENO_REPEATS = 200;
constexpr double TINY_SPEED = 1e-300;  // the velocity of a start at rest, for the direction it moves
constexpr int64_t POLL_EVERY = 64;     // sub-intervals between two looks at the run control
constexpr double RESOLUTION = 1e-9;    // relative to the run's scales: below it, a touch is no impact
constexpr int MAX_EVENTS_PER_PHASE = 256;

// ---------------------------------------------------------------- the excitation
struct Piece { double a0, a1, amp, omega, phase, t_next; int64_t j; };

Piece excitation_piece(const Forcing& fo, double t, int64_t j_hint) {
    if (fo.kind == EXC_HARMONIC) {
        const double omega = fo.p[1];
        const double angle = omega * t + fo.p[2];
        const double phase = angle - TWO_PI * std::floor(angle / TWO_PI);  // reduced to [0, 2 pi)
        return {0.0, 0.0, fo.p[0], omega, phase, INF, j_hint};
    }
    const int64_t n = fo.n_rec;
    const double* rt = fo.rec_t;
    const double* ra = fo.rec_a;
    if (t < rt[0]) return {0.0, 0.0, 0.0, 0.0, 0.0, rt[0], j_hint};
    if (t >= rt[n - 1]) return {0.0, 0.0, 0.0, 0.0, 0.0, INF, j_hint};
    int64_t j = std::min(std::max(j_hint, int64_t(0)), n - 2);
    if (!(rt[j] <= t && t < rt[j + 1])) {
        if (j + 2 < n && rt[j + 1] <= t && t < rt[j + 2]) {
            j += 1;
        } else {
            j = 0;
            int64_t hi = n - 1;
            while (hi - j > 1) {
                const int64_t mid = (j + hi) / 2;
                if (rt[mid] <= t) j = mid;
                else hi = mid;
            }
        }
    }
    const double slope = (ra[j + 1] - ra[j]) / (rt[j + 1] - rt[j]);
    return {ra[j] + slope * (t - rt[j]), slope, 0.0, 0.0, 0.0, rt[j + 1], j};
}

// the run's length (m) and velocity (m/s) scales: the system's and the excitation's, not the start's
void run_scales(const System& sy, const Forcing& fo, double& x, double& xw) {
    double w = std::sqrt(sy.slopes[0] / sy.total_mass);
    double amp = 0.0;
    if (fo.kind == EXC_HARMONIC) {
        amp = std::abs(fo.p[0]);
        w = std::max(w, fo.p[1]);
    } else {
        for (int64_t i = 0; i < fo.n_rec; ++i) amp = std::max(amp, std::abs(fo.rec_a[i]));
    }
    double gaps = 0.0;
    if (sy.has_b)
        for (const Contact& c : sy.contact) gaps += c.gap;
    x = std::max(gaps, amp / (w * w));
    if (!sy.breaks.empty()) x = std::max(x, sy.breaks[0]);
    xw = x * w;
}

// a bound on |lambda| of the pencil lambda^2 M + lambda C + K: sqrt(kappa + (gamma / 2)^2) and gamma, with
// kappa, gamma the largest row sums of |M^-1/2 K M^-1/2| and |M^-1/2 C M^-1/2| (bounds on the Rayleigh
// quotients; k / m and c / m for one mass)
double rate_bound(const Phase& ph, double k_extra) {
    const int n = ph.n;
    double kap = 0.0, gam = 0.0;
    for (int i = 0; i < n; ++i) {
        double sk = 0.0, sc = 0.0;
        for (int j = 0; j < n; ++j) {
            const double s = std::sqrt(ph.minv[static_cast<size_t>(i)] * ph.minv[static_cast<size_t>(j)]);
            sk += std::abs(ph.K[static_cast<size_t>(i * n + j)]) * s;
            sc += std::abs(ph.C[static_cast<size_t>(i * n + j)]) * s;
        }
        kap = std::max(kap, sk);
        gam = std::max(gam, sc);
    }
    kap += k_extra;
    return std::max(std::sqrt(kap + (0.5 * gam) * (0.5 * gam)), gam);
}

// ---------------------------------------------------------------- the run's buffers

struct Buffers {
    std::vector<double> y0s, y1, a0, a1, ym, am, du, dvv;
    std::vector<double> q;  // internal forces
    void size(int n, int nc) {
        y0s.assign(static_cast<size_t>(2 * n), 0.0);
        y1.assign(static_cast<size_t>(2 * n), 0.0);
        ym.assign(static_cast<size_t>(2 * n), 0.0);
        a0.assign(static_cast<size_t>(n), 0.0);
        a1.assign(static_cast<size_t>(n), 0.0);
        am.assign(static_cast<size_t>(n), 0.0);
        q.assign(static_cast<size_t>(n), 0.0);
        du.assign(static_cast<size_t>(std::max(nc, 1)), 0.0);
        dvv.assign(static_cast<size_t>(std::max(nc, 1)), 0.0);
    }
};

// ---------------------------------------------------------------- outputs at an instant

// the isolator's force on its pair (k u + r0 + c_d u' + the Bouc-Wen spring's)
double iso_force(const System& sy, const double* st) {
    const IsoLinear iso = iso_linear(sy, st);
    const Layout& L = sy.lay;
    const double u = rel(st + L.x, sy.iso_i, sy.iso_j), du = rel(st + L.v, sy.iso_i, sy.iso_j);
    return iso.k * u + iso.r0 + sy.c_d * du + sy.bw[0] * st[L.zeta];
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
    const double f_iso = iso_force(sy, st);
    q[sy.iso_i] += f_iso;
    if (sy.iso_j >= 0) q[sy.iso_j] -= f_iso;
    double* fc = row + 2 + 3 * n;
    for (int c = 0; c < sy.nc(); ++c) {
        fc[c] = 0.0;
        if (st[L.in_at(c)] == 0.0) continue;
        const Contact& ct = sy.contact[static_cast<size_t>(c)];
        const double f = law_force(ct.law, ct.p, ct.sign * rel(x, ct.i, ct.j) - ct.gap, ct.sign * rel(v, ct.i, ct.j),
                                   st + L.z_at(c)).f;
        fc[c] = f;
        q[ct.i] += ct.sign * f;
        if (ct.j >= 0) q[ct.j] -= ct.sign * f;
    }
    row[0] = st[T];
    for (int i = 0; i < n; ++i) {
        row[1 + i] = x[i];
        row[1 + n + i] = v[i];
        row[1 + 2 * n + i] = -q[i] / sy.mass[static_cast<size_t>(i)];
    }
    row[1 + 3 * n] = f_iso;
}

void outputs_in_phase(Phase& ph, const System& sy, double t, double tau, const double* y, const double* a,
                      double* row) {
    const int n = ph.n;
    const double ag = table_acceleration(ph, tau);
    row[0] = t;
    for (int i = 0; i < n; ++i) {
        row[1 + i] = y[i];
        row[1 + n + i] = y[n + i];
        row[1 + 2 * n + i] = a[i] + ag;
    }
    double f_iso = ph.kiso * rel(y, ph.iso_i, ph.iso_j) + ph.riso + ph.cd * rel(y + n, ph.iso_i, ph.iso_j);
    if (ph.bw[0] != 0.0) f_iso += ph.bw[0] * phase_zeta(ph, tau);
    row[1 + 3 * n] = f_iso;
    for (int c = 0; c < ph.nc; ++c)
        row[2 + 3 * n + c] = ph.ct[static_cast<size_t>(c)].in ? contact_force(ph, c, y, a).f : 0.0;
    (void)sy;
}

void energies(const double* st, const System& sy, double& kin, double& iso, double& bmp) {
    const Layout& L = sy.lay;
    const int n = sy.n;
    const double* x = st + L.x;
    const double* v = st + L.v;
    kin = 0.0;
    for (int i = 0; i < n; ++i) kin += 0.5 * sy.mass[static_cast<size_t>(i)] * v[i] * v[i];
    const double e_bw = sy.bw[0] != 0.0 ? 0.5 * sy.bw[0] * sy.bw[1] * st[L.zeta] * st[L.zeta] / sy.bw[2] : 0.0;
    double e_k0 = 0.0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) e_k0 += 0.5 * x[i] * sy.k0[static_cast<size_t>(i * n + j)] * x[j];
    iso = iso_energy(sy, st, rel(x, sy.iso_i, sy.iso_j)) + e_bw + e_k0;
    bmp = 0.0;
    for (int c = 0; c < sy.nc(); ++c) {
        const Contact& ct = sy.contact[static_cast<size_t>(c)];
        bmp += law_energy(ct.law, ct.p, st[L.def_at(c)], st + L.z_at(c));
    }
}

void track_abs_acceleration(double* ex, double t, double a) {
    if (std::abs(a) > ex[4]) {
        ex[4] = std::abs(a);
        ex[5] = t;
        ex[6] = a;
    }
}

void track_displacement(double* ex, double t, double d) {
    if (d > ex[0]) {
        ex[0] = d;
        ex[1] = t;
    }
    if (d < ex[2]) {
        ex[2] = d;
        ex[3] = t;
    }
}

// ---------------------------------------------------------------- what a sub-interval adds

// may a velocity, of one sign at both ends with accelerations of opposite signs, turn back inside?
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

// the instants in (0, tau) where the relative velocity of the pair (i, j) crosses zero: 0, 1 or 2 of them
// (two where it turns back inside), from its values and rates at the ends
int pair_velocity_zeros(Phase& ph, int i, int j, double tau, double v0, double v1, double a0, double a1,
                        double xtol, double* out) {
    if (tau <= 0.0) return 0;
    Fn fv, fa;
    const bool poly = !ph.numeric;
    if (poly) {
        pair_poly(ph, i, j, 0.0, 0.0, 1.0, 0.0, fv.q);
        fv.kind = FN_POLY;
    } else {
        fv.kind = FN_PAIR_V;
        fv.i = i;
        fv.j = j;
    }
    if (v0 * v1 < 0.0) {
        out[0] = find_root(fv, ph, 0.0, tau, v0, v1, a0, a1, xtol);
        return 1;
    }
    if (!(v0 * v1 > 0.0 && a0 * a1 < 0.0) || !may_turn_back(tau, v0, v1, a0, a1)) return 0;
    if (poly) {
        pair_poly(ph, i, j, 0.0, 0.0, 0.0, 1.0, fa.q);
        fa.kind = FN_POLY;
    } else {
        fa.kind = FN_PAIR_A;
        fa.i = i;
        fa.j = j;
    }
    const double t_a = find_root(fa, ph, 0.0, tau, a0, a1, NaN, NaN, XTOL_EXTREMUM_S);
    if (!(0.0 < t_a && t_a < tau)) return 0;
    double vm, am;
    fn_eval(fv, ph, t_a, vm, am);
    if (!(vm * v0 < 0.0)) return 0;
    out[0] = find_root(fv, ph, 0.0, t_a, v0, vm, a0, am, xtol);
    out[1] = find_root(fv, ph, t_a, tau, vm, v1, am, a1, xtol);
    return 2;
}

// a pair's displacement (or a dof's) at an instant of the sub-interval
double pair_x_at(Phase& ph, int i, int j, double t) {
    if (!ph.numeric) {
        Poly q;
        pair_poly(ph, i, j, 0.0, 1.0, 0.0, 0.0, q);
        ph.poly_evaluations += 1;
        return poly_val(q, t);
    }
    phase_eval(ph, t, ph.ye.data(), ph.ae.data());
    return rel(ph.ye.data(), i, j);
}

// 7-point Gauss-Lobatto on [0, 1] (nonlinear phases' integrals)
constexpr int N_LOBATTO = 7;
constexpr double LOBATTO_X[N_LOBATTO] = {0.0, 0.08488805186071696, 0.2655756032646429, 0.4999999999999999,
                                         0.7344243967353572, 0.9151119481392831, 1.0};
constexpr double LOBATTO_W[N_LOBATTO] = {0.02380952380952377, 0.1384130236807831, 0.21587269060493133,
                                         0.2438095238095238, 0.2158726906049313, 0.13841302368078298,
                                         0.02380952380952377};

struct Ends { const double *y0, *a0, *y1, *a1; double s0, c0, s1, c1; };

void accumulate(Phase& ph, const System& sy, double* st, double t0, double tau, const Ends& e, double* ledger,
                double* extrema, Buffers& b, bool with_energy) {
    const int n = ph.n;
    const Layout& L = sy.lay;
    bool any_in = false;
    for (const ContactPhase& k : ph.ct) any_in = any_in || k.in;
    const bool linear = !ph.numeric;
    if (tau > 0.0 && linear && (with_energy || any_in)) {
        double vcv, gv;
        linear_integrals(ph, sy.c_lin, sy.mass, tau, e.y0, e.a0, e.s0, e.c0, e.y1, e.a1, e.s1, e.c1, vcv, gv,
                         b.du.data(), b.dvv.data());
        ledger[L_INPUT] -= gv;
        ledger[L_VISCOUS] += vcv;
        for (int c = 0; c < ph.nc; ++c) {
            const ContactPhase& k = ph.ct[static_cast<size_t>(c)];
            if (!k.in) continue;
            const double sg = k.sign, gap = k.gap;
            const int acc = L.acc_at(c);
            const double x0 = sg * rel(e.y0, k.i, k.j) - gap, x1 = sg * rel(e.y1, k.i, k.j) - gap;
            st[acc + A_IMPULSE] += k.kb * (sg * b.du[c] - gap * tau) + k.rb * tau + k.cb * (x1 - x0);
            st[acc + A_WORK] += 0.5 * k.kb * (x1 * x1 - x0 * x0) + k.rb * (x1 - x0) + k.cb * b.dvv[c];
            ledger[L_BUMPER_LOSS] += k.cb * b.dvv[c] + law_branch_loss(k.law, k.p, k.jb, x0, x1, k.lz);
        }
    } else if (tau > 0.0 && (with_energy || any_in)) {
        const double bw = ph.bw[0];
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
            const double ag = table_acceleration(ph, tq);
            double mv = 0.0, vcv = 0.0;
            for (int i = 0; i < n; ++i) {
                mv += sy.mass[static_cast<size_t>(i)] * v[i];
                double s = 0.0;
                for (int j = 0; j < n; ++j) s += sy.c_lin[static_cast<size_t>(i * n + j)] * v[j];
                vcv += v[i] * s;
            }
            ledger[L_INPUT] -= wq * ag * mv;
            ledger[L_VISCOUS] += wq * vcv;
            if (bw != 0.0) ledger[L_HYSTERETIC] += wq * bw * phase_zeta(ph, tq) * rel(v, ph.iso_i, ph.iso_j);
            for (int c = 0; c < ph.nc; ++c) {
                if (!ph.ct[static_cast<size_t>(c)].in) continue;
                const ContactForce f = contact_force(ph, c, y, a);
                const int acc = L.acc_at(c);
                st[acc + A_IMPULSE] += wq * f.f;
                st[acc + A_WORK] += wq * f.f * f.dx;
                ledger[L_BUMPER_LOSS] += wq * (f.f - f.elastic) * f.dx;
            }
        }
        if (bw != 0.0)
            ledger[L_HYSTERETIC] -= bouc_wen_energy(ph, phase_zeta(ph, tau)) - bouc_wen_energy(ph, ph.zeta0);
        for (int c = 0; c < ph.nc; ++c) {  // a linear law's branch in a numerical phase: its spring's loss
            const ContactPhase& k = ph.ct[static_cast<size_t>(c)];
            if (k.in && law_is_linear(k.law)) {
                ledger[L_BUMPER_LOSS] += law_branch_loss(k.law, k.p, k.jb, k.sign * rel(e.y0, k.i, k.j) - k.gap,
                                                         k.sign * rel(e.y1, k.i, k.j) - k.gap, k.lz);
            }
        }
    }
    // displacement extrema of each dof, at its velocity's zeros and the ends
    double zeros[2];
    for (int i = 0; i < n; ++i) {
        double* ex = extrema + 7 * i;
        track_displacement(ex, t0, e.y0[i]);
        track_displacement(ex, t0 + tau, e.y1[i]);
        const int nz = pair_velocity_zeros(ph, i, GROUND, tau, e.y0[n + i], e.y1[n + i], e.a0[i], e.a1[i], XTOL_S,
                                           zeros);
        for (int z = 0; z < nz; ++z) track_displacement(ex, t0 + zeros[z], pair_x_at(ph, i, GROUND, zeros[z]));
    }
    // the contacts' deepest compression: the ends and the pair's velocity zeros
    for (int c = 0; c < ph.nc; ++c) {
        const ContactPhase& k = ph.ct[static_cast<size_t>(c)];
        if (!k.in) continue;
        double& mc = st[L.acc_at(c) + A_MAXCOMP];
        mc = std::max(mc, k.sign * rel(e.y0, k.i, k.j) - k.gap);
        mc = std::max(mc, k.sign * rel(e.y1, k.i, k.j) - k.gap);
        const int nz = pair_velocity_zeros(ph, k.i, k.j, tau, rel(e.y0 + n, k.i, k.j), rel(e.y1 + n, k.i, k.j),
                                           rel(e.a0, k.i, k.j), rel(e.a1, k.i, k.j), XTOL_S, zeros);
        for (int z = 0; z < nz; ++z) mc = std::max(mc, k.sign * pair_x_at(ph, k.i, k.j, zeros[z]) - k.gap);
    }
    // absolute acceleration extrema of each dof
    for (int i = 0; i < n; ++i) {
        double* ex = extrema + 7 * i;
        if (linear) {
            Fn fa, fr;
            abs_acc_poly(ph, i, fa.q);
            fa.kind = FN_POLY;
            poly_deriv(fa.q, fr.q);
            fr.kind = FN_POLY;
            ph.poly_evaluations += 4;
            const double aa0 = fa.q.c[0], aa1 = poly_val(fa.q, tau);
            const double r0 = fr.q.c[0], r1 = poly_val(fr.q, tau);
            track_abs_acceleration(ex, t0, aa0);
            track_abs_acceleration(ex, t0 + tau, aa1);
            if (r0 * r1 < 0.0) {
                const double tm = find_root(fr, ph, 0.0, tau, r0, r1, NaN, NaN, XTOL_EXTREMUM_S);
                ph.poly_evaluations += 1;
                track_abs_acceleration(ex, t0 + tm, poly_val(fa.q, tm));
            }
        } else {
            Fn fr;
            fr.kind = FN_AABS_RATE;
            fr.idx = i;
            double r0, r1, unused;
            track_abs_acceleration(ex, t0, e.a0[i] + table_acceleration(ph, 0.0));
            track_abs_acceleration(ex, t0 + tau, e.a1[i] + table_acceleration(ph, tau));
            fn_eval(fr, ph, 0.0, r0, unused);
            fn_eval(fr, ph, tau, r1, unused);
            if (r0 * r1 < 0.0) {
                const double tm = find_root(fr, ph, 0.0, tau, r0, r1, NaN, NaN, XTOL_EXTREMUM_S);
                phase_eval(ph, tm, b.ym.data(), b.am.data());
                track_abs_acceleration(ex, t0 + tm, b.am[static_cast<size_t>(i)] + table_acceleration(ph, tm));
            }
        }
    }
    // peak contact forces
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
                pair_poly(ph, k.i, k.j, k.rb - k.kb * k.gap, k.kb * k.sign, k.cb * k.sign, 0.0, ff.q);
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

// ---------------------------------------------------------------- the loop's parts

void set_phase(Phase& ph, const double* st, const System& sy, const Piece& pc) {
    const Layout& L = sy.lay;
    const int n = sy.n;
    const IsoLinear iso = iso_linear(sy, st);
    ph.K = sy.k0;
    ph.C = sy.c_lin;
    std::fill(ph.R0.begin(), ph.R0.end(), 0.0);
    sy.add_pair(ph.K, sy.iso_i, sy.iso_j, iso.k);
    ph.R0[static_cast<size_t>(sy.iso_i)] += iso.r0;
    if (sy.iso_j >= 0) ph.R0[static_cast<size_t>(sy.iso_j)] -= iso.r0;
    bool any_nl = false;
    for (int q = 0; q < sy.nc(); ++q) {
        ContactPhase& k = ph.ct[static_cast<size_t>(q)];
        k.in = false;
        k.nl = false;
        k.def0 = st[L.def_at(q)];
        for (int i = 0; i < N_LAW_STATE; ++i) k.lz[i] = st[L.z_at(q) + i];
        if (!sy.has_b || st[L.in_at(q)] == 0.0) continue;
        k.in = true;
        const Contact& ct = sy.contact[static_cast<size_t>(q)];
        if (law_is_linear(ct.law)) {
            // F = kb x + rb + cb x' with x = sign (x_i - x_j) - gap, pushing dof i by -sign F
            const Branch br = law_linear_branch(ct.law, ct.p, st[L.def_at(q)],
                                                ct.sign * rel(st + L.v, ct.i, ct.j), st + L.z_at(q));
            sy.add_pair(ph.K, ct.i, ct.j, br.k);
            sy.add_pair(ph.C, ct.i, ct.j, br.c);
            const double r = ct.sign * (br.r - br.k * ct.gap);
            ph.R0[static_cast<size_t>(ct.i)] += r;
            if (ct.j >= 0) ph.R0[static_cast<size_t>(ct.j)] -= r;
            k.kb = br.k;
            k.cb = br.c;
            k.rb = br.r;
            k.jb = br.j;
        } else {
            k.nl = true;
            any_nl = true;
        }
    }
    ph.ax0 = pc.a0;
    ph.ax1 = pc.a1;
    ph.axh = pc.amp;
    ph.w = pc.omega;
    ph.phi = pc.phase;
    ph.sphi = std::sin(pc.phase);
    ph.cphi = std::cos(pc.phase);
    for (int q = 0; q < 2 * n; ++q) ph.y0[static_cast<size_t>(q)] = st[L.x + q];
    ph.numeric = any_nl || sy.bw[0] != 0.0;
    ph.zeta0 = st[L.zeta];
    ph.dp5_h = -1.0;
    ph.tc_ok = false;
    ph.kiso = iso.k;
    ph.riso = iso.r0;
    // (a Bouc-Wen spring's initial stiffness bounds the rate too)
    const double k_bw = sy.bw[0] != 0.0 ? sy.bw[0] * sy.bw[2] / sy.bw[1] : 0.0;
    double k_extra = 0.0;
    if (k_bw != 0.0) {
        const double mi = ph.minv[static_cast<size_t>(sy.iso_i)];
        const double mj = sy.iso_j >= 0 ? ph.minv[static_cast<size_t>(sy.iso_j)] : 0.0;
        k_extra = k_bw * (mi + mj + (sy.iso_j >= 0 ? 2.0 * std::sqrt(mi * mj) : 0.0));
    }
    ph.rate = rate_bound(ph, k_extra);
}

void run_constants(Phase& ph, const System& sy, const Forcing& fo) {
    ph.size(sy.n, sy.nc());
    run_scales(sy, fo, ph.xrun, ph.vrun);
    ph.xround = ph.xrun;
    ph.vround = ph.vrun;
    for (int i = 0; i < sy.n; ++i) {
        ph.mass[static_cast<size_t>(i)] = sy.mass[static_cast<size_t>(i)];
        ph.minv[static_cast<size_t>(i)] = 1.0 / sy.mass[static_cast<size_t>(i)];
    }
    for (int c = 0; c < sy.nc(); ++c) {
        const Contact& ct = sy.contact[static_cast<size_t>(c)];
        ContactPhase& k = ph.ct[static_cast<size_t>(c)];
        k.gap = ct.gap;
        k.law = ct.law;
        k.p = ct.p;
        k.sign = ct.sign;
        k.i = ct.i;
        k.j = ct.j;
    }
    ph.cd = sy.c_d;
    ph.iso_i = sy.iso_i;
    ph.iso_j = sy.iso_j;
    for (int j = 0; j < BW_PARAMS; ++j) ph.bw[j] = sy.bw[j];
}

struct NumStep { int status; double h, h_num; bool shortened; };

NumStep numeric_step(Phase& ph, double h, double h_num, double rtol, double t) {
    bool shortened = false;
    if (h_num < h) {
        h = h_num;
        shortened = true;
    }
    const int n = ph.n;
    const double atol_d = rtol * 1e-3, atol_v = rtol * 1e-2;
    while (true) {
        const Dp5 r = dp5_step(ph, h);
        double err = std::abs(r.ez) / (rtol * (1.0 + std::abs(r.z)));
        for (int i = 0; i < n; ++i) {
            const double y0x = ph.y0[static_cast<size_t>(i)], y0v = ph.y0[static_cast<size_t>(n + i)];
            err = std::max(err, std::abs(r.ey[i]) / (atol_d + rtol * std::max(std::abs(y0x), std::abs(r.y[i]))));
            err = std::max(err,
                           std::abs(r.ey[n + i]) / (atol_v + rtol * std::max(std::abs(y0v), std::abs(r.y[n + i]))));
        }
        if (err <= 1.0) {
            h_num = h * (err == 0.0 ? 5.0 : std::min(5.0, 0.9 * std::pow(err, -0.2)));
            return {SUCCESS, h, h_num, shortened};
        }
        h *= std::max(0.2, 0.9 * std::pow(err, -0.2));
        shortened = true;
        if (h <= 1e-15 * std::max(1.0, std::abs(t))) return {STEP_FAILED, h, h_num, shortened};
    }
}

int phase_events(const Phase& ph, const double* st, const System& sy, EventRow* evs) {
    int n = iso_events(sy, st, evs, 0);
    n = bumper_events(st, ph, sy, evs, n);
    if (sy.bw[0] != 0.0 && st[sy.lay.zeta] != 0.0) {  // the Bouc-Wen z back through zero: its law changes form
        EventRow& r = evs[n++];
        r = EventRow();
        r.kind = KIND_ZETA;
        r.i = sy.iso_i;
        r.j = sy.iso_j;
        r.alpha = -std::copysign(1.0, st[sy.lay.zeta]);
        r.action = ACT_BOUC_WEN;
    }
    return n;
}

// the pairs whose relative displacement events are functions of: the isolator's and the contacts'
int event_pairs(const System& sy, int* pi, int* pj) {
    int np = 0;
    auto add = [&](int i, int j) {
        for (int q = 0; q < np; ++q)
            if (pi[q] == i && pj[q] == j) return;
        pi[np] = i;
        pj[np] = j;
        ++np;
    };
    add(sy.iso_i, sy.iso_j);
    if (sy.has_b)
        for (const Contact& c : sy.contact) add(c.i, c.j);
    return np;
}

void eval_end(Phase& ph, double h, Buffers& b) {
    if (!ph.numeric) {
        lin_eval(ph, h, b.y1.data(), b.a1.data());
    } else {
        phase_eval(ph, h, b.y1.data(), b.a1.data());
    }
}

// where a sub-interval must end early: a pair's velocity turning back inside (two zeros: a dip of a
// displacement event could hide between them), or, in a numerical phase whose right-hand side has a kink
// there, its velocity's zero.  The cut instant (or h).
double velocity_cuts(Phase& ph, const System& sy, double h, const Buffers& b, const int* pi, const int* pj, int np) {
    const int n = ph.n;
    double cut = h;
    const bool kinks = ph.numeric && (law_switches(ph) || sy.bw[0] != 0.0);
    for (int p = 0; p < np; ++p) {
        const int i = pi[p], j = pj[p];
        const double v0 = rel(b.y0s.data() + n, i, j), v1 = rel(b.y1.data() + n, i, j);
        const double a0 = rel(b.a0.data(), i, j), a1 = rel(b.a1.data(), i, j);
        if (v0 * v1 < 0.0 && kinks) {
            Fn fv;
            fv.kind = FN_PAIR_V;
            fv.i = i;
            fv.j = j;
            const double t_v = find_root(fv, ph, 0.0, h, v0, v1, a0, a1, XTOL_S);
            if (0.0 < t_v && t_v < cut) cut = t_v;
            continue;
        }
        if (!(v0 * v1 > 0.0 && a0 * a1 < 0.0) || !may_turn_back(h, v0, v1, a0, a1)) continue;
        Fn fa, fv;
        if (!ph.numeric) {
            pair_poly(ph, i, j, 0.0, 0.0, 0.0, 1.0, fa.q);
            fa.kind = FN_POLY;
            pair_poly(ph, i, j, 0.0, 0.0, 1.0, 0.0, fv.q);
            fv.kind = FN_POLY;
        } else {
            fa.kind = FN_PAIR_A;
            fv.kind = FN_PAIR_V;
            fa.i = fv.i = i;
            fa.j = fv.j = j;
        }
        const double t_a = find_root(fa, ph, 0.0, h, a0, a1, NaN, NaN, XTOL_EXTREMUM_S);
        double v_a, unused;
        fn_eval(fv, ph, t_a, v_a, unused);
        if (v_a * v0 < 0.0 && 0.0 < t_a && t_a < cut) cut = t_a;  // two velocity zeros: cut where it turns
    }
    return cut;
}

struct Earliest { double tau; int i; };

Earliest earliest_event(Phase& ph, const EventRow* evs, int n_ev, std::vector<double>& ev_end, bool continuing,
                        double h, const Buffers& b) {
    double tau = h;
    int i_ev = -1;
    for (int i = 0; i < n_ev; ++i) {
        double g0, gp0, sc0;
        double* end = &ev_end[static_cast<size_t>(3 * i)];
        if (continuing) {
            g0 = end[0];
            gp0 = end[1];
            sc0 = end[2];
        } else {
            const EventValue e0 = event_value(evs[i], ph, 0.0, b.y0s.data(), b.a0.data());
            g0 = e0.g;
            gp0 = e0.gp;
            sc0 = e0.scale;
        }
        const EventValue e1 = event_value(evs[i], ph, h, b.y1.data(), b.a1.data());
        end[0] = e1.g;
        end[1] = e1.gp;
        end[2] = e1.scale;
        const double tol0 = ROUNDING * sc0;
        if (g0 > tol0 && e1.g > 0.0 && !(gp0 < 0.0 && e1.gp > 0.0)) continue;
        const double r = locate_event(evs, i, ph, h, g0, gp0, tol0, e1.g, e1.gp, ROUNDING * e1.scale, XTOL_S);
        if (r >= 0.0 && (r < tau || (i_ev < 0 && r <= tau))) {
            tau = r;
            i_ev = i;
        }
    }
    return {tau, i_ev};
}

void samples_inside(Phase& ph, const System& sy, Rows& samples, int64_t& j_next, double sample_dt, double t_run0,
                    double t, double tau, double t_end, Buffers& b) {
    while (true) {
        const double ts = t_run0 + static_cast<double>(j_next) * sample_dt;
        if (ts > t + tau || ts > t_end) break;
        phase_eval(ph, ts - t, b.ym.data(), b.am.data());
        outputs_in_phase(ph, sy, ts, ts - t, b.ym.data(), b.am.data(), samples.push());
        j_next += 1;
    }
}

// the bumpers at the end of a sub-interval of length tau: one in contact follows its pair (y1), one out of
// contact relaxes, its loss added to the ledger
void move_bumpers(double* st, const System& sy, const double* y1, double tau, double* ledger) {
    const Layout& L = sy.lay;
    for (int c = 0; c < sy.nc(); ++c) {
        const Contact& ct = sy.contact[static_cast<size_t>(c)];
        const int idx = L.def_at(c);
        double* z = st + L.z_at(c);
        if (st[L.in_at(c)] != 0.0) {
            st[idx] = std::max(0.0, ct.sign * rel(y1, ct.i, ct.j) - ct.gap);
            law_moved(ct.law, ct.p, z, st[idx], true);
        } else if (st[idx] > 0.0) {
            const double relaxed = law_relax(ct.law, ct.p, st[idx], tau, z).d;
            const double e0 = law_energy(ct.law, ct.p, st[idx], z);
            law_moved(ct.law, ct.p, z, relaxed, false);
            ledger[L_BUMPER_LOSS] += e0 - law_energy(ct.law, ct.p, relaxed, z);
            st[idx] = relaxed;
        }
    }
}

void jump(double* st, const System& sy, const EventRow& ev, Rows& contacts, const double* resolution) {
    const Layout& L = sy.lay;
    const double v_res = resolution[0], depth_res = resolution[1], impulse_res = resolution[2];
    const int action = ev.action, index = ev.index;
    const double t_ev = st[T];
    if (action == ACT_CONTACT) {
        const int acc = L.acc_at(index);
        const Contact& ct = sy.contact[static_cast<size_t>(index)];
        st[L.in_at(index)] = 1.0;
        const double comp = st[L.def_at(index)];
        const double v_in = rel(st + L.v, ct.i, ct.j);
        st[acc + A_TSTART] = t_ev;
        st[acc + A_VIN] = std::abs(v_in) > v_res ? v_in : 0.0;  // below the resolution: met at rest
        law_contact_state(ct.law, ct.p, ct.sign * st[acc + A_VIN], st + L.z_at(index), comp);
        st[acc + A_DSTART] = comp;
        st[acc + A_IMPULSE] = 0.0;
        st[acc + A_PEAK] = 0.0;
        st[acc + A_MAXCOMP] = comp;
        st[acc + A_WORK] = 0.0;
    } else if (action == ACT_RELEASE) {
        const int acc = L.acc_at(index);
        const Contact& ct = sy.contact[static_cast<size_t>(index)];
        st[L.in_at(index)] = 0.0;
        law_release_state(ct.law, ct.p, st + L.z_at(index), st[L.def_at(index)]);
        // a touch below the resolution in both depth and impulse is no impact: computed, not listed
        if (st[acc + A_MAXCOMP] - st[acc + A_DSTART] > depth_res || std::abs(st[acc + A_IMPULSE]) > impulse_res) {
            double* r = contacts.push();
            r[0] = static_cast<double>(index);
            r[1] = st[acc + A_TSTART];
            r[2] = t_ev;
            r[3] = st[acc + A_VIN];
            r[4] = rel(st + L.v, ct.i, ct.j);
            r[5] = st[acc + A_IMPULSE];
            r[6] = st[acc + A_PEAK];
            r[7] = st[acc + A_MAXCOMP];
            r[8] = st[acc + A_WORK];
        }
    } else if (action == ACT_LAW_BRANCH) {
        const Contact& ct = sy.contact[static_cast<size_t>(index)];
        law_after_event(ct.law, ct.p, st + L.z_at(index), st[L.def_at(index)], ev.dir);
    } else if (action == ACT_BOUC_WEN) {
        st[L.zeta] = 0.0;
    } else {
        iso_transition(sy, st, action, index, ev.dir);
    }
}

void record_event(double* st, const System& sy, const EventRow& ev, Rows& events, Rows& samples, double sample_dt,
                  double* extrema, Buffers& b, std::vector<double>& row) {
    double* r = events.push();
    r[0] = st[T];
    r[1] = static_cast<double>(ev.action);
    r[2] = static_cast<double>(ev.index);
    outputs(st, sy, b.q.data(), row.data());
    for (int i = 0; i < sy.n; ++i) track_abs_acceleration(extrema + 7 * i, st[T], row[1 + 2 * sy.n + i]);
    if (sample_dt >= 0.0) std::copy(row.begin(), row.end(), samples.push());
}

void finish(const double* st, const System& sy, Rows& samples, Rows& contacts, Buffers& b, std::vector<double>& row) {
    const Layout& L = sy.lay;
    if (samples.row(samples.n - 1)[0] < st[T]) {
        outputs(st, sy, b.q.data(), row.data());
        std::copy(row.begin(), row.end(), samples.push());
    }
    for (int c = 0; c < sy.nc(); ++c) {
        if (st[L.in_at(c)] == 0.0) continue;
        const int acc = L.acc_at(c);
        double* r = contacts.push();
        r[0] = static_cast<double>(c);
        r[1] = st[acc + A_TSTART];
        r[2] = NaN;
        r[3] = st[acc + A_VIN];
        r[4] = NaN;
        r[5] = st[acc + A_IMPULSE];
        r[6] = st[acc + A_PEAK];
        r[7] = st[acc + A_MAXCOMP];
        r[8] = st[acc + A_WORK];
    }
}

}  // namespace

void run_kernel(const System& sy, const Forcing& fo, const double* state0, const RunOptions& opt, int64_t* ctl,
                RunResult& out) {
    const Layout& L = sy.lay;
    const int n = sy.n;
    const double t_end = opt.t_end, sample_dt = opt.sample_dt, rtol = opt.rtol;
    out.reset(sy);
    std::vector<double>& stv = out.state;
    stv.assign(state0, state0 + L.size);
    double* st = stv.data();
    const double t_run0 = st[T];
    double* ledger = out.ledger;
    for (int j = 0; j < LEDGER_LEN; ++j) ledger[j] = 0.0;
    double* extrema = out.extrema.data();
    for (int i = 0; i < n; ++i) {
        double* ex = extrema + 7 * i;
        ex[0] = st[L.x + i];
        ex[1] = t_run0;
        ex[2] = st[L.x + i];
        ex[3] = t_run0;
        ex[4] = 0.0;
        ex[5] = t_run0;
        ex[6] = 0.0;
    }
    Phase ph;
    run_constants(ph, sy, fo);
    Buffers b;
    b.size(n, sy.nc());
    std::vector<double> row(static_cast<size_t>(L.sample_cols()), 0.0);
    const double z_max = sy.bw[0] != 0.0 ? std::pow(sy.bw[2] / (sy.bw[3] + sy.bw[4]), 1.0 / sy.bw[5]) : 0.0;
    const double v_res = RESOLUTION * ph.vrun;
    const double resolution[3] = {v_res, RESOLUTION * ph.xrun, sy.total_mass * v_res};
    std::vector<EventRow> evs(static_cast<size_t>(MAX_EVENTS_PER_PHASE));
    std::vector<double> ev_end(static_cast<size_t>(3 * MAX_EVENTS_PER_PHASE), 0.0);
    int pair_i[64], pair_j[64];
    const int n_pairs = event_pairs(sy, pair_i, pair_j);
    const bool record = fo.kind != EXC_HARMONIC;
    bool continuing = false;
    double t_horizon = INF;
    bool has_ml = false;
    if (sy.has_b)
        for (const Contact& c : sy.contact)
            if (c.law == MULTILINEAR || c.law == MULTILINEAR_KINEMATIC) has_ml = true;
    double h_phase = 0.0;
    double s1 = 0.0, c1 = 1.0;  // the forcing angle's sine and cosine at the end of the last sub-interval
    double rot_w = NaN, rot_h = NaN, rot_s = 0.0, rot_c = 1.0;  // sin and cos of w h, for the last (w, h)
    double t_last = 0.0, h_last = 0.0;
    int n_ev = 0;
    double kin0, iso0, bmp0;
    energies(st, sy, kin0, iso0, bmp0);
    int status = SUCCESS;
    int zero_run = 0;
    double h_num = 1e-4;
    outputs(st, sy, b.q.data(), row.data());
    std::copy(row.begin(), row.end(), out.samples.push());
    for (int i = 0; i < n; ++i) track_abs_acceleration(extrema + 7 * i, t_run0, row[1 + 2 * n + i]);
    int64_t j_next = 1;
    int64_t j_rec = 0;
    int64_t work = 0, published = 0;
    int64_t next_poll = 0;
    const Control control{ctl};
    while (st[T] < t_end) {
        if (work >= next_poll) {  // the run control, polled every POLL_EVERY sub-intervals
            const int64_t left = control.add_work(work - published);  // (the work shows as it is done)
            published = work;
            if (control.stop()) {
                status = INTERRUPTED;
                break;
            }
            if (left <= 0) {
                status = BUDGET;
                break;
            }
            next_poll = work + std::min(POLL_EVERY, left);
        }
        work += 1;
        const double t = st[T];
        const Piece pc = excitation_piece(fo, t, j_rec);
        j_rec = pc.j;
        double h;
        if (continuing) {  // the same phase: only the start values and the forcing move
            ph.phi = pc.phase;
            for (int q = 0; q < 2 * n; ++q) ph.y0[static_cast<size_t>(q)] = st[L.x + q];
            ph.dp5_h = -1.0;
            for (int c = 0; c < sy.nc(); ++c) ph.ct[static_cast<size_t>(c)].def0 = st[L.def_at(c)];
            if (record) {  // (the record's piece: a0 + a1 tau, a new one at each knot)
                ph.ax0 = pc.a0;
                ph.ax1 = pc.a1;
            }
            // the forcing angle where the last sub-interval ended, moved on by the rounding of the clock
            const double wd = pc.omega * ((t - t_last) - h_last);
            ph.sphi = s1 + wd * c1;
            ph.cphi = c1 - wd * s1;
            h = h_phase;
        } else {
            set_phase(ph, st, sy, pc);
            const double horizon = has_ml ? relax_horizon(st, sy) : INF;
            h = TWO_PI / (SUBINTERVALS_PER_PERIOD * std::max(std::max(ph.rate, pc.omega), 1e-300));
            if (has_ml) t_horizon = t + horizon;
            h_phase = h;
        }
        const double t_stop = std::min({pc.t_next, t_end, t_horizon});
        bool to_stop = h >= t_stop - t;
        if (to_stop) h = t_stop - t;
        if (!ph.numeric) {
            taylor(ph, h);
            lin_eval(ph, h, b.y1.data(), b.a1.data());
            ph.evaluations -= 1;  // (the end of the sub-interval: not an evaluation inside it)
            for (int i = 0; i < n; ++i) b.a0[static_cast<size_t>(i)] = ph.X(1)[n + i];
        } else {
            const NumStep ns = numeric_step(ph, h, h_num, rtol, t);
            h = ns.h;
            h_num = ns.h_num;
            if (ns.shortened) to_stop = false;
            if (ns.status != SUCCESS) {
                status = ns.status;
                break;
            }
            const Dp5 r = dp5_step(ph, h);
            std::copy(r.y, r.y + 2 * n, b.y1.begin());
            std::copy(r.a, r.a + n, b.a1.begin());
            phase_rhs(ph, 0.0, ph.y0.data(), ph.zeta0, b.a0.data());
        }
        if (!continuing) n_ev = phase_events(ph, st, sy, evs.data());  // (they stay until one of them fires)
        // a start at rest moves the way its acceleration points: the sign tests take the velocity as the
        // smallest of that sign
        for (int q = 0; q < 2 * n; ++q) b.y0s[static_cast<size_t>(q)] = ph.y0[static_cast<size_t>(q)];
        for (int i = 0; i < n; ++i)
            if (b.y0s[static_cast<size_t>(n + i)] == 0.0 && b.a0[static_cast<size_t>(i)] != 0.0)
                b.y0s[static_cast<size_t>(n + i)] = std::copysign(TINY_SPEED, b.a0[static_cast<size_t>(i)]);
        const double cut = velocity_cuts(ph, sy, h, b, pair_i, pair_j, n_pairs);
        if (cut < h) {
            h = cut;
            to_stop = false;
            eval_end(ph, h, b);
        }
        const Earliest ee = earliest_event(ph, evs.data(), n_ev, ev_end, continuing, h, b);
        double tau = ee.tau;
        const int i_ev = ee.i;
        // the same phase goes on (stopped at a record's knot, not at a relaxing law's horizon or the end)
        continuing = i_ev < 0 && !ph.numeric && (!to_stop || (record && pc.t_next < std::min(t_horizon, t_end)));
        if (i_ev >= 0) {
            to_stop = false;
            if (tau < h) eval_end(ph, tau, b);
        }
        // the forcing angle at the end
        if (pc.omega != 0.0) {
            double sw, cw;
            if (tau == h_phase && rot_w == pc.omega && rot_h == tau) {
                sw = rot_s;
                cw = rot_c;
            } else {
                sw = std::sin(pc.omega * tau);
                cw = std::cos(pc.omega * tau);
                if (tau == h_phase) {
                    rot_w = pc.omega;
                    rot_h = tau;
                    rot_s = sw;
                    rot_c = cw;
                }
            }
            s1 = ph.sphi * cw + ph.cphi * sw;
            c1 = ph.cphi * cw - ph.sphi * sw;
        } else {
            s1 = ph.sphi;
            c1 = ph.cphi;
        }
        const Ends ends{ph.y0.data(), b.a0.data(), b.y1.data(), b.a1.data(), ph.sphi, ph.cphi, s1, c1};
        accumulate(ph, sy, st, t, tau, ends, ledger, extrema, b, opt.with_energy);
        if (sample_dt > 0.0) samples_inside(ph, sy, out.samples, j_next, sample_dt, t_run0, t, tau, t_end, b);
        move_bumpers(st, sy, b.y1.data(), tau, ledger);
        bool finite = true;
        for (int q = 0; q < 2 * n; ++q) finite = finite && std::abs(b.y1[static_cast<size_t>(q)]) <= DBL_MAXV;
        if (!finite) {  // inf or NaN: nothing after it holds
            status = NONFINITE;
            break;
        }
        // the isolator at the sub-interval's end
        ledger[L_HYSTERETIC] += iso_advance(sy, st, rel(ph.y0.data(), sy.iso_i, sy.iso_j),
                                            rel(b.y1.data(), sy.iso_i, sy.iso_j));
        if (sy.bw[0] != 0.0) st[L.zeta] = std::min(std::max(phase_zeta(ph, tau), -z_max), z_max);
        for (int q = 0; q < 2 * n; ++q) st[L.x + q] = b.y1[static_cast<size_t>(q)];
        st[T] = to_stop ? t_stop : t + tau;
        t_last = t;
        h_last = tau;
        if (i_ev < 0) continue;
        jump(st, sy, evs[static_cast<size_t>(i_ev)], out.contacts, resolution);
        record_event(st, sy, evs[static_cast<size_t>(i_ev)], out.events, out.samples, sample_dt, extrema, b, row);
        zero_run = tau <= 1e-12 * std::max(1.0, std::abs(t)) ? zero_run + 1 : 0;
        if (zero_run > ZENO_REPEATS) {
            status = ZENO;
            break;
        }
        if (out.events.n >= opt.max_events) {
            status = MAX_EVENTS;
            break;
        }
    }
    finish(st, sy, out.samples, out.contacts, b, row);
    control.add_work(work - published);
    control.at(CTL_EVALS).fetch_add(ph.evaluations, std::memory_order_relaxed);
    double kin1, iso1, bmp1;
    energies(st, sy, kin1, iso1, bmp1);
    ledger[L_KINETIC] = kin1 - kin0;
    ledger[L_ISOLATOR] = iso1 - iso0;
    ledger[L_BUMPER] = bmp1 - bmp0;
    if (!opt.with_energy)
        for (int j = 0; j < LEDGER_LEN; ++j) ledger[j] = NaN;
    out.status = status;
}

}  // namespace pounding
