// A linear phase's transition over a full sub-interval, computed once per phase and sub-interval length.
//
// Over a sub-interval of length h of a linear phase the motion is linear in its inputs
//     u = (y0, M^-1 R0, ax0, ax1, axh cos(phi), axh sin(phi))     (2n + n + 4 numbers)
// (the start, the restoring force's constant part, the table acceleration's piece and its sine's phase),
// y(h) = T u, with T fixed by the phase's stiffness, damping, h and w.  The same holds for the integrals the
// run accumulates: int v^T C_lin v = u^T Q u, int a_g (m . v) = (ax0, ax1, axh cos, axh sin) R u, and per
// contact pair int (x_i - x_j) = L u, int (v_i - v_j)^2 = u^T Qp u.  T, Q, R, L and Qp are computed from the
// series of each input's unit response (Gauss-Legendre with 12 nodes for the integrals: exact to rounding
// for a sub-interval of at most pi / 4 of every rate) and kept for the last phases met: a sub-interval that
// goes the whole length h then costs a few products, its sines and exponentials none.
#pragma once

#include <vector>

#include "core.hpp"
#include "phase.hpp"

namespace pounding {

struct Transition {
    std::vector<int> grp, grounded;  // the held stops' groups it was made with
    std::vector<int> held;  // (general mode's holds: their constraints, sticking.hpp)
    std::vector<double> K, C;  // the key: the phase's stiffness and damping, h, w and the run's scales (the
    double h = -1.0, w = 0.0;  // series' truncation is relative to them: a transition is a function of its key)
    double xrun = 0.0, vrun = 0.0;
    int dim = 0;               // of u: 3 n + 4
    std::vector<double> T;     // (2n, dim)
    std::vector<double> Q;     // (dim, dim)
    std::vector<double> R;     // (4, dim)
    std::vector<double> L, Qp; // per pair: (dim) and (dim, dim)
    int uses = 0;
    uint64_t made = 0;         // (its stamp: which computation filled it)
};

struct TransitionCache {
    std::vector<Transition> entries;
    int next = 0;
    std::vector<Pair> pairs;  // the contacts' distinct pairs (their integrals' rows)
    std::vector<int> pair_of; // each contact slot's pair
    std::vector<double> scratch;
    // the last two found for a phase (its run's phase count: the same phase, its key unchanged), so that a phase
    // going on finds its own without comparing its matrices
    struct Recent {
        uint64_t phase = 0, made = 0;
        double h = -1.0;
        int idx = -1;
    };
    Recent recent[2];
    uint64_t made = 0, phases = 0;
    void setup(const System& sy);
    // the phase's transition over h, computed now if it is not kept (phase: a count that is the same while
    // the phase's stiffness, damping and holds are, and new at each phase set up: TransitionCache::phases)
    const Transition* get(const Phase& ph, const System& sy, double h, uint64_t phase);
};

// u of the current sub-interval (3 n + 4 values) into out (NF: n fixed at compile time, 0 ph.n at run time)
template <int NF = 0>
inline void transition_inputs(const Phase& ph, double* out) {
    const int n = NF > 0 ? NF : ph.n, ny = 2 * n;
    const double* y0 = ph.y0.data();
    const double* minv = ph.minv.data();
    const double* R0 = ph.R0.data();
    for (int q = 0; q < ny; ++q) out[q] = y0[q];
    for (int i = 0; i < n; ++i) out[ny + i] = minv[i] * R0[i];
    out[ny + n] = ph.ax0;
    out[ny + n + 1] = ph.ax1;
    out[ny + n + 2] = ph.axh * ph.cphi;
    out[ny + n + 3] = ph.axh * ph.sphi;
}

}  // namespace pounding
