// Contact laws: what the engine asks of a bumper's law, by law id.  This header and laws.cpp are the one
// place where a law's kind is tested; each law's Python dataclass (pounding/model/contact_laws/<law>.py) gives
// its LAW_ID and lays out its parameters p[0..N_LAW_PARAMS) and the block of its state z[0..N_LAW_STATE).
//
// Compression d (m, >= 0), its rate dd (m/s).  A law is "linear" when its force is k d + r + c dd on each
// branch (the phase stays a linear ODE); the others are integrated numerically in contact.
#pragma once

#include "core.hpp"

namespace pounding {

enum LawId : int {
    KELVIN_VOIGT = 0, HUNT_CROSSLEY = 1, JANKOWSKI = 2, MULTILINEAR = 3, ELASTIC_PLASTIC = 4, HERTZDAMP = 5,
    MULTILINEAR_KINEMATIC = 6, RIGID = 7
};

constexpr double BRANCH_TIE = 1e-9;  // relative: a compression this close to a breakpoint is at it
constexpr double EDGE_UP_STATE = -1.0;    // an event row's code for a branch's upper and lower edges
constexpr double EDGE_DOWN_STATE = -2.0;

struct Branch { double k, c, r; int j; };       // F = k d + r + c dd on branch j
struct Force { double f, elastic, df_dd, df_ddd; };  // force, its spring part, its partial derivatives
struct Relaxed { double d, rate; };             // a free recovery's compression and its rate
struct Edges { double lower, upper; };          // -1: none

bool law_is_linear(int law);
// a rigid stop (p[0]: the coefficient of restitution): no compression, an impulse at each impact (Newton's
// law), held shut while the motion pushes into it (sticking.hpp); its force in phases is none of the law's
bool law_is_rigid(int law);
inline double law_restitution(const double* p) { return p[0]; }
bool law_has_memory(int law);
bool law_switches_at_rest(int law);
void law_contact_state(int law, const double* p, double rate, double* z, double d);
void law_release_state(int law, const double* p, double* z, double d);
void law_moved(int law, const double* p, double* z, double d, bool in_contact);
Branch law_linear_branch(int law, const double* p, double d, double dd, const double* z);
Edges law_branch_edges(int law, const double* p, int j, const double* z);
double law_branch_loss(int law, const double* p, int j, double d0, double d1, const double* z);
double law_turn_sign(int law, const double* p, const double* z);
void law_after_event(int law, const double* p, double* z, double d, double code);
Force law_force(int law, const double* p, double d, double dd, const double* z);
double law_energy(int law, const double* p, double d, const double* z);
Relaxed law_relax(int law, const double* p, double d0, double tau, const double* z);
double law_relax_horizon(int law, const double* p, double d0, const double* z);
// (value, rate) of a smooth function that crosses zero downwards where the force would turn into a pull
Relaxed law_release(int law, const double* p, double d, double dd, double ddd, const double* z);
// the force along a path of compressions from the unloaded state (a hysteretic law follows it)
void law_force_many(int law, const double* p, const double* d, const double* dd, double* out, int64_t n);

// ---- a law's memory as coordinates of the exact monodromy (monodromy.cpp)
// The numbers a law's state carries from one branch or contact to the next that its force depends on: an
// elastic-plastic bumper's plastic offset (1), a kinematic multi-linear bumper's springs' slips (one per
// breakpoint; a hardening one's unused).  On each branch the force is linear in them and they move with the
// compression or not, so the motion stays a linear mode in the coordinates with them.
constexpr int MAX_LAW_MEMORY = 3;
// In contact: the branch of the state z at compression d and rate dd, F = k d + r + c dd + sum_i g[i] m[i],
// m[i]' = follow[i] d'.  Out of contact (a free recovery, c > 0): the piece it falls on, d' = -(k d + r +
// sum_i g[i] m[i]) / c, m[i]' = follow[i] d', down to lower (-1: none reached), lower's derivative in m[i]
// dlower[i]; at zero compression with a force that would push it further (a kinematic bumper's springs set
// below zero), forgets: a small compression is back at zero at once (c zero).
struct MemoryBranch {
    double k, c, r, lower;
    int j;
    bool forgets;
    double g[MAX_LAW_MEMORY], follow[MAX_LAW_MEMORY], dlower[MAX_LAW_MEMORY];
};
int law_memory_size(int law, const double* p);
// m from z at compression d (the elastic-plastic offset where the branch puts it), and back into z
void law_memory_read(int law, const double* p, const double* z, double d, double* m);
void law_memory_write(int law, const double* p, double* z, const double* m);
MemoryBranch law_memory_branch(int law, const double* p, double d, double dd, const double* z, bool in_contact);
// the derivative in m[i] of branch j's upper (or lower) edge (law_branch_edges) into out[i]
void law_edge_memory(int law, const double* p, int j, const double* z, bool upper, double* out);
// whether the law forgets its memory when the contact ends (its memory then zero)
bool law_forgets_on_release(int law);

}  // namespace pounding
