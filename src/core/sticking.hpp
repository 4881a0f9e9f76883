// Rigid stops held shut: sticking.
//
// A rigid stop (laws.hpp, law_is_rigid) in contact holds its pair's compression at zero: the two ends (or the
// end and the ground) move together while the motion pushes them into each other.  The held stops bind the
// dofs into groups; a group with a stop on the ground does not move relative to the ground (its accelerations
// are zero), the others move as one body (each member's acceleration is the group's mass-weighted mean of the
// accelerations the system would have without the held stops).  The held stops of a group form a tree (a loop
// is never closed: the run bounces instead, see sticking_closes_loop), so each held stop's force is what the
// dofs on its first end's side need: F = sign sum_(k on that side) m_k (a_free_k - a_k), pushing while F > 0.
//
// A friction element that sticks (isolator.hpp's rule 2) ties its pair the same way: a bond like a held stop's,
// of sign +1, whose force is the friction the stick needs.  Bonds are indexed: contact c is bond c, element e's
// tie bond nc + e.
//
// On levers (System::lever_holds: a wall of a moat in plan struck at a floor's corner, whose motion is x - y_c
// theta) the holds are linear constraints instead: each held bond h a row w_h of W (its pair's weights), the
// accelerations held to W a = 0 by the forces W^T lambda, lambda = -A^-1 W a_free, A = W M^-1 W^T (the
// general mode; the same numbers as the groups' where the pairs have no levers, which keep the groups).  A
// bond's force is then sign (X M (a_free - a))_h, X = A^-1 W M^-1 (its row in side), and an impulse p along a
// pair w moves the velocities by P M^-1 w p, P = I - M^-1 W^T A^-1 W, the holds' projection.  A dependent set
// of rows (A singular) is a loop.
#pragma once

#include <vector>

#include "core.hpp"

namespace pounding {

struct Sticking {
    bool any = false;
    bool general = false;       // the holds as linear constraints (System::lever_holds)
    int n = 0, ngrp = 0;
    std::vector<int> grp;       // per dof: its group, -1 when no held stop binds it
    std::vector<int> grounded;  // per group: 1 when a held stop ties it to the ground
    std::vector<double> gmass;  // per group: its mass, kg
    std::vector<int> held;      // the held bonds (a contact's index, or nc + an element's)
    std::vector<int> end_i, end_j;  // per held bond: its pair (end_j GROUND for the ground)
    std::vector<double> end_sign;   // per held bond: its sign (a contact's; +1 for a tie)
    std::vector<double> side;   // per held bond (held.size() x n): +1 dof k on its first end's side, -1 on its
                                // second's (when the first's is held to the ground), 0 neither; in general
                                // mode its row of X = A^-1 W M^-1 (its force's weights on m_k (au_k - a_k))
    std::vector<double> wrow;   // (general mode: per held bond its pair's weights w, n each; a ring's its
                                // compression's gradient at the state's displacements, compression.hpp)
    // general mode with a ring held (a rigid stop on a circular moat's wall): its row turns as the point moves
    // along the ring (refresh: the rows at another state), and the hold keeps W a = -kappa, kappa its
    // centripetal term (|P'|^2 - (n . P')^2) / |P| (bend, per held bond: 0 on a line's), by the multipliers'
    // bias A^-1 kappa (bias; ainv: A^-1, nh x nh)
    bool rings = false;
    std::vector<double> bend, bias, ainv;
    std::vector<int> held_of;   // per bond (nc + n_h): its index in held, -1 when not held
    int nc = 0;                 // (the first tie's bond: the contacts' count)
    std::vector<int> up;        // (scratch: the union-find's parents)
    std::vector<int> roots;     // (scratch: each root's group)
    std::vector<int> stack_;    // (scratch: the walk over the held stops)
    // (general mode: wrow, side, ainv and bias at x and v; false when the rows are dependent)
    bool general_rows(const System& sy, const double* x, const double* v);
    // the groups of the rigid stops in contact in the state (st[in] != 0) and the friction elements sticking;
    // false when they close a loop
    bool build(const System& sy, const double* st);
    // the accelerations a (n) with the held stops, from those without them (in place): project and, with a
    // ring held, its centripetal bias
    void hold(const std::vector<double>& mass, double* a) const;
    // the projection P alone (velocities, and the rates of accelerations on lines' holds), in place
    void project(const std::vector<double>& mass, double* a) const;
    // general mode with a ring held: the rows, A^-1 and the bias at the displacements x and velocities v
    void refresh(const double* x, const double* v);
    // general mode with a ring held: held bond h's multiplier's rate beyond A^-1 W au' (its rows' turn and
    // the centripetal terms' rates), at x, v with the accelerations without (au) and with (a) the holds
    double ring_rate(int h, const double* x, const double* v, const double* au, const double* a) const;
    const System* sys = nullptr;  // (the system of the last build: what refresh reads)
    // held bond h's force, N (sign: the bond's), from the accelerations without (au) and with (a) the held bonds
    double force(double sign, int h, const std::vector<double>& mass, const double* au, const double* a) const;
    // a dof's side of an impact: its group's mass (infinite when it cannot move), kg (not in general mode)
    double side_mass(const std::vector<double>& mass, int k) const;
    // add dv to the velocity of dof k and every dof moving with it (nothing for the ground or a grounded group;
    // not in general mode)
    void add_velocity(double* v, int k, double dv) const;
    // general mode: w . P M^-1 w for a pair's w (1/kg: 0 where the holds keep it from moving)
    double inverse_mass(const std::vector<double>& mass, const Pair& p) const;
    // general mode: v += s P M^-1 w (an impulse -s along the pair's w with the holds: s in N s)
    void impulse(const std::vector<double>& mass, double* v, const Pair& p, double s) const;
    // the same for a row w given whole (n: a ring's contact's, its compression's gradient at the state)
    double inverse_mass_row(const std::vector<double>& mass, const double* w) const;
    void impulse_row(const std::vector<double>& mass, double* v, const double* w, double s) const;
    // general mode: P's entry (i, k) (held dof i's acceleration's weight on dof k's free one)
    double projector(const std::vector<double>& mass, int i, int k) const;
};

// is a held bond a tie (a sticking friction element's)?
inline bool is_tie(const Sticking& s, int h) { return s.held[static_cast<size_t>(h)] >= s.nc; }

// would holding contact c shut close a loop of held bonds (through the ground too)?
bool sticking_closes_loop(const System& sy, const double* st, int c);

}  // namespace pounding
