// A phase's events and their location on the exact trajectory.
//
// An event is a function of the trajectory that fires when it crosses zero downwards: the isolator's yields,
// reversals and branch edges, a contact's start (against the bumper's relaxing surface) and release (the
// force would pull), a law's branch edges and turns, the Bouc-Wen z back through zero.  Most are linear in
// the relative motion of a pair (Pair: dofs i, j, on levers w . x), alpha + beta (x_i - x_j) + gamma (v_i - v_j); a contact start
// adds the relaxing compression, a release is the law's own function.  In a linear phase each is a polynomial
// of the sub-interval's series (plus the relaxation), and its root is found on it.
#pragma once

#include "core.hpp"
#include "phase.hpp"
#include "screen.hpp"

namespace pounding {

// (held: a rigid stop's force; stick: alpha + beta D, D the force a sticking friction element's tie needs)
// (radial: alpha + beta x + gamma x' in a ring's compression x, contact side's: its start, its end, its law's
// branch edges and turns; always evaluated on the trajectory, its function not a polynomial of the series)
// (circle: a plastic circle's switch, side its first z slot: inside, 1 - |z|^2; slipping, z . u')
constexpr int KIND_LINEAR = 0, KIND_RELEASE = 1, KIND_ZETA = 2, KIND_HELD = 3, KIND_STICK = 4, KIND_RADIAL = 5,
              KIND_CIRCLE = 6;
// an event row's side when it is no contact's: SIDE_NONE (rounded against its own terms), SIDE_VELOCITY (a
// velocity rounded against the run's velocity too: a friction slip's end, which starts at rest)
constexpr int SIDE_NONE = -1, SIDE_VELOCITY = -2;
constexpr double ROUNDING = 256.0 * EPS;  // relative size of rounding noise in event values
constexpr double XTOL_S = 1e-15;          // event instants and displacement extrema, s
constexpr double TINY_SPEED = 1e-300;     // the velocity of a start at rest, for the direction it moves, m/s
constexpr double XTOL_EXTREMUM_S = 1e-10; // instants of the other extrema

struct EventRow : Pair {  // (its pair)
    int kind = KIND_LINEAR;
    double alpha = 0.0, beta = 0.0, gamma = 0.0;
    int side = SIDE_NONE;   // the contact whose relaxing surface or release it is (rounding against lengths)
    int action = 0;
    int index = 0;
    double dir = 0.0;
};

struct EventValue { double g, gp, scale; };  // value, rate, size of the terms summed

EventValue event_value_of(const EventRow& e, Phase& ph, double tau, const double* y, const double* a);
// a linear row's value, rate and scale (y, a: the trajectory there) into v: its pair's alpha + beta dx + gamma dv,
// false for a contact's start against its bumper's relaxing surface (event_value_of's: law_relax's); NF: the
// masses fixed at compile time (0: at run time)
template <int NF = 0>
inline bool linear_value(const EventRow& e, const Phase& ph, const double* y, const double* a, EventValue& v) {
    const int n = NF > 0 ? NF : ph.n;
    const double dx = rel(y, e), dv = rel(y + n, e), da = rel(a, e);
    const double g = e.alpha + e.beta * dx + e.gamma * dv;
    const double gp = e.beta * dv + e.gamma * da;
    const double scale = std::abs(e.alpha) + std::abs(e.beta * dx) + std::abs(e.gamma * dv);
    if (e.side == SIDE_NONE) {  // the isolator's events (most of them)
        v = {g, gp, scale};
        return true;
    }
    if (e.side == SIDE_VELOCITY) {
        v = {g, gp, scale + ph.vround};
        return true;
    }
    // a contact's displacement is rounded relative to the run's and the phase's lengths, not its own size
    if (e.action != ACT_CONTACT || !(ph.ct[static_cast<size_t>(e.side)].def0 > 0.0)) {
        v = {g, gp, scale + ph.xround};
        return true;
    }
    return false;
}
// a row's value, rate and scale at tau (y, a: the trajectory there).  A linear row (most rows of most
// sub-intervals) is linear_value's, inline, but a contact's start against its bumper's relaxing surface; every
// other row is event_value_of's
inline EventValue event_value(const EventRow& e, Phase& ph, double tau, const double* y, const double* a) {
    if (e.kind != KIND_LINEAR) return event_value_of(e, ph, tau, y, a);
    EventValue v;
    if (linear_value(e, ph, y, a, v)) return v;
    return event_value_of(e, ph, tau, y, a);
}

// a stick's event value from its tie's held force d (held_force: a tie's two thresholds share it)
EventValue stick_value(const EventRow& e, const EventValue& d);

// a held bond c's force (N: a rigid stop's, or a sticking friction element's tie's, sticking.hpp), its rate
// (N/s) and the size of its terms at tau (y, a: the trajectory there, a with the held bonds' constraint)
EventValue held_force(Phase& ph, int c, double tau, const double* y, const double* a);

// a held bond c's force's rate (N/s) and its second derivative (N/s^2) at tau of a linear phase, each with the
// size of its terms, from the trajectory there (y, a: a with the held bonds' constraint): the equation of motion
// differentiated, no series (force_turn_cut's screen)
struct ForceTurn { double rate, bend, rate_scale, bend_scale; };
ForceTurn held_force_turn(Phase& ph, int c, double tau, const double* y, const double* a);

// A scalar function of tau on the current sub-interval, whose roots the loop looks for: a polynomial of
// the series (a linear phase; with a contact's relaxation added for a contact start), or a function of the
// numerical trajectory
enum FnKind : int {
    FN_POLY = 0,       // q(tau)
    FN_POLY_RELAX,     // q(tau) + the relaxing compression of contact `idx`
    FN_EVENT,          // numerical: event `idx`'s value (rate: its rate)
    FN_EVENT_RATE,     // numerical: event `idx`'s rate (no derivative)
    FN_PAIR_V,         // numerical: v_i - v_j (rate: a_i - a_j)
    FN_PAIR_A,         // numerical: a_i - a_j (no derivative)
    FN_AABS_RATE,      // numerical: dof idx's absolute acceleration's rate (no derivative)
    FN_FORCE_RATE,     // numerical: contact idx's force rate (no derivative)
    FN_NORM_RATE,      // u . u' of the vector u = at + (u_p, u_q) of its two pairs (rate: |u'|^2 + u . u'')
    FN_NORM_BEND,      // that rate (no derivative)
    FN_COMPRESSION_RATE,  // numerical: contact idx's compression's rate (rate: its second derivative)
    FN_COMPRESSION_BEND,  // that second derivative (no derivative)
    FN_CIRCLE_RATE,    // numerical: |z|^2's rate of plastic circle idx (its first z slot; rate: its bend)
    FN_CIRCLE_BEND     // that bend (no derivative)
};
struct Fn {
    int kind = FN_POLY;
    int idx = 0;
    // FN_PAIR_V, FN_PAIR_A: its pair; FN_NORM_*: its two (pointers: a root finder's function is made often,
    // and they outlive it)
    const Pair* pair = nullptr;
    const Pair* second = nullptr;
    const EventRow* evs = nullptr;
    double at[2] = {0.0, 0.0};  // FN_NORM_*: the vector's offset
    Poly q;
};
// f and its rate at tau (fp NaN where the kind has none)
void fn_eval(const Fn& fn, Phase& ph, double tau, double& f, double& fp);

// the root of fn in [xa, xb] where it changes sign (fa, fb; ra, rb its rates there or NaN): Halley's method
// on a polynomial, Newton's on a function with a rate, both kept in the bracket; Brent's method otherwise.
// Stops when the next step would be below xtol.
double find_root(const Fn& fn, Phase& ph, double xa, double xb, double fa, double fb, double ra, double rb,
                 double xtol);
double root_guess(double fa, double fb, double sa, double sb);
inline double value_at_root(double root, double x, double value, double f, double fp) {
    const double dt = root - x;
    return value + dt * (f + 0.5 * dt * fp);
}

// the scalar function of event i in this phase
void event_fn(const EventRow* evs, int i, Phase& ph, Fn& fn);
// its earliest instant in (0, h] (or 0, or -1 for none) from its values at the ends
double locate_event(const EventRow* evs, int i, Phase& ph, double h, double g0, double gp0, double tol0, double g1,
                    double gp1, double tol1, double xtol);

// may a velocity, of one sign at both ends with accelerations of opposite signs, turn back inside?
bool may_turn_back(double h, double v0, double v1, double a0, double a1);
// a plastic circle inside (core.hpp's bw_plastic; z slot q, its first), |z|^2's rate and bend at tau (y, a: the
// trajectory there): 2 z . u' / u_y and 2 (|u'|^2 / u_y + z . u'') / u_y
void circle_turn(Phase& ph, int q, double tau, const double* y, const double* a, double& rate, double& bend);
// whether a pair's relative velocity may cross zero inside the sub-interval (velocity_zeros looks
// for its zeros only then): of opposite signs at its ends, or turning back inside
inline bool velocity_may_cross(const Phase& ph, const Pair& pr) {
    const int n = ph.n;
    const double h = ph.e_h;
    const double v0 = rel(ph.e_y0 + n, pr), v1 = rel(ph.e_y1 + n, pr);
    const double a0 = rel(ph.e_a0, pr), a1 = rel(ph.e_a1, pr);
    return h > 0.0 && (v0 * v1 < 0.0 || (v0 * v1 > 0.0 && a0 * a1 < 0.0 && may_turn_back(h, v0, v1, a0, a1)));
}
// the instants in (0, e_h) where the relative velocity of a pair crosses zero (0, 1, or 2 where it
// turns back inside) and the relative displacement there, from the sub-interval's ends; kept for the
// sub-interval (a shorter end asked later reads the same zeros below it)
const Phase::Zeros& velocity_zeros(Phase& ph, const Pair& pr);

// whether no event can fire in (0, h] (a record's whole step taken at once, run.cpp), beyond any doubt: each
// row's function, linear in the motion (a pair's alpha + beta dx + gamma dv, or a stick's held force), stays
// above its rounding on the screen's bound (sc: its interval [0, h] made, screen.hpp; y1, a1 the motion at h
// give or take sc.shift); a row of another kind, or a contact's relaxing surface, is not cleared.  ends: each
// row's value, rate and scale at h (3 a row), written as it goes
bool events_surely_absent(const EventRow* evs, int n_ev, Phase& ph, const ExtremaScreen& sc, double h,
                          const double* y0, const double* a0, const double* y1, const double* a1, double* ends);

// the contacts' event rows: appended from row n on, the new count returned
int bumper_events(const double* st, const Phase& ph, const System& sy, EventRow* evs, int n);
bool law_switches(const Phase& ph);
double relax_horizon(const double* st, const System& sy);

}  // namespace pounding
