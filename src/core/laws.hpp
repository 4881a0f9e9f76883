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

}  // namespace pounding
