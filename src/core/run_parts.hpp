// The event loop's parts (run.cpp): the excitation at an instant, a phase set up from the state, the
// outputs at an instant and what a sub-interval adds to the run.  Internal to the core.
#pragma once

#include <cstdint>
#include <vector>

#include "core.hpp"
#include "events.hpp"
#include "phase.hpp"
#include "screen.hpp"

namespace pounding::run_parts {

// ---------------------------------------------------------------- the excitation (run_setup.cpp)

// the table's acceleration from the instant t it was taken at, up to t_next: a0 + a1 s + amp sin(omega s +
// phase), s the time since t (j: the record's sample there); its second component's b0 + b1 s + bs sin(omega s
// + phase) + bc cos(omega s + phase)
struct Piece {
    double a0, a1, amp, omega, phase, t_next;
    int64_t j;
    double b0 = 0.0, b1 = 0.0, bs = 0.0, bc = 0.0;
};

// a record's piece j at t (rt[j] <= t < rt[j + 1]): its line a0 + a1 (t' - t) and its end
inline Piece record_piece(const Forcing& fo, double t, int64_t j) {
    const double* rt = fo.rec_t;
    const double* ra = fo.rec_a;
    const double slope = (ra[j + 1] - ra[j]) / (rt[j + 1] - rt[j]);
    Piece pc{ra[j] + slope * (t - rt[j]), slope, 0.0, 0.0, 0.0, rt[j + 1], j};
    if (fo.rec_b != nullptr) {
        const double* rb = fo.rec_b;
        pc.b1 = (rb[j + 1] - rb[j]) / (rt[j + 1] - rt[j]);
        pc.b0 = rb[j] + pc.b1 * (t - rt[j]);
    }
    return pc;
}
// the forcing's piece at t (a record's: found from the piece j_hint; a harmonic's: its angle there)
Piece excitation_piece(const Forcing& fo, double t, int64_t j_hint);
// excitation_piece's where t is most likely in the piece after j_hint (a record's next sample): that one inline
inline Piece next_excitation_piece(const Forcing& fo, double t, int64_t j_hint) {
    if (fo.kind != EXC_HARMONIC && j_hint >= 0 && j_hint + 2 < fo.n_rec && fo.rec_t[j_hint + 1] <= t &&
        t < fo.rec_t[j_hint + 2])
        return record_piece(fo, t, j_hint + 1);
    return excitation_piece(fo, t, j_hint);
}

// the table's acceleration on each dof at t, outside a phase, into ag (n)
void table_at(const Forcing& fo, const System& sy, double t, double* ag);

// the run's length (m) and velocity (m/s) scales: the system's and the excitation's, not the start's
void run_scales(const System& sy, const Forcing& fo, double& x, double& xw);

// ---------------------------------------------------------------- a phase (run_setup.cpp)

// the phase of motion the state is in: its matrices, contacts in force, forcing and rate bound
void set_phase(Phase& ph, const double* st, const System& sy, const Piece& pc);

// what every phase of a run shares: the scales, masses, contacts' constants
void run_constants(Phase& ph, const System& sy, const Forcing& fo);

struct NumStep { int status; double h, h_num; bool shortened; };

// one accepted step of the embedded method of a numerical phase (at most h; h_num: its own step)
NumStep numeric_step(Phase& ph, double h, double h_num, double rtol, double t);

// the event functions of the phase the state is in; their number
int phase_events(const Phase& ph, const double* st, const System& sy, EventRow* evs);

// the pairs whose relative displacement events are functions of: the isolator's and the contacts'
int event_pairs(const System& sy, Pair* pairs);

// ---------------------------------------------------------------- the run's buffers

struct Buffers {
    std::vector<double> y0s, y1, a0, a1, ym, am, du, dvv, u;
    std::vector<int> nz;    // (u's entries that are not zero, its constant forces' only where n is fixed at compile
                            // time: the products with a kept transition skip the rest, by_transition_of)
    std::vector<double> uc; // (and their values, where n is known at run time only)
    int n_nz = 0;
    int terms = 0;          // (where n is fixed at compile time: the forcing's entries of u they take, run.cpp's
                            // ForcingTerms)
    // each free dof's absolute acceleration at the last linear sub-interval's end, and whether this
    // sub-interval goes on from that one in the same phase (its start the same state)
    std::vector<double> aa_end;
    bool went_on = false;
    std::vector<double> q;  // internal forces
    void size(int n, int nc) {
        y0s.assign(static_cast<size_t>(2 * n), 0.0);
        y1.assign(static_cast<size_t>(2 * n), 0.0);
        ym.assign(static_cast<size_t>(2 * n), 0.0);
        a0.assign(static_cast<size_t>(n), 0.0);
        a1.assign(static_cast<size_t>(n), 0.0);
        am.assign(static_cast<size_t>(n), 0.0);
        q.assign(static_cast<size_t>(n), 0.0);
        u.assign(static_cast<size_t>(3 * n + 4), 0.0);
        nz.assign(static_cast<size_t>(3 * n + 4), 0);
        uc.assign(static_cast<size_t>(3 * n + 4), 0.0);
        aa_end.assign(static_cast<size_t>(n), 0.0);
        du.assign(static_cast<size_t>(std::max(nc, 1)), 0.0);
        dvv.assign(static_cast<size_t>(std::max(nc, 1)), 0.0);
    }
};


// ---------------------------------------------------------------- outputs (accumulate.cpp)

// the isolator's force on its pair (k u + r0 + c_d u' + the Bouc-Wen spring's)
double iso_force(const System& sy, int e, const double* st);

// a sample row (or the absolute accelerations and forces q) from the state, outside a phase
void outputs(const double* st, const System& sy, double* q, double* row);

// a sample row inside a phase, at tau after its start (t: the run's time), from y and its accelerations a
void outputs_in_phase(Phase& ph, const System& sy, double t, double tau, const double* y, const double* a,
                      double* row);

// the kinetic, isolator (with the structure's springs) and bumper energies of the state
void energies(const double* st, const System& sy, double& kin, double& iso, double& bmp);

// an extremum record (ex: x max, its time, x min, its time, |a_abs| max, its time, a_abs there)
void track_abs_acceleration(double* ex, double t, double a);
void track_displacement(double* ex, double t, double d);

// dof i's absolute acceleration in a linear phase, -(K x + C v + R0)_i / m_i, and its rate -(K v + C a)_i / m_i
inline double abs_acc_linear(const Phase& ph, int i, const double* y) {
    const int n = ph.n;
    const double* rk = &ph.K[static_cast<size_t>(i * n)];
    const double* rc = &ph.C[static_cast<size_t>(i * n)];
    double q = ph.R0[static_cast<size_t>(i)];
    for (int j = 0; j < n; ++j) q += rk[j] * y[j] + rc[j] * y[n + j];
    return -ph.minv[static_cast<size_t>(i)] * q;
}

inline double abs_acc_rate_linear(const Phase& ph, int i, const double* y, const double* a) {
    const int n = ph.n;
    const double* rk = &ph.K[static_cast<size_t>(i * n)];
    const double* rc = &ph.C[static_cast<size_t>(i * n)];
    double q = 0.0;
    for (int j = 0; j < n; ++j) q += rk[j] * y[n + j] + rc[j] * a[j];
    return -ph.minv[static_cast<size_t>(i)] * q;
}

// ---------------------------------------------------------------- what a sub-interval adds (accumulate.cpp)

// a sub-interval's ends: states, accelerations, the forcing angle's sine and cosine
struct Ends { const double *y0, *a0, *y1, *a1; double s0, c0, s1, c1; };

// a linear sub-interval's integrals when the transition gave them (else the Hermite rule does)
struct Given { bool have = false; double vcv = 0.0, gv = 0.0; };

// the energy integrals, contact statistics and extrema of the sub-interval [t0, t0 + tau] of the phase
// (screen: the phase's screen of its extrema, screen.hpp; nullptr for none)
// whether no extremum accumulate looks for can lie inside [0, tau] but at its ends, beyond any doubt (the
// screen's bound, screen.hpp; sc's interval made here): a record's whole step taken at once (run.cpp)
bool extrema_surely_inside(const Phase& ph, const System& sy, double tau, const Ends& e, const double* extrema,
                           ExtremaScreen& sc);
void accumulate(Phase& ph, const System& sy, double* st, double t0, double tau, const Ends& e, double* ledger,
                double* extrema, Buffers& b, bool with_energy, const Given& given, ExtremaScreen* screen,
                bool ends_only = false);

// ---------------------------------------------------------------- the state at an event (jump.cpp)

// the bumpers at the end of a sub-interval of length tau: one in contact follows its pair (y1), one out of
// contact relaxes, its loss added to the ledger
void move_bumpers(double* st, const System& sy, const double* y1, double tau, double* ledger);

// the state across an event (resolution: the run's velocity, depth and impulse below which a touch is none)
void jump(double* st, const System& sy, const EventRow& ev, Rows& contacts, const double* resolution);

// an event's row, and the sample just after it (its extrema tracked)
void record_event(double* st, const System& sy, const EventRow& ev, Rows& events, Rows& samples, double sample_dt,
                  double* extrema, Buffers& b, std::vector<double>& row, Sticking& stk, const double* ag);

// the end of a run: its last sample, and a row for each contact still going on
void finish(const double* st, const System& sy, Rows& samples, Rows& contacts, Buffers& b, std::vector<double>& row,
            Sticking& stk, const double* ag);

}  // namespace pounding::run_parts
