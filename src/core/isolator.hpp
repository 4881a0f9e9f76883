// A hysteretic element's rate-independent spring (core.hpp's Hysteretic: the isolator is element 0), between
// dofs i and j (or the ground) of deformation u = x_i - x_j: a multi-linear backbone with one of two rules.
//   kinematic (rule 0): a spring of the last slope in parallel with n - 1 elastic-perfectly-plastic springs
//     (spring i of stiffness K_i - K_(i+1), slipping when its strain u - u_i reaches +-D_i); state: the slips
//     u_i and slip directions s_i at the layout's base, from the element's first spring on.
//   elastic (rule 1): the force follows the backbone; state: its branch at the layout's region + e.
// Events: a yield's index is the spring's among the system's; a branch change's and a reversal's the element's.
#pragma once

#include "core.hpp"

namespace pounding {

constexpr int RULE_KINEMATIC = 0, RULE_ELASTIC = 1;

struct EventRow;  // events.hpp

struct IsoLinear { double k, r0; };  // the force is k u + r0 until the element's next event

inline double iso_u(const System& sy, int e, const double* st) {
    return rel(st + sy.lay.x, sy.hyst[static_cast<size_t>(e)].i, sy.hyst[static_cast<size_t>(e)].j);
}

IsoLinear iso_linear(const System& sy, int e, const double* st);
double iso_energy(const System& sy, int e, const double* st, double d);
// every element's event rows after the n already in evs; the new count
int iso_events(const System& sy, const double* st, EventRow* evs, int n);
// the slipping springs moved with their elements from x_start to x_end (displacements, n): the work they did
double iso_advance(const System& sy, double* st, const double* x_start, const double* x_end);
void iso_transition(const System& sy, double* st, int action, int index, double direction);

// The exact monodromy's view of an element (monodromy.cpp).  Its force as linear in u and its slips:
// F = k u + r + sum_s d_slip[s] slip_s, with follows[s] 1 where spring s slips (its slip moves with u), 0 where it
// sticks (both of length n_springs).
IsoLinear iso_linear_in_slips(const System& sy, int e, const double* st, double* d_slip, double* follows);
// An element event's guard, linear in the state: g = du u + dv u' - (slip >= 0 ? slip_slip : 0), slip the
// system's index of the spring whose slip enters it; e the element; dir the direction iso_transition takes (v and
// acc: the dofs' velocities and accelerations at the event, n each)
struct IsoGuard { int e; double du, dv; int slip; double dir; };
IsoGuard iso_guard(const System& sy, int action, int index, const double* st, const double* v, const double* acc);
double backbone_force_at_break(const Hysteretic& h, int j);

}  // namespace pounding
