// The isolator's rate-independent spring, between dofs iso_i and iso_j (or the ground) of deformation
// u = x_i - x_j: a multi-linear backbone with one of two rules.
//   kinematic (rule 0): a spring of the last slope in parallel with n - 1 elastic-perfectly-plastic springs
//     (spring i of stiffness K_i - K_(i+1), slipping when its strain u - u_i reaches +-D_i); state: the slips
//     u_i and slip directions s_i at the layout's base.
//   elastic (rule 1): the force follows the backbone; state: its branch at the layout's region.
#pragma once

#include "core.hpp"

namespace pounding {

constexpr int RULE_KINEMATIC = 0, RULE_ELASTIC = 1;

struct EventRow;  // events.hpp

struct IsoLinear { double k, r0; };  // the force is k u + r0 until the isolator's next event

inline double iso_u(const System& sy, const double* st) { return rel(st + sy.lay.x, sy.iso_i, sy.iso_j); }

IsoLinear iso_linear(const System& sy, const double* st);
double iso_energy(const System& sy, const double* st, double d);
int iso_events(const System& sy, const double* st, EventRow* evs, int n);
double iso_advance(const System& sy, double* st, double d_start, double d_end);
void iso_transition(const System& sy, double* st, int action, int index, double direction);
double backbone_force_at_break(const System& sy, int j);

}  // namespace pounding
