// The event loop (run.hpp).  The run is cut into sub-intervals, each inside one phase of motion and short
// against its periods; on each, every event function is checked for a crossing or a graze and the earliest
// root is located; what the sub-interval adds to the run (energy integrals, extrema, contact statistics) is
// accumulated; then the state jumps at the event.
#include "run.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

#include "events.hpp"
#include "impact.hpp"
#include "isolator.hpp"
#include "laws.hpp"
#include "phase.hpp"
#include "run_parts.hpp"
#include "screen.hpp"
#include "transition.hpp"

namespace pounding {

using namespace run_parts;

namespace {

constexpr double SUBINTERVALS_PER_PERIOD = 8.0;
// a record's step met at its knot by a phase faster than it, taken at once where the screen clears it (its end
// the kept transition's, exact at any length): at most 1 / this of the phase's fastest period, so that the
// series stays short where samples or a fallback ask for it
constexpr double WHOLE_STEPS_PER_PERIOD = 2.5;
constexpr int ZENO_REPEATS = 200;
constexpr int64_t POLL_EVERY = 64;     // sub-intervals between two looks at the run control
constexpr double RESOLUTION = 1e-9;    // relative to the run's scales: below it, a touch is no impact
constexpr int MAX_EVENTS_PER_PHASE = 256;
constexpr double FLIGHT_MARGIN = 1.25;  // a rigid rebound's first sub-interval, in its estimated flights

// ---------------------------------------------------------------- the forcing angle, accelerations

struct Rotation { double w = NaN, h = NaN, s = 0.0, c = 1.0; };  // sin and cos of w h, the last (w, h)
struct Angle { double s, c; };

// sin and cos of the forcing angle tau after the sub-interval's start, by angle addition (sin w tau and
// cos w tau kept for the last tau asked: the phase's sub-interval, most of the time); a record's (w = 0) inline
Angle turned_angle(const Phase& ph, double w, double tau, Rotation& rot);
inline Angle angle_at(const Phase& ph, double w, double tau, Rotation& rot) {
    if (w == 0.0) return {ph.sphi, ph.cphi};
    return turned_angle(ph, w, tau, rot);
}
Angle turned_angle(const Phase& ph, double w, double tau, Rotation& rot) {
    if (!(rot.w == w && rot.h == tau)) {
        rot.w = w;
        rot.h = tau;
        rot.s = std::sin(w * tau);
        rot.c = std::cos(w * tau);
    }
    return {ph.sphi * rot.c + ph.cphi * rot.s, ph.cphi * rot.c - ph.sphi * rot.s};
}

// a linear phase's accelerations at tau from the equation of motion (s, c: the forcing angle's sine and cosine
// there); NF the masses fixed at compile time (0: ph.n at run time), eom_acceleration's choice
template <int NF>
void eom_acceleration_of(const Phase& ph, const double* y, double tau, double s, double c, double* a) {
    const int n = NF > 0 ? NF : ph.n;
    const double g = (ph.ax0 + ph.ax1 * tau) + ph.axh * s;
    // (the second component's, at the same angle)
    const double gb = ph.plain ? 0.0 : (ph.bx0 + ph.bx1 * tau) + ph.bs * s + ph.bc * c;
    with_rows<NF>(ph, [&](const auto& row) {
        for (int i = 0; i < n; ++i) {
            const double* rk = &ph.K[static_cast<size_t>(i * n)];
            const double* rc = &ph.C[static_cast<size_t>(i * n)];
            double q = 0.0;
            row(i, [&](int j) { q += rk[j] * y[j] + rc[j] * y[n + j]; });
            const double f = ph.minv[static_cast<size_t>(i)] * q + ph.minv[static_cast<size_t>(i)] * ph.R0[static_cast<size_t>(i)];
            a[i] = -f - ph.on(i, g, gb);
        }
    });
    if (ph.stk.any) ph.stk.project(ph.mass, a);
}

inline void eom_acceleration(const Phase& ph, const double* y, double tau, double s, double c, double* a) {
    sized(ph.n, [&](auto N) { eom_acceleration_of<decltype(N)::value>(ph, y, tau, s, c, a); });
}

// u^T Q u over u's entries that are not zero (nz: their indices, uc: their values; a product with a zero adds
// a zero, which leaves a sum of finite terms as it is: the same numbers as the whole sum)
double quad_form(const double* Q, const double* uc, int dim, const int* nz, int n_nz) {
    double s = 0.0;
    for (int ia = 0; ia < n_nz; ++ia) {
        const double* qa = Q + nz[ia] * dim;
        double r = 0.0;
        for (int ic = 0; ic < n_nz; ++ic) r += qa[nz[ic]] * uc[ic];
        s += uc[ia] * r;
    }
    return s;
}

// the row's product with u over u's entries that are not zero
double row_product(const double* row, const double* uc, const int* nz, int n_nz) {
    double s = 0.0;
    for (int k = 0; k < n_nz; ++k) s += row[nz[k]] * uc[k];
    return s;
}

// row_product and quad_form where the masses are fixed at compile time (NF > 0): over u's state (its first 2 NF
// entries) whole, then over the masses' constant forces that are not zero (the next NF entries: nz, n_nz, often
// none on a storey), then over the forcing's entries of the run's kind (M, by_transition_of's: FORCING_LINE a
// record's line a0 + a1 tau, FORCING_SINE a harmonic's cosine and sine, FORCING_BOTH the two pairs), the other
// pair's zeros left out.  The same numbers as over u whole: a product with a zero of u adds a zero, which leaves
// the sum as it is (the sum starts at +0 and a sum of finite terms from +0 is never -0), and the entries left are
// summed in the same order
enum ForcingTerms : int { FORCING_LINE = 0, FORCING_SINE, FORCING_BOTH };
template <int D>
double dense_row_product(const double* row, const double* u) {
    double s = 0.0;
    for (int k = 0; k < D; ++k) s += row[k] * u[k];
    return s;
}
template <int NF, int M>
double row_of(const double* r, const double* u, const int* nz, int n_nz) {
    constexpr int F = 3 * NF;
    double s = dense_row_product<2 * NF>(r, u);
    for (int k = 0; k < n_nz; ++k) s += r[nz[k]] * u[nz[k]];
    if constexpr (M != FORCING_SINE) {
        s += r[F] * u[F];
        s += r[F + 1] * u[F + 1];
    }
    if constexpr (M != FORCING_LINE) {
        s += r[F + 2] * u[F + 2];
        s += r[F + 3] * u[F + 3];
    }
    return s;
}
template <int NF, int M>
double quad_of(const double* q, const double* u, const int* nz, int n_nz) {
    constexpr int F = 3 * NF, D = F + 4;
    double s = 0.0;
    for (int a = 0; a < 2 * NF; ++a) s += u[a] * row_of<NF, M>(q + a * D, u, nz, n_nz);
    for (int k = 0; k < n_nz; ++k) s += u[nz[k]] * row_of<NF, M>(q + nz[k] * D, u, nz, n_nz);
    for (int a = M == FORCING_SINE ? F + 2 : F; a < (M == FORCING_LINE ? F + 2 : D); ++a)
        s += u[a] * row_of<NF, M>(q + a * D, u, nz, n_nz);
    return s;
}

// a kept transition's rows and forms times the sub-interval's inputs u (3 n + 4 entries): where the masses are
// fixed at compile time (NF > 0), over u's state whole, its constant forces that are not zero (nz, n_nz) and its
// forcing's entries of the run's kind (terms, one of ForcingTerms); over every entry that is not zero where not
// (nz, uc: by_transition_of's)
template <int NF>
struct InputProducts {
    const double* u;
    const double* uc;
    const int* nz;
    int n_nz, dim, terms;
    double row(const double* r) const {
        if constexpr (NF > 0) {
            if (terms == FORCING_LINE) return row_of<NF, FORCING_LINE>(r, u, nz, n_nz);
            if (terms == FORCING_SINE) return row_of<NF, FORCING_SINE>(r, u, nz, n_nz);
            return row_of<NF, FORCING_BOTH>(r, u, nz, n_nz);
        } else {
            return row_product(r, uc, nz, n_nz);
        }
    }
    double quad(const double* q) const {
        if constexpr (NF > 0) {
            if (terms == FORCING_LINE) return quad_of<NF, FORCING_LINE>(q, u, nz, n_nz);
            if (terms == FORCING_SINE) return quad_of<NF, FORCING_SINE>(q, u, nz, n_nz);
            return quad_of<NF, FORCING_BOTH>(q, u, nz, n_nz);
        } else {
            return quad_form(q, uc, dim, nz, n_nz);
        }
    }
};

// a rigid stop's scales in the phase (h_phase: its sub-interval, short against its periods)
ImpactScales impact_scales(const Phase& ph, double h_phase, double v_res) {
    constexpr double LOCAL = 1e-6;        // a chatter's remainder, against the sub-interval: summed at once
    constexpr double FLIGHT_ROUND = 64.0; // a rebound's height, in the rounding of the run's length: no flight
    return {v_res, FLIGHT_ROUND * ROUNDING * ph.xrun, LOCAL * h_phase, h_phase};
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
double velocity_cuts(Phase& ph, const System& sy, double h, const Buffers& b, const Pair* pairs, int np) {
    const int n = ph.n;
    double cut = h;
    const bool kinks = ph.numeric && (law_switches(ph) || sy.bw_kinks);
    for (int p = 0; p < np; ++p) {
        const Pair& pr = pairs[p];
        double v0 = rel(b.y0s.data() + n, pr);
        const double v1 = rel(b.y1.data() + n, pr);
        const double a0 = rel(b.a0.data(), pr), a1 = rel(b.a1.data(), pr);
        bool rested = false;  // (a levered pair's start taken at rest: its velocity there is rounding's)
        if (pr.levered() && a0 != 0.0) {
            // a levered pair's velocity at a start cut at its zero is the rounding of its terms (w . v of dofs
            // that all move): at rest there, heading the way it accelerates, as start_signs makes a dof at rest
            // (else its zero is found again a rounding's time on, and again: the clock would stand still)
            int d[4];
            double w[4];
            const int m = pr.entries(d, w);
            double size = 0.0;
            for (int r = 0; r < m; ++r) size += std::abs(w[r] * b.y0s[static_cast<size_t>(n + d[r])]);
            // (in a numerical phase, also a velocity whose zero lies within the roots' resolution in time:
            // a cut there found by the root finder on a step of the integration may stop a hair short of it)
            const double resolution = ph.numeric ? 4.0 * XTOL_S * std::abs(a0) : 0.0;
            if (std::abs(v0) <= 8.0 * EPS * size + resolution) {
                v0 = std::copysign(TINY_SPEED, a0);
                rested = true;
            }
        }
        // its velocity's and its acceleration's functions (polynomials of a linear phase's series), made when
        // asked for
        Fn fa, fv;
        auto functions = [&]() {
            if (!ph.numeric) {
                pair_poly(ph, pr, 0.0, 0.0, 0.0, 1.0, fa.q);
                fa.kind = FN_POLY;
                pair_poly(ph, pr, 0.0, 0.0, 1.0, 0.0, fv.q);
                fv.kind = FN_POLY;
            } else {
                fa.kind = FN_PAIR_A;
                fv.kind = FN_PAIR_V;
                fa.pair = &pr;
                fv.pair = &pr;
            }
        };
        if (v0 * v1 < 0.0 && kinks) {  // (kinks: a numerical phase)
            functions();
            double t_lo = 0.0, v_lo = v0, a_lo = a0;
            if (rested) {
                // at rest heading the way it accelerates, and back across zero at the end: the zero is the
                // one after its turn (its rounding at the start would read as a zero there, again and again)
                if (!(a0 * a1 < 0.0)) continue;  // (no turn: the start's rounding alone changed its sign)
                t_lo = find_root(fa, ph, 0.0, h, a0, a1, NaN, NaN, XTOL_EXTREMUM_S);
                double unused;
                fn_eval(fv, ph, t_lo, v_lo, unused);
                if (!(v_lo * v1 < 0.0)) continue;
                a_lo = NaN;
            }
            const double t_v = find_root(fv, ph, t_lo, h, v_lo, v1, a_lo, a1, XTOL_S);
            if (0.0 < t_v && t_v < cut) cut = t_v;
            continue;
        }
        if (!(v0 * v1 > 0.0 && a0 * a1 < 0.0) || !may_turn_back(h, v0, v1, a0, a1)) continue;
        functions();
        const double t_a = find_root(fa, ph, 0.0, h, a0, a1, NaN, NaN, XTOL_EXTREMUM_S);
        double v_a, unused;
        fn_eval(fv, ph, t_a, v_a, unused);
        if (v_a * v0 < 0.0 && 0.0 < t_a && t_a < cut) cut = t_a;  // two velocity zeros: cut where it turns
    }
    return cut;
}

// the same for a ring's contact (core.hpp's Radial), its compression's rate in its pair's place: of one sign at
// both ends and turning back inside (two zeros: a dip of its start or its branch's edge could hide between
// them), cut where it turns.  The cut instant (or h).  (Jankowski's dashpot's kink where that rate is zero, in
// contact, is left to the numerical step's control: cutting there changed its contacts' instants by nothing
// measurable against the reference, tests/test_plan_ring.py.)
double ring_cuts(Phase& ph, double h, const Buffers& b) {
    const int n = ph.n;
    double cut = h;
    for (int c = 0; c < ph.nc; ++c) {
        const ContactPhase& k = ph.ct[static_cast<size_t>(c)];
        if (!k.radial.on) continue;
        const Compression c0 = compression(k, b.y0s.data(), b.y0s.data() + n, b.a0.data());
        const Compression c1 = compression(k, b.y1.data(), b.y1.data() + n, b.a1.data());
        Fn fr, fb;
        fr.kind = FN_COMPRESSION_RATE;
        fb.kind = FN_COMPRESSION_BEND;
        fr.idx = fb.idx = c;
        if (!(c0.dv * c1.dv > 0.0 && c0.da * c1.da < 0.0) || !may_turn_back(h, c0.dv, c1.dv, c0.da, c1.da)) continue;
        const double t_b = find_root(fb, ph, 0.0, h, c0.da, c1.da, NaN, NaN, XTOL_EXTREMUM_S);
        double v_b, unused;
        fn_eval(fr, ph, t_b, v_b, unused);
        if (v_b * c0.dv < 0.0 && 0.0 < t_b && t_b < cut) cut = t_b;
    }
    return cut;
}

// the same for a plastic circle inside (core.hpp's bw_plastic; a ring in z: |z|^2 = 1 its reach, z following
// its pairs), |z|^2's rate of one sign at both ends and turning back inside: cut where it turns
double circle_cuts(Phase& ph, double h, const Buffers& b) {
    double cut = h;
    for (int q = 0; q < ph.nbw; ++q) {
        if (!ph.bw_lin[static_cast<size_t>(q)] || ph.bw[static_cast<size_t>(q)]->bw_mate_slot < q) continue;
        Fn fr, fb;
        fr.kind = FN_CIRCLE_RATE;
        fb.kind = FN_CIRCLE_BEND;
        fr.idx = fb.idx = q;
        double r0, b0, r1, b1;
        // (at the sub-interval's ends as the loop has them: no series made)
        circle_turn(ph, q, 0.0, b.y0s.data(), b.a0.data(), r0, b0);
        circle_turn(ph, q, h, b.y1.data(), b.a1.data(), r1, b1);
        if (!(r0 * r1 > 0.0 && b0 * b1 < 0.0) || !may_turn_back(h, r0, r1, b0, b1)) continue;
        const double t_b = find_root(fb, ph, 0.0, h, b0, b1, NaN, NaN, XTOL_EXTREMUM_S);
        double r_b, unused;
        fn_eval(fr, ph, t_b, r_b, unused);
        if (r_b * r0 < 0.0 && 0.0 < t_b && t_b < cut) cut = t_b;
    }
    return cut;
}

// whether a held force's rate and bend at a sub-interval's two ends (held_force_turn) say, beyond any doubt of
// rounding, that it does not turn back and forth inside: its rates of opposite signs, or its bends of one sign
bool surely_no_turn(const ForceTurn& e0, const ForceTurn& e1) {
    constexpr double MARGIN = 1e-6;  // (of the terms' sizes: far above the series' rounding)
    const double r0 = MARGIN * e0.rate_scale, r1 = MARGIN * e1.rate_scale;
    const double b0 = MARGIN * e0.bend_scale, b1 = MARGIN * e1.bend_scale;
    const bool rates_apart = (e0.rate > r0 && e1.rate < -r1) || (e0.rate < -r0 && e1.rate > r1);
    const bool bends_alike = (e0.bend > b0 && e1.bend > b1) || (e0.bend < -b0 && e1.bend < -b1);
    return rates_apart || bends_alike;
}

// where a sub-interval must also end early: a stuck tie's force whose rate has one sign at both ends but turns
// back and forth inside (its second derivative crossing zero, its rate there of the other sign) could cross
// its threshold and come back unseen between two extrema; cut where its rate turns (a linear phase's
// polynomial), each part then holding one extremum at most.  The cut instant (or h).  With the sub-interval's
// ends (y0 and b's a0, y1, a1 at h), a force that surely does not turn there is passed over without its
// polynomial (the phase's series, the most of a stuck sub-interval's work otherwise).  turns: each bond's
// rate and bend at the end, kept for the next sub-interval (start_kept: this one starts where the last ended,
// on the same piece of the table, so the start's are those; a screen's values, the same to rounding)
double force_turn_cut(Phase& ph, const EventRow* evs, int n_ev, double h, const Buffers* ends, ForceTurn* turns,
                      bool start_kept) {
    double cut = h;
    int last_side = -1;
    for (int i = 0; i < n_ev; ++i) {
        // (a tie's two thresholds share its force: its turns are looked at once)
        if (evs[i].kind != KIND_STICK || evs[i].side == last_side) continue;
        last_side = evs[i].side;
        if (ends != nullptr) {
            ForceTurn& kept = turns[evs[i].side];
            const ForceTurn e0 = start_kept ? kept : held_force_turn(ph, evs[i].side, 0.0, ph.y0.data(), ends->a0.data());
            kept = held_force_turn(ph, evs[i].side, h, ends->y1.data(), ends->a1.data());
            if (surely_no_turn(e0, kept)) continue;
        }
        Fn rate, bend;
        Poly force;
        held_force_poly(ph, evs[i].side, force);
        poly_deriv(force, rate.q);
        poly_deriv(rate.q, bend.q);
        double r0, s0, r1, s1;
        fn_eval(rate, ph, 0.0, r0, s0);
        fn_eval(rate, ph, h, r1, s1);
        if (!((r0 > 0.0 && r1 > 0.0) || (r0 < 0.0 && r1 < 0.0)) || (s0 < 0.0) == (s1 < 0.0)) continue;
        const double tc = find_root(bend, ph, 0.0, h, s0, s1, NaN, NaN, XTOL_EXTREMUM_S);
        double rc, unused;
        fn_eval(rate, ph, tc, rc, unused);
        if ((rc < 0.0) != (r0 < 0.0) && 0.0 < tc && tc < cut) cut = tc;
    }
    return cut;
}

struct Earliest { double tau; int i; };

// (continuing: the same phase goes on from the last sub-interval's end, whose event values stand; but at a
// record's knot a force's rate jumps with the table's, so that a held force's or a stick's is computed anew)
Earliest earliest_event(Phase& ph, const EventRow* evs, int n_ev, std::vector<double>& ev_end, bool continuing,
                        bool at_knot, double h, const Buffers& b) {
    double tau = h;
    int i_ev = -1;
    // (a tie's two thresholds, one row after the other, share its held force at each end: found once)
    int tie = -1;
    bool tie0 = false;
    EventValue d0{}, d1{};
    for (int i = 0; i < n_ev; ++i) {
        double g0, gp0, sc0;
        double* end = &ev_end[static_cast<size_t>(3 * i)];
        const bool stick = evs[i].kind == KIND_STICK;
        const bool force = evs[i].kind == KIND_HELD || stick;
        const bool same_tie = stick && evs[i].side == tie;
        if (stick && !same_tie) {
            tie = evs[i].side;
            tie0 = false;
            d1 = held_force(ph, tie, h, b.y1.data(), b.a1.data());
        }
        if (continuing && !(at_knot && force)) {
            g0 = end[0];
            gp0 = end[1];
            sc0 = end[2];
        } else {
            if (stick && !tie0) {
                d0 = held_force(ph, tie, 0.0, b.y0s.data(), b.a0.data());
                tie0 = true;
            }
            const EventValue e0 = stick ? stick_value(evs[i], d0) : event_value(evs[i], ph, 0.0, b.y0s.data(), b.a0.data());
            g0 = e0.g;
            gp0 = e0.gp;
            sc0 = e0.scale;
        }
        const EventValue e1 = stick ? stick_value(evs[i], d1) : event_value(evs[i], ph, h, b.y1.data(), b.a1.data());
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

}  // namespace

struct RunWorkspace::Impl {
    // the system it was made for: what its buffers' sizes and its transitions depend on
    int n = -1, nc = -1, nbw = -1;
    std::vector<double> mass, c_lin, k0;
    std::vector<Pair> pairs, elements;  // the contacts' pairs; the hysteretic elements' (the outputs' columns)
    bool fits(const System& s) const {
        if (s.n != n || s.nc() != nc || s.n_bw() != nbw || s.mass != mass || s.c_lin != c_lin || s.k0 != k0) return false;
        if (static_cast<int>(elements.size()) != s.n_h()) return false;
        for (int e = 0; e < s.n_h(); ++e)
            if (!same_pair(elements[static_cast<size_t>(e)], s.hyst[static_cast<size_t>(e)])) return false;
        for (int c = 0; c < nc; ++c)
            if (!same_pair(pairs[static_cast<size_t>(c)], s.contact[static_cast<size_t>(c)])) return false;
        return true;
    }
    Phase ph;
    Buffers b;
    std::vector<double> row;
    std::vector<EventRow> evs;
    std::vector<double> ev_end;
    std::vector<double> ev_whole;  // (a whole step's ends, ev_end's once it is taken)
    std::vector<Pair> event_pairs;
    TransitionCache transitions;
    ExtremaScreen screen;  // (the present phase's)
    std::vector<ForceTurn> turns;  // (each bond's held force's rate and bend at the last sub-interval's end)
};

RunWorkspace::RunWorkspace() : impl(new Impl()) {}
RunWorkspace::~RunWorkspace() = default;

namespace {

// ---------------------------------------------------------------- the loop's steps
//
// A run reads as a story (run_kernel, at the end): set up; then, sub-interval by sub-interval, poll the run
// control, take the next sub-interval (the same phase moved on, or a new phase), advance to its end (a kept
// transition, the series, or a numerical step), find the earliest event inside it, accumulate what it adds
// and move the state to its end, then apply the event; finish.  What the steps share is a Loop.

struct Loop {
    const System& sy;
    const Forcing& fo;
    const RunOptions& opt;
    RunResult& out;
    RunWorkspace::Impl& w;
    const Layout& L;
    const int n;
    double* st;
    double* ledger;
    double* extrema;
    double t_run0;
    Phase& ph;
    Buffers& b;
    std::vector<double>& row;
    Control control;
    // the run's constants
    std::vector<double> z_max;  // (each Bouc-Wen spring's largest |z|)
    double resolution[3] = {0.0, 0.0, 0.0};
    bool record = false;
    bool has_ml = false;
    bool has_ring = false;  // (a ring's contact: its compression's turns cut a sub-interval, ring_cuts)
    bool has_circle = false;  // (a plastic circle: its |z|'s turns inside it cut one too, circle_cuts)
    int n_pairs = 0;
    double kin0 = 0.0, iso0 = 0.0, bmp0 = 0.0;
    // what goes from one sub-interval to the next
    bool continuing = false;
    double t_horizon = INF;
    double h_phase = 0.0;
    double s1 = 0.0, c1 = 1.0;  // the forcing angle's sine and cosine at the end of the last sub-interval
    Rotation rot;               // sin and cos of w h, for the last (w, h)
    double t_last = 0.0, h_last = 0.0;
    int n_ev = 0;
    int status = SUCCESS;
    int zero_run = 0;
    // the last event's slip from a stick (a stick's end, or the start's), until another event: its row, its
    // element, the samples after it (and whether it pushed one) and the element's displacement there
    // (springs: the element's spring slots at the touch, a series's surfaces' displacements)
    struct Touch {
        int64_t row = -1;
        int e = -1;
        int64_t samples = 0;
        bool sampled = false;
        double u = 0.0;
        std::vector<double> springs;
    };
    Touch touch;
    double h_num = 1e-4;
    Sticking stk_out;  // (the held stops of the state an output row is made from)
    std::vector<double> ag_now;  // (the table's acceleration on each dof at the present event)
    int64_t j_next = 1, j_rec = 0;
    int64_t work = 0, published = 0, next_poll = 0;
    double h_flight = INF;  // (the last rigid rebound's flight, to first order)
    bool turns_at_end = false;  // (w.turns are the last sub-interval's end's, at its full length)
    // a record's step met at its knot by a phase faster than it, cut in equal parts: their length (0: none), how
    // many are left (the last ends at the knot), whether this sub-interval is one, and whether the last
    // sub-interval ended at a knot
    double h_split = 0.0;
    int parts = 0, parts_left = 0;
    bool in_part = false;
    bool whole = false;  // (this sub-interval the whole step, its parts' count set for a fallback)
    int64_t wholes = 0;  // (the steps taken whole)
    bool at_knot = false;
    // a record's samples at its own step taken one by one by own_samples_of, where the run asks for nothing that
    // such a sample needs the loop's steps for (set up once), and how many were
    bool own_samples = false;
    int64_t owns = 0;
    // this sub-interval's
    Piece pc{};
    double t = 0.0, h = 0.0, t_stop = 0.0, tau = 0.0;
    bool to_stop = false;
    const Transition* tr = nullptr;
    uint64_t phase_id = 0;  // (this phase's count in the workspace: its kept transitions found at once)
    int i_ev = -1;
};

// every dof's extrema and every tracked pair's (a storey's drift) start where the run starts
void start_extrema(const System& sy, const double* st, double t_run0, double* extrema) {
    const Layout& L = sy.lay;
    for (int i = 0; i < sy.n; ++i) {
        double* ex = extrema + DOF_EXTREMA * i;
        ex[EX_D_MAX] = st[L.x + i];
        ex[EX_D_MAX_T] = t_run0;
        ex[EX_D_MIN] = st[L.x + i];
        ex[EX_D_MIN_T] = t_run0;
        ex[EX_A_ABS_MAX] = 0.0;
        ex[EX_A_ABS_MAX_T] = t_run0;
        ex[EX_A_AT_MAX] = 0.0;
    }
    for (int p = 0; p < sy.n_track(); ++p) {
        double* ex = extrema + DOF_EXTREMA * sy.n + PAIR_EXTREMA * p;
        const double d = rel(st + L.x, sy.track[static_cast<size_t>(p)]);
        ex[PX_MAX] = ex[PX_MIN] = d;
        ex[PX_MAX_T] = ex[PX_MIN_T] = t_run0;
    }
    for (int q = 0; q < sy.n_norm(); ++q) {
        double* ex = extrema + sy.norm_extrema_at() + NORM_EXTREMA * q;
        const double u = rel(st + L.x, sy.track[static_cast<size_t>(sy.norm_p[static_cast<size_t>(q)])]);
        const double w = rel(st + L.x, sy.track[static_cast<size_t>(sy.norm_q[static_cast<size_t>(q)])]);
        // (its length with its offset: a corner's distance from a ring's centre)
        const double* at = &sy.norm_at[static_cast<size_t>(2 * q)];
        ex[NX_MAX] = std::hypot(at[0] + u, at[1] + w);
        ex[NX_MAX_T] = t_run0;
        ex[NX_AT_P] = u;
        ex[NX_AT_Q] = w;
    }
}

// the workspace made for this system (another system: new buffers, no transitions kept), with room for the
// event rows a phase can have: the isolator's (two a spring and a reversal), each contact's (its start or
// release, a relaxing law's twin, a branch's two edges and its rate's turn), the Bouc-Wen z's
void fit_workspace(RunWorkspace::Impl& w, const System& sy) {
    if (!w.fits(sy)) {
        w.n = sy.n;
        w.nc = sy.nc();
        w.nbw = sy.n_bw();
        w.mass = sy.mass;
        w.c_lin = sy.c_lin;
        w.k0 = sy.k0;
        w.pairs.clear();
        for (const Contact& c : sy.contact) w.pairs.push_back(c);
        w.elements.clear();
        for (const Hysteretic& h : sy.hyst) w.elements.push_back(h);
        w.ph.size(sy.n, sy.nc(), sy.n_bw());
        w.ph.pattern(sy);
        w.b.size(sy.n, sy.nc());
        w.row.assign(static_cast<size_t>(sy.lay.sample_cols()), 0.0);
        w.transitions.setup(sy);
        w.turns.assign(static_cast<size_t>(sy.nc() + sy.n_h()), ForceTurn{0.0, 0.0, 0.0, 0.0});
    }
    const size_t rows = static_cast<size_t>(
        std::max(MAX_EVENTS_PER_PHASE, 2 * sy.n_springs() + sy.n_h() + 6 * sy.nc() + std::max(1, sy.n_bw())));
    if (w.evs.size() < rows) {
        w.evs.assign(rows, EventRow());
        w.ev_end.assign(3 * rows, 0.0);
        w.ev_whole.assign(3 * rows, 0.0);
    }
}

// the slip from a stick just recorded for element e (sampled: with a sample of its own), for touched_mu_w
void note_touch(Loop& lp, int e, bool sampled) {
    Loop::Touch& t = lp.touch;
    t.row = lp.out.events.n - 1;
    t.e = e;
    t.samples = lp.out.samples.n;
    t.sampled = sampled;
    t.u = iso_u(lp.sy, e, lp.st);
    const Hysteretic& h = lp.sy.hyst[static_cast<size_t>(e)];
    const double* slots = lp.st + lp.L.base + h.first;
    t.springs.assign(slots, slots + h.n_springs());
}

// a friction element at the start: moving, it slips; at rest, it sticks unless its tie would need more than
// its friction (then it slips at once, the way the force pushes: an event at the start)
void start_friction(Loop& lp) {
    const System& sy = lp.sy;
    double* st = lp.st;
    for (const int e : sy.ties) {
        const Hysteretic& h = sy.hyst[static_cast<size_t>(e)];
        const double slip = iso_slip_slot(sy, e, st);
        const double u_rate = rel(st + lp.L.v, h.i, h.j);
        if (slip == 0.0 && u_rate != 0.0) iso_transition(sy, st, ACT_SLIP, e, u_rate > 0.0 ? 1.0 : -1.0);
        if (iso_slip_slot(sy, e, st) != 0.0) continue;
        const double d = tie_force(st, sy, e, lp.stk_out, lp.ag_now.data(), lp.b.q.data(), lp.row.data());
        const double way = friction_slip_way(sy, st, e, d);
        if (way == 0.0) continue;
        iso_transition(sy, st, ACT_SLIP, e, way);
        double* r = lp.out.events.push();
        r[EC_T] = st[T];
        r[EC_ACTION] = static_cast<double>(ACT_SLIP);
        r[EC_INDEX] = static_cast<double>(e);
        note_touch(lp, e, false);  // (no sample of its own: the start's)
    }
}

// the run's constants, its energies at the start and its first sample
void set_up(Loop& lp) {
    const System& sy = lp.sy;
    Phase& ph = lp.ph;
    run_constants(ph, sy, lp.fo);
    ph.rtol = lp.opt.rtol;
    ph.evaluations = 0;
    ph.poly_evaluations = 0;
    ph.series_made = 0;
    lp.w.screen.audited = lp.w.screen.escapes = 0;
    lp.z_max.resize(static_cast<size_t>(sy.n_bw()));
    for (int q = 0; q < sy.n_bw(); ++q) {
        const double* bw = sy.bw_of(q).bw;
        lp.z_max[static_cast<size_t>(q)] = std::pow(bw[2] / (bw[3] + bw[4]), 1.0 / bw[5]);
    }
    const double v_res = RESOLUTION * ph.vrun;
    lp.resolution[0] = v_res;
    lp.resolution[1] = RESOLUTION * ph.xrun;
    lp.resolution[2] = sy.total_mass * v_res;
    std::vector<Pair>& pairs = lp.w.event_pairs;  // (each element's pair and each contact's: n_h + nc at most)
    pairs.resize(static_cast<size_t>(sy.n_h() + sy.nc() + 1));
    lp.n_pairs = event_pairs(sy, pairs.data());
    lp.record = lp.fo.kind != EXC_HARMONIC;
    if (sy.has_b)
        for (const Contact& c : sy.contact)
            if (c.law == MULTILINEAR || c.law == MULTILINEAR_KINEMATIC) lp.has_ml = true;
    for (const Contact& c : sy.contact) lp.has_ring = lp.has_ring || c.radial.on;
    for (const Hysteretic& h : sy.hyst) lp.has_circle = lp.has_circle || h.bw_plastic;
    bool levered = false;
    for (int p = 0; p < lp.n_pairs; ++p) levered = levered || pairs[static_cast<size_t>(p)].levered();
    for (const Pair& p : sy.track) levered = levered || p.levered();
    lp.own_samples = lp.opt.own_samples && lp.record && lp.opt.sample_dt <= 0.0 && sy.ties.empty() &&
                     !lp.has_ring && !lp.has_circle && sy.n_bw() == 0 && !levered && sy.n_norm() == 0;
    lp.ag_now.assign(static_cast<size_t>(lp.n), 0.0);
    table_at(lp.fo, sy, lp.st[T], lp.ag_now.data());
    start_friction(lp);
    energies(lp.st, sy, lp.kin0, lp.iso0, lp.bmp0);
    outputs(lp.st, sy, lp.b.q.data(), lp.row.data());
    held_outputs(lp.st, sy, lp.stk_out, lp.ag_now.data(), lp.row.data());
    std::copy(lp.row.begin(), lp.row.end(), lp.out.samples.push());
    for (int i = 0; i < lp.n; ++i)
        track_abs_acceleration(lp.extrema + DOF_EXTREMA * i, lp.t_run0, lp.row[static_cast<size_t>(1 + 2 * lp.n + i)]);
}

// the run control, polled every POLL_EVERY sub-intervals (the work shows as it is done): false to stop
bool poll(Loop& lp) {
    if (lp.work >= lp.next_poll) {
        const int64_t left = lp.control.add_work(lp.work - lp.published);
        lp.published = lp.work;
        if (lp.control.stop()) {
            lp.status = INTERRUPTED;
            return false;
        }
        if (left <= 0) {
            lp.status = BUDGET;
            return false;
        }
        lp.next_poll = lp.work + std::min(POLL_EVERY, left);
    }
    lp.work += 1;
    return true;
}

// the same phase moved on to the state at t: its start values and the forcing's piece pc
void continue_phase(Loop& lp, const Piece& pc, double t) {
    Phase& ph = lp.ph;
    const double* st = lp.st;
    ph.phi = pc.phase;
    for (int q = 0; q < 2 * lp.n; ++q) ph.y0[static_cast<size_t>(q)] = st[lp.L.x + q];
    ph.dp5_h = -1.0;
    for (int c = 0; c < lp.sy.nc(); ++c) ph.ct[static_cast<size_t>(c)].def0 = st[lp.L.def_at(c)];
    if (lp.record) {  // (the record's piece: a0 + a1 tau, a new one at each knot)
        ph.ax0 = pc.a0;
        ph.ax1 = pc.a1;
        ph.bx0 = pc.b0;
        ph.bx1 = pc.b1;
    }
    // the forcing angle where the last sub-interval ended, moved on by the rounding of the clock
    const double wd = pc.omega * ((t - lp.t_last) - lp.h_last);
    ph.sphi = lp.s1 + wd * lp.c1;
    ph.cphi = lp.c1 - wd * lp.s1;
}

// the next sub-interval: the same phase moved on (only the start values and the forcing move), or a new
// phase; its length h, cut at the forcing's next piece, the end and a relaxing law's horizon
void next_subinterval(Loop& lp) {
    Phase& ph = lp.ph;
    const System& sy = lp.sy;
    const double* st = lp.st;
    const double t = lp.t = st[T];
    lp.b.went_on = lp.continuing;
    const Piece pc = lp.pc = excitation_piece(lp.fo, t, lp.j_rec);
    lp.j_rec = pc.j;
    double h;
    if (lp.continuing) {
        continue_phase(lp, pc, t);
        h = lp.h_phase;
    } else {
        set_phase(ph, st, sy, pc);
        lp.phase_id = ++lp.w.transitions.phases;
        screen_phase(lp.w.screen, ph);
        lp.w.screen.audit = lp.opt.audit_screen;
        const double horizon = lp.has_ml ? relax_horizon(st, sy) : INF;
        h = TWO_PI / (SUBINTERVALS_PER_PERIOD * std::max(std::max(ph.rate, pc.omega), 1e-300));
        if (lp.has_ml) lp.t_horizon = t + horizon;
        lp.h_phase = h;
        // a rebound off a rigid stop: a first sub-interval about its flight long (a series of fewer terms,
        // polynomials of lower degree; the phase's own length from the next on)
        if (FLIGHT_MARGIN * lp.h_flight < h) h = FLIGHT_MARGIN * lp.h_flight;
        lp.h_flight = INF;
    }
    lp.t_stop = std::min({pc.t_next, lp.opt.t_end, lp.t_horizon});
    // a record's step, met at its knot by the same phase, longer than the phase's sub-interval: cut in m equal
    // parts, each taking one kept transition (the nominal step's m-th, the same numbers every step), rather than
    // full sub-intervals and a remainder that would take the phase's series; the m-th part ends at the knot.
    // Only a step as the record's times give it (within a few ulps of the clock): another span's parts would
    // each need a transition of their own, dearer than the series they spare
    lp.whole = false;
    if (!lp.continuing || !lp.record) {
        lp.h_split = 0.0;
    } else if (lp.at_knot) {
        lp.h_split = 0.0;
        const double span = pc.t_next - t, step = lp.fo.p[0];
        const bool own_step = step > 0.0 && std::abs(span - step) <= 8.0 * EPS * (std::abs(t) + step);
        if (lp.t_stop == pc.t_next && span > h && own_step) {
            const double m = std::ceil(span / h);
            lp.h_split = step / m;
            lp.parts = lp.parts_left = static_cast<int>(m);
            // (tried at once first, where it would spare two parts or more: advance_to_end takes it where the
            // screen clears it, or goes on with the first part; the screen costs about what a part does)
            lp.whole = lp.opt.whole_steps && lp.opt.screen_extrema && lp.w.screen.on && ph.plain && m >= 3.0 &&
                       span <= h * (SUBINTERVALS_PER_PERIOD / WHOLE_STEPS_PER_PERIOD);
        }
    }
    lp.in_part = lp.h_split > 0.0 && lp.t_stop == pc.t_next && !lp.whole;
    if (lp.whole) {
        lp.to_stop = true;
        h = lp.t_stop - t;
    } else if (lp.in_part) {
        lp.to_stop = lp.parts_left <= 1 || lp.h_split >= lp.t_stop - t;
        h = lp.to_stop ? lp.t_stop - t : lp.h_split;
    } else {
        lp.to_stop = h >= lp.t_stop - t;
        if (lp.to_stop) h = lp.t_stop - t;
    }
    lp.h = h;
}

// the sub-interval's start with the signs its sign tests take (b.y0s): a start at rest moves the way its
// acceleration points, the velocity taken as the smallest of that sign; a friction slip from rest moves the
// way it slips (its force starts at the threshold, where the pair's acceleration is zero but for the
// rounding, whose sign says nothing)
inline void start_signs(Loop& lp) {
    const Phase& ph = lp.ph;
    Buffers& b = lp.b;
    const int n = lp.n;
    for (int q = 0; q < 2 * n; ++q) b.y0s[static_cast<size_t>(q)] = ph.y0[static_cast<size_t>(q)];
    for (int i = 0; i < n; ++i)
        if (b.y0s[static_cast<size_t>(n + i)] == 0.0 && b.a0[static_cast<size_t>(i)] != 0.0)
            b.y0s[static_cast<size_t>(n + i)] = std::copysign(TINY_SPEED, b.a0[static_cast<size_t>(i)]);
    for (const int e : lp.sy.ties) {
        const Hysteretic& hy = lp.sy.hyst[static_cast<size_t>(e)];
        const double s = lp.st[lp.sy.lay.region + e];
        if (s == 0.0 || rel(ph.y0.data() + n, hy.i, hy.j) != 0.0) continue;
        b.y0s[static_cast<size_t>(n + hy.i)] = (hy.j >= 0 ? b.y0s[static_cast<size_t>(n + hy.j)] : 0.0) + s * TINY_SPEED;
    }
}

// whether a record's whole step surely holds no event and no extremum but at its ends (the screen's bounds,
// screen.hpp): then it is taken at once, its rows' values at its end kept
[[gnu::noinline]] bool whole_step_clear(Loop& lp) {
    Phase& ph = lp.ph;
    Buffers& b = lp.b;
    ExtremaScreen& sc = lp.w.screen;
    if (lp.tr == nullptr || !sc.on) return false;
    start_signs(lp);
    sc.shift = std::abs(lp.tr->h - lp.h);
    screen_interval(sc, ph, ph.y0.data(), b.a0.data(), b.y1.data(), lp.h);
    // (the events first: a step they do not clear is the likelier)
    if (!events_surely_absent(lp.w.evs.data(), lp.n_ev, ph, sc, lp.h, b.y0s.data(), b.a0.data(), b.y1.data(),
                              b.a1.data(), lp.w.ev_whole.data()))
        return false;
    const Ends ends{ph.y0.data(), b.a0.data(), b.y1.data(), b.a1.data(), ph.sphi, ph.cphi, 0.0, 1.0};
    if (!extrema_surely_inside(ph, lp.sy, lp.h, ends, lp.extrema, sc)) return false;
    std::copy(lp.w.ev_whole.begin(), lp.w.ev_whole.begin() + 3 * lp.n_ev, lp.w.ev_end.begin());
    return true;
}

// a linear phase's kept transition over the sub-interval (lp.tr; none: its series will be made), and its
// acceleration at the start (b.a0)
void kept_transition(Loop& lp) {
    Phase& ph = lp.ph;
    ph.tc_ok = false;  // (the series: made when first asked for)
    ph.series_h = lp.h;
    // (computed the first time, the same numbers every time: a run's path never depends on what an
    // earlier run kept; a step of the record's as its times give it: k dt rounded, so within a few ulps
    // of the clock)
    const double step = lp.fo.kind != EXC_HARMONIC ? lp.fo.p[0] : 0.0;
    // (a table of two components, or not on every dof alike: no transition, its inputs are one table's)
    if (!ph.plain) lp.tr = nullptr;
    else if (lp.h == lp.h_phase) lp.tr = lp.w.transitions.get(ph, lp.sy, lp.h, lp.phase_id);
    else if (lp.in_part && std::abs(lp.h - lp.h_split) <= (8.0 + lp.parts) * EPS * (std::abs(lp.t) + step))
        lp.tr = lp.w.transitions.get(ph, lp.sy, lp.h_split, lp.phase_id);  // (the last: the clock's drift over the parts)
    else if (step > 0.0 && std::abs(lp.h - step) <= 8.0 * EPS * (std::abs(lp.t) + step))
        lp.tr = lp.w.transitions.get(ph, lp.sy, step, lp.phase_id);
    eom_acceleration(ph, ph.y0.data(), 0.0, ph.sphi, ph.cphi, lp.b.a0.data());
}

// the state and its acceleration at the sub-interval's end h by its kept transition (b.y1, b.a1; b.u for its
// integrals, and which of its entries they take: where n is fixed its constant forces that are not zero (b.nz) and
// its forcing's terms (b.terms), where not its entries that are not zero (b.uc and b.nz); NF: the masses fixed at
// compile time, 0 known at run time only: by_transition's choice)
template <int NF>
void by_transition_of(Loop& lp, bool pattern_known = false) {
    Phase& ph = lp.ph;
    Buffers& b = lp.b;
    const int n = NF > 0 ? NF : lp.n, dim = 3 * n + 4;
    transition_inputs<NF>(ph, b.u.data());
    const double* u = b.u.data();
    // (the entries of u the products here and in the integrals take: where n is fixed, the constant forces that are
    // not zero and the forcing's pair that is not, or both; where not, every entry that is not zero.  pattern_known:
    // where n is fixed, the same as the last call's, which was of the same phase and the same kind of forcing)
    if (!(NF > 0 && pattern_known)) {
        b.n_nz = 0;
        for (int k = NF > 0 ? 2 * n : 0; k < (NF > 0 ? 3 * n : dim); ++k)
            if (u[k] != 0.0) {
                if constexpr (NF == 0) b.uc[static_cast<size_t>(b.n_nz)] = u[k];  // (where n is fixed: read from u)
                b.nz[static_cast<size_t>(b.n_nz++)] = k;
            }
        if constexpr (NF > 0) {
            constexpr int F = 3 * NF;
            b.terms = u[F + 2] == 0.0 && u[F + 3] == 0.0 ? FORCING_LINE
                      : u[F] == 0.0 && u[F + 1] == 0.0   ? FORCING_SINE
                                                         : FORCING_BOTH;
        }
    }
    const InputProducts<NF> in{u, b.uc.data(), b.nz.data(), b.n_nz, dim, b.terms};
    const double* T = lp.tr->T.data();
    for (int q = 0; q < 2 * n; ++q) b.y1[static_cast<size_t>(q)] = in.row(T + q * dim);
    const Angle an = angle_at(ph, lp.pc.omega, lp.h, lp.rot);
    eom_acceleration_of<NF>(ph, b.y1.data(), lp.h, an.s, an.c, b.a1.data());
}

void by_transition(Loop& lp) {
    sized(lp.n, [&](auto N) { by_transition_of<decltype(N)::value>(lp); });
}

// the state at the sub-interval's end: by the phase's kept transition (a full sub-interval, or a record's
// whole step), its series, or a numerical step (a nonlinear phase; false when it failed)
bool advance_to_end(Loop& lp) {
    Phase& ph = lp.ph;
    Buffers& b = lp.b;
    const int n = lp.n;
    lp.tr = nullptr;
    while (!ph.numeric) {  // (once; twice where a whole step is not cleared: its first part then)
        kept_transition(lp);
        if (lp.tr != nullptr) {
            by_transition(lp);
        } else {
            lin_eval(ph, lp.h, b.y1.data(), b.a1.data());
            ph.evaluations -= 1;  // (the end of the sub-interval: not an evaluation inside it)
        }
        if (!lp.whole || whole_step_clear(lp)) return true;
        // (the step in its parts, as without the screen: the first part's end)
        lp.whole = false;
        lp.in_part = true;
        lp.to_stop = lp.parts_left <= 1 || lp.h_split >= lp.t_stop - lp.t;
        lp.h = lp.to_stop ? lp.t_stop - lp.t : lp.h_split;
        lp.tr = nullptr;
    }
    const NumStep ns = numeric_step(ph, lp.h, lp.h_num, lp.opt.rtol, lp.t);
    lp.h = ns.h;
    lp.h_num = ns.h_num;
    if (ns.shortened) lp.to_stop = false;
    if (ns.status != SUCCESS) {
        lp.status = ns.status;
        return false;
    }
    const Dp5 r = dp5_step(ph, lp.h);
    std::copy(r.y, r.y + 2 * n, b.y1.begin());
    std::copy(r.a, r.a + n, b.a1.begin());
    phase_rhs(ph, 0.0, ph.y0.data(), ph.zeta0.data(), b.a0.data());
    return true;
}

// (the audit, for the tests: a whole step taken looked at on 31 inner instants of the phase's series, each event
// row's function there below zero, or a dof's displacement, a tracked pair's or a free dof's absolute
// acceleration beyond the extremes so far and the step's ends, counted in the screen's escapes)
[[gnu::noinline]] void audit_whole_step(Loop& lp) {
    Phase& ph = lp.ph;
    const Buffers& b = lp.b;
    ExtremaScreen& sc = lp.w.screen;
    const int n = lp.n;
    constexpr double ROUNDED = 1e-12;  // (of the values' sizes: the series' own rounding)
    constexpr int INSIDE = 32;
    double* y = ph.ye.data();
    double* a = ph.ae.data();
    for (int k = 1; k < INSIDE; ++k) {
        const double tk = lp.h * k / INSIDE;
        phase_eval(ph, tk, y, a);
        bool escaped = false;
        for (int i = 0; i < lp.n_ev; ++i) {
            const EventValue ev = event_value(lp.w.evs[static_cast<size_t>(i)], ph, tk, y, a);
            escaped = escaped || ev.g < -ROUNDED * ev.scale;
        }
        auto beyond = [&](double v, double lo, double hi, double size) {
            const double tol = ROUNDED * (size + std::abs(v)) + 1e-12 * ph.xround;
            return v > hi + tol || v < lo - tol;
        };
        for (int i = 0; i < n; ++i) {
            const double* ex = lp.extrema + DOF_EXTREMA * i;
            const double x0 = ph.y0[static_cast<size_t>(i)], x1 = b.y1[static_cast<size_t>(i)];
            escaped = escaped || beyond(y[i], std::min({ex[EX_D_MIN], x0, x1}), std::max({ex[EX_D_MAX], x0, x1}),
                                        std::abs(x0) + std::abs(x1));
            if (ph.stk.any && ph.stk.grp[static_cast<size_t>(i)] >= 0) continue;
            const double aa = a[i] + table_on(ph, i, tk);
            const double aa0 = b.a0[static_cast<size_t>(i)] + table_on(ph, i, 0.0);
            const double aa1 = b.a1[static_cast<size_t>(i)] + table_on(ph, i, lp.h);
            const double top = std::max({ex[EX_A_ABS_MAX], std::abs(aa0), std::abs(aa1)});
            escaped = escaped || beyond(aa, -top, top, top);
        }
        for (int p = 0; p < lp.sy.n_track(); ++p) {
            const double* ex = lp.extrema + DOF_EXTREMA * n + PAIR_EXTREMA * p;
            const Pair& pr = lp.sy.track[static_cast<size_t>(p)];
            const double d0 = rel(ph.y0.data(), pr), d1 = rel(b.y1.data(), pr);
            escaped = escaped || beyond(rel(y, pr), std::min({ex[EX_D_MIN], d0, d1}),
                                        std::max({ex[EX_D_MAX], d0, d1}), std::abs(d0) + std::abs(d1));
        }
        sc.audited += 1;
        if (escaped) sc.escapes += 1;
    }
}

// the sub-interval's ends as the event locators and the velocities' zeros read them (no zeros found yet)
void mark_ends(Phase& ph, const Buffers& b, double h) {
    ph.zeros.clear();
    ph.e_y0 = b.y0s.data();
    ph.e_a0 = b.a0.data();
    ph.e_y1 = b.y1.data();
    ph.e_a1 = b.a1.data();
    ph.e_h = h;
}

// the earliest event inside the sub-interval (a velocity's zero cut first), the sub-interval ended there
// (tau), and whether the same phase goes on after it (stopped at a record's knot, not at a relaxing law's
// horizon or the end)
void earliest(Loop& lp) {
    Phase& ph = lp.ph;
    Buffers& b = lp.b;
    const int n = lp.n;
    if (!lp.continuing) lp.n_ev = phase_events(ph, lp.st, lp.sy, lp.w.evs.data());  // (until one fires)
    if (!lp.whole) start_signs(lp);  // (a whole step's: its screen's, whole_step_clear)
    mark_ends(ph, b, lp.h);
    if (lp.whole) {  // (a whole step the screen cleared, advance_to_end: no event inside)
        lp.wholes += 1;
        if (lp.opt.audit_screen) audit_whole_step(lp);
        lp.h_split = 0.0;
        lp.tau = lp.h;
        lp.i_ev = -1;
        lp.turns_at_end = false;
        lp.continuing = lp.record && lp.pc.t_next < std::min(lp.t_horizon, lp.opt.t_end);
        const Angle end_angle = angle_at(ph, lp.pc.omega, lp.tau, lp.rot);
        lp.s1 = end_angle.s;
        lp.c1 = end_angle.c;
        return;
    }
    double cut = velocity_cuts(ph, lp.sy, lp.h, b, lp.w.event_pairs.data(), lp.n_pairs);
    if (lp.has_ring) cut = std::min(cut, ring_cuts(ph, lp.h, b));  // (b's ends at h, as velocity_cuts reads them)
    if (lp.has_circle) cut = std::min(cut, circle_cuts(ph, lp.h, b));
    // (the ends known where no velocity cut came first; the ties' turns at the start kept from the last
    // sub-interval's end where it went the whole way to this one's start, on the same piece of the table)
    const bool turns_kept = lp.turns_at_end && lp.b.went_on && !lp.at_knot;
    lp.turns_at_end = false;
    if (!ph.numeric && !lp.sy.ties.empty()) {
        const double h = cut;
        cut = std::min(cut, force_turn_cut(ph, lp.w.evs.data(), lp.n_ev, cut, cut == lp.h ? &b : nullptr,
                                           lp.w.turns.data(), turns_kept));
        lp.turns_at_end = h == lp.h && cut == lp.h;
    }
    if (cut < lp.h) {
        lp.h = cut;
        lp.to_stop = false;
        eval_end(ph, lp.h, b);
        lp.tr = nullptr;
        ph.e_h = lp.h;
    }
    const Earliest ee = earliest_event(ph, lp.w.evs.data(), lp.n_ev, lp.w.ev_end, lp.continuing, lp.record, lp.h, b);
    lp.tau = ee.tau;
    lp.i_ev = ee.i;
    lp.continuing = lp.i_ev < 0 && !ph.numeric &&
                    (!lp.to_stop || (lp.record && lp.pc.t_next < std::min(lp.t_horizon, lp.opt.t_end)));
    if (lp.i_ev >= 0) {
        lp.to_stop = false;
        if (lp.tau < lp.h) {
            eval_end(ph, lp.tau, b);
            lp.tr = nullptr;
            ph.e_h = lp.tau;
        }
    }
    const Angle end_angle = angle_at(ph, lp.pc.omega, lp.tau, lp.rot);  // the forcing angle at the end
    lp.s1 = end_angle.s;
    lp.c1 = end_angle.c;
}

// a kept transition's integrals over the sub-interval, as forms of its inputs: the dashpots' and the
// forcing's work, and each contact in progress's compression change and its rate's square (NF: the masses
// fixed at compile time, by_transition_of<NF>'s u whole; 0: n at run time, u's entries that are not zero)
template <int NF>
Given transition_integrals_of(Loop& lp) {
    Given given;
    const Transition* tr = lp.tr;
    if (tr == nullptr) return given;
    Buffers& b = lp.b;
    const int n = NF > 0 ? NF : lp.n, dim = tr->dim;
    const double* u = b.u.data();
    const InputProducts<NF> in{u, b.uc.data(), b.nz.data(), b.n_nz, dim, b.terms};
    given.have = true;
    if (lp.opt.with_energy) {
        given.vcv = in.quad(tr->Q.data());
        for (int k = 0; k < 4; ++k) {
            if (u[2 * n + n + k] == 0.0) continue;
            given.gv += u[2 * n + n + k] * in.row(&tr->R[static_cast<size_t>(k * dim)]);
        }
    }
    for (int c = 0; c < lp.sy.nc(); ++c) {
        if (!lp.ph.ct[static_cast<size_t>(c)].in) continue;
        const int p = lp.w.transitions.pair_of[static_cast<size_t>(c)];
        b.du[static_cast<size_t>(c)] = in.row(&tr->L[static_cast<size_t>(p * dim)]);
        b.dvv[static_cast<size_t>(c)] = in.quad(&tr->Qp[static_cast<size_t>(p * dim * dim)]);
    }
    return given;
}

Given transition_integrals(Loop& lp) {
    return sized(lp.n, [&](auto N) { return transition_integrals_of<decltype(N)::value>(lp); });
}

// what the sub-interval adds (energies, extrema, contact statistics, samples), then the state at its end:
// the bumpers, the isolator, the Bouc-Wen z, the dofs and the clock (false: a motion no longer finite)
bool move_to_end(Loop& lp) {
    Phase& ph = lp.ph;
    Buffers& b = lp.b;
    const System& sy = lp.sy;
    double* st = lp.st;
    const Given given = transition_integrals(lp);
    const Ends ends{ph.y0.data(), b.a0.data(), b.y1.data(), b.a1.data(), ph.sphi, ph.cphi, lp.s1, lp.c1};
    // (a kept transition of another length than tau gave y1: the last part of a split step, or a record's step
    // within a few ulps of the clock; the screen widens its margin by how far y1 may be from the motion at tau)
    lp.w.screen.shift = lp.tr != nullptr ? std::abs(lp.tr->h - lp.tau) : 0.0;
    accumulate(ph, sy, st, lp.t, lp.tau, ends, lp.ledger, lp.extrema, b, lp.opt.with_energy, given,
               lp.opt.screen_extrema ? &lp.w.screen : nullptr, lp.whole);
    if (lp.opt.sample_dt > 0.0)
        samples_inside(ph, sy, lp.out.samples, lp.j_next, lp.opt.sample_dt, lp.t_run0, lp.t, lp.tau, lp.opt.t_end,
                       b);
    move_bumpers(st, sy, b.y1.data(), lp.tau, lp.ledger);
    bool finite = true;
    for (int q = 0; q < 2 * lp.n; ++q) finite = finite && std::abs(b.y1[static_cast<size_t>(q)]) <= DBL_MAXV;
    if (!finite) {  // inf or NaN: nothing after it holds
        lp.status = NONFINITE;
        return false;
    }
    lp.ledger[L_HYSTERETIC] += iso_advance(sy, st, ph.y0.data(), b.y1.data());  // (the isolator at the end)
    if (sy.n_bw() > 0) {
        const double* z = phase_zeta(ph, lp.tau, b.y1.data());
        for (int q = 0; q < sy.n_bw(); ++q) {
            const double zm = lp.z_max[static_cast<size_t>(q)];
            const int mate = sy.bw_of(q).bw_mate_slot;
            // (a bidirectional spring's resultant held to its largest, as a line's z: rounding's guard)
            const double size = mate < 0 ? std::abs(z[q]) : std::hypot(z[q], z[mate]);
            st[lp.L.zeta + q] = mate < 0 ? std::min(std::max(z[q], -zm), zm) : size > zm ? z[q] * (zm / size) : z[q];
        }
    }
    for (int q = 0; q < 2 * lp.n; ++q) st[lp.L.x + q] = b.y1[static_cast<size_t>(q)];
    st[T] = lp.to_stop ? lp.t_stop : lp.t + lp.tau;
    lp.at_knot = lp.to_stop && lp.t_stop == lp.pc.t_next;
    // (a part cut short by a velocity's turn: the rest of the step goes as without parts)
    if (lp.in_part) lp.parts_left = lp.tau == lp.h_split || lp.to_stop ? lp.parts_left - 1 : 0;
    if (lp.in_part && lp.parts_left <= 0) lp.h_split = 0.0;
    lp.t_last = lp.t;
    lp.h_last = lp.tau;
    return true;
}

// a stick whose force touched mu W without passing it (to rounding): the slip it began came back to rest
// before any other event, its element moved no more than the rounding of the run's lengths, and it sticks
// again; neither is an event (the slip's row and its sample are taken back; the samples within it show the
// element held), so that a table whose force peaks at mu W leaves no slips of no length
bool touched_mu_w(Loop& lp, int e) {
    const Loop::Touch& t = lp.touch;
    Rows& events = lp.out.events;
    if (t.row < 0 || t.row != events.n - 1 || t.e != e) return false;
    const double u = iso_u(lp.sy, e, lp.st);
    if (std::abs(u - t.u) > ROUNDING * (lp.ph.xround + std::abs(u))) return false;
    events.n -= 1;
    iso_hold_at(lp.sy, e, t.u, lp.st + lp.L.x, lp.st + lp.L.v);
    std::copy(t.springs.begin(), t.springs.end(), lp.st + lp.L.base + lp.sy.hyst[static_cast<size_t>(e)].first);
    Rows& samples = lp.out.samples;
    for (int64_t r = t.samples; r < samples.n; ++r) {
        double* row = samples.row(r);
        iso_hold_at(lp.sy, e, t.u, row + 1, row + 1 + lp.sy.n);
    }
    if (t.sampled && t.samples >= 1 && t.samples <= samples.n) {  // (the slip's own sample out, those after it up)
        for (int64_t r = t.samples; r < samples.n; ++r)
            std::copy(samples.row(r), samples.row(r) + samples.cols, samples.row(r - 1));
        samples.n -= 1;
    }
    return true;
}

// the event at the sub-interval's end: a rigid stop's impact (resolved in closed form), a held stop's release
// or any other jump; its row and sample (false: the run stops, Zeno or at its most events)
bool apply_event(Loop& lp) {
    const System& sy = lp.sy;
    double* st = lp.st;
    const EventRow& ev = lp.w.evs[static_cast<size_t>(lp.i_ev)];
    EventRow taken = ev;  // (its action as taken: a friction slip's end sticks or slips on)
    table_on_dofs(lp.ph, lp.tau, lp.ag_now.data());
    bool resolved = false;  // (a rigid impact that sent the pair apart or held it: no Zeno step)
    bool untouched = true;  // (false: a touch of mu W, taken back)
    if (ev.action == ACT_CONTACT && law_is_rigid(sy.contact[static_cast<size_t>(ev.index)].law)) {
        resolved = rigid_contact(st, sy, lp.ph, lp.tau, lp.stk_out, ev.index, lp.ag_now.data(),
                                 impact_scales(lp.ph, lp.h_phase, lp.resolution[0]), lp.ledger, lp.out.contacts,
                                 lp.out.chatters, lp.b.q.data(), lp.row.data(), lp.h_flight);
    } else if (ev.kind == KIND_HELD) {
        rigid_release(st, sy, ev.index, lp.out.contacts);
    } else if (ev.action == ACT_STICK) {  // a friction slip at rest: it sticks, or slips on (the way it takes)
        const double d = tie_force(st, sy, ev.index, lp.stk_out, lp.ag_now.data(), lp.b.q.data(), lp.row.data());
        taken.action = friction_decision(sy, st, ev.index, d);
        untouched = !(taken.action == ACT_STICK && touched_mu_w(lp, ev.index));
    } else {
        jump(st, sy, ev, lp.out.contacts, lp.resolution);
    }
    if (untouched)
        record_event(st, sy, taken, lp.out.events, lp.out.samples, lp.opt.sample_dt, lp.extrema, lp.b, lp.row,
                     lp.stk_out, lp.ag_now.data());
    if (ev.action == ACT_RING && iso_travel_used(sy, st, iso_element_of_spring(sy, ev.index))) {
        lp.status = CAPACITY;  // (every surface at its ring: the bearing's travel is used up)
        return false;
    }
    if (ev.kind == KIND_STICK)  // (a stick's end: its slip may yet turn out a touch of mu W)
        note_touch(lp, ev.index, lp.opt.sample_dt >= 0.0);
    else
        lp.touch.row = -1;
    // (a rigid impact that resolved its meeting after a short flight is a chatter's, summed in closed form
    // when it accumulates; one at the same instant as the last event is not)
    const double tau = lp.tau, t = lp.t;
    lp.zero_run = tau <= 1e-12 * std::max(1.0, std::abs(t)) && (!resolved || tau == 0.0) ? lp.zero_run + 1 : 0;
    if (lp.zero_run > ZENO_REPEATS) {
        lp.status = ZENO;
        return false;
    }
    if (lp.out.events.n >= lp.opt.max_events) {
        lp.status = MAX_EVENTS;
        return false;
    }
    return true;
}

// the last sample, the chatters still open, the work and the evaluations, the stored energies' changes
void finish_run(Loop& lp) {
    double* st = lp.st;
    double* ledger = lp.ledger;
    // a slip from a stick at the run's very end: where mu W is touched there, it would end at once; the
    // element is left sticking and the slip not recorded (a continued run starts it, should it go on)
    const Loop::Touch& t = lp.touch;
    if (lp.status == SUCCESS && t.row >= 0 && t.row == lp.out.events.n - 1 &&
        lp.out.events.row(t.row)[EC_T] == st[T] && touched_mu_w(lp, t.e))
        iso_transition(lp.sy, st, ACT_STICK, t.e, 0.0);
    table_at(lp.fo, lp.sy, st[T], lp.ag_now.data());
    finish(st, lp.sy, lp.out.samples, lp.out.contacts, lp.b, lp.row, lp.stk_out, lp.ag_now.data());
    close_chatters(st, lp.sy, lp.out.chatters);
    lp.control.add_work(lp.work - lp.published);
    lp.control.at(CTL_EVALS).fetch_add(lp.ph.evaluations, std::memory_order_relaxed);
    lp.control.at(CTL_SERIES).fetch_add(lp.ph.series_made, std::memory_order_relaxed);
    lp.control.at(CTL_AUDITED).fetch_add(lp.w.screen.audited, std::memory_order_relaxed);
    lp.control.at(CTL_ESCAPES).fetch_add(lp.w.screen.escapes, std::memory_order_relaxed);
    lp.control.at(CTL_WHOLE).fetch_add(lp.wholes, std::memory_order_relaxed);
    lp.control.at(CTL_OWN).fetch_add(lp.owns, std::memory_order_relaxed);
    double kin1, iso1, bmp1;
    energies(st, lp.sy, kin1, iso1, bmp1);
    ledger[L_KINETIC] = kin1 - lp.kin0;
    ledger[L_ISOLATOR] = iso1 - lp.iso0;
    ledger[L_BUMPER] = bmp1 - lp.bmp0;
    if (!lp.opt.with_energy)
        for (int j = 0; j < LEDGER_LEN; ++j) ledger[j] = NaN;
    lp.out.status = lp.status;
}

// A record's samples at the record's own step, one after another, each by the step's kept transition, in a run
// that asks for no history, where a sample needs none of the loop's steps' other cases: the same linear phase going
// on from the knot before (the table's one component on every dof, no contact in progress, no hold), the step
// within the phase's sub-interval, no velocity turning back or crossing zero inside, no event row that its values
// at the ends do not clear, no absolute acceleration's rate changing sign.  What the loop's steps would do then
// comes down to the transition's products, the equation of motion at the end, the rows' values there, the
// extrema, the energy integrals and a bumper's relaxing surface: done here by the same functions
// (next_subinterval, advance_to_end, earliest, accumulate and move_to_end for such a sample, without their tests
// for the other cases).  The phase's tests are made once for the samples that follow one another; each sample
// after the first counts as the loop's poll would count it, and the loop polls where its poll is due.  A sample
// that is not such is left to the loop's steps: what this wrote for it, the loop's next_subinterval writes again.
// NF: the masses fixed at compile time (0: at run time)
enum OwnEnd : int {
    OWN_NONE = 0,  // no sample taken: the loop's steps take this one
    OWN_POLL,      // samples taken, up to the loop's poll (due, or the phase or the run ended)
    OWN_REFUSED    // samples taken, then one that is not such: the loop's steps take it (counted, not polled)
};

template <int NF>
OwnEnd own_samples_of(Loop& lp) {
    Phase& ph = lp.ph;
    const System& sy = lp.sy;
    const Layout& L = lp.L;
    Buffers& b = lp.b;
    const int n = NF > 0 ? NF : lp.n;
    double* st = lp.st;
    // (a record of uneven steps, none of them its own; a step far longer than the phase's sub-interval: its
    // parts', or a whole step's)
    const double step = lp.fo.p[0];
    if (!(lp.continuing && lp.at_knot) || ph.numeric || !ph.plain || ph.stk.any || !(step > 0.0) ||
        step > 2.0 * lp.h_phase)
        return OWN_NONE;
    bool relaxing = false;  // (a bumper's surface recovering after its contact)
    for (int c = 0; c < sy.nc(); ++c) {
        if (ph.ct[static_cast<size_t>(c)].in || st[L.in_at(c)] != 0.0) return OWN_NONE;
        relaxing = relaxing || st[L.def_at(c)] > 0.0;
    }
    for (int i = 0; i < lp.n_ev; ++i)
        if (lp.w.evs[static_cast<size_t>(i)].kind != KIND_LINEAR) return OWN_NONE;
    const bool slips = iso_slips(sy, st);  // (an element that moves with the masses: the same while these go on)
    const Transition* at_step = nullptr;  // (the step's kept transition, once found)
    for (int64_t taken = 0;; ++taken) {
        const OwnEnd no = taken > 0 ? OWN_REFUSED : OWN_NONE;
        if (taken > 0) {  // (the loop's poll: its look at the run control where due, else its count)
            if (!(st[T] < lp.opt.t_end) || !lp.continuing || lp.work >= lp.next_poll) return OWN_POLL;
            lp.work += 1;
            if (relaxing) {
                relaxing = false;
                for (int c = 0; c < sy.nc(); ++c) relaxing = relaxing || st[L.def_at(c)] > 0.0;
            }
        }
        // the sample's span: the whole step, to the next knot (next_subinterval's)
        const double t = lp.t = st[T];
        const Piece pc = lp.pc = next_excitation_piece(lp.fo, t, lp.j_rec);
        lp.j_rec = pc.j;
        const double t_stop = std::min({pc.t_next, lp.opt.t_end, lp.t_horizon});
        const double span = pc.t_next - t;
        const bool own_step = std::abs(span - step) <= 8.0 * EPS * (std::abs(t) + step);
        if (!(own_step && t_stop == pc.t_next && span <= lp.h_phase)) return no;
        lp.t_stop = t_stop;
        lp.h = t_stop - t;
        lp.whole = lp.in_part = false;
        lp.h_split = 0.0;
        continue_phase(lp, pc, t);
        // (kept_transition's, for such a sample: the step's, or the phase's sub-interval's where the span is it)
        ph.tc_ok = false;
        ph.series_h = lp.h;
        if (lp.h == lp.h_phase) {
            lp.tr = lp.w.transitions.get(ph, sy, lp.h, lp.phase_id);
            at_step = nullptr;  // (it may have taken the step's place among the kept ones)
        } else {
            if (at_step == nullptr) at_step = lp.w.transitions.get(ph, sy, step, lp.phase_id);
            lp.tr = at_step;
        }
        eom_acceleration_of<NF>(ph, ph.y0.data(), 0.0, ph.sphi, ph.cphi, b.a0.data());
        // (the inputs' pattern: the phase's constant forces, the record's line, as the sample before's)
        by_transition_of<NF>(lp, taken > 0);
        const double h = lp.h;
        for (int q = 0; q < 2 * n; ++q)
            if (!(std::abs(b.y1[static_cast<size_t>(q)]) <= DBL_MAXV)) return no;  // (the loop stops the run)
        // nothing inside (earliest's and accumulate's tests)
        start_signs(lp);
        mark_ends(ph, b, h);
        for (int p = 0; p < lp.n_pairs; ++p) {  // (no velocity cut: velocity_cuts's test)
            const Pair& pr = lp.w.event_pairs[static_cast<size_t>(p)];
            const double v0 = rel(b.y0s.data() + n, pr), v1 = rel(b.y1.data() + n, pr);
            const double a0 = rel(b.a0.data(), pr), a1 = rel(b.a1.data(), pr);
            if (v0 * v1 > 0.0 && a0 * a1 < 0.0 && may_turn_back(h, v0, v1, a0, a1)) return no;
        }
        for (int i = 0; i < n; ++i) {  // (no displacement extremum inside, no absolute acceleration's)
            if (velocity_may_cross(ph, sy.dof_pair[static_cast<size_t>(i)])) return no;
            const double r0 = abs_acc_rate_linear(ph, i, ph.y0.data(), b.a0.data());
            const double r1 = abs_acc_rate_linear(ph, i, b.y1.data(), b.a1.data());
            if (r0 * r1 < 0.0) return no;
        }
        for (const Pair& pr : sy.track)  // (no tracked pair's extremum inside: a storey's drift)
            if (velocity_may_cross(ph, pr)) return no;
        double* ends = lp.w.ev_whole.data();  // (each row's value, rate and scale at the end: ev_end's once taken)
        for (int i = 0; i < lp.n_ev; ++i) {  // (no event: earliest_event's test)
            const EventRow& ev = lp.w.evs[static_cast<size_t>(i)];
            const double* start = &lp.w.ev_end[static_cast<size_t>(3 * i)];
            EventValue e1;
            if (!linear_value<NF>(ev, ph, b.y1.data(), b.a1.data(), e1))
                e1 = event_value(ev, ph, h, b.y1.data(), b.a1.data());  // (a contact's against a relaxing surface)
            if (!(start[0] > ROUNDING * start[2] && e1.g > 0.0 && !(start[1] < 0.0 && e1.gp > 0.0))) return no;
            ends[3 * i] = e1.g;
            ends[3 * i + 1] = e1.gp;
            ends[3 * i + 2] = e1.scale;
        }
        // taken: what the sample adds (accumulate's, for it), the isolator and the state at its end, the loop's
        // own as its steps leave it
        std::copy(ends, ends + 3 * lp.n_ev, lp.w.ev_end.begin());
        if (lp.opt.with_energy) {  // (linear_contributions's, no contact in progress)
            const Given given = transition_integrals(lp);
            lp.ledger[L_INPUT] -= given.gv;
            lp.ledger[L_VISCOUS] += given.vcv;
        }
        lp.w.screen.shift = std::abs(lp.tr->h - h);
        if (lp.opt.screen_extrema && lp.w.screen.on) lp.w.screen.tau = -1.0;
        for (int i = 0; i < n; ++i) {
            double* ex = lp.extrema + DOF_EXTREMA * i;
            track_displacement(ex, t, ph.y0[static_cast<size_t>(i)]);
            track_displacement(ex, t + h, b.y1[static_cast<size_t>(i)]);
            double& kept = b.aa_end[static_cast<size_t>(i)];
            const double aa0 = kept, aa1 = abs_acc_linear(ph, i, b.y1.data());
            kept = aa1;
            track_abs_acceleration(ex, t, aa0);
            track_abs_acceleration(ex, t + h, aa1);
        }
        for (int p = 0; p < sy.n_track(); ++p) {
            double* ex = lp.extrema + DOF_EXTREMA * n + PAIR_EXTREMA * p;
            const Pair& pr = sy.track[static_cast<size_t>(p)];
            track_displacement(ex, t, rel(ph.y0.data(), pr));
            track_displacement(ex, t + h, rel(b.y1.data(), pr));
        }
        if (relaxing) move_bumpers(st, sy, b.y1.data(), h, lp.ledger);  // (none moves otherwise)
        if (slips) lp.ledger[L_HYSTERETIC] += iso_advance(sy, st, ph.y0.data(), b.y1.data());
        for (int q = 0; q < 2 * n; ++q) st[L.x + q] = b.y1[static_cast<size_t>(q)];
        st[T] = t_stop;
        b.went_on = true;
        lp.to_stop = true;
        lp.tau = h;
        lp.i_ev = -1;
        lp.turns_at_end = false;
        lp.continuing = pc.t_next < std::min(lp.t_horizon, lp.opt.t_end);
        const Angle end_angle = angle_at(ph, pc.omega, h, lp.rot);
        lp.s1 = end_angle.s;
        lp.c1 = end_angle.c;
        lp.at_knot = true;
        lp.t_last = t;
        lp.h_last = h;
        lp.owns += 1;
    }
}

OwnEnd take_own_samples(Loop& lp) {
    return sized(lp.n, [&](auto N) { return own_samples_of<decltype(N)::value>(lp); });
}

}  // namespace

void run_kernel(const System& sy, const Forcing& fo, const double* state0, const RunOptions& opt, int64_t* ctl,
                RunResult& out, RunWorkspace* workspace) {
    out.reset(sy);
    out.state.assign(state0, state0 + sy.lay.size);
    double* st = out.state.data();
    for (int j = 0; j < LEDGER_LEN; ++j) out.ledger[j] = 0.0;
    start_extrema(sy, st, st[T], out.extrema.data());
    std::unique_ptr<RunWorkspace> local;  // (a workspace of this run's own only when none is given)
    if (workspace == nullptr) {
        local = std::make_unique<RunWorkspace>();
        workspace = local.get();
    }
    RunWorkspace::Impl& w = *workspace->impl;
    fit_workspace(w, sy);
    Loop lp{sy, fo, opt, out, w, sy.lay, sy.n, st, out.ledger, out.extrema.data(), st[T], w.ph, w.b, w.row,
            Control{ctl}};
    set_up(lp);
    while (st[T] < opt.t_end) {
        if (!poll(lp)) break;
        if (lp.own_samples && take_own_samples(lp) == OWN_POLL) continue;
        next_subinterval(lp);
        if (!advance_to_end(lp)) break;
        earliest(lp);
        if (!move_to_end(lp)) break;
        if (lp.i_ev >= 0 && !apply_event(lp)) break;
    }
    finish_run(lp);
}

}  // namespace pounding
