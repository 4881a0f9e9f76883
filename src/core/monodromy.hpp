// The exact monodromy of a periodic orbit: the oscillator as a hybrid system of linear modes.
//
// For systems whose every phase is linear (a multi-linear isolator, elastic or kinematic; Kelvin-Voigt bumpers)
// the motion between two events obeys x' = A_m x + b(t) with A_m constant in the mode m.  With the forcing as
// two more states (sin, cos of its angle) and a constant 1 the augmented system is homogeneous and
// X(t) = expm(A~ t) X(0) exactly; at an event with guard g(x) = 0 the perturbations jump by the saltation
// matrix S = I + (f_m' - f_m) grad(g)^T / (grad(g) . f_m).
// Coordinates x: D, V, the bumpers' compressions, the kinematic isolator's slips.
#pragma once

#include <vector>

#include "linalg.hpp"

namespace pounding {

struct Hybrid {
    double mass = 1.0, c_d = 0.0;
    std::vector<double> slopes, breaks;
    bool kinematic = true;
    double gaps[2] = {0, 0}, stiffness[2] = {0, 0}, damping[2] = {0, 0};
};

// the Jacobian (n, n) of the map from x0 at t0 to x at t_end along the events (rows of t, action, index), x at
// t_end, and the row of an event met tangentially (no saltation matrix), or -1
int monodromy(const Hybrid& h, const std::vector<double>& x0, bool in_l, bool in_r, std::vector<double> iso,
              const double* events, int n_events, double t0, double t_end, double omega, double amp, double phase,
              Mat& jac, std::vector<double>& x_end);

}  // namespace pounding
