#include "step.hpp"

#include <algorithm>
#include <cstddef>
#include <cmath>

#include "laws.hpp"

namespace pounding {

namespace {
constexpr double AMPLITUDE_FLOOR_M = 1e-12;
// strobe differences below this fraction of the amplitude are rounding noise
constexpr double STROBE_NOISE = 1e-12;
constexpr int C_SIDE = 0, C_TSTART = 1, C_TEND = 2, C_VIN = 3, C_VOUT = 4, C_IMPULSE = 5, C_PEAK = 6, C_WORK = 8;

// a strobe row: the displacements (n_dof), the velocities (n_dof), then lengths (slips, law states, z)
double strobe_distance(const double* strobe, int cols, int a, int b, double tol_d, double tol_v, int n_dof) {
    const double* ra = strobe + static_cast<size_t>(a) * cols;
    const double* rb = strobe + static_cast<size_t>(b) * cols;
    double dist = 0.0;
    for (int q = 0; q < cols; ++q) {
        const bool velocity = q >= n_dof && q < 2 * n_dof;
        dist = std::max(dist, std::abs(ra[q] - rb[q]) / (velocity ? tol_v : tol_d));
    }
    return dist;
}

double window_distance(const double* strobe, int cols, int n, int k, int first, int last, double tol_d, double tol_v,
                       int n_dof) {
    double out = 0.0;
    for (int j = first; j < last; ++j)
        out = std::max(out, strobe_distance(strobe, cols, n - 1 - j, n - 1 - j - k, tol_d, tol_v, n_dof));
    return out;
}

void smallest_period(const double* strobe, int cols, int n, int k, int window, bool round_window, double tol_d,
                     double tol_v, double steady_rtol, int n_dof, int& p_out, int& m_out) {
    const double loose = std::max(1.0, std::min(100.0, 1e-2 / steady_rtol));
    for (int p = 1; p < k; ++p) {
        if (k % p != 0) continue;
        const int m = round_window ? p * ((window + p - 1) / p) : window;
        bool ok = n >= m + p;
        for (int j = 0; ok && j < m; ++j)
            ok = strobe_distance(strobe, cols, n - 1 - j, n - 1 - j - p, tol_d, tol_v, n_dof) <= loose;
        if (ok) {
            p_out = p;
            m_out = m;
            return;
        }
    }
    p_out = k;
    m_out = round_window ? k * ((window + k - 1) / k) : window;
}
}  // namespace

void impact_row(const double* contact, double mass, double* out) {
    const double v_in = contact[C_VIN], v_out = contact[C_VOUT];
    const double dt = contact[C_TEND] - contact[C_TSTART];
    out[0] = v_in != 0.0 ? -v_out / v_in : NaN;
    out[1] = dt;
    out[2] = contact[C_IMPULSE];
    out[3] = dt > 0.0 ? contact[C_IMPULSE] / dt : NaN;
    out[4] = contact[C_PEAK];
    out[5] = 0.5 * mass * (v_in * v_in - v_out * v_out);
    out[6] = contact[C_WORK];
}

void add_impacts(const Rows& contacts, double mass, double* sums) {
    double vals[N_IMPACT];
    for (int64_t i = 0; i < contacts.n; ++i) {
        const double* c = contacts.row(i);
        if (std::isnan(c[C_TEND])) continue;  // still going on: counted by the run that sees it end
        impact_row(c, mass, vals);
        const int side = static_cast<int>(c[C_SIDE]);
        if (side > 1) continue;  // (a sweep's metrics: the first two contact slots, a one-mass system's bumpers)
        const int base = side * SIDE_SUMS;
        sums[base + S_COUNT] += 1.0;
        for (int j = 0; j < N_IMPACT; ++j) {
            if (j == 0 && std::isnan(vals[j])) continue;
            if (j == 0) sums[base + S_N_RESTITUTION] += 1.0;
            sums[base + S_SUMS + j] += vals[j];
        }
    }
}

void periodicity(const double* strobe, int cols, const double* cyc, int n, int window, int max_period,
                 double steady_rtol, double omega, bool round_window, int n_dof, int& k_out, int& m_out) {
    double amp = AMPLITUDE_FLOOR_M;
    for (int j = std::max(0, n - window); j < n; ++j)
        amp = std::max(amp, 0.5 * (cyc[static_cast<size_t>(j) * CYCLE_COLS + CY_DMAX] -
                                   cyc[static_cast<size_t>(j) * CYCLE_COLS + CY_DMIN]));
    const double tol_d = steady_rtol * amp;
    const double tol_v = tol_d * omega;
    for (int k = 1; k <= max_period; ++k) {
        const int m = round_window ? k * ((window + k - 1) / k) : window;
        if (n < 2 * m + k) continue;
        const double recent = window_distance(strobe, cols, n, k, 0, m, tol_d, tol_v, n_dof);
        if (recent > 1.0) continue;
        if (recent * steady_rtol <= STROBE_NOISE) {  // rounding noise: converged
            smallest_period(strobe, cols, n, k, window, round_window, tol_d, tol_v, steady_rtol, n_dof, k_out, m_out);
            return;
        }
        const double older = window_distance(strobe, cols, n, k, m, 2 * m, tol_d, tol_v, n_dof);
        const double ratio = older > 0.0 ? recent / older : 0.0;
        if (ratio >= 1.0) continue;
        if (recent <= 1.0 - std::pow(ratio, static_cast<double>(k) / m)) {
            smallest_period(strobe, cols, n, k, window, round_window, tol_d, tol_v, steady_rtol, n_dof, k_out, m_out);
            return;
        }
    }
    k_out = 0;
    m_out = window;
}

void step_kernel(const System& sy, double amp, double omega, const double* state0, const Steady& steady, double rtol,
                 int64_t max_events, int64_t* ctl, StepResult& out) {
    const double period = TWO_PI / omega;
    const double t0 = state0[T];
    Forcing fo;
    fo.kind = EXC_HARMONIC;
    fo.p[0] = amp;
    fo.p[1] = omega;
    fo.p[2] = -(omega * t0);  // A(t0) = 0 exactly: phase 0 at the step's start
    const Layout& L = sy.lay;
    const int n_state = sy.state_size();
    const int n_sp = sy.n_springs();
    const int nd = sy.n, nc = sy.nc();
    const int n_cycles = steady.n_cycles;
    const int nz = std::max(1, sy.n_bw());
    const int cols = 2 * nd + n_sp + nc * N_LAW_STATE + nz;  // x, v, the slips, the bumpers' law states, z
    std::vector<double> strobe(static_cast<size_t>(n_cycles) * cols);
    std::vector<double> starts(static_cast<size_t>(n_cycles) * n_state);
    std::vector<double> cyc(static_cast<size_t>(n_cycles) * CYCLE_COLS, 0.0);
    std::vector<double> st(state0, state0 + n_state);
    int status = SUCCESS;
    int n = 0, k = 0, m = steady.measure_cycles;
    RunOptions opt;
    opt.sample_dt = -1.0;
    opt.rtol = rtol;
    opt.max_events = max_events;
    opt.with_energy = false;  // a step measures extrema and contacts, not the ledger
    std::vector<char> memory(static_cast<size_t>(nc));
    for (int c = 0; c < nc; ++c) memory[static_cast<size_t>(c)] = law_has_memory(sy.contact[static_cast<size_t>(c)].law);
    RunResult run;  // (its buffers, and the phases' transitions, kept from cycle to cycle)
    RunWorkspace workspace;
    while (n < n_cycles) {
        std::copy(st.begin(), st.end(), starts.begin() + static_cast<std::ptrdiff_t>(n) * n_state);
        opt.t_end = t0 + (n + 1) * period;
        run_kernel(sy, fo, st.data(), opt, ctl, run, &workspace);
        st = run.state;
        status = run.status;
        double* cy = &cyc[static_cast<size_t>(n) * CYCLE_COLS];
        cy[CY_DMAX] = run.extrema[EX_D_MAX];  // (the first dof's: the isolated mass)
        cy[CY_DMIN] = run.extrema[EX_D_MIN];
        cy[CY_AMAX] = run.extrema[EX_A_ABS_MAX];
        add_impacts(run.contacts, sy.mass[0], cy + CY_SUMS);
        cy[CY_EVENTS] = static_cast<double>(run.events.n);
        if (!sy.ties.empty())  // (sticks: a friction isolator's only)
            for (int64_t e = 0; e < run.events.n; ++e)
                cy[CY_STICKS] += run.events.row(e)[EC_ACTION] == static_cast<double>(ACT_STICK) ? 1.0 : 0.0;
        double* sb = &strobe[static_cast<size_t>(n) * cols];
        for (int q = 0; q < 2 * nd; ++q) sb[q] = st[L.x + q];
        for (int q = 0; q < n_sp; ++q) sb[2 * nd + q] = st[L.base + q];
        // a hysteretic bumper's state is memory as the slips are; a stateless law's is 0
        for (int c = 0; c < nc; ++c)
            for (int q = 0; q < N_LAW_STATE; ++q)
                sb[2 * nd + n_sp + c * N_LAW_STATE + q] = memory[static_cast<size_t>(c)] ? st[L.z_at(c) + q] : 0.0;
        sb[cols - nz] = 0.0;
        for (int q = 0; q < sy.n_bw(); ++q)  // (each Bouc-Wen z as a length)
            sb[cols - nz + q] = st[L.zeta + q] * sy.bw_of(q).bw[1];
        n += 1;
        if (status != SUCCESS) break;
        if (steady.adaptive) {
            periodicity(strobe.data(), cols, cyc.data(), n, steady.measure_cycles, steady.max_period, steady.steady_rtol,
                        omega, steady.adaptive, nd, k, m);
            if (k > 0) break;
        }
    }
    if (!steady.adaptive || k == 0)
        periodicity(strobe.data(), cols, cyc.data(), n, steady.measure_cycles, steady.max_period, steady.steady_rtol,
                    omega, steady.adaptive && k > 0, nd, k, m);
    m = std::min(m, n);
    out.window.assign(WINDOW_COLS, 0.0);
    out.window[W_DMAX] = -INF;
    out.window[W_DMIN] = INF;
    out.window[W_CYCLES] = m;
    for (int j = n - m; j < n; ++j) {
        const double* cy = &cyc[static_cast<size_t>(j) * CYCLE_COLS];
        out.window[W_DMAX] = std::max(out.window[W_DMAX], cy[CY_DMAX]);
        out.window[W_DMIN] = std::min(out.window[W_DMIN], cy[CY_DMIN]);
        out.window[W_AMAX] = std::max(out.window[W_AMAX], cy[CY_AMAX]);
        for (int q = 0; q < 2 * SIDE_SUMS; ++q) out.window[W_SUMS + q] += cy[CY_SUMS + q];
        out.window[W_EVENTS] += cy[CY_EVENTS];
        out.window[W_STICKS] += cy[CY_STICKS];
    }
    out.strobes.resize(static_cast<size_t>(m) * 2);
    for (int j = 0; j < m; ++j) {
        out.strobes[2 * j] = strobe[static_cast<size_t>(n - m + j) * cols];
        out.strobes[2 * j + 1] = strobe[static_cast<size_t>(n - m + j) * cols + nd];
    }
    out.state = st;
    out.cycles_run = n;
    out.period_multiple = k;
    out.window_state.assign(starts.begin() + static_cast<std::ptrdiff_t>(n - m) * n_state,
                            starts.begin() + static_cast<std::ptrdiff_t>(n - m + 1) * n_state);
    out.status = status;
}

}  // namespace pounding
