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
#include <stdexcept>
#include <vector>

#include "core.hpp"
#include "events.hpp"
#include "impact.hpp"
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

// a NumPy array owning a copy of several buffers, one after the other (each: its values, its length)
Array1 array1_of(std::initializer_list<std::pair<const double*, size_t>> parts) {
    size_t n = 0;
    for (const auto& part : parts) n += part.second;
    double* data = new double[n > 0 ? n : 1];
    size_t at = 0;
    for (const auto& part : parts) {
        if (part.second > 0) std::memcpy(data + at, part.first, part.second * sizeof(double));
        at += part.second;
    }
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

// a table's NumPy array, None without rows (the caller makes its empty array)
nb::object table(Rows& r) {
    return r.n > 0 ? nb::cast(rows_array(r)) : nb::none();
}

// A system enters by name: its contact slots (ContactSlot) and hysteretic elements (Element) built with keyword
// arguments, the System from them the same way; a pickle carries each by name too.  (The sizes and indices are
// checked in Python, pounding._core.system: the core trusts its inputs.)  A pair's levers (Pair) come apart:
// lever_i, arm_i_m, lever_j, arm_j_m (-1 and 0: none).
void set_levers(Pair& p, int lever_i, double arm_i, int lever_j, double arm_j) {
    p.set_levers(lever_i, arm_i, lever_j, arm_j);
}
void levers_state(nb::dict& d, const Pair& p) {
    d["lever_i"] = p.li;
    d["arm_i_m"] = p.ai;
    d["lever_j"] = p.lj;
    d["arm_j_m"] = p.aj;
}
void levers_from_state(Pair& p, const nb::dict& d) {
    if (!d.contains("lever_i")) return;  // (a pickle from before levers)
    set_levers(p, nb::cast<int>(d["lever_i"]), nb::cast<double>(d["arm_i_m"]), nb::cast<int>(d["lever_j"]),
               nb::cast<double>(d["arm_j_m"]));
}

// a tracked pair (its relative displacement's exact extrema): dof i against dof j or the ground, with levers
Pair tracked_of(int i, int j, int lever_i, double arm_i, int lever_j, double arm_j) {
    Pair p;
    p.i = i;
    p.j = j;
    set_levers(p, lever_i, arm_i, lever_j, arm_j);
    return p;
}
nb::dict tracked_state(const Pair& p) {
    nb::dict d;
    d["i"] = p.i;
    d["j"] = p.j;
    levers_state(d, p);
    return d;
}
Pair tracked_from_state(const nb::dict& d) {
    Pair p = tracked_of(nb::cast<int>(d["i"]), nb::cast<int>(d["j"]), -1, 0.0, -1, 0.0);
    levers_from_state(p, d);
    return p;
}

// a pair's levers as read-only fields of its Python class (a TrackedPair's, a ContactSlot's, an Element's)
template <class T>
void with_levers(nb::class_<T>& c) {
    c.def_ro("lever_i", &T::li).def_ro("arm_i_m", &T::ai).def_ro("lever_j", &T::lj).def_ro("arm_j_m", &T::aj);
}

Contact contact_of(int i, int j, double sign, double gap_m, int law, const std::vector<double>& params) {
    Contact c;
    c.i = i;
    c.j = j;
    c.sign = sign;
    c.gap = gap_m;
    c.law = law;
    for (int k = 0; k < N_LAW_PARAMS; ++k) c.p[k] = k < static_cast<int>(params.size()) ? params[k] : 0.0;
    return c;
}

Hysteretic element_of(int i, int j, double c_d, const std::vector<double>& slopes, const std::vector<double>& breaks,
                      int rule, double friction, double friction_fast, double friction_rate,
                      const std::vector<double>& surface_friction, const std::vector<double>& surface_ring,
                      const std::vector<double>& bw, int bw_mate, bool bw_plastic) {
    Hysteretic h;
    h.i = i;
    h.j = j;
    h.c_d = c_d;
    h.slopes = slopes;
    h.breaks = breaks;
    h.rule = rule;
    h.friction = friction;
    h.friction_fast = friction_fast;
    h.friction_rate = friction_rate;
    h.surface_friction = surface_friction;
    h.surface_ring = surface_ring;
    for (int k = 0; k < BW_PARAMS; ++k) h.bw[k] = k < static_cast<int>(bw.size()) ? bw[k] : 0.0;
    h.bw_mate = bw_mate;
    h.bw_plastic = bw_plastic;
    return h;
}

// a contact on a ring's wall (Radial): the point's pair along y, its place from the centre at rest, the radius
void set_ring(Contact& c, const Pair& y, double px, double py, double radius) {
    c.radial.on = true;
    c.radial.y = y;
    c.radial.px = px;
    c.radial.py = py;
    c.radial.radius = radius;
}

nb::dict contact_state(const Contact& c) {
    nb::dict d;
    d["i"] = c.i;
    d["j"] = c.j;
    d["sign"] = c.sign;
    d["gap_m"] = c.gap;
    d["law"] = c.law;
    d["params"] = std::vector<double>(c.p, c.p + N_LAW_PARAMS);
    levers_state(d, c);
    if (c.radial.on) {
        d["ring_y"] = tracked_state(c.radial.y);
        d["ring_px_m"] = c.radial.px;
        d["ring_py_m"] = c.radial.py;
        d["ring_radius_m"] = c.radial.radius;
    }
    return d;
}

Contact contact_from_state(const nb::dict& d) {
    Contact c = contact_of(nb::cast<int>(d["i"]), nb::cast<int>(d["j"]), nb::cast<double>(d["sign"]),
                           nb::cast<double>(d["gap_m"]), nb::cast<int>(d["law"]),
                           nb::cast<std::vector<double>>(d["params"]));
    levers_from_state(c, d);
    if (d.contains("ring_y")) {  // (a ring's wall: core.hpp's Radial)
        set_ring(c, tracked_from_state(nb::cast<nb::dict>(d["ring_y"])), nb::cast<double>(d["ring_px_m"]),
                 nb::cast<double>(d["ring_py_m"]), nb::cast<double>(d["ring_radius_m"]));
    }
    return c;
}

nb::dict element_state(const Hysteretic& h) {
    nb::dict d;
    d["i"] = h.i;
    d["j"] = h.j;
    d["c_d"] = h.c_d;
    d["slopes"] = h.slopes;
    d["breaks"] = h.breaks;
    d["rule"] = h.rule;
    d["friction_n"] = h.friction;
    d["friction_fast_n"] = h.friction_fast;
    d["friction_rate_s_m"] = h.friction_rate;
    d["surface_friction_n"] = h.surface_friction;
    d["surface_ring_n_m"] = h.surface_ring;
    d["bw"] = std::vector<double>(h.bw, h.bw + BW_PARAMS);
    d["bw_mate"] = h.bw_mate;
    if (h.bw_plastic) d["bw_plastic"] = true;  // (a plastic circle's; absent before it was one)
    levers_state(d, h);
    return d;
}

Hysteretic element_from_state(const nb::dict& d) {
    Hysteretic h = element_of(nb::cast<int>(d["i"]), nb::cast<int>(d["j"]), nb::cast<double>(d["c_d"]),
                      nb::cast<std::vector<double>>(d["slopes"]), nb::cast<std::vector<double>>(d["breaks"]),
                      nb::cast<int>(d["rule"]), d.contains("friction_n") ? nb::cast<double>(d["friction_n"]) : 0.0,
                      d.contains("friction_fast_n") ? nb::cast<double>(d["friction_fast_n"]) : 0.0,
                      d.contains("friction_rate_s_m") ? nb::cast<double>(d["friction_rate_s_m"]) : 0.0,
                      d.contains("surface_friction_n") ? nb::cast<std::vector<double>>(d["surface_friction_n"])
                                                       : std::vector<double>{},
                      d.contains("surface_ring_n_m") ? nb::cast<std::vector<double>>(d["surface_ring_n_m"])
                                                     : std::vector<double>{},
                      d.contains("bw") ? nb::cast<std::vector<double>>(d["bw"]) : std::vector<double>{},
                      d.contains("bw_mate") ? nb::cast<int>(d["bw_mate"]) : -1,
                      d.contains("bw_plastic") && nb::cast<bool>(d["bw_plastic"]));
    levers_from_state(h, d);
    return h;
}

void fill_system(System& s, int n, const std::vector<double>& mass, const std::vector<double>& k0,
                 const std::vector<double>& c0, const std::vector<Hysteretic>& elements, bool has_b, const std::vector<Contact>& contacts, const std::vector<Pair>& tracked,
                 const std::vector<double>& infl, const std::vector<int>& norm_p, const std::vector<int>& norm_q,
                 const std::vector<double>& norm_at) {
    s.n = n;
    s.mass = mass;
    s.k0 = k0;
    s.c0 = c0;
    s.hyst = elements;
    s.has_b = has_b;
    s.contact = contacts;
    s.track = tracked;
    s.norm_p = norm_p;
    s.norm_q = norm_q;
    if (!norm_at.empty() && norm_at.size() != 2 * norm_p.size())
        throw std::invalid_argument("norm_at: 2 values a vector (its offset), or none");
    s.norm_at = norm_at;
    if (!infl.empty() && static_cast<int>(infl.size()) != 2 * n)
        throw std::invalid_argument("infl: 2 n values (each dof's influence of the two components), or none");
    s.infl = infl;
    s.finish();
}

nb::dict system_state(const System& s) {
    nb::dict d;
    d["n"] = s.n;
    d["mass"] = s.mass;
    d["k0"] = s.k0;
    d["c0"] = s.c0;
    nb::list elements, contacts;
    for (const Hysteretic& h : s.hyst) elements.append(element_state(h));
    for (const Contact& c : s.contact) contacts.append(contact_state(c));
    d["elements"] = elements;
    d["has_b"] = s.has_b;
    d["contacts"] = contacts;
    nb::list tracked;
    for (const Pair& p : s.track) tracked.append(tracked_state(p));
    d["tracked"] = tracked;
    d["norm_p"] = s.norm_p;
    d["norm_q"] = s.norm_q;
    d["norm_at"] = s.norm_at;
    d["infl"] = s.infl;
    return d;
}

void system_from_state(System& s, const nb::dict& d) {
    std::vector<Hysteretic> elements;
    std::vector<Contact> contacts;
    std::vector<Pair> tracked;
    if (d.contains("tracked")) {
        for (nb::handle p : nb::cast<nb::list>(d["tracked"])) tracked.push_back(tracked_from_state(nb::cast<nb::dict>(p)));
    } else {  // (a pickle from before levers: the pairs' ends apart)
        const std::vector<int> ti = nb::cast<std::vector<int>>(d["track_i"]), tj = nb::cast<std::vector<int>>(d["track_j"]);
        for (size_t q = 0; q < ti.size(); ++q) tracked.push_back(tracked_of(ti[q], tj[q], -1, 0.0, -1, 0.0));
    }
    for (nb::handle e : nb::cast<nb::list>(d["elements"]))
        elements.push_back(element_from_state(nb::cast<nb::dict>(e)));
    for (nb::handle c : nb::cast<nb::list>(d["contacts"]))
        contacts.push_back(contact_from_state(nb::cast<nb::dict>(c)));
    if (d.contains("bw") && !elements.empty()) {  // (a pickle from before each element had its own: element 0's)
        const std::vector<double> bw = nb::cast<std::vector<double>>(d["bw"]);
        for (int k = 0; k < BW_PARAMS && k < static_cast<int>(bw.size()); ++k) elements[0].bw[k] = bw[k];
    }
    fill_system(s, nb::cast<int>(d["n"]), nb::cast<std::vector<double>>(d["mass"]),
                nb::cast<std::vector<double>>(d["k0"]), nb::cast<std::vector<double>>(d["c0"]), elements,
                nb::cast<bool>(d["has_b"]), contacts,
                tracked,
                d.contains("infl") ? nb::cast<std::vector<double>>(d["infl"]) : std::vector<double>(),
                d.contains("norm_p") ? nb::cast<std::vector<int>>(d["norm_p"]) : std::vector<int>(),
                d.contains("norm_q") ? nb::cast<std::vector<int>>(d["norm_q"]) : std::vector<int>(),
                d.contains("norm_at") ? nb::cast<std::vector<double>>(d["norm_at"]) : std::vector<double>());
}

// (p: amplitude, omega, phase, then the second component's amplitude and phase; rec_b empty: no second
// component, else the same length as rec_t)
Forcing forcing_of(int kind, Vec p, Vec rec_t, Vec rec_a, Vec rec_b) {
    Forcing f;
    f.kind = kind;
    for (int j = 0; j < 3; ++j) f.p[j] = j < static_cast<int>(p.shape(0)) ? p(j) : 0.0;
    for (int j = 0; j < 2; ++j) f.pb[j] = j + 3 < static_cast<int>(p.shape(0)) ? p(j + 3) : 0.0;
    f.rec_t = rec_t.data();
    f.rec_a = rec_a.data();
    f.rec_b = rec_b.shape(0) == rec_t.shape(0) && rec_b.shape(0) > 0 ? rec_b.data() : nullptr;
    f.n_rec = static_cast<int64_t>(rec_t.shape(0));
    return f;
}

}  // namespace

NB_MODULE(_pounding_core, m) {
    m.doc() = "pounding's compiled core (C++17): the event-driven engine and its kernels.";

    auto tracked = nb::class_<Pair>(m, "TrackedPair")
        .def("__init__",
             [](Pair* p, int i, int j, int lever_i, double arm_i_m, int lever_j, double arm_j_m) {
                 new (p) Pair(tracked_of(i, j, lever_i, arm_i_m, lever_j, arm_j_m));
             },
             nb::kw_only(), nb::arg("i"), nb::arg("j"), nb::arg("lever_i") = -1, nb::arg("arm_i_m") = 0.0,
             nb::arg("lever_j") = -1, nb::arg("arm_j_m") = 0.0)
        .def_ro("i", &Pair::i)
        .def_ro("j", &Pair::j)
        .def("__getstate__", &tracked_state)
        .def("__setstate__", [](Pair& p, const nb::dict& d) { new (&p) Pair(tracked_from_state(d)); });

    with_levers(tracked);

    auto slot = nb::class_<Contact>(m, "ContactSlot")
        .def("__init__",
             [](Contact* c, int i, int j, double sign, double gap_m, int law, const std::vector<double>& params,
                int lever_i, double arm_i_m, int lever_j, double arm_j_m, const Pair* ring_y, double ring_px_m,
                double ring_py_m, double ring_radius_m) {
                 new (c) Contact(contact_of(i, j, sign, gap_m, law, params));
                 set_levers(*c, lever_i, arm_i_m, lever_j, arm_j_m);
                 if (ring_y != nullptr) set_ring(*c, *ring_y, ring_px_m, ring_py_m, ring_radius_m);
             },
             nb::kw_only(), nb::arg("i"), nb::arg("j"), nb::arg("sign"), nb::arg("gap_m"), nb::arg("law"),
             nb::arg("params"), nb::arg("lever_i") = -1, nb::arg("arm_i_m") = 0.0, nb::arg("lever_j") = -1,
             nb::arg("arm_j_m") = 0.0, nb::arg("ring_y").none() = nb::none(), nb::arg("ring_px_m") = 0.0,
             nb::arg("ring_py_m") = 0.0, nb::arg("ring_radius_m") = 0.0)
        .def_ro("i", &Contact::i)
        .def_ro("j", &Contact::j)
        .def_ro("sign", &Contact::sign)
        .def_ro("gap_m", &Contact::gap)
        .def_ro("law", &Contact::law)
        .def_prop_ro("params", [](const Contact& c) { return std::vector<double>(c.p, c.p + N_LAW_PARAMS); })
        .def_prop_ro("ring_y", [](const Contact& c) -> nb::object {
            return c.radial.on ? nb::cast(c.radial.y) : nb::none();
        })
        .def_prop_ro("ring_px_m", [](const Contact& c) { return c.radial.px; })
        .def_prop_ro("ring_py_m", [](const Contact& c) { return c.radial.py; })
        .def_prop_ro("ring_radius_m", [](const Contact& c) { return c.radial.radius; })
        .def("__getstate__", &contact_state)
        .def("__setstate__", [](Contact& c, const nb::dict& d) { new (&c) Contact(contact_from_state(d)); });

    with_levers(slot);

    auto element = nb::class_<Hysteretic>(m, "Element")
        .def("__init__",
             [](Hysteretic* h, int i, int j, double c_d, const std::vector<double>& slopes,
                const std::vector<double>& breaks, int rule, double friction_n, double friction_fast_n,
                double friction_rate_s_m, const std::vector<double>& surface_friction_n,
                const std::vector<double>& surface_ring_n_m, const std::vector<double>& bw, int bw_mate,
                bool bw_plastic, int lever_i, double arm_i_m, int lever_j, double arm_j_m) {
                 new (h) Hysteretic(element_of(i, j, c_d, slopes, breaks, rule, friction_n, friction_fast_n,
                                               friction_rate_s_m, surface_friction_n, surface_ring_n_m, bw,
                                               bw_mate, bw_plastic));
                 set_levers(*h, lever_i, arm_i_m, lever_j, arm_j_m);
             },
             nb::kw_only(), nb::arg("i"), nb::arg("j"), nb::arg("c_d"), nb::arg("slopes"), nb::arg("breaks"),
             nb::arg("rule"), nb::arg("friction_n") = 0.0, nb::arg("friction_fast_n") = 0.0,
             nb::arg("friction_rate_s_m") = 0.0, nb::arg("surface_friction_n") = std::vector<double>{},
             nb::arg("surface_ring_n_m") = std::vector<double>{}, nb::arg("bw") = std::vector<double>{},
             nb::arg("bw_mate") = -1, nb::arg("bw_plastic") = false, nb::arg("lever_i") = -1, nb::arg("arm_i_m") = 0.0,
             nb::arg("lever_j") = -1, nb::arg("arm_j_m") = 0.0)
        .def_ro("i", &Hysteretic::i)
        .def_ro("j", &Hysteretic::j)
        .def_ro("c_d", &Hysteretic::c_d)
        .def_ro("slopes", &Hysteretic::slopes)
        .def_ro("breaks", &Hysteretic::breaks)
        .def_ro("rule", &Hysteretic::rule)
        .def_ro("friction_n", &Hysteretic::friction)
        .def_ro("friction_fast_n", &Hysteretic::friction_fast)
        .def_ro("friction_rate_s_m", &Hysteretic::friction_rate)
        .def_ro("surface_friction_n", &Hysteretic::surface_friction)
        .def_ro("surface_ring_n_m", &Hysteretic::surface_ring)
        .def_prop_ro("bw", [](const Hysteretic& h) { return std::vector<double>(h.bw, h.bw + BW_PARAMS); })
        .def_ro("bw_mate", &Hysteretic::bw_mate)
        .def_ro("bw_plastic", &Hysteretic::bw_plastic)
        .def("__getstate__", &element_state)
        .def("__setstate__", [](Hysteretic& h, const nb::dict& d) { new (&h) Hysteretic(element_from_state(d)); });

    with_levers(element);

    nb::class_<System>(m, "System")
        .def("__init__",
             [](System* s, int n, const std::vector<double>& mass, const std::vector<double>& k0,
                const std::vector<double>& c0, const std::vector<Hysteretic>& elements,
                bool has_b, const std::vector<Contact>& contacts,
                const std::vector<Pair>& tracked, const std::vector<double>& infl, const std::vector<int>& norm_p,
                const std::vector<int>& norm_q, const std::vector<double>& norm_at) {
                 new (s) System();
                 fill_system(*s, n, mass, k0, c0, elements, has_b, contacts, tracked, infl, norm_p, norm_q,
                             norm_at);
             },
             nb::kw_only(), nb::arg("n"), nb::arg("mass"), nb::arg("k0"), nb::arg("c0"), nb::arg("elements"),
             nb::arg("has_b"), nb::arg("contacts"), nb::arg("tracked"),
             nb::arg("infl") = std::vector<double>(), nb::arg("norm_p") = std::vector<int>(),
             nb::arg("norm_q") = std::vector<int>(), nb::arg("norm_at") = std::vector<double>())
        .def_ro("n", &System::n)
        .def_ro("mass", &System::mass)
        .def_ro("plain", &System::plain)
        .def_ro("infl", &System::infl)
        .def_prop_ro("n_elements", &System::n_h)
        .def_prop_ro("levered", [](const System& s) {  // (a contact or an element on a lever)
            for (const Contact& c : s.contact)
                if (c.levered()) return true;
            for (const Hysteretic& h : s.hyst)
                if (h.levered()) return true;
            return false;
        })
        .def_ro("has_b", &System::has_b)
        .def_prop_ro("state_size", &System::state_size)
        .def_prop_ro("sample_cols", [](const System& s) { return s.lay.sample_cols(); })
        .def_prop_ro("norm_extrema_at", &System::norm_extrema_at)
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
            d["n_bouc_wen"] = s.lay.n_bw;
            d["base"] = s.lay.base;
            d["n_springs"] = s.lay.n_sp;
            d["size"] = s.lay.size;
            d["sample_cols"] = s.lay.sample_cols();
            return d;
        })
        .def("__getstate__", &system_state)
        .def("__setstate__", [](System& s, const nb::dict& d) {
            new (&s) System();
            system_from_state(s, d);
        });

    m.def("run",
          [](const System& sy, int kind, Vec p, Vec rec_t, Vec rec_a, Vec rec_b, Vec state0, double t_end,
             double sample_dt, double rtol, int64_t max_events, bool with_energy, Ctl ctl, bool screen_extrema,
             bool audit_screen, bool whole_steps, bool own_samples) {
              const Forcing fo = forcing_of(kind, p, rec_t, rec_a, rec_b);
              RunOptions opt;
              opt.screen_extrema = screen_extrema;
              opt.audit_screen = audit_screen;
              opt.whole_steps = whole_steps;
              opt.own_samples = own_samples;
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
              // the fixed-size outputs as one array (the state, the ledger, the extrema, the norms: Python takes
              // views of it), a table without rows as None: a NumPy array costs a short run more than its
              // arithmetic (nanobind's export and its release, some 3,700 instructions each)
              const size_t size = out.state.size(), norms_at = size + LEDGER_LEN + sy.norm_extrema_at();
              return nb::make_tuple(array1_of({{out.state.data(), size}, {out.ledger, size_t(LEDGER_LEN)},
                                               {out.extrema.data(), out.extrema.size()}}),
                                    size, norms_at, out.status,
                                    table(out.samples), table(out.contacts), table(out.events), table(out.chatters));
          },
          nb::arg("system"), nb::arg("kind"), nb::arg("p"), nb::arg("rec_t"), nb::arg("rec_a"), nb::arg("rec_b"),
          nb::arg("state0"), nb::arg("t_end"), nb::arg("sample_dt"), nb::arg("rtol"), nb::arg("max_events"), nb::arg("with_energy"),
          nb::arg("ctl"), nb::arg("screen_extrema") = true, nb::arg("audit_screen") = false,
          nb::arg("whole_steps") = true, nb::arg("own_samples") = true);

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

    m.def("held_force_probe", [](const System& sy, int kind, Vec p, Vec rec_t, Vec rec_a, Vec rec_b, Vec state) {
        const Forcing fo = forcing_of(kind, p, rec_t, rec_a, rec_b);
        std::vector<double> out;
        held_force_probe(sy, fo, state.data(), out);
        return array2(out.data(), out.size() / 3, 3);
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

    m.def("spectrum_pair", [](Vec t, Vec ax, Vec ay, Vec omegas, double zeta, Vec cos_a, Vec sin_a, OutMat out,
                              Ctl ctl) {
        int status;
        {
            nb::gil_scoped_release release;
            status = spectrum_pair_kernel(t.data(), ax.data(), ay.data(), static_cast<int64_t>(t.shape(0)),
                                          omegas.data(), static_cast<int64_t>(omegas.shape(0)), zeta, cos_a.data(),
                                          sin_a.data(), static_cast<int64_t>(cos_a.shape(0)), out.data(), ctl.data());
        }
        return status;
    });

    m.def("monodromy", [](const System& sy, Vec st0, Mat2 events, double t_end, double omega, double amp,
                          double phase) {
        Mat jac;
        std::vector<double> x_end;
        const int bad = monodromy(sy, st0.data(), events.data(), static_cast<int>(events.shape(0)), t_end, omega,
                                  amp, phase, jac, x_end);
        return nb::make_tuple(array2(jac.data(), jac.rows(), jac.cols()), array1(x_end.data(), x_end.size()), bad);
    });

    // the event locator's numerics, for the tests
    m.def("root_guess", &root_guess);
    m.def("value_at_root", &value_at_root);

    m.def("expm", [](Mat2 a) {
        Mat x(static_cast<Eigen::Index>(a.shape(0)), static_cast<Eigen::Index>(a.shape(1)));
        std::memcpy(x.data(), a.data(), static_cast<size_t>(x.size()) * sizeof(double));
        const Mat e = expm(x);
        return array2(e.data(), e.rows(), e.cols());
    });

    // the state vector's layout and the outputs' columns, as the core writes them: what Python reads them by
    nb::dict layout;
    // the state's offsets and the outputs' columns of a one-mass system with its two contact slots (the left
    // and the right bumper); a system's own: System.layout
    const Layout one(1, 2, 1, 0, 1);
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
    layout["NORM_EXTREMA"] = static_cast<int>(NORM_EXTREMA);
    layout["EVENT_COLS"] = static_cast<int>(EVENT_COLS);
    layout["LEDGER_LEN"] = static_cast<int>(LEDGER_LEN);
    layout["CHATTER_COLS"] = run_parts::CHATTER_COLS;
    layout["WINDOW_COLS"] = WINDOW_COLS;
    layout["CYCLE_COLS"] = CYCLE_COLS;
    layout["SIDE_SUMS"] = SIDE_SUMS;
    layout["N_IMPACT"] = N_IMPACT;
    layout["CTL_SERIES"] = CTL_SERIES;
    layout["CTL_AUDITED"] = CTL_AUDITED;
    layout["CTL_ESCAPES"] = CTL_ESCAPES;
    layout["CTL_WHOLE"] = CTL_WHOLE;
    layout["CTL_OWN"] = CTL_OWN;
    layout["CTL_LEN"] = CTL_LEN;
    // a step's per-cycle record and window (step.hpp), and a contact side's sums within them
    layout["CY_DMAX"] = CY_DMAX;
    layout["CY_DMIN"] = CY_DMIN;
    layout["CY_AMAX"] = CY_AMAX;
    layout["CY_SUMS"] = CY_SUMS;
    layout["CY_EVENTS"] = CY_EVENTS;
    layout["CY_STICKS"] = CY_STICKS;
    layout["W_DMAX"] = W_DMAX;
    layout["W_DMIN"] = W_DMIN;
    layout["W_AMAX"] = W_AMAX;
    layout["W_CYCLES"] = W_CYCLES;
    layout["W_SUMS"] = W_SUMS;
    layout["W_EVENTS"] = W_EVENTS;
    layout["W_STICKS"] = W_STICKS;
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
                                       {"bumper_dissipation_j", CC_DISSIPATION}});  // a contact table's columns
    m.attr("EVENT_COLUMNS") = named({{"t_s", EC_T}, {"action", EC_ACTION}, {"index", EC_INDEX}});
    m.attr("LEDGER") = named({{"input", L_INPUT}, {"viscous", L_VISCOUS}, {"hysteretic", L_HYSTERETIC},
                              {"bumper_loss", L_BUMPER_LOSS}, {"kinetic", L_KINETIC}, {"isolator", L_ISOLATOR},
                              {"bumper", L_BUMPER}});  // the energy ledger's slots
    m.attr("DOF_EXTREMA") = named({{"d_max", EX_D_MAX}, {"d_max_t", EX_D_MAX_T}, {"d_min", EX_D_MIN},
                                   {"d_min_t", EX_D_MIN_T}, {"a_abs_max", EX_A_ABS_MAX},
                                   {"a_abs_max_t", EX_A_ABS_MAX_T}, {"a_at_max", EX_A_AT_MAX}});  // a dof's
    m.attr("PAIR_EXTREMA") = named({{"max", PX_MAX}, {"max_t", PX_MAX_T}, {"min", PX_MIN},
                                    {"min_t", PX_MIN_T}});  // a tracked pair's (a storey's drift)
    // a tracked vector's (a bearing's displacement in plan): its length's largest, when, its components there
    m.attr("NORM_EXTREMA") = named({{"max", NX_MAX}, {"max_t", NX_MAX_T}, {"at_p", NX_AT_P}, {"at_q", NX_AT_Q}});
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
    status["CAPACITY"] = static_cast<int>(CAPACITY);
    m.attr("STATUS") = status;
    nb::dict actions;  // the events' actions: an event table's second column
    actions["yield"] = static_cast<int>(ACT_YIELD);
    actions["reversal"] = static_cast<int>(ACT_REVERSAL);
    actions["branch"] = static_cast<int>(ACT_REGION);
    actions["contact_start"] = static_cast<int>(ACT_CONTACT);
    actions["contact_end"] = static_cast<int>(ACT_RELEASE);
    actions["bumper_branch"] = static_cast<int>(ACT_LAW_BRANCH);
    actions["bouc_wen_zero"] = static_cast<int>(ACT_BOUC_WEN);
    actions["stick"] = static_cast<int>(ACT_STICK);
    actions["slip"] = static_cast<int>(ACT_SLIP);
    actions["surface_slip"] = static_cast<int>(ACT_SURFACE_SLIP);
    actions["ring"] = static_cast<int>(ACT_RING);
    actions["ring_off"] = static_cast<int>(ACT_RING_OFF);
    actions["circle_slip"] = static_cast<int>(ACT_CIRCLE_SLIP);
    actions["circle_stick"] = static_cast<int>(ACT_CIRCLE_STICK);
    m.attr("ACTIONS") = actions;
    m.attr("N_LAW_STATE") = N_LAW_STATE;
    m.attr("N_LAW_PARAMS") = N_LAW_PARAMS;
    m.attr("WINDOW_COLS") = WINDOW_COLS;
    m.attr("CYCLE_COLS") = CYCLE_COLS;
    m.attr("SIDE_SUMS") = SIDE_SUMS;
}
