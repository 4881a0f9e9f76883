// A certified screen of a sub-interval's extrema, from its ends alone.
//
// A dof's displacement (or a pair's, or an absolute acceleration) is extreme inside a sub-interval where its
// rate is zero; finding it exactly takes the phase's series and a root.  Most of those extrema, in a record's
// long run, are smaller than the largest the run has already met: they change nothing.  The screen proves it
// without the series, and only the extrema it cannot clear are found as before (run.cpp, accumulate.cpp), so
// the results are the same numbers.
//
// On a linear phase whose table is a line over the sub-interval (a record's piece), y' = A y + b0 + b1 t, and
// z = y'' = (a, a') obeys z' = A z exactly, A = [[0, I], [P(-M^-1 K), P(-M^-1 C)]] (P: the held stops'
// projection, a mass-weighted mean within a group or zero, never larger than its largest entry).  In the norm
// ||(p, q)||_s = max(s max|p_i|, max|q_i|),
//     ||A w||_s <= alpha ||w||_s,  alpha = max(s, max_i (kr_i / s + cr_i)),   the q rows' part: beta = max_i (...)
// (kr_i = sum_j |K_ij| / m_i, cr_i = sum_j |C_ij| / m_i), so ||z(t)||_s <= e^(alpha t) ||z(0)||_s = Z over the
// sub-interval.  A function f with its values and rates at the two ends differs from their cubic Hermite
// interpolant by at most h^4 / 384 max |f''''| inside; for a dof's displacement f'''' = a_i'' (at most beta Z),
// for its absolute acceleration -(M^-1 (K a'' + C a'''))_i (at most (kr_i + cr_i alpha) beta Z).  The cubic's
// range on [0, h] is found in closed form; with that bound and a margin far above the rounding of the series'
// own extremum, an extremum whose range stays inside the largest so far is passed over.  Where the end is the
// motion at tau give or take a shift (a kept transition of a length a few ulps of the clock off: a step's last
// part), the bounds are narrowed by how far the shift moves the end's value and rate (accumulate.cpp).
#pragma once

#include <vector>

#include "core.hpp"
#include "phase.hpp"

namespace pounding {

struct ExtremaScreen {
    bool on = false;             // the phase linear, its table a line over each sub-interval (a record's)
    double s = 0.0;              // the norm's weight of an acceleration against a jerk, 1/s
    double alpha = 0.0;          // ||A||_s, 1/s
    double beta = 0.0;           // the bound of A's acceleration rows, 1/s
    std::vector<double> kr, cr;  // per dof: sum_j |K_ij| / m_i, 1/s^2; sum_j |C_ij| / m_i, 1/s
    std::vector<double> jerk;    // (scratch, n)
    // the sub-interval's (made when first asked for): its length, Z (m/s^3), and the ends' largest |x| and
    // |v| with the run's scales (the series' rounding is relative to them)
    double tau = -1.0, z = 0.0, xscale = 0.0, vscale = 0.0;
    // |tau - the length y1 is the motion at| (a kept transition's of another length: the last of a step's
    // parts, or a record's step, within a few ulps of the clock), set by the loop for each sub-interval
    double shift = 0.0;
    // the audit (RunOptions::audit_screen): each extremum the screen clears is found all the same, and counted
    // where it falls outside the range the bound gives
    bool audit = false;
    int64_t audited = 0, escapes = 0;
};

// the phase's rates (a phase that is not linear, or whose table is not a line, is not screened)
void screen_phase(ExtremaScreen& sc, const Phase& ph);

// the sub-interval [0, tau]'s Z and scales, from its ends (y0, a0 at 0; y1 at tau)
void screen_interval(ExtremaScreen& sc, const Phase& ph, const double* y0, const double* a0, const double* y1,
                     double tau);

// the range on [0, h] of the cubic Hermite interpolant of f's values f0, f1 and rates d0, d1 at the ends,
// widened by the bound h^4 / 384 f4 on f's distance from it (|f''''| at most f4): f's own range; and the size
// of the terms
struct Range { double lo, hi, size; };
Range hermite_range(double f0, double d0, double f1, double d1, double h, double f4);

// (the audit, for the tests: an extremum the screen cleared, found all the same, counted in escapes when it
// lies outside the widened range r by more than off and the rounding, of the values and of scale)
void audit_value(ExtremaScreen& sc, const Range& r, double off, double scale, double value);

// whether f surely stays within [lo, hi] on [0, h]: its values f0, f1 and rates d0, d1 at the ends, |f''''| at
// most f4 inside, rounding relative to scale
bool surely_within(double f0, double d0, double f1, double d1, double h, double f4, double lo, double hi,
                   double scale);
// the same from the range (hermite_range's, over an h > 0 and a finite f4)
bool surely_within(const Range& r, double lo, double hi, double scale);

}  // namespace pounding
