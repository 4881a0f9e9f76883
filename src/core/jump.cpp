// The state at the end of a sub-interval and across an event (run_parts.hpp): the bumpers moved on, the jump
// at an event, its row and sample, and a run's last rows.
#include <algorithm>
#include <cmath>

#include "impact.hpp"
#include "isolator.hpp"
#include "laws.hpp"
#include "run_parts.hpp"

namespace pounding::run_parts {

namespace {

// a contact's velocity as its rows give it: its pair's (a line's), or the rate of its compression (a ring's:
// sign +1, the point's speed along the wall's normal)
double contact_speed(const Contact& ct, const double* st, const Layout& L) {
    return ct.radial.on ? compression(ct, st + L.x, st + L.v).dv : rel(st + L.v, ct);
}

// a contact table's row from a contact's running totals (acc: its block of the state), its end and the
// contact's velocity there (contact_speed)
void contact_row(Rows& contacts, int c, const double* acc, double t_end, double v_out) {
    double* r = contacts.push();
    r[CC_CONTACT] = static_cast<double>(c);
    r[CC_T_START] = acc[A_TSTART];
    r[CC_T_END] = t_end;
    r[CC_V_IN] = acc[A_VIN];
    r[CC_V_OUT] = v_out;
    r[CC_IMPULSE] = acc[A_IMPULSE];
    r[CC_PEAK_FORCE] = acc[A_PEAK];
    r[CC_MAX_COMPRESSION] = acc[A_MAXCOMP];
    r[CC_DISSIPATION] = acc[A_WORK];
}

}  // namespace

// the bumpers at the end of a sub-interval of length tau: one in contact follows its pair (y1), one out of
// contact relaxes, its loss added to the ledger
void move_bumpers(double* st, const System& sy, const double* y1, double tau, double* ledger) {
    const Layout& L = sy.lay;
    for (int c = 0; c < sy.nc(); ++c) {
        const Contact& ct = sy.contact[static_cast<size_t>(c)];
        const int idx = L.def_at(c);
        double* z = st + L.z_at(c);
        if (st[L.in_at(c)] != 0.0) {
            st[idx] = std::max(0.0, compression_of(ct, y1));
            law_moved(ct.law, ct.p, z, st[idx], true);
        } else if (st[idx] > 0.0) {
            const double relaxed = law_relax(ct.law, ct.p, st[idx], tau, z).d;
            const double e0 = law_energy(ct.law, ct.p, st[idx], z);
            law_moved(ct.law, ct.p, z, relaxed, false);
            ledger[L_BUMPER_LOSS] += e0 - law_energy(ct.law, ct.p, relaxed, z);
            st[idx] = relaxed;
        }
    }
}

// the state across an event: a contact starts (its incoming velocity and its law's state) or ends (a row
// of the contact table), a law changes branch, the Bouc-Wen z through zero, an isolator's spring
void jump(double* st, const System& sy, const EventRow& ev, Rows& contacts, const double* resolution) {
    const Layout& L = sy.lay;
    const double v_res = resolution[0], depth_res = resolution[1], impulse_res = resolution[2];
    const int action = ev.action, index = ev.index;
    const double t_ev = st[T];
    if (action == ACT_CONTACT) {
        const int acc = L.acc_at(index);
        const Contact& ct = sy.contact[static_cast<size_t>(index)];
        st[L.in_at(index)] = 1.0;
        const double comp = st[L.def_at(index)];
        const double v_in = contact_speed(ct, st, L);
        st[acc + A_TSTART] = t_ev;
        st[acc + A_VIN] = std::abs(v_in) > v_res ? v_in : 0.0;  // below the resolution: met at rest
        law_contact_state(ct.law, ct.p, ct.sign * st[acc + A_VIN], st + L.z_at(index), comp);
        st[acc + A_DSTART] = comp;
        st[acc + A_IMPULSE] = 0.0;
        st[acc + A_PEAK] = 0.0;
        st[acc + A_MAXCOMP] = comp;
        st[acc + A_WORK] = 0.0;
    } else if (action == ACT_RELEASE) {
        const int acc = L.acc_at(index);
        const Contact& ct = sy.contact[static_cast<size_t>(index)];
        st[L.in_at(index)] = 0.0;
        law_release_state(ct.law, ct.p, st + L.z_at(index), st[L.def_at(index)]);
        // a touch below the resolution in both depth and impulse is no impact: computed, not listed
        if (st[acc + A_MAXCOMP] - st[acc + A_DSTART] > depth_res || std::abs(st[acc + A_IMPULSE]) > impulse_res) {
            contact_row(contacts, index, st + acc, t_ev, contact_speed(ct, st, L));
        }
    } else if (action == ACT_LAW_BRANCH) {
        const Contact& ct = sy.contact[static_cast<size_t>(index)];
        law_after_event(ct.law, ct.p, st + L.z_at(index), st[L.def_at(index)], ev.dir);
    } else if (action == ACT_BOUC_WEN) {
        st[L.zeta + sy.hyst[static_cast<size_t>(index)].bw_slot] = 0.0;
    } else {
        iso_transition(sy, st, action, index, ev.dir);
    }
}

// an event's row, and the sample just after it
void record_event(double* st, const System& sy, const EventRow& ev, Rows& events, Rows& samples, double sample_dt,
                  double* extrema, Buffers& b, std::vector<double>& row, Sticking& stk, const double* ag) {
    double* r = events.push();
    r[EC_T] = st[T];
    r[EC_ACTION] = static_cast<double>(ev.action);
    r[EC_INDEX] = static_cast<double>(ev.index);
    outputs(st, sy, b.q.data(), row.data());
    held_outputs(st, sy, stk, ag, row.data());
    for (int i = 0; i < sy.n; ++i) track_abs_acceleration(extrema + DOF_EXTREMA * i, st[T], row[1 + 2 * sy.n + i]);
    if (sample_dt >= 0.0) std::copy(row.begin(), row.end(), samples.push());
}

// the end of a run: its last sample, and a row for each contact still going on
void finish(const double* st, const System& sy, Rows& samples, Rows& contacts, Buffers& b, std::vector<double>& row,
            Sticking& stk, const double* ag) {
    const Layout& L = sy.lay;
    if (samples.row(samples.n - 1)[0] < st[T]) {
        outputs(st, sy, b.q.data(), row.data());
        held_outputs(st, sy, stk, ag, row.data());
        std::copy(row.begin(), row.end(), samples.push());
    }
    for (int c = 0; c < sy.nc(); ++c) {
        if (st[L.in_at(c)] == 0.0) continue;
        contact_row(contacts, c, st + L.acc_at(c), NaN, NaN);  // (still in contact at the end)
    }
}

}  // namespace pounding::run_parts
