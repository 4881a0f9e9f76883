// A hysteretic element's rate-independent spring (core.hpp's Hysteretic: the isolator is element 0), between
// dofs i and j (or the ground) of deformation u = x_i - x_j (w . x on levers): a multi-linear backbone with one
// of two rules.
//   kinematic (rule 0): a spring of the last slope in parallel with n - 1 elastic-perfectly-plastic springs
//     (spring i of stiffness K_i - K_(i+1), slipping when its strain u - u_i reaches +-D_i); state: the slips
//     u_i and slip directions s_i at the layout's base, from the element's first spring on.
//   elastic (rule 1): the force follows the backbone; state: its branch at the layout's region + e.
//   Coulomb friction (rule 2): a spring of its one slope k in parallel with a friction force F (Hysteretic's
//     friction, N) that sticks rigidly: while it slips, k u + s F with s the slip's direction (the sign of u');
//     while it sticks, its pair is tied (sticking.hpp: a bond, nc + e) and the force is k u plus the friction
//     the tie needs, D.  State: s at region + e (0 sticking).  A slip ends where u' = 0: there the run decides
//     (friction_decision) to stick, when |D| <= F, or to slip the other way; a stick ends where |D| reaches F.
//     Every phase is linear.  (F = mu W and k = W / R: a friction pendulum; k = 0: a flat slider.)
//     With a velocity dependence (friction_rate > 0) a slip's force is k u + s (F_fast - (F_fast - F)
//     e^(-rate |u'|)): its linear phase holds s F_fast, and the rest (iso_rate_force) makes the slip's phases
//     numerical; a stick and its end, and the decision where a slip ends, are F's (the friction at rest).  The
//     same dependence on the kinematic rule of one break (a sliding bearing's elastic pre-slip, F its yield
//     force): while its spring slips the way s the rest is s (F_fast - F) (1 - e^(-rate |u'|)).
//   Surfaces in series (Hysteretic::series(): the series model of a triple friction pendulum, Fenz and
//     Constantinou 2008): surface g a spring of stiffness k_g (slopes[g]) in parallel with its friction F_g
//     (surface_friction[g]), the surfaces one after another without mass between them, each carrying the
//     element's force F; u = sum of their displacements u_g.  A surface slips where F reaches k_g u_g +- F_g
//     and stays held otherwise; one that slips the way s reaches its ring at u_g = s d_g (breaks[g]) and is
//     held there (rigid) until F comes back to k_g s d_g - s F_g.  A stiff ring (surface_ring[g] = k_r > 0)
//     instead adds k_r (|u_g| - d_g) to the surface's spring beyond its travel: the surface slides on against it,
//     stiffer, and comes off it where u_g comes back to its travel (ACT_RING_OFF).  While the element slips the
//     way s with the set S of surfaces slipping, each u_g = (F - s F_g + c_g) / K_g (K_g = k_g, c_g = 0 within its
//     travel; K_g = k_g + k_r, c_g = k_r d_g sign(u_g) on a stiff ring), so F = (u - sum_{g not in S} u_g + sum_S
//     (s F_g - c_g) / K_g) / sum_S (1 / K_g): linear in u.  Its events: a held surface's threshold or a slipping
//     one's ring (each at a value of u: ACT_SURFACE_SLIP, ACT_RING, ACT_RING_OFF), the slip at rest (as one
//     surface's), and while the whole element sticks the tie's force D (all of F) reaching the lowest threshold
//     up or the highest down.  A slip whose every surface reaches its rigid ring has used up the bearing's
//     travel: the run stops (CAPACITY).  State: s at region + e; each surface's u_g and state (0 held, s slipping
//     the way s, 2 s held at its rigid ring, 3 s slipping on its stiff ring) at the springs' slots (core.hpp).
// Events: a yield's index is the spring's among the system's; a branch change's, a reversal's, a stick's and a
// slip's the element's; a surface's slip or ring the spring's (its surface's) among the system's.
#pragma once

#include <algorithm>
#include <cmath>

#include "core.hpp"

namespace pounding {

constexpr int RULE_KINEMATIC = 0, RULE_ELASTIC = 1, RULE_FRICTION = 2;

struct EventRow;  // events.hpp

struct IsoLinear { double k, r0; };  // the force is k u + r0 until the element's next event

inline double iso_u(const System& sy, int e, const double* st) {
    return rel(st + sy.lay.x, sy.hyst[static_cast<size_t>(e)]);
}

// the displacements x and velocities v (n each) with element e held at u, its pair's relative velocity none:
// where a touch of a friction threshold was taken back (it moved by rounding), the state and the samples within
inline void iso_hold_at(const System& sy, int e, double u, double* x, double* v) {
    const Hysteretic& h = sy.hyst[static_cast<size_t>(e)];
    x[h.i] = u + (h.j >= 0 ? x[h.j] : 0.0);
    v[h.i] = h.j >= 0 ? v[h.j] : 0.0;
}

IsoLinear iso_linear(const System& sy, int e, const double* st);
// the element whose springs hold the system's spring (or series surface) index
int iso_element_of_spring(const System& sy, int index);
// a friction element's slip direction in the state (+-1; 0 sticking): its slot, for e a friction element
inline double& iso_slip_slot(const System& sy, int e, double* st) { return st[sy.lay.region + e]; }
// element e's friction slip direction (+-1; 0 sticking, or not a friction element)
inline double iso_slip(const System& sy, int e, const double* st) {
    return iso_is_friction(sy.hyst[static_cast<size_t>(e)]) ? st[sy.lay.region + e] : 0.0;
}
// the way element e's velocity-dependent friction slips in the state (+-1; 0 sticking, or none): the friction
// rule's, or a pre-slip's (the kinematic rule of one break with friction_rate: a sliding bearing's elastic
// pre-slip, its spring's slip direction)
inline double iso_rate_slip(const System& sy, int e, const double* st) {
    const Hysteretic& h = sy.hyst[static_cast<size_t>(e)];
    if (h.rule == RULE_FRICTION) return st[sy.lay.region + e];
    if (h.friction_rate == 0.0 || h.rule != RULE_KINEMATIC || h.has_bw() || h.n_springs() != 1) return 0.0;
    return st[sy.lay.base + sy.lay.n_sp + h.first];
}
// element e's force beyond its linear branch's while it slips the way s at the rate du (u'): a
// velocity-dependent friction's -s (F_fast - F) e^(-rate s du) on the friction rule (its branch holds s F_fast),
// s (F_fast - F) (1 - e^(-rate s du)) on a pre-slip's (its branch holds its yield force, s F); 0 for every other
// element and state
inline double iso_rate_force(const Hysteretic& h, double s, double du) {
    if (s == 0.0 || h.friction_rate == 0.0) return 0.0;
    if (h.rule == RULE_FRICTION) return -s * (h.friction_fast - h.friction) * std::exp(-h.friction_rate * s * du);
    return s * (h.friction_fast - h.friction) * (1.0 - std::exp(-h.friction_rate * s * du));
}
// whether element e slipping the way s has that rest (a numerical phase): a velocity dependence whose fast
// friction is not its friction at rest
inline bool iso_rate_dependent(const Hysteretic& h, double s) {
    return s != 0.0 && h.friction_rate != 0.0 && h.friction_fast != h.friction;
}
// A friction circle's velocity dependence (a bidirectional Bouc-Wen spring's, the friction circle of a sliding
// bearing in plan, with friction_rate > 0): its force is bw[0] z times (F_fast - (F_fast - F) e^(-rate s)) / F,
// F = bw[0] (mu W at rest) and F_fast = friction_fast, at the slip's rate s (m/s): z . u' (both mates') while
// a plastic circle slips, none while it sticks inside (its force bw[0] z exactly: its phases stay linear), |u'|
// on Bouc-Wen's smooth circle (Constantinou's, 3D-BASIS's and SAP2000's).  The factor f and df / ds.
struct CircleScale { double f, df; };
inline CircleScale circle_scale(const Hysteretic& h, double s) {
    if (h.friction_rate == 0.0) return {1.0, 0.0};
    const double r = h.friction_fast / h.bw[0], e = std::exp(-h.friction_rate * s);
    return {r - (r - 1.0) * e, h.friction_rate * (r - 1.0) * e};
}
// the slip's rate it reads: u' (du, dm) and z (zq, zm) the two mates', slipping a plastic circle's state (its
// z . u' at least 0: a slip turned inwards by an impulse is at rest until its stick is found)
inline double circle_speed(const Hysteretic& h, bool slipping, double du, double dm, double zq, double zm) {
    return h.bw_plastic ? (slipping ? std::max(zq * du + zm * dm, 0.0) : 0.0) : std::hypot(du, dm);
}
// the factor on element e's Bouc-Wen force in the state st (outside a phase): 1 without a velocity dependence
// or inside a plastic circle
inline double circle_factor(const System& sy, int e, const double* st) {
    const Hysteretic& h = sy.hyst[static_cast<size_t>(e)];
    if (h.friction_rate == 0.0 || !h.has_bw() || h.bw_mate < 0) return 1.0;
    const Layout& L = sy.lay;
    const Hysteretic& m = sy.hyst[static_cast<size_t>(h.bw_mate)];
    const bool slipping = st[L.region + std::min(e, h.bw_mate)] != 0.0;  // (the circle's first element's flag)
    if (h.bw_plastic && !slipping) return 1.0;
    const double s = circle_speed(h, slipping, rel(st + L.v, h), rel(st + L.v, m), st[L.zeta + h.bw_slot],
                                  st[L.zeta + m.bw_slot]);
    return circle_scale(h, s).f;
}
// its rate at the acceleration ddu (u''): (F_fast - F) rate e^(-rate s du) ddu (either rule's)
inline double iso_rate_force_rate(const Hysteretic& h, double s, double du, double ddu) {
    if (s == 0.0 || h.friction_rate == 0.0) return 0.0;
    return (h.friction_fast - h.friction) * h.friction_rate * std::exp(-h.friction_rate * s * du) * ddu;
}
double iso_energy(const System& sy, int e, const double* st, double d);
// every element's event rows after the n already in evs; the new count
int iso_events(const System& sy, const double* st, EventRow* evs, int n);
// the slipping springs moved with their elements from x_start to x_end (displacements, n): the work they did
double iso_advance(const System& sy, double* st, const double* x_start, const double* x_end);
// whether iso_advance has an element to move in st (a spring that slips, a friction element or a series of
// surfaces that slips): where none, it does no work and leaves st as it is
bool iso_slips(const System& sy, const double* st);
void iso_transition(const System& sy, double* st, int action, int index, double direction);
// a friction element's slip that has come to rest (u' = 0), given the force D its tie would need there (N): it
// sticks (|D| <= F: its pair's relative velocity set to zero) or slips on, the way D pushes; the action taken
// (ACT_STICK, or ACT_REVERSAL / ACT_SLIP when it slips back / on)
int friction_decision(const System& sy, double* st, int e, double tie_force);
// the way a friction element held at rest slips under its tie's force D (N): 0 if it holds (D within its
// thresholds: +-F, a series's lowest up and highest down), else +-1
double friction_slip_way(const System& sy, const double* st, int e, double tie_force);
// the way a held friction element slips where its tie's force is at one of its thresholds: the nearer one's
double friction_threshold_way(const System& sy, const double* st, int e, double tie_force);
// a series whose slip the way of its state has every surface at its ring (its travel used up)
bool iso_travel_used(const System& sy, const double* st, int e);

// The exact monodromy's view of an element (monodromy.cpp).  Its force as linear in u and its slips:
// F = k u + r + sum_s d_slip[s] slip_s, with follows[s] 1 where spring s slips (its slip moves with u), 0 where it
// sticks (both of length n_springs).  A series of friction surfaces: its slips are the surfaces' displacements,
// each slipping one following the force (follows[g] = k / K_g), each held one in it (d_slip -k); held, none.
IsoLinear iso_linear_in_slips(const System& sy, int e, const double* st, double* d_slip, double* follows);
// An element event's guard, linear in the state: g = du u + dv u' - (slip >= 0 ? slip_slip : 0), slip the
// system's index of the spring whose slip enters it; e the element; dir the direction iso_transition takes (v and
// acc: the dofs' velocities and accelerations at the event, n each)
struct IsoGuard { int e; double du, dv; int slip; double dir; };
IsoGuard iso_guard(const System& sy, int action, int index, const double* st, const double* v, const double* acc);
// A series's event (a surface's slip, a ring's entry or exit; index: the surface's spring among the system's) as a
// guard linear in u and the element's surfaces: g = du u + sum_g d_surface[g] u_g (the series' force less the force
// where it happens; d_surface of length n_springs), dir the way it slips
IsoGuard series_guard(const System& sy, int action, int index, const double* st, double* d_surface);
double backbone_force_at_break(const Hysteretic& h, int j);

}  // namespace pounding
