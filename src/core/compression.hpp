// A contact's compression and the direction its force pushes along, for either kind of contact (core.hpp's
// Contact): a line's (its pair's sign w . x less its gap) and a ring's (Radial: a point's distance from the
// ring's centre less the radius, pushed along the normal).  Every path that reads a compression or pushes a
// contact's force goes through these, a line's number for number as its pair's own arithmetic.
#pragma once

#include <cmath>

#include "core.hpp"

namespace pounding {

// a contact's compression (m), its rate (m/s) and its second derivative (m/s^2) from the displacements x,
// velocities v and accelerations a (n each; a may be null: da 0).  A line's: sign w . x - gap; a ring's
// (Radial): the point's distance from the centre less the radius
struct Compression { double d, dv, da; };
template <class C>
inline Compression compression(const C& c, const double* x, const double* v, const double* a = nullptr) {
    if (__builtin_expect(!c.radial.on, 1)) {
        const double sg = c.sign;
        return {sg * rel(x, c) - c.gap, sg * rel(v, c), a != nullptr ? sg * rel(a, c) : 0.0};
    }
    const Radial& q = c.radial;
    const double px = q.px + rel(x, c), py = q.py + rel(x, q.y);
    const double r = std::hypot(px, py);
    const double nx = px / r, ny = py / r;
    const double vx = rel(v, c), vy = rel(v, q.y);
    const double dv = nx * vx + ny * vy;
    // (d'' = n . u'' + |u'|^2 - (n . u')^2) / r: the normal turns as the point moves along the wall)
    const double da = a != nullptr ? nx * rel(a, c) + ny * rel(a, q.y) + (vx * vx + vy * vy - dv * dv) / r : 0.0;
    return {r - q.radius, dv, da};
}
// the compression alone (m)
template <class C>
inline double compression_of(const C& c, const double* x) {
    if (__builtin_expect(!c.radial.on, 1)) return c.sign * rel(x, c) - c.gap;
    return std::hypot(c.radial.px + rel(x, c), c.radial.py + rel(x, c.radial.y)) - c.radial.radius;
}
// a ring's centripetal term (m/s^2): its compression's second derivative at zero acceleration,
// (|P'|^2 - (n . P')^2) / |P| (the normal turning as the point P moves along the wall)
template <class C>
inline double ring_bend(const C& c, const double* x, const double* v) {
    const Radial& q = c.radial;
    const double px = q.px + rel(x, c), py = q.py + rel(x, q.y);
    const double r = std::hypot(px, py);
    const double vx = rel(v, c), vy = rel(v, q.y);
    const double dv = (px / r) * vx + (py / r) * vy;
    return (vx * vx + vy * vy - dv * dv) / r;
}
// a ring's point along a motion of velocities v and accelerations a_m: its normal n, the normal's turn
// n' = (P' - n (n . P')) / |P|, the centripetal term kappa and its rate (kappa' from P' and P'')
struct RingTurn { double nx, ny, tx, ty, bend, bend_rate; };
template <class C>
inline RingTurn ring_turn(const C& c, const double* x, const double* v, const double* a_m) {
    const Radial& q = c.radial;
    const double px = q.px + rel(x, c), py = q.py + rel(x, q.y);
    const double r = std::hypot(px, py);
    const double nx = px / r, ny = py / r;
    const double vx = rel(v, c), vy = rel(v, q.y), ax = rel(a_m, c), ay = rel(a_m, q.y);
    const double dv = nx * vx + ny * vy;
    const double bend = (vx * vx + vy * vy - dv * dv) / r;
    const double bend_rate = (2.0 * (vx * ax + vy * ay) - 2.0 * dv * (bend + nx * ax + ny * ay) - bend * dv) / r;
    return {nx, ny, (vx - nx * dv) / r, (vy - ny * dv) / r, bend, bend_rate};
}
// a ring's push's rate (m/s^3): d/dt (n . a_p + kappa), the point's compression's second derivative with the
// accelerations a_p (n, those pushing it) and their rate jerk, along a motion of velocities v and
// accelerations a_m
template <class C>
inline double ring_push_rate(const C& c, const double* x, const double* v, const double* a_p, const double* a_m,
                             const double* jerk) {
    const RingTurn t = ring_turn(c, x, v, a_m);
    return t.tx * rel(a_p, c) + t.ty * rel(a_p, c.radial.y) + t.nx * rel(jerk, c) + t.ny * rel(jerk, c.radial.y) +
           t.bend_rate;
}
// a force f along a contact's compression onto q (n): q += f grad(compression) (a line's f sign w; a ring's
// f (n_x w_x + n_y w_y) at the displacements x)
template <class C>
inline void push_contact(double* q, const C& c, const double* x, double f) {
    if (__builtin_expect(!c.radial.on, 1)) return push_pair(q, c, c.sign * f);
    const double px = c.radial.px + rel(x, c), py = c.radial.py + rel(x, c.radial.y);
    const double r = std::hypot(px, py);
    push_pair(q, c, f * (px / r));
    push_pair(q, c.radial.y, f * (py / r));
}
// the rate of that push on dof i, f and its rate given (N, N/s): d/dt (f grad(compression))_i
template <class C>
inline double push_contact_rate(const C& c, int i, const double* x, const double* v, double f, double rate) {
    if (__builtin_expect(!c.radial.on, 1)) return weight_on(c, i) * (c.sign * rate);
    const Radial& q = c.radial;
    const double wx = weight_on(c, i), wy = weight_on(q.y, i);
    if (wx == 0.0 && wy == 0.0) return 0.0;
    const double px = q.px + rel(x, c), py = q.py + rel(x, q.y);
    const double r = std::hypot(px, py);
    const double nx = px / r, ny = py / r;
    const double vx = rel(v, c), vy = rel(v, q.y);
    const double dv = nx * vx + ny * vy;
    const double nx_rate = (vx - nx * dv) / r, ny_rate = (vy - ny * dv) / r;  // (the normal's turn)
    return wx * (rate * nx + f * nx_rate) + wy * (rate * ny + f * ny_rate);
}

}  // namespace pounding
