#pragma once

#include "core.hpp"

namespace pounding {

// peaks out[3 j..3 j + 3) = (max |u|, max |u'|, max |a_abs|) of oscillator omegas[j] (rad/s), damping ratio zeta
// (0 <= zeta < 1), at rest at t[0] under the record acc (m/s^2, linear between the samples t) up to t[n - 1];
// polls the stop flag once per oscillator and counts the intervals against the budget
int spectrum_kernel(const double* t, const double* acc, int64_t n, const double* omegas, int64_t n_omega, double zeta,
                    double* out, int64_t* ctl);

// peaks out[j n_angle + q] = max over time of |cos_a[q] u_x + sin_a[q] u_y| of oscillator omegas[j] (rad/s,
// damping ratio zeta) under the two components ax and ay of one ground motion (m/s^2, on the samples t): each
// direction's response exact, its peaks between samples found as spectrum_kernel's; polls once per oscillator
int spectrum_pair_kernel(const double* t, const double* ax, const double* ay, int64_t n, const double* omegas,
                         int64_t n_omega, double zeta, const double* cos_a, const double* sin_a, int64_t n_angle,
                         double* out, int64_t* ctl);

}  // namespace pounding
