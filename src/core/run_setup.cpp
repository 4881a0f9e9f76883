// A phase of motion set up from the state, and the excitation at an instant (run_parts.hpp).
#include "run_parts.hpp"

#include <algorithm>
#include <cmath>

#include "events.hpp"
#include "isolator.hpp"
#include "laws.hpp"
#include "phase.hpp"

namespace pounding::run_parts {

// ---------------------------------------------------------------- the excitation

Piece excitation_piece(const Forcing& fo, double t, int64_t j_hint) {
    if (fo.kind == EXC_HARMONIC) {
        const double omega = fo.p[1];
        const double angle = omega * t + fo.p[2];
        const double phase = angle - TWO_PI * std::floor(angle / TWO_PI);  // reduced to [0, 2 pi)
        Piece pc{0.0, 0.0, fo.p[0], omega, phase, INF, j_hint};
        if (fo.pb[0] != 0.0) {  // (pb0 sin(angle + d), d its phase's lead on the first's)
            const double d = fo.pb[1] - fo.p[2];
            pc.bs = fo.pb[0] * std::cos(d);
            pc.bc = fo.pb[0] * std::sin(d);
        }
        return pc;
    }
    const int64_t n = fo.n_rec;
    const double* rt = fo.rec_t;
    if (t < rt[0]) return {0.0, 0.0, 0.0, 0.0, 0.0, rt[0], j_hint};
    if (t >= rt[n - 1]) return {0.0, 0.0, 0.0, 0.0, 0.0, INF, j_hint};
    int64_t j = std::min(std::max(j_hint, int64_t(0)), n - 2);
    if (!(rt[j] <= t && t < rt[j + 1])) {
        if (j + 2 < n && rt[j + 1] <= t && t < rt[j + 2]) {
            j += 1;
        } else {
            j = 0;
            int64_t hi = n - 1;
            while (hi - j > 1) {
                const int64_t mid = (j + hi) / 2;
                if (rt[mid] <= t) j = mid;
                else hi = mid;
            }
        }
    }
    return record_piece(fo, t, j);
}

void table_at(const Forcing& fo, const System& sy, double t, double* ag) {
    const Piece pc = excitation_piece(fo, t, 0);
    const double ga = pc.a0 + pc.amp * std::sin(pc.phase);
    if (sy.plain) {
        for (int i = 0; i < sy.n; ++i) ag[i] = ga;
        return;
    }
    const double gb = pc.b0 + pc.bs * std::sin(pc.phase) + pc.bc * std::cos(pc.phase);
    for (int i = 0; i < sy.n; ++i)
        ag[i] = sy.infl[static_cast<size_t>(2 * i)] * ga + sy.infl[static_cast<size_t>(2 * i + 1)] * gb;
}

// the run's length (m) and velocity (m/s) scales: the system's and the excitation's, not the start's
void run_scales(const System& sy, const Forcing& fo, double& x, double& xw) {
    // (the isolator's first slope; a structure without one, fixed at its base: its stiffest own spring)
    // (a flat slider's, of no slope: the same; a structure without any spring: 1 Hz)
    double k = sy.n_h() > 0 ? sy.iso().slopes[0] : 0.0;
    if (k == 0.0)
        for (int i = 0; i < sy.n; ++i) k = std::max(k, sy.k0[static_cast<size_t>(i * sy.n + i)]);
    double w = k > 0.0 ? std::sqrt(k / sy.total_mass) : TWO_PI;
    double amp = 0.0;
    if (fo.kind == EXC_HARMONIC) {
        amp = std::abs(fo.p[0]);
        w = std::max(w, fo.p[1]);
    } else {
        for (int64_t i = 0; i < fo.n_rec; ++i) amp = std::max(amp, std::abs(fo.rec_a[i]));
    }
    if (!sy.plain) {  // (the most any dof feels: |r_i| of the first's peak and |q_i| of the second's)
        double amp_b = 0.0;
        if (fo.kind == EXC_HARMONIC) amp_b = std::abs(fo.pb[0]);
        else if (fo.rec_b != nullptr)
            for (int64_t i = 0; i < fo.n_rec; ++i) amp_b = std::max(amp_b, std::abs(fo.rec_b[i]));
        const double amp_a = amp;
        amp = 0.0;
        for (int i = 0; i < sy.n; ++i)
            amp = std::max(amp, std::abs(sy.infl[static_cast<size_t>(2 * i)]) * amp_a +
                                    std::abs(sy.infl[static_cast<size_t>(2 * i + 1)]) * amp_b);
    }
    double gaps = 0.0;
    if (sy.has_b)
        for (const Contact& c : sy.contact) gaps += c.gap;
    x = std::max(gaps, amp / (w * w));
    if (sy.n_h() > 0 && !sy.iso().breaks.empty()) x = std::max(x, sy.iso().breaks[0]);
    xw = x * w;
}

// a bound on |lambda| of the pencil lambda^2 M + lambda C + K: sqrt(kappa + (gamma / 2)^2) and gamma, with
// kappa, gamma the largest row sums of |M^-1/2 K M^-1/2| and |M^-1/2 C M^-1/2| (bounds on the Rayleigh
// quotients; k / m and c / m for one mass)
static double rate_bound(const Phase& ph, double k_extra) {
    const int n = ph.n;
    double kap = 0.0, gam = 0.0;
    for (int i = 0; i < n; ++i) {
        double sk = 0.0, sc = 0.0;
        for (int j = 0; j < n; ++j) {
            const double s = std::sqrt(ph.minv[static_cast<size_t>(i)] * ph.minv[static_cast<size_t>(j)]);
            sk += std::abs(ph.K[static_cast<size_t>(i * n + j)]) * s;
            sc += std::abs(ph.C[static_cast<size_t>(i * n + j)]) * s;
        }
        kap = std::max(kap, sk);
        gam = std::max(gam, sc);
    }
    kap += k_extra;
    return std::max(std::sqrt(kap + (0.5 * gam) * (0.5 * gam)), gam);
}


// ---------------------------------------------------------------- the loop's parts

void set_phase(Phase& ph, const double* st, const System& sy, const Piece& pc) {
    const Layout& L = sy.lay;
    const int n = sy.n;
    if (ph.K.size() == sy.k0.size() && ph.C.size() == sy.c_lin.size()) {  // (no reallocation: a copy)
        std::copy(sy.k0.begin(), sy.k0.end(), ph.K.begin());
        std::copy(sy.c_lin.begin(), sy.c_lin.end(), ph.C.begin());
    } else {
        ph.K = sy.k0;
        ph.C = sy.c_lin;
    }
    std::fill(ph.R0.begin(), ph.R0.end(), 0.0);
    IsoLinear iso{0.0, 0.0};
    ph.el_k.resize(static_cast<size_t>(sy.n_h()));
    ph.el_r.resize(static_cast<size_t>(sy.n_h()));
    ph.el_s.assign(static_cast<size_t>(sy.n_h()), 0.0);
    ph.rate_fr.clear();
    for (int e = 0; e < sy.n_h(); ++e) {  // each element's present branch
        const Hysteretic& h = sy.hyst[static_cast<size_t>(e)];
        const IsoLinear el = iso_linear(sy, e, st);
        sy.add_pair(ph.K, h, el.k);
        push_pair(ph.R0.data(), h, el.r0);
        ph.el_k[static_cast<size_t>(e)] = el.k;
        ph.el_r[static_cast<size_t>(e)] = el.r0;
        const double s = iso_rate_slip(sy, e, st);
        ph.el_s[static_cast<size_t>(e)] = s;
        if (iso_rate_dependent(h, s)) ph.rate_fr.push_back({&h, s});
        if (e == 0) iso = el;
    }
    bool any_nl = false;
    for (int q = 0; q < sy.nc(); ++q) {
        ContactPhase& k = ph.ct[static_cast<size_t>(q)];
        k.in = false;
        k.nl = false;
        k.def0 = st[L.def_at(q)];
        for (int i = 0; i < N_LAW_STATE; ++i) k.lz[i] = st[L.z_at(q) + i];
        if (!sy.has_b || st[L.in_at(q)] == 0.0) continue;
        k.in = true;
        const Contact& ct = sy.contact[static_cast<size_t>(q)];
        if (law_is_linear(ct.law)) {
            // F = kb x + rb + cb x' with x = sign (x_i - x_j) - gap, pushing dof i by -sign F
            const Branch br = law_linear_branch(ct.law, ct.p, st[L.def_at(q)],
                                                compression(ct, st + L.x, st + L.v).dv, st + L.z_at(q));
            k.kb = br.k;
            k.cb = br.c;
            k.rb = br.r;
            k.jb = br.j;
            if (ct.radial.on) {  // (a ring's: its normal turns, the phase is nonlinear)
                any_nl = true;
                if (law_is_rigid(ct.law)) continue;  // (held on it: a constraint, sticking.hpp, no force law)
                k.nl = true;
                any_nl = true;
                continue;
            }
            sy.add_pair(ph.K, ct, br.k);
            sy.add_pair(ph.C, ct, br.c);
            push_pair(ph.R0.data(), ct, ct.sign * (br.r - br.k * ct.gap));
        } else {
            k.nl = true;
            any_nl = true;
        }
    }
    ph.stk.build(sy, st);  // (the rigid stops held shut)
    ph.ax0 = pc.a0;
    ph.ax1 = pc.a1;
    ph.axh = pc.amp;
    ph.w = pc.omega;
    ph.phi = pc.phase;
    ph.sphi = std::sin(pc.phase);
    ph.cphi = std::cos(pc.phase);
    ph.bx0 = pc.b0;
    ph.bx1 = pc.b1;
    ph.bs = pc.bs;
    ph.bc = pc.bc;
    for (int q = 0; q < 2 * n; ++q) ph.y0[static_cast<size_t>(q)] = st[L.x + q];
    bool all_linear = true;  // (every Bouc-Wen spring a plastic circle inside: a linear spring, exact phases)
    for (int q = 0; q < sy.n_bw(); ++q) {
        ph.zeta0[static_cast<size_t>(q)] = st[L.zeta + q];
        const Hysteretic& h = sy.bw_of(q);
        const bool plastic = h.bw_plastic;
        // (one flag for both mates: the circle's first element's, whatever a state made by hand has in the other)
        const int first = plastic ? std::min(q, h.bw_mate_slot) : q;
        const bool slip = plastic && st[L.region + sy.bw_el[static_cast<size_t>(first)]] != 0.0;
        ph.bw_slip[static_cast<size_t>(q)] = slip;
        ph.bw_lin[static_cast<size_t>(q)] = plastic && !slip;
        all_linear = all_linear && plastic && !slip;
        if (!plastic || slip) continue;
        // (inside: z = z0 + (u - u0) / u_y, its force bw[0] z a spring of bw[0] / u_y and a constant)
        const double k_c = h.bw[0] / h.bw[1];
        const double zoff = st[L.zeta + q] - rel(st + L.x, h) / h.bw[1];
        ph.zoff[static_cast<size_t>(q)] = zoff;
        sy.add_pair(ph.K, h, k_c);
        push_pair(ph.R0.data(), h, h.bw[0] * zoff);
    }
    ph.numeric = any_nl || !all_linear || !ph.rate_fr.empty();
    ph.dp5_h = -1.0;
    ph.tc_ok = false;
    ph.kiso = iso.k;
    ph.riso = iso.r0;
    // (the Bouc-Wen springs' initial stiffnesses bound the rate too)
    double k_extra = 0.0;
    for (int q = 0; q < sy.n_bw(); ++q) {
        if (ph.bw_lin[static_cast<size_t>(q)]) continue;  // (a plastic circle inside: in K already)
        const Hysteretic& h = sy.bw_of(q);
        double k_bw = h.bw[0] * h.bw[2] / h.bw[1];
        if (h.friction_rate != 0.0) k_bw *= std::max(1.0, h.friction_fast / h.bw[0]);  // (a circle's mu(s))
        if (h.levered()) {  // (k w^T M^-1 w at most k (sum |w_k| sqrt(1 / m_k))^2)
            int d[4];
            double w[4];
            const int m = h.entries(d, w);
            double s = 0.0;
            for (int r = 0; r < m; ++r) s += std::abs(w[r]) * std::sqrt(ph.minv[static_cast<size_t>(d[r])]);
            k_extra += k_bw * s * s;
        } else {
            const double mi = ph.minv[static_cast<size_t>(h.i)];
            const double mj = h.j >= 0 ? ph.minv[static_cast<size_t>(h.j)] : 0.0;
            k_extra += k_bw * (mi + mj + (h.j >= 0 ? 2.0 * std::sqrt(mi * mj) : 0.0));
        }
    }
    ph.rate = rate_bound(ph, k_extra);
}

void run_constants(Phase& ph, const System& sy, const Forcing& fo) {
    run_scales(sy, fo, ph.xrun, ph.vrun);
    ph.xround = ph.xrun;
    ph.vround = ph.vrun;
    for (int i = 0; i < sy.n; ++i) {
        ph.mass[static_cast<size_t>(i)] = sy.mass[static_cast<size_t>(i)];
        ph.minv[static_cast<size_t>(i)] = 1.0 / sy.mass[static_cast<size_t>(i)];
    }
    ph.plain = sy.plain;
    ph.rA.resize(static_cast<size_t>(sy.n));
    ph.rB.resize(static_cast<size_t>(sy.n));
    for (int i = 0; i < sy.n; ++i) {
        ph.rA[static_cast<size_t>(i)] = sy.infl[static_cast<size_t>(2 * i)];
        ph.rB[static_cast<size_t>(i)] = sy.infl[static_cast<size_t>(2 * i + 1)];
    }
    for (int c = 0; c < sy.nc(); ++c) {
        const Contact& ct = sy.contact[static_cast<size_t>(c)];
        ContactPhase& k = ph.ct[static_cast<size_t>(c)];
        k.gap = ct.gap;
        k.law = ct.law;
        k.p = ct.p;
        k.sign = ct.sign;
        k.radial = ct.radial;
        static_cast<Pair&>(k) = ct;
    }
    // the isolator's numbers for its output column and its Bouc-Wen spring (none: a fixed base, force 0)
    ph.cd = sy.n_h() > 0 ? sy.iso().c_d : 0.0;
    ph.iso = sy.n_h() > 0 ? static_cast<const Pair&>(sy.iso()) : Pair();
    ph.bw.resize(static_cast<size_t>(sy.n_bw()));
    for (int q = 0; q < sy.n_bw(); ++q) ph.bw[static_cast<size_t>(q)] = &sy.bw_of(q);
}

NumStep numeric_step(Phase& ph, double h, double h_num, double rtol, double t) {
    bool shortened = false;
    if (h_num < h) {
        h = h_num;
        shortened = true;
    }
    const int n = ph.n;
    const double atol_d = rtol * NUMERIC_X_FLOOR_M, atol_v = rtol * NUMERIC_V_FLOOR_M_S;
    while (true) {
        const Dp5 r = dp5_step(ph, h);
        double err = 0.0;
        for (int q = 0; q < ph.nbw; ++q) {  // (a plastic circle inside: its z the displacements', checked there)
            if (ph.bw_lin[static_cast<size_t>(q)]) continue;
            err = std::max(err, std::abs(r.ez[q]) / (rtol * (1.0 + std::abs(r.z[q]))));
        }
        for (int i = 0; i < n; ++i) {
            const double y0x = ph.y0[static_cast<size_t>(i)], y0v = ph.y0[static_cast<size_t>(n + i)];
            err = std::max(err, std::abs(r.ey[i]) / (atol_d + rtol * std::max(std::abs(y0x), std::abs(r.y[i]))));
            err = std::max(err,
                           std::abs(r.ey[n + i]) / (atol_v + rtol * std::max(std::abs(y0v), std::abs(r.y[n + i]))));
        }
        if (err <= 1.0) {
            h_num = h * (err == 0.0 ? 5.0 : std::min(5.0, 0.9 * std::pow(err, -0.2)));
            return {SUCCESS, h, h_num, shortened};
        }
        h *= std::max(0.2, 0.9 * std::pow(err, -0.2));
        shortened = true;
        if (h <= 1e-15 * std::max(1.0, std::abs(t))) return {STEP_FAILED, h, h_num, shortened};
    }
}

int phase_events(const Phase& ph, const double* st, const System& sy, EventRow* evs) {
    int n = iso_events(sy, st, evs, 0);
    n = bumper_events(st, ph, sy, evs, n);
    for (int q = 0; q < sy.n_bw(); ++q) {  // a Bouc-Wen z back through zero: its law changes form
        const Hysteretic& h = sy.bw_of(q);
        if (h.bw_plastic) {  // (a plastic circle's, one for both mates: reached, or its slip's end)
            if (h.bw_mate_slot < q) continue;
            EventRow& r = evs[n++];
            r = EventRow();
            r.kind = KIND_CIRCLE;
            static_cast<Pair&>(r) = h;
            r.side = q;
            r.index = sy.bw_el[static_cast<size_t>(q)];
            const bool slipping = st[sy.lay.region + r.index] != 0.0;
            r.action = slipping ? ACT_CIRCLE_STICK : ACT_CIRCLE_SLIP;
            continue;
        }
        const double z = st[sy.lay.zeta + q];
        if (z == 0.0) continue;
        EventRow& r = evs[n++];
        r = EventRow();
        r.kind = KIND_ZETA;
        static_cast<Pair&>(r) = sy.bw_of(q);
        r.side = q;  // (its z's slot)
        r.index = sy.bw_el[static_cast<size_t>(q)];
        r.alpha = -std::copysign(1.0, z);
        r.action = ACT_BOUC_WEN;
    }
    return n;
}

// the pairs whose relative displacement events are functions of: the elements' and the contacts'
int event_pairs(const System& sy, Pair* pairs) {
    int np = 0;
    auto add = [&](const Pair& p) {
        for (int q = 0; q < np; ++q)
            if (same_pair(pairs[q], p)) return;
        pairs[np++] = p;
    };
    for (const Hysteretic& h : sy.hyst) add(h);
    if (sy.has_b)
        for (const Contact& c : sy.contact) add(c);
    return np;
}
}  // namespace pounding::run_parts

namespace pounding {

void held_force_probe(const System& sy, const Forcing& fo, const double* st, std::vector<double>& out) {
    using namespace run_parts;
    Phase ph;
    ph.size(sy.n, sy.nc(), sy.n_bw());
    ph.pattern(sy);
    run_constants(ph, sy, fo);
    set_phase(ph, st, sy, excitation_piece(fo, st[T], 0));
    std::vector<double> a(static_cast<size_t>(sy.n));
    phase_rhs(ph, 0.0, ph.y0.data(), ph.zeta0.data(), a.data(), true);
    out.clear();
    for (size_t h = 0; h < ph.stk.held.size(); ++h) {
        const int c = ph.stk.held[h];
        if (c >= sy.nc()) continue;  // (a tie's: not a stop)
        const EventValue v = held_force(ph, c, 0.0, ph.y0.data(), a.data());
        out.insert(out.end(), {static_cast<double>(c), v.g, v.gp});
    }
}

}  // namespace pounding
