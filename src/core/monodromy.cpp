#include "monodromy.hpp"

#include <algorithm>
#include <cmath>

#include "impact.hpp"
#include "impact_parts.hpp"
#include "isolator.hpp"
#include "laws.hpp"
#include "sticking.hpp"

namespace pounding {

namespace {

// a contact law's branch event is a turn where the compression's rate is at most this much of the motion's
// velocity scale, an edge where it is more (monodromy's ACT_LAW_BRANCH)
constexpr double BRANCH_TURN_RATE = 1e-6;

// where each block of x starts; after x (monodromy_size), the contacts' laws' memory (law_memory_size: an
// elastic-plastic bumper's plastic offset, a kinematic multi-linear bumper's slips), propagated with x and
// left out of the map's Jacobian (a start's memory held, as the map's finite differences hold it)
struct Coords {
    int n, nc, nsp, v, def, slip, pub, mem, size;
    std::vector<int> mem_at;  // each contact's first memory coordinate
    explicit Coords(const System& sy)
        : n(sy.n), nc(sy.nc()), nsp(sy.n_springs()), v(sy.n), def(2 * sy.n), slip(2 * sy.n + sy.nc()),
          pub(monodromy_size(sy)), mem(pub), size(pub) {
        for (int c = 0; sy.has_b && c < nc; ++c) {
            const Contact& ct = sy.contact[static_cast<size_t>(c)];
            mem_at.push_back(size);
            size += law_memory_size(ct.law, ct.p);
        }
    }
    int memory(const System& sy, int c) const {
        const Contact& ct = sy.contact[static_cast<size_t>(c)];
        return law_memory_size(ct.law, ct.p);
    }
};

// x into the state vector st and back (the mode's numbers stay in st)
void to_state(const System& sy, const Coords& cx, const std::vector<double>& xa, double* st) {
    for (int i = 0; i < cx.n; ++i) {
        st[sy.lay.x + i] = xa[i];
        st[sy.lay.v + i] = xa[cx.v + i];
    }
    for (int c = 0; c < cx.nc; ++c) st[sy.lay.def_at(c)] = xa[cx.def + c];
    for (int s = 0; s < cx.nsp; ++s) st[sy.lay.base + s] = xa[cx.slip + s];
    for (int c = 0; c < static_cast<int>(cx.mem_at.size()); ++c) {
        const Contact& ct = sy.contact[static_cast<size_t>(c)];
        if (cx.memory(sy, c) > 0) law_memory_write(ct.law, ct.p, st + sy.lay.z_at(c), xa.data() + cx.mem_at[c]);
    }
}

void from_state(const System& sy, const Coords& cx, const double* st, std::vector<double>& xa) {
    for (int i = 0; i < cx.n; ++i) {
        xa[i] = st[sy.lay.x + i];
        xa[cx.v + i] = st[sy.lay.v + i];
    }
    for (int c = 0; c < cx.nc; ++c) xa[cx.def + c] = st[sy.lay.def_at(c)];
    for (int s = 0; s < cx.nsp; ++s) xa[cx.slip + s] = st[sy.lay.base + s];
    for (int c = 0; c < static_cast<int>(cx.mem_at.size()); ++c) {
        const Contact& ct = sy.contact[static_cast<size_t>(c)];
        if (cx.memory(sy, c) > 0)
            law_memory_read(ct.law, ct.p, st + sy.lay.z_at(c), st[sy.lay.def_at(c)], xa.data() + cx.mem_at[c]);
    }
}

// a contact's compression rate in st (compression.hpp's)
double compression_rate(const System& sy, const double* st, int c) {
    return compression(sy.contact[static_cast<size_t>(c)], st + sy.lay.x, st + sy.lay.v).dv;
}

// the branch (in contact) or the free recovery's piece (apart) of contact c in st, in the law's memory
MemoryBranch branch_of(const System& sy, int c, const double* st) {
    const Contact& ct = sy.contact[static_cast<size_t>(c)];
    const bool in = st[sy.lay.in_at(c)] != 0.0;
    return law_memory_branch(ct.law, ct.p, st[sy.lay.def_at(c)], in ? compression_rate(sy, st, c) : 0.0,
                             st + sy.lay.z_at(c), in);
}

// (i, j) += s as a pair's spring into an n x n matrix
void add_pair(Mat& a, int i, int j, double s) {
    a(i, i) += s;
    if (j >= 0) {
        a(j, j) += s;
        a(i, j) -= s;
        a(j, i) -= s;
    }
}

// A~ of the mode in st, (size + 3, size + 3): x, then sin(theta), cos(theta), 1
Mat augmented(const System& sy, const Coords& cx, const double* st, double omega, double amp) {
    const int n = cx.n, size = cx.size;
    const int s_ = size, c_ = size + 1, one = size + 2;
    Mat a = Mat::Zero(size + 3, size + 3), K = Mat::Zero(n, n), C = Mat::Zero(n, n),
        G = Mat::Zero(n, std::max(cx.nsp, 1));
    std::vector<double> R(static_cast<size_t>(n), 0.0);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            K(i, j) = sy.k0[static_cast<size_t>(i * n + j)];
            C(i, j) = sy.c_lin[static_cast<size_t>(i * n + j)];
        }
    std::vector<double> d_slip(static_cast<size_t>(std::max(cx.nsp, 1))), follows(d_slip.size());
    for (int e = 0; e < sy.n_h(); ++e) {  // each element: -F on dof i, +F on dof j
        const Hysteretic& h = sy.hyst[static_cast<size_t>(e)];
        const IsoLinear il = iso_linear_in_slips(sy, e, st, d_slip.data(), follows.data());
        add_pair(K, h.i, h.j, il.k);
        R[static_cast<size_t>(h.i)] += il.r0;
        if (h.j >= 0) R[static_cast<size_t>(h.j)] -= il.r0;
        for (int s = 0; s < h.n_springs(); ++s) {
            const int col = h.first + s;
            G(h.i, col) += d_slip[static_cast<size_t>(s)];
            a(cx.slip + col, cx.v + h.i) = follows[static_cast<size_t>(s)];  // a slipping spring moves with u
            if (h.j >= 0) {
                G(h.j, col) -= d_slip[static_cast<size_t>(s)];
                a(cx.slip + col, cx.v + h.j) = -follows[static_cast<size_t>(s)];
            }
        }
    }
    Mat Gm = Mat::Zero(n, std::max(size - cx.mem, 1));  // (each contact's force on the dofs per unit of memory)
    for (int c = 0; sy.has_b && c < cx.nc; ++c) {  // each contact: -sign F on dof i, +sign F on dof j
        const Contact& ct = sy.contact[static_cast<size_t>(c)];
        const MemoryBranch b = branch_of(sy, c, st);
        const int row = cx.def + c, nm = cx.memory(sy, c), at = cx.mem_at[static_cast<size_t>(c)];
        if (st[sy.lay.in_at(c)] != 0.0) {
            add_pair(K, ct.i, ct.j, b.k);
            add_pair(C, ct.i, ct.j, b.c);
            const double r = ct.sign * (b.r - b.k * ct.gap);
            R[static_cast<size_t>(ct.i)] += r;
            if (ct.j >= 0) R[static_cast<size_t>(ct.j)] -= r;
            a(row, cx.v + ct.i) = ct.sign;  // the compression follows the pair
            if (ct.j >= 0) a(row, cx.v + ct.j) = -ct.sign;
            for (int q = 0; q < nm; ++q) {
                Gm(ct.i, at + q - cx.mem) += ct.sign * b.g[q];
                if (ct.j >= 0) Gm(ct.j, at + q - cx.mem) -= ct.sign * b.g[q];
                if (b.follow[q] != 0.0)
                    for (int col = 0; col < size; ++col) a(at + q, col) = b.follow[q] * a(row, col);
            }
        } else if (b.c > 0.0) {  // relaxing: c d' = -(k d + r + g . m)
            a(row, row) = -b.k / b.c;
            if (b.r != 0.0) a(row, one) = -b.r / b.c;
            for (int q = 0; q < nm; ++q) a(row, at + q) = -b.g[q] / b.c;
            for (int q = 0; q < nm; ++q)
                if (b.follow[q] != 0.0)
                    for (int col = 0; col < size + 3; ++col) a(at + q, col) = b.follow[q] * a(row, col);
        }
    }
    for (int i = 0; i < n; ++i) {
        const double m = sy.mass[static_cast<size_t>(i)];
        a(i, cx.v + i) = 1.0;
        for (int j = 0; j < n; ++j) {
            a(cx.v + i, j) = -K(i, j) / m;
            a(cx.v + i, cx.v + j) = -C(i, j) / m;
        }
        for (int s = 0; s < cx.nsp; ++s) a(cx.v + i, cx.slip + s) = -G(i, s) / m;
        for (int q = cx.mem; q < size; ++q) a(cx.v + i, q) = -Gm(i, q - cx.mem) / m;
        a(cx.v + i, one) = -R[static_cast<size_t>(i)] / m;
        a(cx.v + i, s_) = -amp * sy.infl[static_cast<size_t>(2 * i)];  // the table moves every mass (its first
        // component: a monodromy's forcing has no second)
    }
    a(s_, c_) = omega;
    a(c_, s_) = -omega;
    return a;
}

void add_rel(std::vector<double>& g, int at, int i, int j, double s) {
    g[static_cast<size_t>(at + i)] += s;
    if (j >= 0) g[static_cast<size_t>(at + j)] -= s;
}

// expm(a tau), the states that evolve alone (a relaxing contact) by their scalar exponential
Mat exponential(const Mat& a, double tau) {
    const int size = static_cast<int>(a.rows());
    std::vector<int> rest;
    for (int i = 0; i < size; ++i) {
        bool joined = false;
        for (int j = 0; j < size; ++j)
            if (i != j && (a(i, j) != 0.0 || a(j, i) != 0.0)) joined = true;
        if (joined) rest.push_back(i);
    }
    const int nr = static_cast<int>(rest.size());
    Mat sub = Mat::Zero(nr, nr);
    for (int i = 0; i < nr; ++i)
        for (int j = 0; j < nr; ++j) sub(i, j) = a(rest[i], rest[j]) * tau;
    const Mat block = nr > 0 ? expm(sub) : sub;
    Mat out = Mat::Zero(size, size);
    for (int i = 0; i < size; ++i) out(i, i) = std::exp(a(i, i) * tau);
    for (int i = 0; i < nr; ++i)
        for (int j = 0; j < nr; ++j) out(rest[i], rest[j]) = block(i, j);
    return out;
}

// the mode's accelerations with the rigid stops held in st: each held group's rows of the velocities' rates
// replaced by their mass-weighted mean (sticking.hpp), a group held to the ground's by zero
void hold_rows(const System& sy, const Coords& cx, const double* st, Mat& a) {
    if (!sy.has_b && sy.ties.empty()) return;
    Sticking stk;
    stk.build(sy, st);
    if (!stk.any) return;
    std::vector<double> col(static_cast<size_t>(cx.n));
    for (int q = 0; q < a.cols(); ++q) {
        for (int i = 0; i < cx.n; ++i) col[static_cast<size_t>(i)] = a(cx.v + i, q);
        stk.project(sy.mass, col.data());
        for (int i = 0; i < cx.n; ++i) a(cx.v + i, q) = col[static_cast<size_t>(i)];
    }
}

// the mode of the state st: its linear field, with its holds
Mat mode(const System& sy, const Coords& cx, const double* st, double omega, double amp) {
    Mat a = augmented(sy, cx, st, omega, amp);
    hold_rows(sy, cx, st, a);
    return a;
}

bool any_held(const System& sy, const double* st) {
    for (const int c : sy.rigid)
        if (sy.has_b && st[sy.lay.in_at(c)] != 0.0) return true;
    return false;
}

// whether the impact at event e on rigid stop c began a hold: the next event of c is its release
bool begins_hold(const double* events, int n_events, int e, int c) {
    for (int k = e + 1; k < n_events; ++k) {
        if (static_cast<int>(events[3 * k + 2]) != c) continue;
        const int action = static_cast<int>(events[3 * k + 1]);
        if (action == ACT_RELEASE) return true;
        if (action == ACT_CONTACT) return false;
    }
    return false;
}

// a series's slipping surfaces where the force puts them, as the engine has them at every step: their rows of the
// Jacobian those of d u_g = (k / K_g) (d u - the held surfaces' d u_h) (the surfaces that start to slip together,
// or one whose threshold a perturbation moves within the engine's grouping, forget where they were held)
void follow_force(const System& sy, const Coords& cx, const double* st, Mat& jac) {
    for (int e = 0; e < sy.n_h(); ++e) {
        const Hysteretic& h = sy.hyst[static_cast<size_t>(e)];
        if (!h.series() || st[sy.lay.region + e] == 0.0) continue;
        const int m = h.n_springs();
        std::vector<double> d_slip(static_cast<size_t>(m)), follows(static_cast<size_t>(m));
        const IsoLinear il = iso_linear_in_slips(sy, e, st, d_slip.data(), follows.data());
        if (il.k == 0.0) continue;
        for (int q = 0; q < jac.cols(); ++q) {
            double du = jac(h.i, q) - (h.j >= 0 ? jac(h.j, q) : 0.0);  // (d u - sum of the held d u_h)
            for (int g = 0; g < m; ++g) du += d_slip[static_cast<size_t>(g)] / il.k * jac(cx.slip + h.first + g, q);
            for (int g = 0; g < m; ++g)
                if (follows[static_cast<size_t>(g)] != 0.0) jac(cx.slip + h.first + g, q) = follows[static_cast<size_t>(g)] * du;
        }
    }
}

// a start where friction elements stick (no rigid stop held): a perturbation of a tied pair's relative velocity
// slides it by its square and sticks again, its momentum kept: the velocities' rows projected as the ties hold
// them (a held group's mass-weighted mean, a group tied to the ground at rest)
void tied_velocities(const System& sy, const Coords& cx, const double* st, Mat& jac) {
    if (sy.ties.empty()) return;
    Sticking stk;
    stk.build(sy, st);
    if (!stk.any) return;
    for (size_t h = 0; h < stk.held.size(); ++h)
        if (!is_tie(stk, static_cast<int>(h))) return;  // (a rigid stop held: a perturbation away from it leaves it)
    std::vector<double> col(static_cast<size_t>(cx.n));
    for (int q = 0; q < jac.cols(); ++q) {
        for (int i = 0; i < cx.n; ++i) col[static_cast<size_t>(i)] = jac(cx.v + i, q);
        stk.project(sy.mass, col.data());
        for (int i = 0; i < cx.n; ++i) jac(cx.v + i, q) = col[static_cast<size_t>(i)];
    }
}

Mat top_left(const Mat& m, int n) {
    Mat out = Mat::Zero(n, n);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) out(i, j) = m(i, j);
    return out;
}

// the saltation matrix of a guard whose gradient is grad, the field f_before before and f_after after, applied
// to jac; false where the guard is met tangentially and the field jumps (no saltation matrix)
bool saltation(const std::vector<double>& grad, const std::vector<double>& f_before,
               const std::vector<double>& f_after, Mat& jac) {
    const int n = static_cast<int>(jac.rows());
    double rate = 0.0;
    for (int i = 0; i < n; ++i) rate += grad[static_cast<size_t>(i)] * f_before[static_cast<size_t>(i)];
    if (rate == 0.0) {  // (tangent: no saltation, unless the field does not jump)
        for (int i = 0; i < n; ++i)
            if (f_after[static_cast<size_t>(i)] != f_before[static_cast<size_t>(i)]) return false;
        return true;
    }
    Mat jump = Mat::Identity(n, n);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            jump(i, j) += (f_after[static_cast<size_t>(i)] - f_before[static_cast<size_t>(i)]) *
                          grad[static_cast<size_t>(j)] / rate;
    jac = (jump * jac).eval();
    return true;
}

// From t to t_end in the mode a, across the edges of the free recoveries' pieces on the way: a multi-linear
// bumper apart falls from branch to branch, a kinematic one's springs start to slip back, one reaches zero.
// These are no events of the run (the engine takes a recovery's pieces in closed form within a sub-interval),
// so they are found here, each from its piece's closed form (law_relax_horizon).  False where one is met
// tangentially, or beyond a bound on their number.
bool propagate(const System& sy, const Coords& cx, std::vector<double>& st, std::vector<double>& xa, Mat& jac,
               Mat& a, double& t, double t_end, double omega, double amp) {
    const int n = cx.size;
    for (int pass = 0;; ++pass) {
        for (int c = 0; sy.has_b && c < cx.nc; ++c)  // (a recovery at zero that forgets a compression at once:
            // a law with memory's)
            if (cx.memory(sy, c) > 0 && st[sy.lay.in_at(c)] == 0.0 && branch_of(sy, c, st.data()).forgets)
                jac.row(cx.def + c).setZero();
        double h = t_end - t;
        int which = -1;
        MemoryBranch b{};  // (the piece that ends first: its edge and how the memory moves it)
        for (int c = 0; sy.has_b && c < cx.nc; ++c) {
            if (st[sy.lay.in_at(c)] != 0.0 || !(st[sy.lay.def_at(c)] > 0.0)) continue;
            const Contact& ct = sy.contact[static_cast<size_t>(c)];
            const double edge = law_relax_horizon(ct.law, ct.p, st[sy.lay.def_at(c)], st.data() + sy.lay.z_at(c));
            if (edge < h) {
                h = edge;
                which = c;
                b = branch_of(sy, c, st.data());
            }
        }
        if (which >= 0 && pass >= 4 * cx.nc + 64) return false;  // (more pieces than a recovery has: refused)
        const Mat step = exponential(a, h);
        xa = matvec(step, xa);
        jac = (top_left(step, n) * jac).eval();
        if (which < 0) {
            t = t_end;
            to_state(sy, cx, xa, st.data());
            return true;
        }
        t += h;
        const std::vector<double> f_before = matvec(a, xa);
        to_state(sy, cx, xa, st.data());
        const Contact& ct = sy.contact[static_cast<size_t>(which)];
        std::vector<double> grad(static_cast<size_t>(n), 0.0);  // d - lower(m)
        grad[static_cast<size_t>(cx.def + which)] = 1.0;
        const int at = cx.mem_at[static_cast<size_t>(which)];
        for (int q = 0; q < cx.memory(sy, which); ++q) grad[static_cast<size_t>(at + q)] = -b.dlower[q];
        st[sy.lay.def_at(which)] = std::max(b.lower, 0.0);  // (where the engine puts it: law_relax)
        law_moved(ct.law, ct.p, st.data() + sy.lay.z_at(which), st[sy.lay.def_at(which)], false);
        from_state(sy, cx, st.data(), xa);
        a = mode(sy, cx, st.data(), omega, amp);
        if (!saltation(grad, f_before, matvec(a, xa), jac)) return false;
    }
}
}  // namespace

namespace {
int propagated(const System& sy, const double* st0, const double* events, int n_events, double t_end,
               double omega, double amp, double phase, Mat& jac, std::vector<double>& x_end) {
    const Coords cx(sy);
    const int n = cx.size, pub = cx.pub;
    std::vector<double> st(st0, st0 + sy.state_size()), next(st.size());
    double t = st0[T];
    std::vector<double> xa(static_cast<size_t>(n + 3), 0.0);
    from_state(sy, cx, st.data(), xa);
    xa[static_cast<size_t>(n)] = std::sin(omega * t + phase);
    xa[static_cast<size_t>(n + 1)] = std::cos(omega * t + phase);
    xa[static_cast<size_t>(n + 2)] = 1.0;
    jac = Mat::Identity(n, pub);  // (the memory's rows zero at the start: held, ...
    for (int c = 0; sy.has_b && c < cx.nc; ++c) {  // ... but where it moves with the compression: there by it)
        const MemoryBranch b = branch_of(sy, c, st.data());
        for (int q = 0; q < cx.memory(sy, c); ++q) jac(cx.mem_at[static_cast<size_t>(c)] + q, cx.def + c) = b.follow[q];
    }
    tied_velocities(sy, cx, st.data(), jac);
    Mat a = mode(sy, cx, st.data(), omega, amp);
    for (int e = 0; e <= n_events; ++e) {
        if (e > 0) follow_force(sy, cx, st.data(), jac);  // (after an event)
        const double t_ev = e < n_events ? events[3 * e] : t_end;
        if (!propagate(sy, cx, st, xa, jac, a, t, t_ev, omega, amp)) {
            x_end.assign(xa.begin(), xa.begin() + pub);
            return e;
        }
        if (e == n_events) break;
        const int action = static_cast<int>(events[3 * e + 1]), index = static_cast<int>(events[3 * e + 2]);
        const std::vector<double> f_before = matvec(a, xa);
        to_state(sy, cx, xa, st.data());
        next = st;
        std::vector<double> grad(static_cast<size_t>(n), 0.0);
        if ((action == ACT_CONTACT || action == ACT_RELEASE) && sy.has_b &&
            law_is_rigid(sy.contact[static_cast<size_t>(index)].law)) {
            // a rigid stop: its impact is a reset of the velocities (Newton's law), whose saltation matrix is
            // R + (f+ - R f-) grad^T / (grad . f-); one that begins a hold (a chatter's accumulation, taken at
            // that instant) brings the pair to rest, R's with e = 0, and f+ is the held mode's.  Its release,
            // where the hold's force falls to zero, leaves the field continuous: no saltation
            if (action == ACT_RELEASE) {
                if (st[sy.lay.in_at(index)] == 0.0) return -2 - e;  // (a hold this did not see begin)
                next[sy.lay.in_at(index)] = 0.0;
                st = next;
                a = mode(sy, cx, st.data(), omega, amp);
                continue;
            }
            if (any_held(sy, st.data())) return -2 - e;  // (an impact while a stop is held: its groups' reset)
            {  // (impacts at one instant: their joint reset has no saltation here)
                double scale = 0.0;
                for (int i = 0; i < sy.n; ++i) scale = std::max(scale, std::abs(st[sy.lay.x + i]));
                for (const int d : sy.rigid) scale = std::max(scale, sy.contact[static_cast<size_t>(d)].gap);
                if (run_parts::others_touch(st.data(), sy, index, 64.0 * ROUNDING * scale + MIN_NORMAL))
                    return -2 - e;
            }
            const bool holds = begins_hold(events, n_events, e, index);
            const Contact& ct = sy.contact[static_cast<size_t>(index)];
            const double restitution = holds ? 0.0 : law_restitution(ct.p);
            const double mi = sy.mass[static_cast<size_t>(ct.i)];
            const double mj = ct.j >= 0 ? sy.mass[static_cast<size_t>(ct.j)] : INF;
            const double mu = 1.0 / (1.0 / mi + (ct.j >= 0 ? 1.0 / mj : 0.0));
            // R = I - (1 + e) u n^T on the velocities: n^T v the compression rate, u the velocities' change per
            // unit of it
            std::vector<double> u(static_cast<size_t>(n), 0.0), nn(static_cast<size_t>(n), 0.0);
            u[static_cast<size_t>(cx.v + ct.i)] = ct.sign * mu / mi;
            nn[static_cast<size_t>(cx.v + ct.i)] = ct.sign;
            if (ct.j >= 0) {
                u[static_cast<size_t>(cx.v + ct.j)] = -ct.sign * mu / mj;
                nn[static_cast<size_t>(cx.v + ct.j)] = -ct.sign;
            }
            Mat reset = Mat::Identity(n, n);
            for (int r = 0; r < n; ++r)
                for (int q = 0; q < n; ++q) reset(r, q) -= (1.0 + restitution) * u[static_cast<size_t>(r)] * nn[static_cast<size_t>(q)];
            add_rel(grad, 0, ct.i, ct.j, ct.sign);
            double rate = 0.0;
            for (int q = 0; q < n; ++q) rate += grad[static_cast<size_t>(q)] * f_before[static_cast<size_t>(q)];
            if (!(rate > 0.0)) {  // (met at rest or grazing: no saltation)
                x_end.assign(xa.begin(), xa.begin() + pub);
                return e;
            }
            std::vector<double> xr(xa);
            for (int r = 0; r < n; ++r) {
                double sum = 0.0;
                for (int q = 0; q < n; ++q) sum += reset(r, q) * xa[static_cast<size_t>(q)];
                xr[static_cast<size_t>(r)] = sum;
            }
            // the mode after it: the same stop free (or held), an element's slipping springs stopped by the jump
            next = st;
            to_state(sy, cx, xr, next.data());
            if (holds) {
                next[sy.lay.in_at(index)] = 1.0;
                next[sy.lay.def_at(index)] = 0.0;
            }
            run_parts::after_velocity_jump(next.data(), sy);
            const Mat a_after = mode(sy, cx, next.data(), omega, amp);
            const std::vector<double> f_after = matvec(a_after, xr);
            std::vector<double> rf(static_cast<size_t>(n), 0.0);  // R f-
            for (int r = 0; r < n; ++r)
                for (int q = 0; q < n; ++q) rf[static_cast<size_t>(r)] += reset(r, q) * f_before[static_cast<size_t>(q)];
            Mat jump = reset;
            for (int r = 0; r < n; ++r)
                for (int q = 0; q < n; ++q)
                    jump(r, q) += (f_after[static_cast<size_t>(r)] - rf[static_cast<size_t>(r)]) * grad[static_cast<size_t>(q)] / rate;
            jac = (jump * jac).eval();
            xa = xr;
            st = next;
            a = a_after;
            continue;
        }
        if (action == ACT_CONTACT || action == ACT_RELEASE) {
            const Contact& ct = sy.contact[static_cast<size_t>(index)];
            const MemoryBranch b = branch_of(sy, index, st.data());
            const int nm = cx.memory(sy, index), at = cx.mem_at[static_cast<size_t>(index)];
            double* z_next = next.data() + sy.lay.z_at(index);
            if (action == ACT_CONTACT) {  // sign (x_i - x_j) - gap reaches the (relaxing) compression
                // (a law with memory and no damping may rest compressed, where its force fell to zero: that
                // depth's own perturbation is not followed here)
                if (nm > 0 && !(b.c > 0.0) && !law_forgets_on_release(ct.law) && st[sy.lay.def_at(index)] > 0.0)
                    return -2 - e;
                add_rel(grad, 0, ct.i, ct.j, ct.sign);
                if (b.c > 0.0) grad[static_cast<size_t>(cx.def + index)] = -1.0;
                next[sy.lay.in_at(index)] = 1.0;
                law_contact_state(ct.law, ct.p, 0.0, z_next, next[sy.lay.def_at(index)]);
            } else {  // the force falls to 0
                add_rel(grad, 0, ct.i, ct.j, ct.sign * b.k);
                add_rel(grad, cx.v, ct.i, ct.j, ct.sign * b.c);
                for (int q = 0; q < nm; ++q) grad[static_cast<size_t>(at + q)] = b.g[q];
                next[sy.lay.in_at(index)] = 0.0;
                law_release_state(ct.law, ct.p, z_next, next[sy.lay.def_at(index)]);
            }
        } else if (action == ACT_LAW_BRANCH && sy.has_b && law_is_linear(sy.contact[static_cast<size_t>(index)].law)) {
            // a contact law's branch: the compression at an edge of its branch (which the law's memory may
            // move), or its rate through zero on a branch that ends there (a turn).  Which of them, from the rate
            // (the event table does not say): still at a turn (to the root's rounding: at most 1e-11 of the
            // motion's velocity scale, the table's amp / omega or the fastest mass's, over the random draws of
            // tests/test_law_monodromy.py), moving at an edge (2e-3 of it at least there); the bound between them
            // is 1e-6 of it (the scale at least the gap times omega: a table at rest).  Refused, never taken for
            // the other: an edge met still (a grazing of the edge), an event met moving away from every edge, one
            // met still, away from an edge, on a law that cannot turn
            const Contact& ct = sy.contact[static_cast<size_t>(index)];
            const double d = st[sy.lay.def_at(index)], dd = compression_rate(sy, st.data(), index);
            const double* z = st.data() + sy.lay.z_at(index);
            // the branch before the event: the one the compression leaves (at an edge, the law's ties take the
            // branch the rate goes to)
            const int j = law_memory_branch(ct.law, ct.p, d, -dd, z, true).j;
            const Edges edges = law_branch_edges(ct.law, ct.p, j, z);
            const auto at_edge = [&](double edge) {
                return edge >= 0.0 && std::abs(d - edge) <= 1e-7 * edge + 64.0 * ROUNDING * ct.gap;
            };
            double v_scale = std::max(amp != 0.0 ? std::abs(amp) / omega : 0.0, ct.gap * omega);
            for (int i = 0; i < sy.n; ++i) v_scale = std::max(v_scale, std::abs(st[sy.lay.v + i]));
            const bool still = std::abs(dd) <= BRANCH_TURN_RATE * v_scale;
            const bool up = at_edge(edges.upper), down = at_edge(edges.lower);
            double code = 0.0, dedge[MAX_LAW_MEMORY];
            if (!still && (up || down)) {  // d - edge(m)
                code = up ? EDGE_UP_STATE : EDGE_DOWN_STATE;
                grad[static_cast<size_t>(cx.def + index)] = 1.0;
                law_edge_memory(ct.law, ct.p, j, z, up, dedge);
                const int at = cx.mem_at[static_cast<size_t>(index)];
                for (int q = 0; q < cx.memory(sy, index); ++q) grad[static_cast<size_t>(at + q)] = -dedge[q];
            } else if (still && !(up || down) && law_turn_sign(ct.law, ct.p, z) != 0.0) {  // d' through zero
                add_rel(grad, cx.v, ct.i, ct.j, ct.sign);
            } else {
                return -2 - e;  // (neither, or both: not an event this propagation can take)
            }
            law_after_event(ct.law, ct.p, next.data() + sy.lay.z_at(index), d, code);
        } else if (action == ACT_SLIP) {
            // a stick's end (its tie's force at mu W) or the start's slip: the slip begins from the force's
            // balance, the pair's relative acceleration zero on both sides, so the field goes on continuous (no
            // saltation, as a held stop's release); the way it slips is that of the threshold the tie's force is at
            std::vector<double> q(static_cast<size_t>(sy.n)), row(static_cast<size_t>(sy.lay.sample_cols()));
            Sticking stk;
            std::vector<double> ag(static_cast<size_t>(sy.n));
            for (int i = 0; i < sy.n; ++i)
                ag[static_cast<size_t>(i)] = sy.infl[static_cast<size_t>(2 * i)] * (amp * xa[static_cast<size_t>(n)]);
            const double d = run_parts::tie_force(st.data(), sy, index, stk, ag.data(), q.data(), row.data());
            iso_transition(sy, next.data(), ACT_SLIP, index, friction_threshold_way(sy, st.data(), index, d));
            st = next;
            a = mode(sy, cx, st.data(), omega, amp);
            continue;
        } else if (action == ACT_STICK) {  // a friction slip at rest, held: the guard its pair's velocity
            const Hysteretic& h = sy.hyst[static_cast<size_t>(index)];
            add_rel(grad, cx.v, h.i, h.j, 1.0);
            iso_transition(sy, next.data(), ACT_STICK, index, 0.0);
        } else if (action == ACT_YIELD || action == ACT_REVERSAL || action == ACT_REGION) {
            const IsoGuard g = iso_guard(sy, action, index, st.data(), xa.data() + cx.v, f_before.data() + cx.v);
            const Hysteretic& h = sy.hyst[static_cast<size_t>(g.e)];
            add_rel(grad, 0, h.i, h.j, g.du);
            add_rel(grad, cx.v, h.i, h.j, g.dv);
            if (g.slip >= 0) grad[static_cast<size_t>(cx.slip + g.slip)] = -1.0;
            iso_transition(sy, next.data(), action, index, g.dir);
        } else if (action == ACT_SURFACE_SLIP || action == ACT_RING || action == ACT_RING_OFF) {
            // a series's surface starts to slip, or one slipping meets its ring or leaves a stiff one: the force
            // reaches where it happens (the held surfaces in it, a threshold's own surface's spring)
            const int e_of = iso_element_of_spring(sy, index);
            const Hysteretic& h = sy.hyst[static_cast<size_t>(e_of)];
            std::vector<double> d_surface(static_cast<size_t>(h.n_springs()));
            const IsoGuard g = series_guard(sy, action, index, st.data(), d_surface.data());
            add_rel(grad, 0, h.i, h.j, g.du);
            for (int q = 0; q < h.n_springs(); ++q) grad[static_cast<size_t>(cx.slip + h.first + q)] += d_surface[static_cast<size_t>(q)];
            iso_transition(sy, next.data(), action, index, g.dir);
        } else {
            return -2 - e;  // (a contact law's branch, a Bouc-Wen spring: no linear modes)
        }
        const Mat a_after = mode(sy, cx, next.data(), omega, amp);
        if (!saltation(grad, f_before, matvec(a_after, xa), jac)) {
            x_end.assign(xa.begin(), xa.begin() + pub);
            return e;
        }
        if (action == ACT_RELEASE && law_forgets_on_release(sy.contact[static_cast<size_t>(index)].law)) {
            const int at = cx.mem_at[static_cast<size_t>(index)];  // (its memory back to zero whatever it was)
            for (int q = 0; q < cx.memory(sy, index); ++q) jac.row(at + q).setZero();
        }
        if (action == ACT_CONTACT) {  // the compression is the depth (the relaxing surface's, met)
            const Contact& ct = sy.contact[static_cast<size_t>(index)];
            next[sy.lay.def_at(index)] = std::max(0.0, ct.sign * rel(next.data() + sy.lay.x, ct.i, ct.j) - ct.gap);
        }
        st = next;
        from_state(sy, cx, st.data(), xa);  // (a yield's slip put on its break)
        a = a_after;
    }
    x_end.assign(xa.begin(), xa.begin() + pub);
    return -1;
}
}  // namespace

int monodromy(const System& sy, const double* st0, const double* events, int n_events, double t_end, double omega,
              double amp, double phase, Mat& jac, std::vector<double>& x_end) {
    const int out = propagated(sy, st0, events, n_events, t_end, omega, amp, phase, jac, x_end);
    jac = jac.topRows(monodromy_size(sy)).eval();  // (the laws' memory left out)
    return out;
}

}  // namespace pounding
