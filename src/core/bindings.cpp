// The module pounding._pounding_core: the compiled core's one door, which pounding/_core.py wraps.  Plain
// numbers and NumPy arrays in and out; every run releases the GIL and polls the run control array.
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/tuple.h>
#include <nanobind/stl/vector.h>

#include <algorithm>
#include <initializer_list>
#include <utility>
#include <cstring>
#include <vector>

#include "core.hpp"
#include "events.hpp"
#include "laws.hpp"
#include "monodromy.hpp"
#include "run.hpp"
#include "spectrum.hpp"
#include "step.hpp"

namespace nb = nanobind;
using namespace pounding;

namespace {

using Vec = nb::ndarray<const double, nb::ndim<1>, nb::c_contig, nb::device::cpu>;
using Mat2 = nb::ndarray<const double, nb::ndim<2>, nb::c_contig, nb::device::cpu>;
using OutVec = nb::ndarray<double, nb::ndim<1>, nb::c_contig, nb::device::cpu>;
using OutMat = nb::ndarray<double, nb::ndim<2>, nb::c_contig, nb::device::cpu>;
using Ctl = nb::ndarray<int64_t, nb::ndim<1>, nb::c_contig, nb::device::cpu>;
using Array1 = nb::ndarray<nb::numpy, double, nb::ndim<1>>;
using Array2 = nb::ndarray<nb::numpy, double, nb::ndim<2>>;

// a NumPy array owning a copy of ``values`` (shape (n,) or (rows, cols))
Array1 array1(const double* values, size_t n) {
    double* data = new double[n > 0 ? n : 1];
    if (n > 0) std::memcpy(data, values, n * sizeof(double));
    nb::capsule owner(data, [](void* p) noexcept { delete[] static_cast<double*>(p); });
    return Array1(data, {n}, owner);
}

Array2 array2(const double* values, size_t rows, size_t cols) {
    const size_t n = rows * cols;
    double* data = new double[n > 0 ? n : 1];
    if (n > 0) std::memcpy(data, values, n * sizeof(double));
    nb::capsule owner(data, [](void* p) noexcept { delete[] static_cast<double*>(p); });
    return Array2(data, {rows, cols}, owner);
}

// a NumPy array that takes over the rows' buffer (no copy: a long run's tables are most of its memory)
Array2 rows_array(Rows& r) {
    const size_t rows = static_cast<size_t>(r.n), cols = static_cast<size_t>(r.cols);
    double* owned = r.release();
    nb::capsule owner(owned, [](void* p) noexcept { std::free(p); });
    return Array2(owned, {rows, cols}, owner);
}

// a contact from (i, j, sign, gap, law, params); a hysteretic element from (i, j, c_d, slopes, breaks, rule)
using ContactTuple = std::tuple<int, int, double, double, int, std::vector<double>>;
using ElementTuple = std::tuple<int, int, double, std::vector<double>, std::vector<double>, int>;
using SystemState = std::tuple<int, std::vector<double>, std::vector<double>, std::vector<double>,
                               std::vector<ElementTuple>, std::vector<double>, bool, std::vector<ContactTuple>,
                               std::vector<int>, std::vector<int>>;

SystemState system_state(const System& s) {
    std::vector<ContactTuple> cs;
    for (const Contact& c : s.contact)
        cs.emplace_back(c.i, c.j, c.sign, c.gap, c.law, std::vector<double>(c.p, c.p + N_LAW_PARAMS));
    std::vector<ElementTuple> es;
    for (const Hysteretic& h : s.hyst) es.emplace_back(h.i, h.j, h.c_d, h.slopes, h.breaks, h.rule);
    return {s.n, s.mass, s.k0, s.c0, es, std::vector<double>(s.bw, s.bw + BW_PARAMS), s.has_b, cs, s.track_i,
            s.track_j};
}

// (the sizes and indices are checked in Python, pounding._core.system: the core trusts its inputs)
void fill_system(System& s, const SystemState& st) {
    s.n = std::get<0>(st);
    s.mass = std::get<1>(st);
    s.k0 = std::get<2>(st);
    s.c0 = std::get<3>(st);
    s.hyst.clear();
    for (const ElementTuple& t : std::get<4>(st)) {
        Hysteretic h;
        h.i = std::get<0>(t);
        h.j = std::get<1>(t);
        h.c_d = std::get<2>(t);
        h.slopes = std::get<3>(t);
        h.breaks = std::get<4>(t);
        h.rule = std::get<5>(t);
        s.hyst.push_back(h);
    }
    const std::vector<double>& bw = std::get<5>(st);
    for (int j = 0; j < BW_PARAMS; ++j) s.bw[j] = j < static_cast<int>(bw.size()) ? bw[j] : 0.0;
    s.has_b = std::get<6>(st);
    s.contact.clear();
    for (const ContactTuple& t : std::get<7>(st)) {
        Contact c;
        c.i = std::get<0>(t);
        c.j = std::get<1>(t);
        c.sign = std::get<2>(t);
        c.gap = std::get<3>(t);
        c.law = std::get<4>(t);
        const std::vector<double>& p = std::get<5>(t);
        for (int j = 0; j < N_LAW_PARAMS; ++j) c.p[j] = j < static_cast<int>(p.size()) ? p[j] : 0.0;
        s.contact.push_back(c);
    }
    s.track_i = std::get<8>(st);
    s.track_j = std::get<9>(st);
    s.finish();
}

Forcing forcing_of(int kind, Vec p, Vec rec_t, Vec rec_a) {
    Forcing f;
    f.kind = kind;
    for (int j = 0; j < 3; ++j) f.p[j] = j < static_cast<int>(p.shape(0)) ? p(j) : 0.0;
    f.rec_t = rec_t.data();
    f.rec_a = rec_a.data();
    f.n_rec = static_cast<int64_t>(rec_t.shape(0));
    return f;
}

}  // namespace

NB_MODULE(_pounding_core, m) {
    m.doc() = "pounding's compiled core (C++17): the event-driven engine and its kernels.";

    nb::class_<System>(m, "System")
        .def("__init__",
             [](System* s, int n, const std::vector<double>& mass, const std::vector<double>& k0,
                const std::vector<double>& c0, const std::vector<ElementTuple>& elements,
                const std::vector<double>& bw, bool has_b, const std::vector<ContactTuple>& contacts,
                const std::vector<int>& track_i, const std::vector<int>& track_j) {
                 new (s) System();
                 fill_system(*s, SystemState{n, mass, k0, c0, elements, bw, has_b, contacts, track_i, track_j});
             })
        .def_ro("n", &System::n)
        .def_ro("mass", &System::mass)
        .def_prop_ro("n_elements", &System::n_h)
        .def_ro("has_b", &System::has_b)
        .def_prop_ro("state_size", &System::state_size)
        .def_prop_ro("layout", [](const System& s) {
            nb::dict d;
            d["x"] = s.lay.x;
            d["v"] = s.lay.v;
            d["def"] = s.lay.def;
            d["in"] = s.lay.in;
            d["region"] = s.lay.region;
            d["acc"] = s.lay.acc;
            d["z"] = s.lay.z;
            d["zeta"] = s.lay.zeta;
            d["base"] = s.lay.base;
            d["n_springs"] = s.lay.n_sp;
            d["size"] = s.lay.size;
            d["sample_cols"] = s.lay.sample_cols();
            return d;
        })
        .def("__getstate__", [](const System& s) { return system_state(s); })
        .def("__setstate__", [](System& s, const SystemState& st) {
            new (&s) System();
            fill_system(s, st);
        });

    m.def("run",
          [](const System& sy, int kind, Vec p, Vec rec_t, Vec rec_a, Vec state0, double t_end, double sample_dt,
             double rtol, int64_t max_events, bool with_energy, Ctl ctl) {
              const Forcing fo = forcing_of(kind, p, rec_t, rec_a);
              RunOptions opt;
              opt.t_end = t_end;
              opt.sample_dt = sample_dt;
              opt.rtol = rtol;
              opt.max_events = max_events;
              opt.with_energy = with_energy;
              RunResult out;
              {
                  nb::gil_scoped_release release;
                  // each thread keeps its last system's buffers and transitions for its next run
                  thread_local RunWorkspace workspace;
                  run_kernel(sy, fo, state0.data(), opt, ctl.data(), out, &workspace);
              }
              return nb::make_tuple(array1(out.state.data(), out.state.size()), rows_array(out.samples),
                                    rows_array(out.contacts), rows_array(out.events),
                                    array1(out.ledger, LEDGER_LEN), array1(out.extrema.data(), out.extrema.size()),
                                    out.status, rows_array(out.chatters));
          },
          nb::arg("system"), nb::arg("kind"), nb::arg("p"), nb::arg("rec_t"), nb::arg("rec_a"), nb::arg("state0"),
          nb::arg("t_end"), nb::arg("sample_dt"), nb::arg("rtol"), nb::arg("max_events"), nb::arg("with_energy"),
          nb::arg("ctl"));

    m.def("step",
          [](const System& sy, double amp, double omega, Vec state0, bool adaptive, int n_cycles, int measure_cycles,
             double steady_rtol, int max_period, double rtol, int64_t max_events, Ctl ctl) {
              const Steady steady{adaptive, n_cycles, measure_cycles, steady_rtol, max_period};
              StepResult out;
              {
                  nb::gil_scoped_release release;
                  step_kernel(sy, amp, omega, state0.data(), steady, rtol, max_events, ctl.data(), out);
              }
              return nb::make_tuple(array1(out.state.data(), out.state.size()), out.cycles_run, out.period_multiple,
                                    array1(out.window.data(), out.window.size()),
                                    array1(out.window_state.data(), out.window_state.size()),
                                    array2(out.strobes.data(), out.strobes.size() / 2, 2), out.status);
          });

    m.def("periodicity", [](Mat2 strobe, Mat2 cyc, int n, int window, int max_period, double steady_rtol, double omega,
                            bool round_window) {
        int k = 0, mm = 0;
        periodicity(strobe.data(), static_cast<int>(strobe.shape(1)), cyc.data(), n, window, max_period, steady_rtol,
                    omega, round_window, 1, k, mm);
        return nb::make_tuple(k, mm);
    });

    m.def("impact_row", [](Vec contact, double mass, OutVec out) { impact_row(contact.data(), mass, out.data()); });

    m.def("law_force_many", [](int law, Vec p, Vec d, Vec dd, OutVec out) {
        double params[N_LAW_PARAMS] = {0};
        for (int j = 0; j < N_LAW_PARAMS && j < static_cast<int>(p.shape(0)); ++j) params[j] = p(j);
        law_force_many(law, params, d.data(), dd.data(), out.data(), static_cast<int64_t>(d.shape(0)));
    });

    m.def("spectrum", [](Vec t, Vec acc, Vec omegas, double zeta, OutMat out, Ctl ctl) {
        int status;
        {
            nb::gil_scoped_release release;
            status = spectrum_kernel(t.data(), acc.data(), static_cast<int64_t>(t.shape(0)), omegas.data(),
                                     static_cast<int64_t>(omegas.shape(0)), zeta, out.data(), ctl.data());
        }
        return status;
    });

    m.def("monodromy", [](const System& sy, Vec st0, Mat2 events, double t_end, double omega, double amp,
                          double phase) {
        Mat jac;
        std::vector<double> x_end;
        const int bad = monodromy(sy, st0.data(), events.data(), static_cast<int>(events.shape(0)), t_end, omega,
                                  amp, phase, jac, x_end);
        return nb::make_tuple(array2(jac.a.data(), jac.rows, jac.cols), array1(x_end.data(), x_end.size()), bad);
    });

    // the event locator's numerics, for the tests
    m.def("root_guess", &root_guess);
    m.def("value_at_root", &value_at_root);

    m.def("expm", [](Mat2 a) {
        Mat x(static_cast<int>(a.shape(0)), static_cast<int>(a.shape(1)));
        std::memcpy(x.a.data(), a.data(), x.a.size() * sizeof(double));
        const Mat e = expm(x);
        return array2(e.a.data(), e.rows, e.cols);
    });

    // the state vector's layout and the outputs' columns, as the core writes them: what Python reads them by
    nb::dict layout;
    // the state's offsets and the outputs' columns of a one-mass system with its two contact slots (the left
    // and the right bumper); a system's own: System.layout
    const Layout one(1, 2, 1, 0);
    layout["T"] = T;
    layout["D"] = one.x;
    layout["V"] = one.v;
    layout["DEF"] = one.def;
    layout["IN"] = one.in;
    layout["REGION"] = one.region;
    layout["ACC"] = one.acc;
    layout["N_ACC"] = N_ACC;
    layout["A_TSTART"] = A_TSTART;
    layout["A_VIN"] = A_VIN;
    layout["A_DSTART"] = A_DSTART;
    layout["A_IMPULSE"] = A_IMPULSE;
    layout["A_PEAK"] = A_PEAK;
    layout["A_MAXCOMP"] = A_MAXCOMP;
    layout["A_WORK"] = A_WORK;
    layout["Z"] = one.z;
    layout["ZETA"] = one.zeta;
    layout["STATE_BASE"] = one.base;
    layout["N_CONTACTS"] = one.nc;
    layout["N_LAW_STATE"] = N_LAW_STATE;
    layout["N_LAW_PARAMS"] = N_LAW_PARAMS;
    layout["BW_PARAMS"] = BW_PARAMS;
    layout["SAMPLE_COLS"] = one.sample_cols();
    layout["CONTACT_COLS"] = static_cast<int>(CONTACT_COLS);
    layout["DOF_EXTREMA"] = static_cast<int>(DOF_EXTREMA);
    layout["PAIR_EXTREMA"] = static_cast<int>(PAIR_EXTREMA);
    layout["EVENT_COLS"] = EVENT_COLS;
    layout["LEDGER_LEN"] = static_cast<int>(LEDGER_LEN);
    layout["WINDOW_COLS"] = WINDOW_COLS;
    layout["CYCLE_COLS"] = CYCLE_COLS;
    layout["SIDE_SUMS"] = SIDE_SUMS;
    layout["N_IMPACT"] = N_IMPACT;
    layout["CTL_LEN"] = CTL_LEN;
    // a step's per-cycle record and window (step.hpp), and a contact side's sums within them
    layout["CY_DMAX"] = CY_DMAX;
    layout["CY_DMIN"] = CY_DMIN;
    layout["CY_AMAX"] = CY_AMAX;
    layout["CY_SUMS"] = CY_SUMS;
    layout["W_DMAX"] = W_DMAX;
    layout["W_DMIN"] = W_DMIN;
    layout["W_AMAX"] = W_AMAX;
    layout["W_CYCLES"] = W_CYCLES;
    layout["W_SUMS"] = W_SUMS;
    layout["S_COUNT"] = S_COUNT;
    layout["S_N_RESTITUTION"] = S_N_RESTITUTION;
    layout["S_SUMS"] = S_SUMS;
    m.attr("LAYOUT") = layout;
    // the outputs' columns and slots by name (core.hpp's enums): pounding._core reads them by these names
    const auto named = [](std::initializer_list<std::pair<const char*, int>> items) {
        nb::dict d;
        for (const auto& [name, index] : items) d[name] = index;
        return d;
    };
    m.attr("CONTACT_COLUMNS") = named({{"contact", CC_CONTACT}, {"t_start_s", CC_T_START}, {"t_end_s", CC_T_END},
                                       {"v_in_m_s", CC_V_IN}, {"v_out_m_s", CC_V_OUT}, {"impulse_n_s", CC_IMPULSE},
                                       {"peak_force_n", CC_PEAK_FORCE}, {"max_compression_m", CC_MAX_COMPRESSION},
                                       {"work_j", CC_WORK}});  // a contact table's columns
    m.attr("LEDGER") = named({{"input", L_INPUT}, {"viscous", L_VISCOUS}, {"hysteretic", L_HYSTERETIC},
                              {"bumper_loss", L_BUMPER_LOSS}, {"kinetic", L_KINETIC}, {"isolator", L_ISOLATOR},
                              {"bumper", L_BUMPER}});  // the energy ledger's slots
    m.attr("DOF_EXTREMA") = named({{"d_max", EX_D_MAX}, {"d_max_t", EX_D_MAX_T}, {"d_min", EX_D_MIN},
                                   {"d_min_t", EX_D_MIN_T}, {"a_abs_max", EX_A_ABS_MAX},
                                   {"a_abs_max_t", EX_A_ABS_MAX_T}, {"a_at_max", EX_A_AT_MAX}});  // a dof's
    m.attr("PAIR_EXTREMA") = named({{"max", PX_MAX}, {"max_t", PX_MAX_T}, {"min", PX_MIN},
                                    {"min_t", PX_MIN_T}});  // a tracked pair's (a storey's drift)
    m.attr("EXCITATION") = named({{"harmonic", EXC_HARMONIC}, {"record", EXC_RECORD}});  // the forcing's kinds
    nb::dict laws;  // each law's id: the Python dataclasses' LAW_ID (tests/test_core.py holds them equal)
    laws["kelvin_voigt"] = static_cast<int>(KELVIN_VOIGT);
    laws["hunt_crossley"] = static_cast<int>(HUNT_CROSSLEY);
    laws["jankowski"] = static_cast<int>(JANKOWSKI);
    laws["multilinear"] = static_cast<int>(MULTILINEAR);
    laws["elastic_plastic"] = static_cast<int>(ELASTIC_PLASTIC);
    laws["hertzdamp"] = static_cast<int>(HERTZDAMP);
    laws["multilinear_kinematic"] = static_cast<int>(MULTILINEAR_KINEMATIC);
    laws["rigid"] = static_cast<int>(RIGID);
    m.attr("LAW_IDS") = laws;
    nb::dict status;  // how a run ended: pounding.Status (tests/test_core.py holds them equal)
    status["SUCCESS"] = static_cast<int>(SUCCESS);
    status["ZENO"] = static_cast<int>(ZENO);
    status["MAX_EVENTS"] = static_cast<int>(MAX_EVENTS);
    status["STEP_FAILED"] = static_cast<int>(STEP_FAILED);
    status["INTERRUPTED"] = static_cast<int>(INTERRUPTED);
    status["BUDGET"] = static_cast<int>(BUDGET);
    status["NONFINITE"] = static_cast<int>(NONFINITE);
    m.attr("STATUS") = status;
    nb::dict actions;  // the events' actions: an event table's second column
    actions["yield"] = static_cast<int>(ACT_YIELD);
    actions["reversal"] = static_cast<int>(ACT_REVERSAL);
    actions["branch"] = static_cast<int>(ACT_REGION);
    actions["contact_start"] = static_cast<int>(ACT_CONTACT);
    actions["contact_end"] = static_cast<int>(ACT_RELEASE);
    actions["bumper_branch"] = static_cast<int>(ACT_LAW_BRANCH);
    actions["bouc_wen_zero"] = static_cast<int>(ACT_BOUC_WEN);
    m.attr("ACTIONS") = actions;
    m.attr("N_LAW_STATE") = N_LAW_STATE;
    m.attr("N_LAW_PARAMS") = N_LAW_PARAMS;
    m.attr("WINDOW_COLS") = WINDOW_COLS;
    m.attr("CYCLE_COLS") = CYCLE_COLS;
    m.attr("SIDE_SUMS") = SIDE_SUMS;
}
