// One phase of motion: fixed isolator branch, fixed contacts, one piece of the excitation.
//
// Within a phase, with y = (x, v) the n displacements and velocities relative to the ground,
//     M x'' + C x' + K x + R0 = -M 1 a_g(tau),   a_g(tau) = ax0 + ax1 tau + axh sin(w tau + phi)
// (tau since the sub-interval's start) with constant coefficients, plus the forces of nonlinear contact laws
// and of a Bouc-Wen spring when there are any.
//
// A linear phase is solved exactly on each sub-interval by the power series of its solution about the
// sub-interval's start: y(tau) = sum_k Y_k tau^k, the coefficients by the recurrence the equation of motion
// gives (X_(k+1) = V_k / (k + 1), V_(k+1) = (-M^-1 (K X_k + C V_k) - g_k) / (k + 1), g_k the table
// acceleration's own series).  A sub-interval is short against every period and decay time of the phase
// (|lambda| h <= pi / 4 for each eigenvalue lambda, and w h <= pi / 4), so the series converges like
// (pi / 4)^k / k!: its terms are summed until they fall below the rounding of the motion's scale (about 20;
// checked on the terms themselves), which is the exact solution to rounding, undamped resonance, k = 0 and
// critical damping included.  Every quantity the loop asks inside a sub-interval (an event function, a
// velocity, an absolute acceleration, a contact force) is a linear function of y, hence a polynomial in tau
// whose coefficients follow from the Y_k: roots and extrema are found on it.
//
// A phase with a nonlinear law in contact or a Bouc-Wen spring is integrated by Dormand-Prince 5(4), a step
// of any length tau from the sub-interval's start being one step.
#pragma once

#include <cmath>
#include <type_traits>
#include <vector>

#include "compression.hpp"
#include "core.hpp"
#include "isolator.hpp"
#include "laws.hpp"
#include "sticking.hpp"

namespace pounding {

// a numerical phase's step keeps its error within rtol (NUMERIC_X_FLOOR_M + |x|) on each displacement and rtol
// (NUMERIC_V_FLOOR_M_S + |v|) on each velocity (run_setup.cpp's numeric_step)
constexpr double NUMERIC_X_FLOOR_M = 1e-3, NUMERIC_V_FLOOR_M_S = 1e-2;
constexpr int MAX_TERMS = 48;  // of a sub-interval's series (about 20 are used: the bound is a safeguard)

// a contact slot in this phase
struct ContactPhase : Pair {
    bool in = false, nl = false;  // in contact; with a nonlinear law (integrated numerically)
    int law = 0;
    const double* p = nullptr;
    double sign = 1.0, gap = 0.0;
    double def0 = 0.0;             // the compression at the start (a relaxing bumper's)
    double kb = 0.0, cb = 0.0, rb = 0.0;  // a linear law's branch: F = kb x + rb + cb x'
    int jb = 0;
    double lz[N_LAW_STATE] = {0};  // the law's state in this phase
    Radial radial;                 // (a ring's wall: core.hpp)
};

// a polynomial in tau: c[0] + c[1] tau + ... + c[deg] tau^deg
struct Poly {
    int deg = -1;
    double c[MAX_TERMS + 1];
};

struct Phase {
    int n = 1, ny = 2, nc = 0;
    // the equation of motion: stiffness and damping (the isolator's branch, linear contacts' branches), the
    // restoring force at x = 0, the inverse masses; the table acceleration's piece
    std::vector<double> K, C, R0, minv, mass;
    // where K and C can be nonzero (System::kc_start, kc_col; sparse false: everywhere), what with_rows walks
    std::vector<int> kc_start, kc_col;
    bool sparse = false;
    double ax0 = 0.0, ax1 = 0.0, axh = 0.0, w = 0.0, phi = 0.0, sphi = 0.0, cphi = 1.0;
    // the table's second component, on the first's angle: bx0 + bx1 tau + bs sin(w tau + phi) + bc cos(w tau +
    // phi); how the two move each dof (rA, rB: System::infl's columns), plain: the first alone, on every dof
    double bx0 = 0.0, bx1 = 0.0, bs = 0.0, bc = 0.0;
    bool plain = true;
    std::vector<double> rA, rB;
    std::vector<double> y0;  // the sub-interval's start: x (n) then v (n)
    // the Bouc-Wen springs (System::bw_el's elements, by their z's slot: each its pair and numbers) and their z
    // at the start
    std::vector<const Hysteretic*> bw;
    int nbw = 0;
    std::vector<double> zeta0;
    std::vector<char> bw_slip;  // per spring: 1 a plastic circle's slipping on it (core.hpp's bw_plastic)
    // per spring: 1 a plastic circle's inside it, its force bw[0] z = (bw[0] / u_y) u + bw[0] zoff in the
    // phase's K and R0 (linear: z = zoff + u / u_y, zoff set with the phase); zlin: z so found (phase_zeta)
    std::vector<char> bw_lin;
    std::vector<double> zoff, zlin;
    bool numeric = false;
    double rtol = 0.0;  // the run's relative tolerance: a numerical phase's accuracy (run.cpp's numeric_step)
    std::vector<ContactPhase> ct;
    Sticking stk;  // the rigid stops held shut in this phase: every acceleration is projected by it
    // the isolator: its pair, dashpot and linear branch (force kiso u + riso + cd u')
    Pair iso;
    double cd = 0.0, kiso = 0.0, riso = 0.0;
    std::vector<double> el_k, el_r;  // every hysteretic element's branch (force el_k u + el_r), for the outputs
    std::vector<double> el_s;        // and its velocity-dependent friction's slip direction (isolator.hpp)
    struct RateFriction { const Hysteretic* h; double s; };
    std::vector<RateFriction> rate_fr;  // the elements slipping with a velocity-dependent friction (numerical)
    // the run's and the phase's length (m) and velocity (m/s) scales, what event values are rounded against
    double xrun = 0.0, vrun = 0.0, xround = 0.0, vround = 0.0;
    double rate = 0.0;  // a bound on the phase's |eigenvalues|, 1/s
    // the series of the current sub-interval of length series_h: Y_k at tc[k * ny], k < nt; made when first
    // asked for (ensure_series)
    mutable int nt = 0;
    mutable bool tc_ok = false;
    double series_h = 0.0;
    mutable std::vector<double> tc;
    mutable std::vector<double> rbuf;  // M^-1 R0
    // the last Dormand-Prince step: its length (-1: none); y (ny), a (n), the error (ny), z (nbw), its error (nbw)
    double dp5_h = -1.0;
    std::vector<double> dp5;
    std::vector<double> work;  // scratch: the derivatives at an end, the table's, m . D, forces, DP5 stages
    int w_D = 0, w_g = 0, w_gb = 0, w_P = 0, w_q = 0, w_stage = 0;
    std::vector<double> ye, ae;  // an evaluation's y and a (the root finders')
    std::vector<double> au, aur;  // accelerations without the held stops, their rates (held forces)
    // the current sub-interval's ends, as the loop has them (the start's velocities at rest signed by their
    // accelerations), its length, and the relative velocities' zeros found on it so far (per pair)
    const double *e_y0 = nullptr, *e_a0 = nullptr, *e_y1 = nullptr, *e_a1 = nullptr;
    double e_h = 0.0;
    struct Zeros : Pair { double h; int count; double t[2], x[2]; };
    std::vector<Zeros> zeros;
    // evaluations of the trajectory at an instant inside a sub-interval (a series summed, a numerical step),
    // and of scalar polynomials (a root finder's iterations on a linear phase)
    mutable int64_t evaluations = 0;
    mutable int64_t poly_evaluations = 0;
    mutable int64_t series_made = 0;  // (the sub-intervals' series made: the dearest work of a linear one)

    void size(int n_dof, int n_contacts, int n_bouc_wen) {
        nbw = n_bouc_wen;
        zeta0.assign(static_cast<size_t>(std::max(nbw, 1)), 0.0);
        bw_slip.assign(static_cast<size_t>(std::max(nbw, 1)), 0);
        bw_lin.assign(static_cast<size_t>(std::max(nbw, 1)), 0);
        zoff.assign(static_cast<size_t>(std::max(nbw, 1)), 0.0);
        zlin.assign(static_cast<size_t>(std::max(nbw, 1)), 0.0);
        n = n_dof;
        ny = 2 * n;
        nc = n_contacts;
        kc_start.clear();
        kc_col.clear();
        sparse = false;
        K.assign(static_cast<size_t>(n * n), 0.0);
        C.assign(static_cast<size_t>(n * n), 0.0);
        R0.assign(static_cast<size_t>(n), 0.0);
        minv.assign(static_cast<size_t>(n), 0.0);
        mass.assign(static_cast<size_t>(n), 1.0);
        y0.assign(static_cast<size_t>(ny), 0.0);
        ct.assign(static_cast<size_t>(nc), ContactPhase());
        tc.assign(static_cast<size_t>((MAX_TERMS + 1) * ny), 0.0);
        ye.assign(static_cast<size_t>(ny), 0.0);
        rbuf.assign(static_cast<size_t>(n), 0.0);
        ae.assign(static_cast<size_t>(n), 0.0);
        au.assign(static_cast<size_t>(n), 0.0);
        aur.assign(static_cast<size_t>(n), 0.0);
        dp5.assign(static_cast<size_t>(2 * ny + n + 2 * nbw), 0.0);
        w_D = 0;                 // 10 n
        w_g = 10 * n;            // 10
        w_gb = w_g + 10;         // 10
        w_P = w_gb + 10;         // 10
        w_q = w_P + 10;          // 9 n (C D_m; the forces in phase_rhs)
        w_stage = w_q + 9 * n;   // 8 (ny + nbw)
        work.assign(static_cast<size_t>(w_stage + 8 * (ny + nbw)), 0.0);
    }
    // the pattern of the system's K and C (System::pattern), kept for the phase's loops
    void pattern(const System& sy) {
        kc_start = sy.kc_start;
        kc_col = sy.kc_col;
        sparse = !kc_start.empty();
    }
    // the table acceleration on dof i from its components' values (or derivatives) ga and gb
    double on(int i, double ga, double gb) const {
        return plain ? ga : rA[static_cast<size_t>(i)] * ga + rB[static_cast<size_t>(i)] * gb;
    }
    const double* X(int k) const { return &tc[static_cast<size_t>(k * ny)]; }
    const double* Vk(int k) const { return &tc[static_cast<size_t>(k * ny + n)]; }
};

// ---------------------------------------------------------------- walking a row of K and C

// each column j of a row, f(j) in ascending order: every one (DenseRows), or those where the phase's K or C can
// be nonzero (SparseRows, its pattern): a sum over them is the dense row's sum without its zero terms, the
// same number
struct DenseRows {
    int n;
    template <class F>
    void operator()(int, F&& f) const {
        for (int j = 0; j < n; ++j) f(j);
    }
};
struct SparseRows {
    const int* start;
    const int* col;
    template <class F>
    void operator()(int i, F&& f) const {
        for (int q = start[i], e = start[i + 1]; q < e; ++q) f(col[q]);
    }
};
// body(N) with N a std::integral_constant of the masses n fixed at compile time, for the small systems the core
// has its kernels sized for (1 to 8 masses: a building of up to 8 levels), 0 beyond (n known at run time only):
// one source, each instantiation the same sums in the same order
template <class B>
decltype(auto) sized(int n, B&& body) {
    switch (n) {
        case 1: return body(std::integral_constant<int, 1>{});
        case 2: return body(std::integral_constant<int, 2>{});
        case 3: return body(std::integral_constant<int, 3>{});
        case 4: return body(std::integral_constant<int, 4>{});
        case 5: return body(std::integral_constant<int, 5>{});
        case 6: return body(std::integral_constant<int, 6>{});
        case 7: return body(std::integral_constant<int, 7>{});
        case 8: return body(std::integral_constant<int, 8>{});
        default: return body(std::integral_constant<int, 0>{});
    }
}

// body(rows) with the phase's way to walk a row, chosen once for the whole body (a loop over rows inside it is
// the plain loop, instruction for instruction, on a dense phase; NF: the phase's n fixed at compile time, 0
// known at run time only)
template <int NF = 0, class B>
auto with_rows(const Phase& ph, B&& body) {
    if (ph.sparse) return body(SparseRows{ph.kc_start.data(), ph.kc_col.data()});
    return body(DenseRows{NF > 0 ? NF : ph.n});
}

// ---------------------------------------------------------------- the linear phase's series

// the series of y from y0 under the accelerations -r - (a0 + a1 tau + amp sin(w tau + phi)) 1 besides the
// phase's springs and dashpots (r: n values or null; sin phi = sp, cos phi = cp), accurate over [0, h], into t
// (coefficient k of y at t[k ny]); the number of terms
int series(const Phase& ph, const double* y0, const double* r, double a0, double a1, double amp, double sp,
           double cp, double h, double* t);
// the series of the sub-interval from y0 (forcing angle sphi, cphi at its start), accurate over [0, h]
void taylor(const Phase& ph, double h);
// the current sub-interval's series, made over [0, series_h] if it is not yet
inline void ensure_series(const Phase& ph) {
    if (!ph.tc_ok) taylor(ph, ph.series_h);
}
// y (ny) and the acceleration a (n) at tau of the current series
void lin_eval(const Phase& ph, double tau, double* y, double* a);
// the table acceleration's series about the sub-interval's start, coefficients 0..m of tau: its first
// component's into ga, its second's into gb
void table_series(const Phase& ph, int m, double* ga, double* gb);
// the table acceleration's derivatives G_0..G_m at tau (sin and cos of the forcing angle there given): its
// first component's into g, its second's into gb (when not null)
void table_derivatives(const Phase& ph, double tau, double s, double c, int m, double* g, double* gb = nullptr);

// scalar polynomials of the current series: alpha + beta (x_i - x_j) + gamma (v_i - v_j) + delta (a_i - a_j)
// (x_i - x_j: the pair's w . x)
void pair_poly(const Phase& ph, const Pair& pr, double alpha, double beta, double gamma, double delta, Poly& q);
// the relative displacement x_i - x_j at tau of the current series (as pair_poly's polynomial of it would give)
double pair_x(const Phase& ph, const Pair& pr, double tau);
// dof i's absolute acceleration -(K x + C v + R0)_i / m_i (a linear phase's: no sine)
void abs_acc_poly(const Phase& ph, int i, Poly& q);
// the derivative of q
void poly_deriv(const Poly& q, Poly& out);
inline double poly_val(const Poly& q, double t) {
    double f = q.c[q.deg];
    for (int k = q.deg - 1; k >= 0; --k) f = f * t + q.c[k];
    return f;
}
// value, first and second derivatives
inline void poly_val3(const Poly& q, double t, double& f, double& f1, double& f2) {
    f = q.deg >= 0 ? q.c[q.deg] : 0.0;
    f1 = 0.0;
    f2 = 0.0;
    for (int k = q.deg - 1; k >= 0; --k) {
        f2 = f2 * t + f1;
        f1 = f1 * t + f;
        f = f * t + q.c[k];
    }
    f2 *= 2.0;
}

// over [0, tau] of a linear phase: int v^T C_lin v (vcv), int a_g (m . v) (gv) (when energy), and for each contact c in
// contact with a linear law int (x_i - x_j) (du[c]) and int (v_i - v_j)^2 (dvv[c]): the two-point Hermite rule
// of order 8 on the derivatives at both ends (the equation of motion differentiated), exact to degree 17
void linear_integrals(Phase& ph, const std::vector<double>& c_lin, const std::vector<double>& mass, double tau,
                      const double* y0, const double* a0, double s0, double c0, const double* y1, const double* a1,
                      double s1, double c1, bool energy, double& vcv, double& gv, double* du, double* dvv);

// ---------------------------------------------------------------- held rigid stops

// the accelerations (n) at (tau, y) without the held stops' constraint (zeta: the Bouc-Wen z there, nbw)
void free_acceleration(Phase& ph, double tau, const double* y, const double* zeta, double* au);
// the held force of contact c as a polynomial of the current series (a linear phase)
void held_force_poly(const Phase& ph, int c, Poly& q);

// ---------------------------------------------------------------- the numerical phase

// the rate of Bouc-Wen spring q's z at the velocities v (n) and the springs' z (nbw)
double zeta_rate(const Phase& ph, int q, const double* v, const double* z);
// the factor a friction circle's velocity dependence puts on Bouc-Wen spring q's force (isolator.hpp's
// circle_scale) at the velocities v (n) and z (nbw); with acc (the accelerations, n) and rate, its slip's rate's
// derivative into *rate (0 where it has none)
CircleScale circle_scale(const Phase& ph, int q, const double* v, const double* z, const double* acc = nullptr,
                         double* rate = nullptr);
// the accelerations (n) at (tau, y, z) with the nonlinear forces (z: the Bouc-Wen springs', nbw)
void phase_rhs(Phase& ph, double tau, const double* y, const double* z, double* a, bool held = true);
// the step of length h from the start: y (ny), a (n), z (nbw); the error estimates
struct Dp5 { const double* y; const double* a; const double* ey; const double* z; const double* ez; };
Dp5 dp5_step(Phase& ph, double h);

// ---------------------------------------------------------------- the trajectory inside a sub-interval

// y (ny), a (n) at tau: the series of a linear phase, a numerical step of a nonlinear one
void phase_eval(Phase& ph, double tau, double* y, double* a);
// the Bouc-Wen springs' z at tau (nbw; nullptr without any); x: the displacements there (a linear phase's z
// follow them: its springs are plastic circles inside, bw_lin)
const double* phase_zeta(Phase& ph, double tau, const double* x);

inline double table_acceleration(const Phase& ph, double tau) {
    return ph.ax0 + ph.ax1 * tau + ph.axh * std::sin(ph.w * tau + ph.phi);
}
// the second component's (0 for a plain table)
inline double table_b(const Phase& ph, double tau) {
    if (ph.plain) return 0.0;
    const double ang = ph.w * tau + ph.phi;
    return ph.bx0 + ph.bx1 * tau + ph.bs * std::sin(ang) + ph.bc * std::cos(ang);
}
// the table acceleration on dof i at tau
inline double table_on(const Phase& ph, int i, double tau) {
    return ph.on(i, table_acceleration(ph, tau), table_b(ph, tau));
}
// the table acceleration's slope along a pair: w . (each dof's)
inline double table_slope_on(const Phase& ph, const Pair& pr) {
    int d[4];
    double w[4];
    const int m = pr.entries(d, w);
    double s = 0.0;
    for (int r = 0; r < m; ++r) s += w[r] * ph.on(d[r], ph.ax1, ph.bx1);
    return s;
}
// the table acceleration on every dof at tau into ag (n)
inline void table_on_dofs(const Phase& ph, double tau, double* ag) {
    const double ga = table_acceleration(ph, tau), gb = table_b(ph, tau);
    for (int i = 0; i < ph.n; ++i) ag[i] = ph.on(i, ga, gb);
}

// contact c in contact: force N, its spring part N, d(force)/dt N/s, the compression's rate m/s.  A linear
// law's force is its phase's branch's (kb x + rb + cb x'): a law with a state has it from there
struct ContactForce { double f, elastic, rate, dx; };
inline ContactForce contact_force(const Phase& ph, int c, const double* y, const double* a) {
    const ContactPhase& k = ph.ct[static_cast<size_t>(c)];
    const Compression cp = compression(k, y, y + ph.n, a);
    const double dd = cp.d, dv = cp.dv, da = cp.da;
    if (law_is_linear(k.law)) {
        const double fel = k.kb * dd + k.rb;
        return {fel + k.cb * dv, fel, k.kb * dv + k.cb * da, dv};
    }
    const Force f = law_force(k.law, k.p, dd, dv, k.lz);
    return {f.f, f.elastic, f.df_dd * dv + f.df_ddd * da, dv};
}

// the energy a Bouc-Wen spring (its element h) holds at z
inline double bouc_wen_energy(const Hysteretic& h, double z) { return 0.5 * h.bw[0] * h.bw[1] * z * z / h.bw[2]; }
// the Bouc-Wen springs' together at z (nbw)
inline double bouc_wen_energy(const Phase& ph, const double* z) {
    double e = 0.0;
    for (int b = 0; b < ph.nbw; ++b) e += bouc_wen_energy(*ph.bw[static_cast<size_t>(b)], z[b]);
    return e;
}

}  // namespace pounding
