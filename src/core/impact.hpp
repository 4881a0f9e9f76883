// A rigid stop's events (laws.hpp law_is_rigid): Newton's impact, a chatter's accumulation, sticking and its
// release.  Internal to the core (run.cpp calls it at a rigid stop's contact and release events).
//
// At an impact the pair's normal velocity vn (the compression rate) reverses to -e vn by an impulse between
// the two sides, each side a free dof, a group of dofs held together (its mass) or the ground and what is
// held to it (immovable).  Chatter: while the motion pushes the stop shut (acceleration A > 0 after the
// impact), the rebounds shrink geometrically, e each time: flights 2 u e^k / A from a rebound speed u, which
// accumulate at t + 2 u / (A (1 - e)) (to first order; accumulation() in impact.cpp sums the pair's local
// model, the push with its rates in time and its change with the opening and its speed, to rounding).  Impacts
// are followed one by one until that remainder is short against the phase's time scales or the rebound's
// height u^2 / (2 A) is below the run's length resolution; the remainder is then taken at once (the relative
// velocity brought to rest, its kinetic energy lost) and the stop is held (sticking.hpp) until its force would
// pull.
#pragma once

#include "core.hpp"
#include "phase.hpp"
#include "sticking.hpp"

namespace pounding::run_parts {

constexpr int CHATTER_COLS = 5;  // contact, t first impact, t end (accumulation or last impact), impacts, accumulated

struct ImpactScales {
    double v_res;      // m/s: a slower meeting has no impulse
    double h_min;      // m: a rebound below this height is no flight
    double local_s;    // s: a remainder this short is summed in closed form
    double window_s;   // s: impacts this close follow one another in one sequence
};

// contact c (a rigid stop) met at st[T], tau into the phase ph that led to it (ag: the table's acceleration
// then); true when the impact resolved the meeting (a rebound, the stop held, or the motion leaving it),
// false when nothing moved apart
// (flight: the rebound's flight time to first order, 2 u / A, or INF; the next sub-interval need not be longer)
bool rigid_contact(double* st, const System& sy, const Phase& ph, double tau, Sticking& stk, int c, const double* ag,
                   const ImpactScales& sc, double* ledger, Rows& contacts, Rows& chatters, double* q, double* row,
                   double& flight);
// after a velocity jump: a hysteretic element's slipping springs and a deformable bumper's law's turns follow the
// new velocities (their reversal events watch a velocity crossing zero, which a jump steps over)
void after_velocity_jump(double* st, const System& sy);
// a held rigid stop c released at st[T]: the hold's row
void rigid_release(double* st, const System& sy, int c, Rows& contacts);
// the chatter sequences still open at the end of a run (three impacts or more)
void close_chatters(const double* st, const System& sy, Rows& chatters);
// a sample row from outputs() corrected for the held stops: their dofs' absolute accelerations and their forces
void held_outputs(const double* st, const System& sy, Sticking& stk, const double* ag, double* row);

// the force friction element e's tie would need in the state, were it sticking (N: isolator.hpp's D; stk and
// row are scratch)
double tie_force(double* st, const System& sy, int e, Sticking& stk, const double* ag, double* q, double* row);

}  // namespace pounding::run_parts
