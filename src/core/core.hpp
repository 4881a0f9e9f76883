// The compiled core of pounding: plain structures in (a system, a forcing, options), arrays out.
//
// Everything here is C++17 on the standard library and Eigen's headers (linalg.hpp); the only door into it
// from Python is the module pounding._pounding_core (bindings.cpp), which pounding/_core.py wraps.
// Validation stays in Python: the core trusts its inputs.
//
// A system has n degrees of freedom (masses, displacements relative to the ground, which the table moves),
// a linear part (springs and dashpots between them), hysteretic elements (each a multi-linear spring with its
// dashpot between a dof and the ground or another dof: the isolator is element 0) and contact slots, each a pair (a dof against the ground or another dof) with a
// gap and a law.  Elements and contacts are indexed blocks of the state vector; a one-mass system is n = 1.
//
// The state vector (doubles), by Layout:
//   T time s | x + i displacements m | v + i velocities m/s | def + c compressions | in + c in contact (1.0)
//   region + e element e's backbone branch (elastic rule) or its slip (friction rule: -1, 0 sticking, +1)
//   | acc + N_ACC c a contact's running totals
//   z + N_LAW_STATE c a contact law's state | zeta + b the Bouc-Wen z of spring b (one slot when there is none)
//   | base + g slips of every element's springs
//   (element e's from its first), then base + n_sp + g their slip directions (a series of friction surfaces:
//   each surface's displacement, then its state: +-1 slipping, 0 held, +-2 held at its ring on that side)
// For n = 1 and two contact slots that is Python's long-standing layout (T 0, D 1, V 2, ..., STATE_BASE 37).
#pragma once

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <new>
#include <utility>
#include <limits>
#include <vector>

namespace pounding {

constexpr int N_LAW_PARAMS = 10;
constexpr int N_LAW_STATE = 7;
constexpr int N_ACC = 7;
constexpr int BW_PARAMS = 6;    // Bouc-Wen: force per unit z (k u_y), u_y, a, beta, gamma, n (an element's)
constexpr int MAX_BRANCHES = 4; // of a multi-linear contact law
constexpr int GROUND = -1;      // a pair's second end when it is the ground (the table)

constexpr int T = 0;
constexpr int A_TSTART = 0, A_VIN = 1, A_DSTART = 2, A_IMPULSE = 3, A_PEAK = 4, A_MAXCOMP = 5, A_WORK = 6;

// a run's exact extrema: per dof, its displacement's max and min (m) with their times (s) and its absolute
// acceleration's largest magnitude (m/s^2), its time and signed value; then per tracked pair (a storey's
// drift), the relative displacement's max and min with their times
enum DofExtremum : int { EX_D_MAX = 0, EX_D_MAX_T, EX_D_MIN, EX_D_MIN_T, EX_A_ABS_MAX, EX_A_ABS_MAX_T, EX_A_AT_MAX,
                         DOF_EXTREMA };
enum PairExtremum : int { PX_MAX = 0, PX_MAX_T, PX_MIN, PX_MIN_T, PAIR_EXTREMA };
// then per tracked vector (two tracked pairs as its components: a bearing's displacement in plan, x and y),
// its length's largest (m), its time (s) and the two components there
enum NormExtremum : int { NX_MAX = 0, NX_MAX_T, NX_AT_P, NX_AT_Q, NORM_EXTREMA };

// where each block of the state vector starts, for n dofs, nc contact slots, n_h hysteretic elements, n_sp
// springs of theirs in all and n_bw Bouc-Wen springs (their z: one slot at least, 0 without any)
struct Layout {
    int n = 1, nc = 2, n_h = 1, n_sp = 0, n_bw = 0;
    int x = 1, v = 2, def = 3, in = 5, region = 7, acc = 8, z = 22, zeta = 36, base = 37, size = 37;
    Layout() = default;
    Layout(int n_dof, int n_contacts, int n_elements, int n_springs, int n_bouc_wen)
        : n(n_dof), nc(n_contacts), n_h(n_elements), n_sp(n_springs), n_bw(n_bouc_wen) {
        x = 1;
        v = x + n;
        def = v + n;
        in = def + nc;
        region = in + nc;
        acc = region + n_h;
        z = acc + N_ACC * nc;
        zeta = z + N_LAW_STATE * nc;
        base = zeta + std::max(1, n_bw);
        size = base + 2 * n_sp;
    }
    int def_at(int c) const { return def + c; }
    int in_at(int c) const { return in + c; }
    int acc_at(int c) const { return acc + N_ACC * c; }
    int z_at(int c) const { return z + N_LAW_STATE * c; }
    // the outputs' columns: samples t, x (n), v (n), absolute accelerations (n), each hysteretic element's force
    // (the isolator's first), contact forces
    int sample_cols() const { return 1 + 3 * n + n_h + nc; }
    int extrema_len() const { return DOF_EXTREMA * n; }
};

// how a run ended: the codes of pounding.Status
enum Status : int {
    SUCCESS = 0, ZENO = -1, MAX_EVENTS = -2, STEP_FAILED = -4, INTERRUPTED = -5, BUDGET = -6, NONFINITE = -7,
    CAPACITY = -8  // a friction isolator's surfaces all at their rings: its travel used up
    // (-3, DEGENERATE_PHASE, is gone: an undamped resonance is solved as any phase)
};

// events' actions (their codes in a run's event table)
enum Action : int {
    ACT_YIELD = 0, ACT_REVERSAL = 1, ACT_REGION = 2, ACT_CONTACT = 3, ACT_RELEASE = 4, ACT_LAW_BRANCH = 5,
    ACT_BOUC_WEN = 6, ACT_STICK = 7, ACT_SLIP = 8, ACT_SURFACE_SLIP = 9, ACT_RING = 10, ACT_RING_OFF = 11,
    ACT_CIRCLE_SLIP = 12, ACT_CIRCLE_STICK = 13  // (a plastic circle's: Hysteretic::bw_plastic)
};

// the run control Python shares with a running kernel (int64): a stop flag, the work done (sub-intervals),
// its budget, and the trajectory evaluations at an instant (what locating events costs); the series made, the
// screen's audit, a record's steps taken whole, and its samples taken by their own (run.cpp's own_samples_of)
constexpr int CTL_STOP = 0, CTL_WORK = 1, CTL_BUDGET = 2, CTL_EVALS = 3, CTL_SERIES = 4, CTL_AUDITED = 5,
              CTL_ESCAPES = 6, CTL_WHOLE = 7, CTL_OWN = 8, CTL_LEN = 9;

// outputs' columns (bindings.cpp exports each by name: pounding._core reads them by these names)
// a contact's row: its slot, start and end (s), velocities in and out (m/s), impulse (N s), peak force (N),
// deepest compression (m), the energy the contact took from the motion (J: dissipated, or kept in a
// kinematic bumper's set)
enum ContactCol : int { CC_CONTACT = 0, CC_T_START, CC_T_END, CC_V_IN, CC_V_OUT, CC_IMPULSE, CC_PEAK_FORCE,
                        CC_MAX_COMPRESSION, CC_DISSIPATION, CONTACT_COLS };
// an event's row: its time (s), its action (enum Action), the element's or the contact's index
enum EventCol : int { EC_T = 0, EC_ACTION, EC_INDEX, EVENT_COLS };
enum Ledger : int { L_INPUT = 0, L_VISCOUS, L_HYSTERETIC, L_BUMPER_LOSS, L_KINETIC, L_ISOLATOR, L_BUMPER,
                    LEDGER_LEN };

constexpr double DBL_MAXV = std::numeric_limits<double>::max();
constexpr double NaN = std::numeric_limits<double>::quiet_NaN();
constexpr double INF = std::numeric_limits<double>::infinity();
constexpr double EPS = 2.220446049250313e-16;
constexpr double TWO_PI = 6.283185307179586;
constexpr double MIN_NORMAL = 2.2250738585072014e-308;
constexpr double EXP_NORMAL_LIMIT = 708.39;  // exp(-x) is below the smallest normal double for larger x

// What a contact or an element acts between, a Pair: dof i, plus arm ai times dof li (a lever: a point of a
// floor in plan moves as x - y_c theta), against dof j (plus aj times dof lj) or the ground.  Its relative
// value is w . y, w its weights (+1 on i, +ai on li, -1 on j, -aj on lj), and a force f along it pushes the
// dofs by f w.  Without levers (li, lj -1) that is y_i - y_j, number for number as a pair always was.
struct Pair {
    int i = 0, j = GROUND;
    int li = -1, lj = -1;  // the lever dofs (-1: none; set_levers sets them)
    double ai = 0.0, aj = 0.0;
    bool lev = false;      // li >= 0 || lj >= 0, kept (the hot paths ask it at every relative value)
    bool levered() const { return lev; }
    void set_levers(int lever_i, double arm_i, int lever_j, double arm_j) {
        li = lever_i;
        ai = lever_i >= 0 ? arm_i : 0.0;
        lj = lever_j;
        aj = lever_j >= 0 ? arm_j : 0.0;
        lev = li >= 0 || lj >= 0;
    }
    // sum |w|: how much larger |w . y| can be than the largest |y_k|
    double weight() const {
        if (!levered()) return j >= 0 ? 2.0 : 1.0;
        return 1.0 + (li >= 0 ? std::abs(ai) : 0.0) + (j >= 0 ? 1.0 + (lj >= 0 ? std::abs(aj) : 0.0) : 0.0);
    }
    // its weights as (dof, weight) entries into d, w (4 each at most); their count
    int entries(int* d, double* w) const {
        int m = 0;
        d[m] = i, w[m++] = 1.0;
        if (li >= 0) d[m] = li, w[m++] = ai;
        if (j >= 0) {
            d[m] = j, w[m++] = -1.0;
            if (lj >= 0) d[m] = lj, w[m++] = -aj;
        }
        return m;
    }
};
// the weight of dof d in a pair's w (0: not in it)
inline double weight_on(const Pair& p, int d) {
    double w = 0.0;
    if (p.i == d) w += 1.0;
    if (p.li == d) w += p.ai;
    if (p.j >= 0 && p.j == d) w -= 1.0;
    if (p.j >= 0 && p.lj == d) w -= p.aj;
    return w;
}
// whether two pairs move a dof in common (their ends' and levers': the ground is none)
inline bool shares_dof(const Pair& a, const Pair& b) {
    int da[4], db[4];
    double w[4];
    const int m = a.entries(da, w), k = b.entries(db, w);
    for (int p = 0; p < m; ++p)
        for (int q = 0; q < k; ++q)
            if (da[p] == db[q]) return true;
    return false;
}
inline bool same_pair(const Pair& a, const Pair& b) {
    return a.i == b.i && a.j == b.j && a.lev == b.lev &&
           (!a.lev || (a.li == b.li && a.lj == b.lj && a.ai == b.ai && a.aj == b.aj));
}

// A radial contact: a ring's wall (a circular moat) struck by a point of a floor.  The point sits at (px, py)
// from the ring's centre at rest and moves by (u_x, u_y): its contact's own pair's w . x and pair y's.  Its
// compression is |(px + u_x, py + u_y)| - radius, and the wall pushes it back along the normal there, n = (px +
// u_x, py + u_y) / |.|: a force f pushes the dofs by -f (n_x w_x + n_y w_y).  Not a linear function of the
// motion: a phase in contact with it is integrated numerically, and its start's event is evaluated on the
// trajectory (events.cpp's KIND_RADIAL).
struct Radial {
    bool on = false;
    Pair y;
    double px = 0.0, py = 0.0, radius = 0.0;
};

// One contact: a bumper (or a stop) on a pair (Pair: dof i against dof j or the ground, x_i - x_j its w . x
// on levers) behind a gap.  Its compression is sign (x_i - x_j) - gap in contact; it pushes dof i by -sign F
// and dof j by +sign F (the dofs by -sign F w).  (A one-mass system's left bumper is sign -1, its right +1.)
struct Contact : Pair {
    double sign = 1.0;
    double gap = 0.0;
    int law = 0;
    double p[N_LAW_PARAMS] = {0};
    Radial radial;  // (on: a ring's wall, struck along its normal; sign +1, gap its clearance at rest)
};

// A hysteretic element: a rate-independent multi-linear spring (slopes N/m, n_springs + 1; breaks m, n_springs)
// with its rule (0 kinematic, 1 elastic, 2 Coulomb friction: isolator.hpp) and a dashpot c_d (N s/m), between
// dof i and dof j (or the ground), deformed by u = x_i - x_j (its pair's w . x on levers: a bearing at a plan
// position).  The isolator is element 0 of a system, and carries its Bouc-Wen spring if it has one; a storey
// with a hysteretic backbone is another.
struct Hysteretic : Pair {
    double c_d = 0.0;
    std::vector<double> slopes, breaks;
    int rule = 0;
    double friction = 0.0;  // N: the Coulomb force of rule 2 (a friction isolator: mu W), 0 for the others
    // rule 2's velocity dependence: a slip's force F_fast - (F_fast - friction) e^(-rate |u'|) (friction at
    // rest, F_fast fast), as OpenSees' VelDependent; rate 0 (s/m): Coulomb's constant friction.  The same on
    // the kinematic rule of one break (a sliding bearing's elastic pre-slip: friction its yield force).  On a
    // bidirectional Bouc-Wen spring (a friction circle: both mates the same numbers) the same dependence of its
    // force bw[0] z, friction unused (bw[0] is the force at rest: isolator.hpp's circle_scale)
    double friction_fast = 0.0, friction_rate = 0.0;
    // rule 2 with surfaces in series (a triple friction pendulum's series model, isolator.hpp): each surface's
    // friction (N; slopes its stiffness, breaks its travel to its ring); empty: one surface (friction, slopes[0])
    std::vector<double> surface_friction;
    // each surface's ring stiffness (N/m; 0: rigid), empty: every ring rigid
    std::vector<double> surface_ring;
    // its Bouc-Wen spring (bw[0] 0: none), in parallel: force bw[0] z, z' = u' / u_y (a - |z|^n (gamma +
    // beta sgn(u' z))), z of layout slot zeta + bw_slot (set by System::finish, -1: none).  With a mate (the
    // element of the same bearing along the other axis, the same numbers) the two are one bidirectional
    // spring, Park, Wen and Ang's yielding under the resultant (phase.cpp's zeta_rate)
    double bw[BW_PARAMS] = {0};
    int bw_slot = -1;
    int bw_mate = -1;       // its mate's element (-1: none)
    int bw_mate_slot = -1;  // its mate's z slot (set by System::finish)
    // its bidirectional spring elastic-perfectly-plastic (with a mate, the same flag; a = 1): Bouc-Wen's limit
    // n -> infinity, |z| <= 1.  Inside the circle z' = u' / u_y (elastic: it sticks), on it while z . u' > 0
    // z' = (u' - (z . u') z) / u_y (it slips, its force bw[0] z turning along the slip: the friction circle).
    // State: region + e, the same in both mates, 0 inside, 1 slipping; the switches are events (the circle
    // reached, ACT_CIRCLE_SLIP; z . u' back through zero, ACT_CIRCLE_STICK: events.cpp's circle_value)
    bool bw_plastic = false;
    bool has_bw() const { return bw[0] != 0.0; }
    int first = 0;  // its first spring's index among the system's (set by System::finish)
    bool series() const { return !surface_friction.empty(); }
    // its springs: a series's surfaces (each with a displacement and a state), the backbone's breaks otherwise
    int n_springs() const { return series() ? static_cast<int>(slopes.size()) : static_cast<int>(slopes.size()) - 1; }
};

bool law_is_rigid(int law);  // (laws.hpp: the contact laws' one place)
bool iso_is_friction(const Hysteretic& h);  // (isolator.hpp: the isolator rules' one place)

// The system as the kernels take it (pounding.engine.simulate.kernel_system packs a one-mass system).
struct System {
    int n = 1;                    // degrees of freedom
    std::vector<double> mass;     // kg, n
    std::vector<double> k0, c0;   // the linear springs and dashpots besides the elements (N/m, N s/m), n x n
    std::vector<Hysteretic> hyst; // the hysteretic elements, the isolator first (none: a fixed base)
    bool has_b = false;           // the contacts are active
    std::vector<Contact> contact; // the contact slots
    std::vector<Pair> track;  // pairs whose relative displacement's extrema a run finds (drifts, a bearing's)
    // vectors whose length's largest a run finds: two tracked pairs each (indices into track), its components
    std::vector<int> norm_p, norm_q;
    // and each vector's offset (2 a vector, m: a floor's corner's place from a ring's centre, whose distance
    // from it is the length found); empty: none
    std::vector<double> norm_at;
    std::vector<Pair> dof_pair;  // (derived: each dof against the ground, made once for the hot paths)
    // how the ground's two components move each dof (n x 2, row by dof: the table acceleration on dof i is
    // infl[2 i] a_x + infl[2 i + 1] a_y); empty: every dof moves with the first component (a line's table)
    std::vector<double> infl;
    // derived by finish(): the damping of every phase (c0 and the elements' dashpots), the layout
    std::vector<double> c_lin;
    std::vector<int> rigid;  // the contacts with a rigid stop's law
    std::vector<int> ties;   // the elements with the friction rule (each ties its pair while it sticks)
    bool lever_holds = false;  // a rigid contact or a tie on a lever: holds are linear constraints (sticking.hpp)
    std::vector<int> bw_el;  // the elements with a Bouc-Wen spring, by their z's slot
    bool bw_kinks = false;   // a Bouc-Wen spring but a plastic circle: its law's kinks at u' = 0 (velocity_cuts)
    double total_mass = 0.0;
    bool plain = true;  // the table moves every dof with its first component alone (infl's rows 1, 0)
    // where any phase's stiffness or damping can be nonzero (k0, c_lin and every element's and contact's pair),
    // row by row: row i's columns kc_col[kc_start[i]..kc_start[i + 1]) in ascending order; empty below 6 dofs
    // or above half the entries, where the plain loops are as quick (derived by finish())
    std::vector<int> kc_start, kc_col;
    Layout lay;

    int n_springs() const {  // the elements' springs, all together
        int s = 0;
        for (const Hysteretic& h : hyst) s += h.n_springs();
        return s;
    }
    int n_h() const { return static_cast<int>(hyst.size()); }
    int n_track() const { return static_cast<int>(track.size()); }
    int n_norm() const { return static_cast<int>(norm_p.size()); }
    // where the tracked vectors' extrema start in a run's extrema (after the dofs' and the pairs')
    int norm_extrema_at() const { return DOF_EXTREMA * n + PAIR_EXTREMA * n_track(); }
    const Hysteretic& iso() const { return hyst[0]; }
    int state_size() const { return lay.size; }
    int nc() const { return static_cast<int>(contact.size()); }
    int n_bw() const { return static_cast<int>(bw_el.size()); }
    const Hysteretic& bw_of(int b) const { return hyst[static_cast<size_t>(bw_el[static_cast<size_t>(b)])]; }
    void finish() {
        int first = 0;
        bw_el.clear();
        bw_kinks = false;
        for (int e = 0; e < n_h(); ++e) {
            Hysteretic& h = hyst[static_cast<size_t>(e)];
            h.first = first;
            first += h.n_springs();
            h.bw_slot = h.has_bw() ? n_bw() : -1;
            if (h.has_bw()) bw_el.push_back(e);
            bw_kinks = bw_kinks || (h.has_bw() && !h.bw_plastic);
        }
        for (Hysteretic& h : hyst)
            h.bw_mate_slot = h.bw_mate >= 0 ? hyst[static_cast<size_t>(h.bw_mate)].bw_slot : -1;
        lay = Layout(n, nc(), n_h(), n_springs(), n_bw());
        dof_pair.assign(static_cast<size_t>(n), Pair());
        for (int i = 0; i < n; ++i) dof_pair[static_cast<size_t>(i)].i = i;
        c_lin = c0;
        if (static_cast<int>(c_lin.size()) != n * n) c_lin.assign(static_cast<size_t>(n * n), 0.0);
        if (static_cast<int>(k0.size()) != n * n) k0.assign(static_cast<size_t>(n * n), 0.0);
        for (const Hysteretic& h : hyst) add_pair(c_lin, h, h.c_d);
        rigid.clear();
        for (int c = 0; c < nc(); ++c)
            if (law_is_rigid(contact[static_cast<size_t>(c)].law)) rigid.push_back(c);
        ties.clear();
        for (int e = 0; e < n_h(); ++e)
            if (iso_is_friction(hyst[static_cast<size_t>(e)])) ties.push_back(e);
        lever_holds = false;
        for (const int c : rigid)  // (a ring's row turns: a linear constraint too, sticking.hpp)
            lever_holds = lever_holds || contact[static_cast<size_t>(c)].levered() || contact[static_cast<size_t>(c)].radial.on;
        for (const int e : ties) lever_holds = lever_holds || hyst[static_cast<size_t>(e)].levered();
        total_mass = 0.0;
        for (double m : mass) total_mass += m;
        if (static_cast<int>(infl.size()) != 2 * n) {
            infl.assign(static_cast<size_t>(2 * n), 0.0);
            for (int i = 0; i < n; ++i) infl[static_cast<size_t>(2 * i)] = 1.0;
        }
        if (static_cast<int>(norm_at.size()) != 2 * n_norm()) norm_at.assign(static_cast<size_t>(2 * n_norm()), 0.0);
        plain = true;
        for (int i = 0; i < n; ++i)
            plain = plain && infl[static_cast<size_t>(2 * i)] == 1.0 && infl[static_cast<size_t>(2 * i + 1)] == 0.0;
        pattern();
    }
    // kc_start, kc_col: the union of the nonzeros k0, c_lin and every pair's w w^T can place
    void pattern() {
        std::vector<char> on(static_cast<size_t>(n * n), 0);
        for (int q = 0; q < n * n; ++q)
            on[static_cast<size_t>(q)] = k0[static_cast<size_t>(q)] != 0.0 || c_lin[static_cast<size_t>(q)] != 0.0;
        auto mark = [&](const Pair& p) {
            int d[4];
            double w[4];
            const int m = p.entries(d, w);
            for (int r = 0; r < m; ++r)
                for (int c = 0; c < m; ++c) on[static_cast<size_t>(d[r] * n + d[c])] = 1;
        };
        for (const Hysteretic& h : hyst) mark(h);
        for (const Contact& c : contact) mark(c);
        int nnz = 0;
        for (char b : on) nnz += b;
        kc_start.clear();
        kc_col.clear();
        if (n < 6 || 2 * nnz > n * n) return;  // (small or dense enough: the plain loops are as quick)
        kc_start.push_back(0);
        for (int i = 0; i < n; ++i) {
            for (int j = 0; j < n; ++j)
                if (on[static_cast<size_t>(i * n + j)]) kc_col.push_back(j);
            kc_start.push_back(static_cast<int>(kc_col.size()));
        }
    }
    // a spring (or dashpot) of constant s between dofs i and j (or the ground) into an n x n matrix
    void add_pair(std::vector<double>& a, int i, int j, double s) const {
        a[static_cast<size_t>(i * n + i)] += s;
        if (j >= 0) {
            a[static_cast<size_t>(j * n + j)] += s;
            a[static_cast<size_t>(i * n + j)] -= s;
            a[static_cast<size_t>(j * n + i)] -= s;
        }
    }
    // s w w^T of a pair (Pair) into an n x n matrix
    void add_pair(std::vector<double>& a, const Pair& p, double s) const {
        if (!p.levered()) return add_pair(a, p.i, p.j, s);
        int d[4];
        double w[4];
        const int m = p.entries(d, w);
        for (int r = 0; r < m; ++r)
            for (int c = 0; c < m; ++c) a[static_cast<size_t>(d[r] * n + d[c])] += s * w[r] * w[c];
    }
};

// a pair's relative value: y[i] - y[j] (y[i] against the ground)
inline double rel(const double* y, int i, int j) { return j >= 0 ? y[i] - y[j] : y[i]; }
// a pair's (Pair): w . y
inline double rel(const double* y, const Pair& p) {
    if (__builtin_expect(!p.lev, 1)) return rel(y, p.i, p.j);
    const double a = y[p.i] + (p.li >= 0 ? p.ai * y[p.li] : 0.0);
    return p.j >= 0 ? a - (y[p.j] + (p.lj >= 0 ? p.aj * y[p.lj] : 0.0)) : a;
}
// a force f along a pair onto q (n): q += f w
inline void push_pair(double* q, const Pair& p, double f) {
    q[p.i] += f;
    if (p.li >= 0) q[p.li] += p.ai * f;
    if (p.j >= 0) {
        q[p.j] -= f;
        if (p.lj >= 0) q[p.lj] -= p.aj * f;
    }
}

// The excitation: harmonic (p = amplitude m/s^2, omega rad/s, phase rad) or a record (times s and
// accelerations m/s^2, linear between samples; p[0] its uniform step, 0 if none).  It moves the ground,
// so every mass feels -m a_g (dof i: -m_i (infl[2 i] a_g + infl[2 i + 1] b_g)).  Its second component b_g:
// a harmonic's pb[0] sin(omega t + pb[1]) (the same omega), a record's rec_b on the same times (null: none).
constexpr int EXC_HARMONIC = 0, EXC_RECORD = 1;
struct Forcing {
    int kind = EXC_HARMONIC;
    double p[3] = {0, 0, 0};
    double pb[2] = {0, 0};
    const double* rec_t = nullptr;
    const double* rec_a = nullptr;
    const double* rec_b = nullptr;
    int64_t n_rec = 0;
};

// the run control Python shares (an int64 array of CTL_LEN): its stop flag polled, the work done added to
// as it is done (kernels on other threads may share the array), the budget read
struct Control {
    int64_t* ctl;
    std::atomic<int64_t>& at(int i) const { return *reinterpret_cast<std::atomic<int64_t>*>(ctl + i); }
    bool stop() const { return at(CTL_STOP).load(std::memory_order_relaxed) != 0; }
    // add n to the work done; the work left of the budget after it
    int64_t add_work(int64_t n) const {
        const int64_t done = at(CTL_WORK).fetch_add(n, std::memory_order_relaxed) + n;
        return ctl[CTL_BUDGET] - done;
    }
};

// A growable table of rows (the run's outputs), in row-major order.
struct Rows {
    int cols;
    int64_t n = 0;
    explicit Rows(int c = 1, int64_t reserve = 64) : cols(c) {
        grow(static_cast<size_t>(std::max<int64_t>(reserve, 1) * std::max(c, 1)));
    }
    ~Rows() { std::free(buf_); }
    Rows(const Rows& o) : cols(o.cols), n(o.n) {
        grow(std::max(o.cap_, size_t(1)));
        if (o.n > 0) std::memcpy(buf_, o.buf_, static_cast<size_t>(o.n * o.cols) * sizeof(double));
    }
    Rows(Rows&& o) noexcept : cols(o.cols), n(o.n), buf_(o.buf_), cap_(o.cap_) {
        o.buf_ = nullptr;
        o.cap_ = 0;
        o.n = 0;
    }
    Rows& operator=(Rows o) noexcept {
        std::swap(cols, o.cols);
        std::swap(n, o.n);
        std::swap(buf_, o.buf_);
        std::swap(cap_, o.cap_);
        return *this;
    }
    // (the buffer grows by doubling with realloc: a large one is remapped, not copied, and the kernel
    // zeroes only the pages the rows reach)
    double* push() {
        const size_t need = static_cast<size_t>((n + 1) * cols);
        if (need > cap_) grow(std::max(need, 2 * cap_));
        double* r = buf_ + static_cast<size_t>(n++ * cols);
        std::fill(r, r + cols, 0.0);
        return r;
    }
    void clear() { n = 0; }
    double* row(int64_t i) { return buf_ + static_cast<size_t>(i * cols); }
    const double* row(int64_t i) const { return buf_ + static_cast<size_t>(i * cols); }
    // the buffer (n * cols values, at least one), handed over: the caller frees it with std::free
    double* release() {
        if (buf_ == nullptr) grow(1);
        double* out = buf_;
        buf_ = nullptr;
        cap_ = 0;
        n = 0;
        return out;
    }

  private:
    double* buf_ = nullptr;
    size_t cap_ = 0;  // (values)
    void grow(size_t values) {
        void* p = std::realloc(buf_, values * sizeof(double));
        if (p == nullptr) throw std::bad_alloc();
        buf_ = static_cast<double*>(p);
        cap_ = values;
    }
};

inline double sgn(double x) { return x > 0.0 ? 1.0 : (x < 0.0 ? -1.0 : 0.0); }

}  // namespace pounding
