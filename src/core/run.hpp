// The event-driven run: a system under a forcing from a state to an end time, every non-smooth instant
// located on the exact trajectory.  What a run returns: the final state, the history samples, the contacts,
// the events, the energy ledger, the exact extrema and how it ended.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "core.hpp"

namespace pounding {

struct RunOptions {
    double t_end = 0.0;
    double sample_dt = 0.0;   // the history's step (0: events only; < 0: not even those)
    double rtol = 1e-10;      // of the numerical integration of nonlinear phases
    int64_t max_events = 10000000;
    bool with_energy = true;  // the energy ledger outside contacts (a sweep's steps need only the contacts')
    // a record's extrema inside a sub-interval screened from its ends (screen.hpp: the same numbers; false
    // finds every one, for the tests that show it)
    bool screen_extrema = true;
    // (the tests': each extremum the screen clears found all the same and held against its bound, the counts in
    // the run control's CTL_AUDITED and CTL_ESCAPES)
    bool audit_screen = false;
    // a record's step whose parts the screen clears of every event and extremum taken at once, by one kept
    // transition (run.cpp; false: in its parts, as the screen alone would)
    bool whole_steps = true;
    // a record's samples at its own step taken one after another by the step's kept transition, in a run without
    // history, where nothing in a sample needs the loop's other cases (run.cpp's own_samples_of: the same numbers;
    // false: every sample by the loop's steps, for the tests that show it)
    bool own_samples = true;
};

struct RunResult {
    std::vector<double> state;
    Rows samples{1, 256};     // (t, x (n), v (n), absolute accelerations (n), isolator force, contact forces)
    Rows contacts{CONTACT_COLS, 16};
    Rows events{EVENT_COLS, 64};
    // rigid stops' chatter sequences: contact, first impact's time, the accumulation's (or the last impact's),
    // the impacts followed one by one, 1 when the sequence accumulated (the stop then held)
    Rows chatters{5, 4};
    double ledger[LEDGER_LEN] = {0};
    // per dof: x max, its time, x min, its time, |a_abs| max, its time, a_abs there; then per tracked pair:
    // its relative displacement's max, its time, min, its time
    std::vector<double> extrema;
    int status = SUCCESS;
    void reset(const System& sy) {  // (a result reused run after run keeps its buffers)
        samples.cols = sy.lay.sample_cols();
        samples.clear();
        contacts.clear();
        events.clear();
        chatters.clear();
        extrema.assign(static_cast<size_t>(sy.norm_extrema_at() + NORM_EXTREMA * sy.n_norm()), 0.0);
        status = SUCCESS;
    }
};

// a run's buffers and the transitions it computed, kept for the next run of the same system (a sweep's
// cycles): one per thread
class RunWorkspace {
  public:
    RunWorkspace();
    ~RunWorkspace();
    struct Impl;
    std::unique_ptr<Impl> impl;
};

void run_kernel(const System& sy, const Forcing& fo, const double* state0, const RunOptions& opt, int64_t* ctl,
                RunResult& out, RunWorkspace* workspace = nullptr);

// the held rigid stops' forces and their rates in time in the state st under fo, as a phase's held-release
// events take them (events.cpp's held_force): per held contact (contact, N, N/s) into out, 3 each (for the
// tests: a rate against the force's differences along a run)
void held_force_probe(const System& sy, const Forcing& fo, const double* st, std::vector<double>& out);

}  // namespace pounding
