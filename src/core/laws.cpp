// The contact laws (laws.hpp): Kelvin-Voigt, Hunt-Crossley, Jankowski, Hertzdamp, the multi-linear
// backbone (elastic, or with Masing's loops from Iwan's springs), the elastic-plastic impact law and the rigid
// stop.
#include "laws.hpp"

#include <algorithm>
#include <cmath>

namespace pounding {
namespace {

// ---------------------------------------------------------------- each law's parameters, decoded once
// (in the order its Python dataclass's params() writes them: pounding/model/contact_laws/<law>.py)

struct KelvinVoigtP { double k, c; };  // stiffness, damping
KelvinVoigtP kelvin_voigt(const double* p) { return {p[0], p[1]}; }

// Hunt-Crossley, Jankowski and Hertzdamp: stiffness, damping (Hertzdamp's xi_norm), exponent
struct HertzP { double k, c, n; };
HertzP hertz(const double* p) { return {p[0], p[1], p[2]}; }

// the multi-linear backbone, elastic or kinematic: damping, the number of slopes n, 4 slopes, 3 breakpoints
struct MlP { double c; int n; const double* k; const double* b; };
MlP multilinear(const double* p) { return {p[0], static_cast<int>(p[1]), p + 2, p + 6}; }

struct EpP { double k1, k2, dy; };  // elastic-plastic: the elastic and the plastic slopes, the yield compression
EpP elastic_plastic(const double* p) { return {p[0], p[1], p[2]}; }

// ---------------------------------------------------------------- multi-linear backbone
// p: damping, number of slopes n, 4 slopes, 3 breakpoints
constexpr double ML_TIE = 1e-9;  // relative: a compression this close above a breakpoint recovers below it

struct MlBranch { double force, slope; int j; double offset; };

MlBranch ml_branch(const MlP& ml, double d) {
    const int n = ml.n;
    double force = 0.0, lower = 0.0;
    for (int j = 0; j < n; ++j) {
        const double k = ml.k[j];
        if (j == n - 1 || d <= ml.b[j]) return {force + k * (d - lower), k, j, force - k * lower};
        const double upper = ml.b[j];
        force += k * (upper - lower);
        lower = upper;
    }
    return {0.0, 0.0, 0, 0.0};
}

struct Line { double k, offset, lower; };

Line ml_branch_line(const MlP& ml, int j) {
    const double lower = j == 0 ? 0.0 : ml.b[j - 1];
    const double k = ml.k[j];
    return {k, ml_branch(ml, lower).force - k * lower, lower};
}

double ml_energy(const MlP& ml, double d) {
    const int n = ml.n;
    double energy = 0.0, force = 0.0, lower = 0.0;
    for (int j = 0; j < n; ++j) {
        const double k = ml.k[j];
        const double upper = j == n - 1 ? d : std::min(d, ml.b[j]);
        if (upper <= lower) break;
        energy += (force + 0.5 * k * (upper - lower)) * (upper - lower);
        force += k * (upper - lower);
        lower = upper;
    }
    return energy;
}

struct DownBranch { double k, offset, lower, t_edge; };

DownBranch ml_down_branch(const MlP& ml, double d) {
    const double c = ml.c;
    int j = ml_branch(ml, d).j;
    if (j > 0 && d <= ml.b[j - 1] * (1.0 + ML_TIE)) j -= 1;
    const Line l = ml_branch_line(ml, j);
    if (j == 0) return {l.k, l.offset, l.lower, INF};
    if (l.k > 0.0) {
        const double target = -l.offset / l.k;
        return {l.k, l.offset, l.lower, c / l.k * std::log((d - target) / (l.lower - target))};
    }
    return {l.k, l.offset, l.lower, (d - l.lower) * c / l.offset};
}

Relaxed ml_relax(const MlP& ml, double d0, double tau) {
    const double c = ml.c;
    if (c <= 0.0 || d0 <= 0.0) return {0.0, 0.0};
    double d = d0, left = tau;
    for (int pass = 0; pass < 8; ++pass) {
        const DownBranch b = ml_down_branch(ml, d);
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

double ml_relax_horizon(const MlP& ml, double d0) {
    if (ml.c <= 0.0 || d0 <= 0.0) return INF;
    return ml_down_branch(ml, d0).t_edge;
}

// ---------------------------------------------------------------- elastic-plastic (ImpactMaterial)
// p: k1, k2, dy; state z[0]: the plastic offset (>= 0) on the elastic branch, or a line's code
constexpr int EP_ELASTIC = 0, EP_YIELD_BRANCH = 1, EP_UNLOAD_BRANCH = 2;
constexpr double EP_YIELD = -1.0, EP_UNLOAD = -2.0;

struct EpLine { double k, r; int j; };

EpLine ep_line(const EpP& ep, double z) {
    const double k1 = ep.k1, k2 = ep.k2;
    if (z == EP_YIELD) return {k2, (k1 - k2) * ep.dy, EP_YIELD_BRANCH};
    if (z == EP_UNLOAD) return {k2, 0.0, EP_UNLOAD_BRANCH};
    return {k1, -k1 * z, EP_ELASTIC};
}

Edges ep_edges(const EpP& ep, double z) {
    if (z < 0.0) return {-1.0, -1.0};
    const double k1 = ep.k1, k2 = ep.k2;
    const double s = k1 * z / (k1 - k2);
    return {z > 0.0 ? s : -1.0, ep.dy + s};
}

double ep_turn_sign(double z) {
    if (z == EP_YIELD) return 1.0;
    if (z == EP_UNLOAD) return -1.0;
    return 0.0;
}

double ep_after_event(const EpP& ep, double z, double d, double code) {
    const double k1 = ep.k1, k2 = ep.k2;
    if (z == EP_YIELD) {
        const double f = k2 * d + (k1 - k2) * ep.dy;
        return std::max(d - f / k1, 0.0);
    }
    if (z == EP_UNLOAD) return std::max(d * (1.0 - k2 / k1), 0.0);
    return code;
}

double ep_force(const EpP& ep, double d, double z) {
    const EpLine l = ep_line(ep, z);
    return std::max(l.k * d + l.r, 0.0);
}

double ep_energy(const EpP& ep, double d, double z) {
    const double k1 = ep.k1, k2 = ep.k2;
    const double f = ep_force(ep, d, z);
    const double dp = z >= 0.0 ? z : std::max(d - f / k1, 0.0);
    return 0.5 * f * f / k1 + 0.5 * k1 * k2 * dp * dp / (k1 - k2);
}

void ep_force_path(const EpP& ep, const double* d, double* out, int64_t n) {
    const double k1 = ep.k1, k2 = ep.k2, dy = ep.dy;
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

double kb_linear_slope(const MlP& ml) {
    const int n = ml.n;
    double k = ml.k[0];
    for (int i = 0; i < n - 1; ++i) {
        const double step = ml.k[i] - ml.k[i + 1];
        if (step > 0.0) k -= step;
    }
    return std::max(k, 0.0);
}

struct KbSpring { double force, k, r; int m; };

KbSpring kb_spring(const MlP& ml, const double* z, double x, double dx) {
    const int n = ml.n;
    double k = kb_linear_slope(ml), r = 0.0;
    int m = 0;
    for (int i = 0; i < n - 1; ++i) {
        const double b = ml.b[i];
        const double step = ml.k[i] - ml.k[i + 1];
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

Edges kb_edges(const MlP& ml, int j, const double* z) {
    const int n = ml.n;
    double lower = -1.0, upper = INF;
    int count = 0;
    for (int i = 0; i < n - 1; ++i) {
        const double b = ml.b[i];
        const double step = ml.k[i] - ml.k[i + 1];
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

double kb_turn_sign(const MlP& ml, const double* z) {
    const int n = ml.n;
    for (int i = 0; i < n - 1; ++i)
        if (z[4 + i] != 0.0) return z[4 + i];
    return 0.0;
}

void kb_after_event(const MlP& ml, double* z, double x, double code) {
    const int n = ml.n;
    if (code == 0.0) {
        for (int i = 0; i < n - 1; ++i) {
            const double s = z[4 + i];
            if (s != 0.0) {
                z[1 + i] = x - s * ml.b[i];
                z[4 + i] = 0.0;
            }
        }
        return;
    }
    const double sg = code == KB_EDGE_UP ? 1.0 : -1.0;
    double best = INF;
    for (int i = 0; i < n - 1; ++i) {
        const double b = ml.b[i];
        const double step = ml.k[i] - ml.k[i + 1];
        if (step > 0.0 && z[4 + i] == 0.0) best = std::min(best, std::abs(x - (z[1 + i] + sg * b)) / b);
        else if (step < 0.0) best = std::min(best, std::abs(x - b) / b);
    }
    for (int i = 0; i < n - 1; ++i) {
        const double b = ml.b[i];
        const double step = ml.k[i] - ml.k[i + 1];
        if (step > 0.0 && z[4 + i] == 0.0) {
            const double gap = std::abs(x - (z[1 + i] + sg * b)) / b;
            if (gap <= best + KB_TIE) z[4 + i] = sg;
        }
    }
}

double kb_branch_loss(const MlP& ml, const double* z, double x0, double x1) {
    const int n = ml.n;
    double loss = 0.0;
    for (int i = 0; i < n - 1; ++i) {
        const double s = z[4 + i];
        if (s != 0.0) loss += s * (ml.k[i] - ml.k[i + 1]) * ml.b[i] * (x1 - x0);
    }
    return loss;
}

double kb_energy(const MlP& ml, double x, const double* z) {
    const int n = ml.n;
    const double k_lin = kb_linear_slope(ml);
    double e = 0.5 * k_lin * x * x;
    for (int i = 0; i < n - 1; ++i) {
        const double b = ml.b[i];
        const double step = ml.k[i] - ml.k[i + 1];
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

void kb_contact_state(const MlP& ml, double* z, double x) {
    const int n = ml.n;
    for (int i = 0; i < n - 1; ++i) {
        if (z[4 + i] < 0.0) {
            z[1 + i] = x + ml.b[i];
            z[4 + i] = 0.0;
        }
    }
}

void kb_release_state(const MlP& ml, double* z, double x) {
    const int n = ml.n;
    for (int i = 0; i < n - 1; ++i) {
        if (z[4 + i] > 0.0) {
            z[1 + i] = x - ml.b[i];
            z[4 + i] = 0.0;
        }
    }
}

void kb_moved(const MlP& ml, double* z, double x, bool in_contact) {
    const int n = ml.n;
    for (int i = 0; i < n - 1; ++i) {
        const double b = ml.b[i];
        if (ml.k[i] - ml.k[i + 1] <= 0.0) continue;
        double s = z[4 + i];
        if (s == 0.0 && !in_contact && x - (z[1 + i] - b) <= KB_TIE * b) {
            s = -1.0;
            z[4 + i] = s;
        }
        if (s != 0.0) z[1 + i] = x - s * b;
    }
}

Line kb_down_piece(const MlP& ml, const double* z, double x) {
    const int n = ml.n;
    double k = kb_linear_slope(ml), r = 0.0, lower = 0.0;
    for (int i = 0; i < n - 1; ++i) {
        const double b = ml.b[i];
        const double step = ml.k[i] - ml.k[i + 1];
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

Relaxed kb_relax(const MlP& ml, double d0, double tau, const double* z) {
    const double c = ml.c;
    if (d0 <= 0.0) return {0.0, 0.0};
    double x = d0, left = tau;
    for (int pass = 0; pass < 16; ++pass) {
        const Line pc = kb_down_piece(ml, z, x);
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

double kb_relax_horizon(const MlP& ml, double d0, const double* z) {
    const double c = ml.c;
    if (c <= 0.0 || d0 <= 0.0) return INF;
    const Line pc = kb_down_piece(ml, z, d0);
    const double k = pc.k, r = pc.offset, lower = pc.lower;
    if (k * d0 + r <= 0.0) return INF;
    if (k > 0.0) {
        const double target = -r / k;
        if (target >= lower) return INF;
        return c / k * std::log((d0 - target) / (lower - target));
    }
    return (d0 - lower) * c / r;
}

void kb_force_path(const MlP& ml, const double* d, const double* v, double* out, int64_t count) {
    const int n = ml.n;
    const double k_lin = kb_linear_slope(ml);
    double e[3] = {0.0, 0.0, 0.0};
    double prev = 0.0;
    for (int64_t q = 0; q < count; ++q) {
        const double x = d[q];
        double f = k_lin * x + ml.c * v[q];
        for (int i = 0; i < n - 1; ++i) {
            const double b = ml.b[i];
            const double step = ml.k[i] - ml.k[i + 1];
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
    if (law == KELVIN_VOIGT) {
        const KelvinVoigtP kv = kelvin_voigt(p);
        return {kv.k, kv.c, 0.0, 0};
    }
    const MlP ml = multilinear(p);
    const Line l = ml_branch_line(ml, j);
    return {l.k, ml.c, l.offset, j};
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
    if (law == HERTZDAMP) {  // (its damping xi_norm k / v_in, from the speed the contact started at)
        const HertzP h = hertz(p);
        z[0] = rate > 0.0 ? h.c * h.k / rate : 0.0;
    } else if (law == MULTILINEAR_KINEMATIC) {
        kb_contact_state(multilinear(p), z, d);
    } else {
        z[0] = 0.0;
    }
}

void law_release_state(int law, const double* p, double* z, double d) {
    if (law == ELASTIC_PLASTIC) z[0] = 0.0;
    else if (law == MULTILINEAR_KINEMATIC) kb_release_state(multilinear(p), z, d);
}

void law_moved(int law, const double* p, double* z, double d, bool in_contact) {
    if (law == MULTILINEAR_KINEMATIC) kb_moved(multilinear(p), z, d, in_contact);
}

Branch law_linear_branch(int law, const double* p, double d, double dd, const double* z) {
    if (law == KELVIN_VOIGT) {
        const KelvinVoigtP kv = kelvin_voigt(p);
        return {kv.k, kv.c, 0.0, 0};
    }
    if (law == RIGID) return {0.0, 0.0, 0.0, 0};
    if (law == ELASTIC_PLASTIC) {
        const EpLine l = ep_line(elastic_plastic(p), z[0]);
        return {l.k, 0.0, l.r, l.j};
    }
    const MlP ml = multilinear(p);
    if (law == MULTILINEAR_KINEMATIC) {
        const KbSpring s = kb_spring(ml, z, d, dd);
        return {s.k, ml.c, s.r, s.m};
    }
    int j = ml_branch(ml, d).j;
    if (j < ml.n - 1 && dd > 0.0 && std::abs(d - ml.b[j]) <= BRANCH_TIE * ml.b[j]) j += 1;
    else if (j > 0 && dd < 0.0 && std::abs(d - ml.b[j - 1]) <= BRANCH_TIE * ml.b[j - 1]) j -= 1;
    return branch_coefficients(law, p, j);
}

Edges law_branch_edges(int law, const double* p, int j, const double* z) {
    if (law == ELASTIC_PLASTIC) return ep_edges(elastic_plastic(p), z[0]);
    if (law == MULTILINEAR_KINEMATIC) return kb_edges(multilinear(p), j, z);
    if (law != MULTILINEAR) return {-1.0, -1.0};
    const MlP ml = multilinear(p);
    return {j > 0 ? ml.b[j - 1] : -1.0, j < ml.n - 1 ? ml.b[j] : -1.0};
}

double law_branch_loss(int law, const double* p, int j, double d0, double d1, const double* z) {
    if (law == ELASTIC_PLASTIC && j == EP_YIELD_BRANCH) {
        const EpP ep = elastic_plastic(p);
        return (ep.k1 - ep.k2) * ep.dy * (d1 - d0);
    }
    if (law == MULTILINEAR_KINEMATIC) return kb_branch_loss(multilinear(p), z, d0, d1);
    return 0.0;
}

double law_turn_sign(int law, const double* p, const double* z) {
    if (law == ELASTIC_PLASTIC) return ep_turn_sign(z[0]);
    if (law == MULTILINEAR_KINEMATIC) return kb_turn_sign(multilinear(p), z);
    return 0.0;
}

void law_after_event(int law, const double* p, double* z, double d, double code) {
    if (law == ELASTIC_PLASTIC) z[0] = ep_after_event(elastic_plastic(p), z[0], d, code);
    else if (law == MULTILINEAR_KINEMATIC) kb_after_event(multilinear(p), z, d, code);
}

Force law_force(int law, const double* p, double d, double dd, const double* z) {
    if (law == RIGID) return {0.0, 0.0, 0.0, 0.0};  // (a held stop's force: sticking.hpp)
    if (law == KELVIN_VOIGT) {
        const KelvinVoigtP kv = kelvin_voigt(p);
        return {kv.k * d + kv.c * dd, kv.k * d, kv.k, kv.c};
    }
    if (law == ELASTIC_PLASTIC) {
        const EpP ep = elastic_plastic(p);
        const double f = ep_force(ep, d, z[0]);
        return {f, f, ep_line(ep, z[0]).k, 0.0};
    }
    if (law == MULTILINEAR_KINEMATIC) {
        const MlP ml = multilinear(p);
        const KbSpring s = kb_spring(ml, z, d, dd);
        return {s.force + ml.c * dd, s.force, s.k, ml.c};
    }
    if (law == MULTILINEAR) {
        const MlP ml = multilinear(p);
        const MlBranch b = ml_branch(ml, d);
        return {b.force + ml.c * dd, b.force, b.slope, ml.c};
    }
    const HertzP h = hertz(p);
    const double k = h.k, n = h.n;
    const double c = law == HERTZDAMP ? z[0] : h.c;
    const double dpos = d > 0.0 ? d : 0.0;
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
    if (law == KELVIN_VOIGT) return 0.5 * kelvin_voigt(p).k * d * d;
    if (law == MULTILINEAR) return ml_energy(multilinear(p), d);
    if (law == ELASTIC_PLASTIC) return ep_energy(elastic_plastic(p), d, z[0]);
    if (law == MULTILINEAR_KINEMATIC) return kb_energy(multilinear(p), d, z);
    const HertzP h = hertz(p);
    const double dpos = d > 0.0 ? d : 0.0;
    return h.k * std::pow(dpos, h.n + 1.0) / (h.n + 1.0);
}

Relaxed law_relax(int law, const double* p, double d0, double tau, const double* z) {
    if (d0 <= 0.0 || law == RIGID) return {0.0, 0.0};
    if (law == KELVIN_VOIGT) {
        const KelvinVoigtP kv = kelvin_voigt(p);
        if (kv.c <= 0.0) return {0.0, 0.0};
        const double rate = kv.k / kv.c;
        const double x = rate * tau;
        if (x > EXP_NORMAL_LIMIT) return {0.0, 0.0};  // (below the smallest normal double: exactly 0)
        const double d = d0 * std::exp(-x);
        if (d < MIN_NORMAL) return {0.0, 0.0};
        return {d, -rate * d};
    }
    if (law == MULTILINEAR) return ml_relax(multilinear(p), d0, tau);
    if (law == MULTILINEAR_KINEMATIC) return kb_relax(multilinear(p), d0, tau, z);
    if (law == JANKOWSKI || law == ELASTIC_PLASTIC) return {0.0, 0.0};
    const HertzP h = hertz(p);
    const double c = law == HERTZDAMP ? z[0] : h.c;
    if (c <= 0.0) return {0.0, 0.0};
    const double speed = h.k / c;
    const double d = d0 - speed * tau;
    if (d <= 0.0) return {0.0, 0.0};
    return {d, -speed};
}

double law_relax_horizon(int law, const double* p, double d0, const double* z) {
    if (law == MULTILINEAR) return ml_relax_horizon(multilinear(p), d0);
    if (law == MULTILINEAR_KINEMATIC) return kb_relax_horizon(multilinear(p), d0, z);
    return INF;
}

Relaxed law_release(int law, const double* p, double d, double dd, double ddd, const double* z) {
    if (law == RIGID) return {1.0, 0.0};  // (a held stop releases by its force: sticking.hpp)
    if (law == KELVIN_VOIGT) {
        const KelvinVoigtP kv = kelvin_voigt(p);
        return {kv.k * d + kv.c * dd, kv.k * dd + kv.c * ddd};
    }
    if (law == JANKOWSKI) return {1.0, 0.0};
    if (law == ELASTIC_PLASTIC) {
        const EpLine l = ep_line(elastic_plastic(p), z[0]);
        return {l.k * d + std::abs(l.r), l.k * dd};
    }
    if (law == MULTILINEAR_KINEMATIC) {
        const MlP ml = multilinear(p);
        const KbSpring s = kb_spring(ml, z, d, dd);
        return {s.force + ml.c * dd, s.k * dd + ml.c * ddd};
    }
    if (law == MULTILINEAR) {
        const MlP ml = multilinear(p);
        const MlBranch b = ml_branch(ml, d);
        return {b.force + ml.c * dd, b.slope * dd + ml.c * ddd};
    }
    const HertzP h = hertz(p);
    const double c = law == HERTZDAMP ? z[0] : h.c;
    return {h.k + c * dd, c * ddd};
}

void law_force_many(int law, const double* p, const double* d, const double* dd, double* out, int64_t n) {
    if (law == ELASTIC_PLASTIC) {
        ep_force_path(elastic_plastic(p), d, out, n);
        return;
    }
    if (law == MULTILINEAR_KINEMATIC) {
        kb_force_path(multilinear(p), d, dd, out, n);
        return;
    }
    double z[N_LAW_STATE] = {0};
    if (law == RIGID) {  // (no force at any compression: the impulses are the law)
        for (int64_t i = 0; i < n; ++i) out[i] = 0.0;
        return;
    }
    for (int64_t i = 0; i < n; ++i) out[i] = law_force(law, p, d[i], dd[i], z).f;
}

// ---------------------------------------------------------------- the memory as the monodromy's coordinates

int law_memory_size(int law, const double* p) {
    if (law == ELASTIC_PLASTIC) return 1;
    if (law == MULTILINEAR_KINEMATIC) return multilinear(p).n - 1;
    return 0;
}

void law_memory_read(int law, const double* p, const double* z, double d, double* m) {
    if (law == ELASTIC_PLASTIC) {  // the offset the elastic line would have if the branch turned here
        const EpP ep = elastic_plastic(p);
        const double soft = 1.0 - ep.k2 / ep.k1;
        if (z[0] == EP_YIELD) m[0] = d * soft - (ep.k1 - ep.k2) * ep.dy / ep.k1;
        else if (z[0] == EP_UNLOAD) m[0] = d * soft;
        else m[0] = z[0];
    } else if (law == MULTILINEAR_KINEMATIC) {
        for (int i = 0; i < multilinear(p).n - 1; ++i) m[i] = z[1 + i];
    }
}

void law_memory_write(int law, const double* p, double* z, const double* m) {
    if (law == ELASTIC_PLASTIC) {
        if (z[0] >= 0.0) z[0] = std::max(m[0], 0.0);
    } else if (law == MULTILINEAR_KINEMATIC) {
        for (int i = 0; i < multilinear(p).n - 1; ++i) z[1 + i] = m[i];
    }
}

MemoryBranch law_memory_branch(int law, const double* p, double d, double dd, const double* z, bool in_contact) {
    MemoryBranch b{};
    b.lower = -1.0;
    if (law == ELASTIC_PLASTIC) {  // (no free recovery: it springs back on release)
        if (!in_contact) return b;
        const EpP ep = elastic_plastic(p);
        const EpLine l = ep_line(ep, z[0]);
        b.k = l.k;
        b.j = l.j;
        if (l.j == EP_ELASTIC) b.g[0] = -ep.k1;  // k1 (d - m)
        else b.follow[0] = 1.0 - ep.k2 / ep.k1;
        if (l.j == EP_YIELD_BRANCH) b.r = l.r;
        return b;
    }
    if (law == MULTILINEAR_KINEMATIC) {
        const MlP ml = multilinear(p);
        b.c = ml.c;
        if (in_contact) {
            const KbSpring s = kb_spring(ml, z, d, dd);
            b.k = s.k, b.r = s.r, b.j = s.m;
            for (int i = 0; i < ml.n - 1; ++i) {
                const double step = ml.k[i] - ml.k[i + 1];
                if (!(step > 0.0)) continue;
                if (z[4 + i] == 0.0) {  // stuck: step (d - u_i), its u_i term out of r
                    b.r += step * z[1 + i];
                    b.g[i] = -step;
                } else {
                    b.follow[i] = 1.0;
                }
            }
            return b;
        }
        const Line pc = kb_down_piece(ml, z, d);
        b.k = pc.k, b.r = pc.offset;
        if (!(d > 0.0) && pc.offset > 0.0) {  // (at zero, pushed there: a small compression back at once)
            b.c = 0.0;
            b.forgets = true;
        } else if (!(d > 0.0) && pc.offset < 0.0) {
            b.c = 0.0;  // (at zero with a set that would pull it open: kb_relax keeps it there)
        }
        for (int i = 0; i < ml.n - 1; ++i) {
            const double bi = ml.b[i];
            const double step = ml.k[i] - ml.k[i + 1];
            if (!(step > 0.0)) continue;
            const double u = z[1 + i];
            if (z[4 + i] == 0.0 && d - (u - bi) > KB_TIE * bi) {  // (as kb_down_piece has it)
                b.r += step * u;
                b.g[i] = -step;
            } else {
                b.follow[i] = 1.0;  // slipping back with the compression
            }
        }
        if (law_relax_horizon(law, p, d, z) < INF) {
            b.lower = pc.lower;
            for (int i = 0; i < ml.n - 1; ++i)  // (the stuck spring whose slip sets lower)
                if (b.g[i] != 0.0 && z[1 + i] - ml.b[i] == pc.lower) {
                    b.dlower[i] = 1.0;
                    break;
                }
        }
        return b;
    }
    if (law == MULTILINEAR && !in_contact) {
        const MlP ml = multilinear(p);
        const DownBranch db = ml_down_branch(ml, d);
        b.k = db.k, b.c = ml.c, b.r = db.offset;
        if (db.t_edge < INF) b.lower = db.lower;
        return b;
    }
    const Branch br = law_linear_branch(law, p, d, dd, z);
    b.k = br.k, b.c = br.c, b.r = br.r, b.j = br.j;
    return b;
}

void law_edge_memory(int law, const double* p, int j, const double* z, bool upper, double* out) {
    for (int i = 0; i < MAX_LAW_MEMORY; ++i) out[i] = 0.0;
    if (law == ELASTIC_PLASTIC) {
        const EpP ep = elastic_plastic(p);
        if (z[0] >= 0.0 && (upper || z[0] > 0.0)) out[0] = ep.k1 / (ep.k1 - ep.k2);
        return;
    }
    if (law != MULTILINEAR_KINEMATIC) return;
    const MlP ml = multilinear(p);
    const Edges edges = kb_edges(ml, j, z);
    const double edge = upper ? edges.upper : edges.lower;
    for (int i = 0; i < ml.n - 1; ++i) {  // (the stuck spring whose slip sets it, as kb_edges finds it)
        if (!(ml.k[i] - ml.k[i + 1] > 0.0) || z[4 + i] != 0.0) continue;
        if ((upper ? z[1 + i] + ml.b[i] : z[1 + i] - ml.b[i]) == edge) {
            out[i] = 1.0;
            return;
        }
    }
}

bool law_forgets_on_release(int law) { return law == ELASTIC_PLASTIC; }

}  // namespace pounding
