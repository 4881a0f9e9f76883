// The exact monodromy of a periodic orbit: a system of n dofs as a hybrid system of linear modes.
//
// For systems whose every phase is linear (multi-linear hysteretic elements, elastic or kinematic, without a
// Bouc-Wen spring; friction of a constant coefficient, a single surface or surfaces in series; contact laws with
// one linear branch, Kelvin-Voigt) the motion between two events obeys
// x' = A_m x + b(t) with A_m constant in the mode m (which contacts touch, which springs slip, which backbone
// branch holds).  With the harmonic forcing as two more states (sin, cos of its angle) and a constant 1 the
// augmented system is homogeneous and X(t) = expm(A~ t) X(0) exactly; at an event with guard g(x) = 0 the
// perturbations jump by the saltation matrix S = I + (f_m' - f_m) grad(g)^T / (grad(g) . f_m).
// Coordinates x: the displacements (n), the velocities (n), the contacts' compressions (nc), the elements'
// slips (n_sp; a series's: its surfaces' displacements, the slipping ones put where the force puts them after
// every event): for one mass with its two bumpers, x_0, v_0, delta_wall0_left, delta_wall0_right, u_i.  A start
// where friction ties hold (no rigid stop held) forgets a perturbation of a tied pair's relative velocity.
#pragma once

#include <vector>

#include "core.hpp"
#include "linalg.hpp"

namespace pounding {

// the length of x for the system
inline int monodromy_size(const System& sy) { return 2 * sy.n + sy.nc() + sy.n_springs(); }

// The Jacobian (size, size) of the map from x at the state vector st0 (its time and mode) to x at t_end along
// the events (rows of t, action, index) under the table acceleration amp sin(omega t + phase), and x at t_end.
// Returns -1, or the row of an event met tangentially (no saltation matrix), or -2 - row for an event of a
// kind that has no linear modes (a contact law's branch, a Bouc-Wen spring).
int monodromy(const System& sy, const double* st0, const double* events, int n_events, double t_end, double omega,
              double amp, double phase, Mat& jac, std::vector<double>& x_end);

}  // namespace pounding
