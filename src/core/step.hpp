// One frequency step of a stepped-sine sweep: cycles until steady (or a fixed number), then the last ones
// measured; and the per-impact measurements (the paper's Sect. 3.5) the step sums over its window.
#pragma once

#include <vector>

#include "core.hpp"
#include "run.hpp"

namespace pounding {

// impact_row's columns
constexpr int N_IMPACT = 7;  // restitution, contact_time_s, impulse, mean force, peak force, E_d, bumper's
constexpr int S_COUNT = 0, S_N_RESTITUTION = 1, S_SUMS = 2, SIDE_SUMS = S_SUMS + N_IMPACT;
void impact_row(const double* contact, double mass, double* out);
void add_impacts(const Rows& contacts, double mass, double* sums);

// the per-cycle record and the window: the first dof's extrema, the first two slots' impact sums, and the
// events the run located (every one; and the sticks of its friction isolators)
constexpr int CY_DMAX = 0, CY_DMIN = 1, CY_AMAX = 2, CY_SUMS = 3, CY_EVENTS = CY_SUMS + 2 * SIDE_SUMS,
              CY_STICKS = CY_EVENTS + 1, CYCLE_COLS = CY_STICKS + 1;
constexpr int W_DMAX = 0, W_DMIN = 1, W_AMAX = 2, W_CYCLES = 3, W_SUMS = 4, W_EVENTS = W_SUMS + 2 * SIDE_SUMS,
              W_STICKS = W_EVENTS + 1, WINDOW_COLS = W_STICKS + 1;

struct Steady { bool adaptive; int n_cycles; int measure_cycles; double steady_rtol; int max_period; };

struct StepResult {
    std::vector<double> state;
    int cycles_run = 0, period_multiple = 0;
    std::vector<double> window;        // WINDOW_COLS
    std::vector<double> window_state;  // the state at the window's start
    std::vector<double> strobes;       // (m, 2): the first dof's x and v at each of the window's cycle ends
    int status = SUCCESS;
};

void step_kernel(const System& sy, double amp, double omega, const double* state0, const Steady& steady, double rtol,
                 int64_t max_events, int64_t* ctl, StepResult& out);

// the smallest period multiple k with which the last cycles repeat, and the window m (for tests: the strobes
// (n, strobe_cols) and the cycles' records (n, CYCLE_COLS))
void periodicity(const double* strobe, int strobe_cols, const double* cyc, int n, int window, int max_period,
                 double steady_rtol, double omega, bool round_window, int n_dof, int& k, int& m);

}  // namespace pounding
