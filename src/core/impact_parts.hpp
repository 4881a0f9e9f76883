// What impact.cpp and impacts_at_once.cpp share (internal to the core).
#pragma once

#include <vector>

#include "impact.hpp"
#include "run_parts.hpp"

namespace pounding::run_parts {

// the accelerations (n) of the state without the held stops (au) and with them (a)
void state_accelerations(const double* st, const System& sy, const Sticking& stk, const double* ag, double* q,
                         double* row, std::vector<double>& au, std::vector<double>& a);
// a free rigid stop's impact at t counted in its running sequence (a new one after a pause longer than
// window_s, the last one's row written when it held three impacts or more)
void count_impact(double* st, const Layout& L, int c, double t, double window_s, Rows& chatters);
// a free rigid stop's running sequence ended at t by a hold (its row, when it held three impacts or more)
void end_sequence(double* st, const Layout& L, int c, double t, Rows& chatters);
// impacts at one instant on the rigid stops touching contact c through shared dofs, one of them free
// besides c: Moreau's law (each separates at least e times its closing speed, the impulses pushing only),
// those left at rest held where the motion pushes them shut.  False where contact c meets its stop alone
// (or with held stops only: their groups' masses take the impact) or the problem was not solved: the
// impacts are then taken one by one
// whether two contacts move a dof in common (a ring's second pair, its y, too)
inline bool contacts_share_dof(const Contact& a, const Contact& b) {
    if (shares_dof(a, b)) return true;
    if (a.radial.on && (shares_dof(a.radial.y, b) || (b.radial.on && shares_dof(a.radial.y, b.radial.y)))) return true;
    return b.radial.on && shares_dof(a, b.radial.y);
}
// whether another free rigid stop touches (within h) at a dof of contact c's (most impacts: none)
inline bool others_touch(const double* st, const System& sy, int c, double h) {
    const Layout& L = sy.lay;
    const Contact& own = sy.contact[static_cast<size_t>(c)];
    for (const int d : sy.rigid) {
        if (d == c || st[L.in_at(d)] != 0.0) continue;
        const Contact& ct = sy.contact[static_cast<size_t>(d)];
        if (contacts_share_dof(own, ct) && compression_of(ct, st + L.x) >= -h) return true;
    }
    return false;
}
// general mode (holds on levers): the velocities moved onto the held stops' constraints (W v = 0), the
// kinetic energy this takes added to the contacts' loss.  Moreau's impacts leave a held stop separating, or a
// stop at rest closing, at up to v_res; held at that rate, a corner would drift off or into its wall while
// its hold's force worked on it, outside the ledger
void settle_holds(double* st, const System& sy, const Sticking& stk, double* ledger);
// (ph, tau: the phase that led to the instant, for the rates of the forces that are zero to the rounding)
bool impacts_at_once(double* st, const System& sy, const Phase& ph, double tau, Sticking& stk, int c, const double* ag,
                     const ImpactScales& sc, double* ledger, Rows& contacts, Rows& chatters, double* q,
                     double* row);

}  // namespace pounding::run_parts
