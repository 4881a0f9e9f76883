// The contact laws (laws.hpp): Kelvin-Voigt, Hunt-Crossley, Jankowski, Hertzdamp, the multi-linear
// backbone (elastic, or with Masing's loops from Iwan's springs), the elastic-plastic impact law and the rigid
// stop.
#include "laws.hpp"

#include <algorithm>
#include <cmath>

namespace pounding {
namespace {

// ---------------------------------------------------------------- multi-linear backbone
// p: damping, number of slopes n, 4 slopes, 3 breakpoints
constexpr double ML_TIE = 1e-9;  // relative: a compression this close above a breakpoint recovers below it

struct MlBranch { double force, slope; int j; double offset; };

MlBranch ml_branch(const double* p, double d) {
    const int n = static_cast<int>(p[1]);
    double force = 0.0, lower = 0.0;
    for (int j = 0; j < n; ++j) {
        const double k = p[2 + j];
        if (j == n - 1 || d <= p[6 + j]) return {force + k * (d - lower), k, j, force - k * lower};
        const double upper = p[6 + j];
        force += k * (upper - lower);
        lower = upper;
    }
    return {0.0, 0.0, 0, 0.0};
}

struct Line { double k, offset, lower; };

Line ml_branch_line(const double* p, int j) {
    const double lower = j == 0 ? 0.0 : p[5 + j];
    const double k = p[2 + j];
    return {k, ml_branch(p, lower).force - k * lower, lower};
}

double ml_energy(const double* p, double d) {
    const int n = static_cast<int>(p[1]);
    double energy = 0.0, force = 0.0, lower = 0.0;
    for (int j = 0; j < n; ++j) {
        const double k = p[2 + j];
        const double upper = j == n - 1 ? d : std::min(d, p[6 + j]);
        if (upper <= lower) break;
        energy += (force + 0.5 * k * (upper - lower)) * (upper - lower);
        force += k * (upper - lower);
        lower = upper;
    }
    return energy;
}

struct DownBranch { double k, offset, lower, t_edge; };

DownBranch ml_down_branch(const double* p, double d) {
    const double c = p[0];
    int j = ml_branch(p, d).j;
    if (j > 0 && d <= p[5 + j] * (1.0 + ML_TIE)) j -= 1;
    const Line l = ml_branch_line(p, j);
    if (j == 0) return {l.k, l.offset, l.lower, INF};
    if (l.k > 0.0) {
        const double target = -l.offset / l.k;
        return {l.k, l.offset, l.lower, c / l.k * std::log((d - target) / (l.lower - target))};
    }
    return {l.k, l.offset, l.lower, (d - l.lower) * c / l.offset};
}

Relaxed ml_relax(const double* p, double d0, double tau) {
    const double c = p[0];
    if (c <= 0.0 || d0 <= 0.0) return {0.0, 0.0};
    double d = d0, left = tau;
    for (int pass = 0; pass < 8; ++pass) {
        const DownBranch b = ml_down_branch(p, d);
        if (b.t_edge < left) {
            left -= b.t_edge;
            d = b.lower;
            continue;
        }
        if (b.k > 0.0) {
            const double x = b.k / c * left;
            if (x > EXP_NORMAL_LIMIT) return {0.0, 0.0};
            const double target = -b.offset / b.k;
            const double d_new = target + (d - target) * std::exp(-x);
            if (d_new < MIN_NORMAL) return {0.0, 0.0};
            return {d_new, -(b.k * d_new + b.offset) / c};
        }
        return {d - b.offset / c * left, -b.offset / c};
    }
    return {0.0, 0.0};
}

double ml_relax_horizon(const double* p, double d0) {
    if (p[0] <= 0.0 || d0 <= 0.0) return INF;
    return ml_down_branch(p, d0).t_edge;
}

// ---------------------------------------------------------------- elastic-plastic (ImpactMaterial)
// p: k1, k2, dy; state z[0]: the plastic offset (>= 0) on the elastic branch, or a line's code
constexpr int EP_ELASTIC = 0, EP_YIELD_BRANCH = 1, EP_UNLOAD_BRANCH = 2;
constexpr double EP_YIELD = -1.0, EP_UNLOAD = -2.0;

struct EpLine { double k, r; int j; };

EpLine ep_line(const double* p, double z) {
    const double k1 = p[0], k2 = p[1];
    if (z == EP_YIELD) return {k2, (k1 - k2) * p[2], EP_YIELD_BRANCH};
    if (z == EP_UNLOAD) return {k2, 0.0, EP_UNLOAD_BRANCH};
    return {k1, -k1 * z, EP_ELASTIC};
}

Edges ep_edges(const double* p, double z) {
    if (z < 0.0) return {-1.0, -1.0};
    const double k1 = p[0], k2 = p[1];
    const double s = k1 * z / (k1 - k2);
    return {z > 0.0 ? s : -1.0, p[2] + s};
}

double ep_turn_sign(double z) {
    if (z == EP_YIELD) return 1.0;
    if (z == EP_UNLOAD) return -1.0;
    return 0.0;
}

double ep_after_event(const double* p, double z, double d, double code) {
    const double k1 = p[0], k2 = p[1];
    if (z == EP_YIELD) {
        const double f = k2 * d + (k1 - k2) * p[2];
        return std::max(d - f / k1, 0.0);
    }
    if (z == EP_UNLOAD) return std::max(d * (1.0 - k2 / k1), 0.0);
    return code;
}

double ep_force(const double* p, double d, double z) {
    const EpLine l = ep_line(p, z);
    return std::max(l.k * d + l.r, 0.0);
}

double ep_energy(const double* p, double d, double z) {
    const double k1 = p[0], k2 = p[1];
    const double f = ep_force(p, d, z);
    const double dp = z >= 0.0 ? z : std::max(d - f / k1, 0.0);
    return 0.5 * f * f / k1 + 0.5 * k1 * k2 * dp * dp / (k1 - k2);
}

void ep_force_path(const double* p, const double* d, double* out, int64_t n) {
    const double k1 = p[0], k2 = p[1], dy = p[2];
    double f = 0.0, prev = 0.0;
    for (int64_t i = 0; i < n; ++i) {
        const double x = d[i];
        if (x <= 0.0) {
            f = 0.0;
            prev = 0.0;
            out[i] = 0.0;
            continue;
        }
        f = f + k1 * (x - prev);
        f = std::min(std::max(f, k2 * x), k1 * dy + k2 * (x - dy));
        prev = x;
        out[i] = f;
    }
}

// ---------------------------------------------------------------- kinematic multi-linear (Iwan's springs)
// p as the multi-linear law's; state z[1 + i] the slip u_i, z[4 + i] its direction (-1, 0, +1)
constexpr double KB_TIE = 1e-9;
constexpr double KB_EDGE_UP = -1.0;

double kb_linear_slope(const double* p) {
    const int n = static_cast<int>(p[1]);
    double k = p[2];
    for (int i = 0; i < n - 1; ++i) {
        const double step = p[2 + i] - p[3 + i];
        if (step > 0.0) k -= step;
    }
    return std::max(k, 0.0);
}

struct KbSpring { double force, k, r; int m; };

KbSpring kb_spring(const double* p, const double* z, double x, double dx) {
    const int n = static_cast<int>(p[1]);
    double k = kb_linear_slope(p), r = 0.0;
    int m = 0;
    for (int i = 0; i < n - 1; ++i) {
        const double b = p[6 + i];
        const double step = p[2 + i] - p[3 + i];
        if (step > 0.0) {
            const double s = z[4 + i];
            if (s == 0.0) {
                k += step;
                r -= step * z[1 + i];
            } else {
                r += s * step * b;
            }
        } else if (step < 0.0) {
            if (x - b > KB_TIE * b || (std::abs(x - b) <= KB_TIE * b && dx > 0.0)) {
                k -= step;
                r += step * b;
                m += 1;
            }
        }
    }
    return {k * x + r, k, r, m};
}

Edges kb_edges(const double* p, int j, const double* z) {
    const int n = static_cast<int>(p[1]);
    double lower = -1.0, upper = INF;
    int count = 0;
    for (int i = 0; i < n - 1; ++i) {
        const double b = p[6 + i];
        const double step = p[2 + i] - p[3 + i];
        if (step > 0.0) {
            if (z[4 + i] == 0.0) {
                const double u = z[1 + i];
                upper = std::min(upper, u + b);
                if (u - b > 0.0) lower = std::max(lower, u - b);
            }
        } else if (step < 0.0) {
            if (count < j) lower = std::max(lower, b);
            else if (count == j) upper = std::min(upper, b);
            count += 1;
        }
    }
    return {lower, upper < INF ? upper : -1.0};
}

double kb_turn_sign(const double* p, const double* z) {
    const int n = static_cast<int>(p[1]);
    for (int i = 0; i < n - 1; ++i)
        if (z[4 + i] != 0.0) return z[4 + i];
    return 0.0;
}

void kb_after_event(const double* p, double* z, double x, double code) {
    const int n = static_cast<int>(p[1]);
    if (code == 0.0) {
        for (int i = 0; i < n - 1; ++i) {
            const double s = z[4 + i];
            if (s != 0.0) {
                z[1 + i] = x - s * p[6 + i];
                z[4 + i] = 0.0;
            }
        }
        return;
    }
    const double sg = code == KB_EDGE_UP ? 1.0 : -1.0;
    double best = INF;
    for (int i = 0; i < n - 1; ++i) {
        const double b = p[6 + i];
        const double step = p[2 + i] - p[3 + i];
        if (step > 0.0 && z[4 + i] == 0.0) best = std::min(best, std::abs(x - (z[1 + i] + sg * b)) / b);
        else if (step < 0.0) best = std::min(best, std::abs(x - b) / b);
    }
    for (int i = 0; i < n - 1; ++i) {
        const double b = p[6 + i];
        const double step = p[2 + i] - p[3 + i];
        if (step > 0.0 && z[4 + i] == 0.0) {
            const double gap = std::abs(x - (z[1 + i] + sg * b)) / b;
            if (gap <= best + KB_TIE) z[4 + i] = sg;
        }
    }
}

double kb_branch_loss(const double* p, const double* z, double x0, double x1) {
    const int n = static_cast<int>(p[1]);
    double loss = 0.0;
    for (int i = 0; i < n - 1; ++i) {
        const double s = z[4 + i];
        if (s != 0.0) loss += s * (p[2 + i] - p[3 + i]) * p[6 + i] * (x1 - x0);
    }
    return loss;
}

double kb_energy(const double* p, double x, const double* z) {
    const int n = static_cast<int>(p[1]);
    const double k_lin = kb_linear_slope(p);
    double e = 0.5 * k_lin * x * x;
    for (int i = 0; i < n - 1; ++i) {
        const double b = p[6 + i];
        const double step = p[2 + i] - p[3 + i];
        if (step > 0.0) {
            const double s = z[4 + i];
            const double strain = s == 0.0 ? x - z[1 + i] : s * b;
            e += 0.5 * step * strain * strain;
        } else if (step < 0.0 && x > b) {
            e -= 0.5 * step * (x - b) * (x - b);
        }
    }
    return e;
}

void kb_contact_state(const double* p, double* z, double x) {
    const int n = static_cast<int>(p[1]);
    for (int i = 0; i < n - 1; ++i) {
        if (z[4 + i] < 0.0) {
            z[1 + i] = x + p[6 + i];
            z[4 + i] = 0.0;
        }
    }
}

void kb_release_state(const double* p, double* z, double x) {
    const int n = static_cast<int>(p[1]);
    for (int i = 0; i < n - 1; ++i) {
        if (z[4 + i] > 0.0) {
            z[1 + i] = x - p[6 + i];
            z[4 + i] = 0.0;
        }
    }
}

void kb_moved(const double* p, double* z, double x, bool in_contact) {
    const int n = static_cast<int>(p[1]);
    for (int i = 0; i < n - 1; ++i) {
        const double b = p[6 + i];
        if (p[2 + i] - p[3 + i] <= 0.0) continue;
        double s = z[4 + i];
        if (s == 0.0 && !in_contact && x - (z[1 + i] - b) <= KB_TIE * b) {
            s = -1.0;
            z[4 + i] = s;
        }
        if (s != 0.0) z[1 + i] = x - s * b;
    }
}

Line kb_down_piece(const double* p, const double* z, double x) {
    const int n = static_cast<int>(p[1]);
    double k = kb_linear_slope(p), r = 0.0, lower = 0.0;
    for (int i = 0; i < n - 1; ++i) {
        const double b = p[6 + i];
        const double step = p[2 + i] - p[3 + i];
        if (step > 0.0) {
            const double u = z[1 + i];
            if (z[4 + i] == 0.0 && x - (u - b) > KB_TIE * b) {
                k += step;
                r -= step * u;
                lower = std::max(lower, u - b);
            } else {
                r -= step * b;
            }
        } else if (step < 0.0 && x - b > KB_TIE * b) {
            k -= step;
            r += step * b;
            lower = std::max(lower, b);
        }
    }
    return {k, r, lower};
}

Relaxed kb_relax(const double* p, double d0, double tau, const double* z) {
    const double c = p[0];
    if (d0 <= 0.0) return {0.0, 0.0};
    double x = d0, left = tau;
    for (int pass = 0; pass < 16; ++pass) {
        const Line pc = kb_down_piece(p, z, x);
        const double k = pc.k, r = pc.offset, lower = pc.lower;
        const double f = k * x + r;
        if (f <= 0.0) return {x, 0.0};
        double t_edge;
        if (k > 0.0) {
            const double target = -r / k;
            if (target >= lower) {
                if (c <= 0.0) return {target, 0.0};
                const double arg = k / c * left;
                if (arg > EXP_NORMAL_LIMIT) return {target, 0.0};
                const double gap = (x - target) * std::exp(-arg);
                if (gap < MIN_NORMAL) return {target, 0.0};
                return {target + gap, -k * gap / c};
            }
            t_edge = c > 0.0 ? c / k * std::log((x - target) / (lower - target)) : 0.0;
        } else {
            t_edge = c > 0.0 ? (x - lower) * c / r : 0.0;
        }
        if (t_edge < left || c <= 0.0) {
            left -= t_edge;
            x = lower;
            if (x <= 0.0) return {0.0, 0.0};
            continue;
        }
        if (k > 0.0) {
            const double target = -r / k;
            const double gap = (x - target) * std::exp(-k / c * left);
            return {target + gap, -k * gap / c};
        }
        return {x - r / c * left, -r / c};
    }
    return {x, 0.0};
}

double kb_relax_horizon(const double* p, double d0, const double* z) {
    const double c = p[0];
    if (c <= 0.0 || d0 <= 0.0) return INF;
    const Line pc = kb_down_piece(p, z, d0);
    const double k = pc.k, r = pc.offset, lower = pc.lower;
    if (k * d0 + r <= 0.0) return INF;
    if (k > 0.0) {
        const double target = -r / k;
        if (target >= lower) return INF;
        return c / k * std::log((d0 - target) / (lower - target));
    }
    return (d0 - lower) * c / r;
}

void kb_force_path(const double* p, const double* d, const double* v, double* out, int64_t count) {
    const int n = static_cast<int>(p[1]);
    const double k_lin = kb_linear_slope(p);
    double e[3] = {0.0, 0.0, 0.0};
    double prev = 0.0;
    for (int64_t q = 0; q < count; ++q) {
        const double x = d[q];
        double f = k_lin * x + p[0] * v[q];
        for (int i = 0; i < n - 1; ++i) {
            const double b = p[6 + i];
            const double step = p[2 + i] - p[3 + i];
            if (step > 0.0) {
                e[i] = std::min(std::max(e[i] + x - prev, -b), b);
                f += step * e[i];
            } else if (step < 0.0 && x > b) {
                f -= step * (x - b);
            }
        }
        prev = x;
        out[q] = f;
    }
}

Branch branch_coefficients(int law, const double* p, int j) {
    if (law == KELVIN_VOIGT) return {p[0], p[1], 0.0, 0};
    const Line l = ml_branch_line(p, j);
    return {l.k, p[0], l.offset, j};
}

}  // namespace

// ---------------------------------------------------------------- the dispatch: what the engine asks

bool law_is_linear(int law) {
    return law == KELVIN_VOIGT || law == RIGID || law == MULTILINEAR || law == ELASTIC_PLASTIC || law == MULTILINEAR_KINEMATIC;
}

bool law_is_rigid(int law) { return law == RIGID; }

bool law_has_memory(int law) { return law == ELASTIC_PLASTIC || law == MULTILINEAR_KINEMATIC; }

bool law_switches_at_rest(int law) { return law == JANKOWSKI; }

void law_contact_state(int law, const double* p, double rate, double* z, double d) {
    if (law == HERTZDAMP) z[0] = rate > 0.0 ? p[1] * p[0] / rate : 0.0;
    else if (law == MULTILINEAR_KINEMATIC) kb_contact_state(p, z, d);
    else z[0] = 0.0;
}

void law_release_state(int law, const double* p, double* z, double d) {
    if (law == ELASTIC_PLASTIC) z[0] = 0.0;
    else if (law == MULTILINEAR_KINEMATIC) kb_release_state(p, z, d);
}

void law_moved(int law, const double* p, double* z, double d, bool in_contact) {
    if (law == MULTILINEAR_KINEMATIC) kb_moved(p, z, d, in_contact);
}

Branch law_linear_branch(int law, const double* p, double d, double dd, const double* z) {
    if (law == KELVIN_VOIGT) return {p[0], p[1], 0.0, 0};
    if (law == RIGID) return {0.0, 0.0, 0.0, 0};
    if (law == ELASTIC_PLASTIC) {
        const EpLine l = ep_line(p, z[0]);
        return {l.k, 0.0, l.r, l.j};
    }
    if (law == MULTILINEAR_KINEMATIC) {
        const KbSpring s = kb_spring(p, z, d, dd);
        return {s.k, p[0], s.r, s.m};
    }
    const int n = static_cast<int>(p[1]);
    int j = ml_branch(p, d).j;
    if (j < n - 1 && dd > 0.0 && std::abs(d - p[6 + j]) <= BRANCH_TIE * p[6 + j]) j += 1;
    else if (j > 0 && dd < 0.0 && std::abs(d - p[5 + j]) <= BRANCH_TIE * p[5 + j]) j -= 1;
    return branch_coefficients(law, p, j);
}

Edges law_branch_edges(int law, const double* p, int j, const double* z) {
    if (law == ELASTIC_PLASTIC) return ep_edges(p, z[0]);
    if (law == MULTILINEAR_KINEMATIC) return kb_edges(p, j, z);
    if (law != MULTILINEAR) return {-1.0, -1.0};
    const int n = static_cast<int>(p[1]);
    return {j > 0 ? p[5 + j] : -1.0, j < n - 1 ? p[6 + j] : -1.0};
}

double law_branch_loss(int law, const double* p, int j, double d0, double d1, const double* z) {
    if (law == ELASTIC_PLASTIC && j == EP_YIELD_BRANCH) return (p[0] - p[1]) * p[2] * (d1 - d0);
    if (law == MULTILINEAR_KINEMATIC) return kb_branch_loss(p, z, d0, d1);
    return 0.0;
}

double law_turn_sign(int law, const double* p, const double* z) {
    if (law == ELASTIC_PLASTIC) return ep_turn_sign(z[0]);
    if (law == MULTILINEAR_KINEMATIC) return kb_turn_sign(p, z);
    return 0.0;
}

void law_after_event(int law, const double* p, double* z, double d, double code) {
    if (law == ELASTIC_PLASTIC) z[0] = ep_after_event(p, z[0], d, code);
    else if (law == MULTILINEAR_KINEMATIC) kb_after_event(p, z, d, code);
}

Force law_force(int law, const double* p, double d, double dd, const double* z) {
    const double k = p[0];
    double c = p[1];
    if (law == RIGID) return {0.0, 0.0, 0.0, 0.0};  // (a held stop's force: sticking.hpp)
    if (law == KELVIN_VOIGT) return {k * d + c * dd, k * d, k, c};
    if (law == ELASTIC_PLASTIC) {
        const double f = ep_force(p, d, z[0]);
        return {f, f, ep_line(p, z[0]).k, 0.0};
    }
    if (law == MULTILINEAR_KINEMATIC) {
        const KbSpring s = kb_spring(p, z, d, dd);
        return {s.force + k * dd, s.force, s.k, k};
    }
    if (law == MULTILINEAR) {
        const MlBranch b = ml_branch(p, d);
        return {b.force + k * dd, b.force, b.slope, k};
    }
    const double dpos = d > 0.0 ? d : 0.0;
    const double n = p[2];
    if (law == HERTZDAMP) c = z[0];
    const double dn = std::pow(dpos, n);
    const double slope = dpos > 0.0 ? n * std::pow(dpos, n - 1.0) : (n == 1.0 ? 1.0 : 0.0);
    if (law == HUNT_CROSSLEY || law == HERTZDAMP) return {dn * (k + c * dd), k * dn, slope * (k + c * dd), c * dn};
    // Jankowski: the dashpot c d^((n-1)/2) on the approach only
    if (dd <= 0.0 || dpos <= 0.0) return {k * dn, k * dn, k * slope, 0.0};
    const double root = std::pow(dpos, 0.5 * (n - 1.0));
    return {k * dn + c * root * dd, k * dn, k * slope + 0.5 * (n - 1.0) * c * root / dpos * dd, c * root};
}

double law_energy(int law, const double* p, double d, const double* z) {
    if (law == RIGID) return 0.0;
    if (law == KELVIN_VOIGT) return 0.5 * p[0] * d * d;
    if (law == MULTILINEAR) return ml_energy(p, d);
    if (law == ELASTIC_PLASTIC) return ep_energy(p, d, z[0]);
    if (law == MULTILINEAR_KINEMATIC) return kb_energy(p, d, z);
    const double dpos = d > 0.0 ? d : 0.0;
    return p[0] * std::pow(dpos, p[2] + 1.0) / (p[2] + 1.0);
}

Relaxed law_relax(int law, const double* p, double d0, double tau, const double* z) {
    if (d0 <= 0.0 || law == RIGID) return {0.0, 0.0};
    if (law == KELVIN_VOIGT) {
        if (p[1] <= 0.0) return {0.0, 0.0};
        const double rate = p[0] / p[1];
        const double x = rate * tau;
        if (x > EXP_NORMAL_LIMIT) return {0.0, 0.0};  // (below the smallest normal double: exactly 0)
        const double d = d0 * std::exp(-x);
        if (d < MIN_NORMAL) return {0.0, 0.0};
        return {d, -rate * d};
    }
    if (law == MULTILINEAR) return ml_relax(p, d0, tau);
    if (law == MULTILINEAR_KINEMATIC) return kb_relax(p, d0, tau, z);
    const double c = law == HERTZDAMP ? z[0] : p[1];
    if (law == JANKOWSKI || law == ELASTIC_PLASTIC || c <= 0.0) return {0.0, 0.0};
    const double speed = p[0] / c;
    const double d = d0 - speed * tau;
    if (d <= 0.0) return {0.0, 0.0};
    return {d, -speed};
}

double law_relax_horizon(int law, const double* p, double d0, const double* z) {
    if (law == MULTILINEAR) return ml_relax_horizon(p, d0);
    if (law == MULTILINEAR_KINEMATIC) return kb_relax_horizon(p, d0, z);
    return INF;
}

Relaxed law_release(int law, const double* p, double d, double dd, double ddd, const double* z) {
    if (law == RIGID) return {1.0, 0.0};  // (a held stop releases by its force: sticking.hpp)
    if (law == KELVIN_VOIGT) return {p[0] * d + p[1] * dd, p[0] * dd + p[1] * ddd};
    if (law == JANKOWSKI) return {1.0, 0.0};
    if (law == ELASTIC_PLASTIC) {
        const EpLine l = ep_line(p, z[0]);
        return {l.k * d + std::abs(l.r), l.k * dd};
    }
    if (law == MULTILINEAR_KINEMATIC) {
        const KbSpring s = kb_spring(p, z, d, dd);
        return {s.force + p[0] * dd, s.k * dd + p[0] * ddd};
    }
    if (law == MULTILINEAR) {
        const MlBranch b = ml_branch(p, d);
        return {b.force + p[0] * dd, b.slope * dd + p[0] * ddd};
    }
    const double c = law == HERTZDAMP ? z[0] : p[1];
    return {p[0] + c * dd, c * ddd};
}

void law_force_many(int law, const double* p, const double* d, const double* dd, double* out, int64_t n) {
    if (law == ELASTIC_PLASTIC) {
        ep_force_path(p, d, out, n);
        return;
    }
    if (law == MULTILINEAR_KINEMATIC) {
        kb_force_path(p, d, dd, out, n);
        return;
    }
    double z[N_LAW_STATE] = {0};
    if (law == RIGID) {  // (no force at any compression: the impulses are the law)
        for (int64_t i = 0; i < n; ++i) out[i] = 0.0;
        return;
    }
    for (int64_t i = 0; i < n; ++i) out[i] = law_force(law, p, d[i], dd[i], z).f;
}

}  // namespace pounding
