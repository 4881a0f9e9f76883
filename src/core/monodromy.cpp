#include "monodromy.hpp"

#include <cmath>

#include "core.hpp"

namespace pounding {

namespace {
constexpr int I_DL = 2, I_DR = 3, FIRST_SLIP = 4;

// A~_m, (n + 3, n + 3): x, then sin(theta), cos(theta), 1
Mat augmented(const Hybrid& h, bool in_l, bool in_r, const std::vector<double>& iso, double omega, double amp) {
    const int n_sp = h.kinematic ? static_cast<int>(h.slopes.size()) - 1 : 0;
    const int n = FIRST_SLIP + n_sp;
    Mat a(n + 3, n + 3);
    const int s_ = n, c_ = n + 1, one = n + 2;
    const double m = h.mass;
    a(0, 1) = 1.0;
    a(1, 1) -= h.c_d / m;
    if (h.kinematic) {
        a(1, 0) -= h.slopes[n_sp] / m;
        for (int i = 0; i < n_sp; ++i) {
            const double dk = h.slopes[i] - h.slopes[i + 1];
            const double s = iso[i];
            if (s == 0.0) {
                a(1, 0) -= dk / m;
                a(1, FIRST_SLIP + i) += dk / m;
            } else {
                a(1, one) -= s * dk * h.breaks[i] / m;
                a(FIRST_SLIP + i, 1) = 1.0;  // a slipping spring moves with the mass
            }
        }
    } else {
        const int r = static_cast<int>(iso[0]);
        const int j = std::abs(r);
        const double k = h.slopes[j];
        a(1, 0) -= k / m;
        if (j > 0) {
            double f_break = h.slopes[0] * h.breaks[0];
            double dot = 0.0;
            for (int i = 1; i < j; ++i) dot += h.slopes[i] * (h.breaks[i] - h.breaks[i - 1]);
            f_break += dot;
            a(1, one) -= (r > 0 ? 1.0 : -1.0) * (f_break - k * h.breaks[j - 1]) / m;
        }
    }
    for (int side = 0; side < 2; ++side) {
        const bool touching = side == 0 ? in_l : in_r;
        const int row = side == 0 ? I_DL : I_DR;
        const double sign = side == 0 ? -1.0 : 1.0;
        const double kb = h.stiffness[side], cb = h.damping[side], gap = h.gaps[side];
        if (touching) {
            a(1, 0) -= kb / m;
            a(1, 1) -= cb / m;
            a(1, one) += sign * kb * gap / m;
            a(row, 1) = sign;  // the compression follows the mass
        } else if (cb > 0.0) {
            a(row, row) = -kb / cb;  // relaxing
        }
    }
    a(1, s_) = -amp;
    a(s_, c_) = omega;
    a(c_, s_) = -omega;
    return a;
}

std::vector<double> guard_gradient(const Hybrid& h, int action, int index, int n) {
    std::vector<double> g(n, 0.0);
    const double sign = index == 0 ? -1.0 : 1.0;
    if (action == ACT_CONTACT) {
        g[0] = sign;
        if (h.damping[index] > 0.0) g[index == 0 ? I_DL : I_DR] = -1.0;
    } else if (action == ACT_RELEASE) {
        g[0] = sign * h.stiffness[index];
        g[1] = sign * h.damping[index];
    } else if (action == ACT_YIELD) {
        g[0] = 1.0;
        g[FIRST_SLIP + index] = -1.0;
    } else if (action == ACT_REVERSAL) {
        g[1] = 1.0;
    } else if (action == ACT_REGION) {
        g[0] = 1.0;
    }
    return g;
}

void next_mode(int action, int index, bool& in_l, bool& in_r, std::vector<double>& iso, const std::vector<double>& x,
               double acc) {
    if (action == ACT_CONTACT || action == ACT_RELEASE) {
        const bool now = action == ACT_CONTACT;
        if (index == 0) in_l = now;
        else in_r = now;
    } else if (action == ACT_YIELD) {
        iso[index] = x[0] - x[FIRST_SLIP + index] > 0.0 ? 1.0 : -1.0;
    } else if (action == ACT_REVERSAL) {
        for (double& s : iso) s = 0.0;
    } else if (action == ACT_REGION) {
        const double heading = x[1] != 0.0 ? x[1] : acc;
        iso[0] += heading > 0.0 ? 1.0 : -1.0;
    }
}

void after_event(const Hybrid& h, int action, int index, std::vector<double>& x) {
    if (action == ACT_CONTACT) {
        const double depth = (index == 0 ? -x[0] : x[0]) - h.gaps[index];
        x[index == 0 ? I_DL : I_DR] = std::max(0.0, depth);
    } else if (action == ACT_YIELD) {
        const double strain = x[0] - x[FIRST_SLIP + index];
        const double sign = strain > 0.0 ? 1.0 : (strain < 0.0 ? -1.0 : 0.0);
        x[FIRST_SLIP + index] = x[0] - sign * h.breaks[index];
    }
}

// expm(a tau), the states that evolve alone (a relaxing bumper) by their scalar exponential
Mat exponential(const Mat& a, double tau) {
    const int size = a.rows;
    std::vector<int> rest;
    for (int i = 0; i < size; ++i) {
        bool joined = false;
        for (int j = 0; j < size; ++j)
            if (i != j && (a(i, j) != 0.0 || a(j, i) != 0.0)) joined = true;
        if (joined) rest.push_back(i);
    }
    const int nr = static_cast<int>(rest.size());
    Mat sub(nr, nr);
    for (int i = 0; i < nr; ++i)
        for (int j = 0; j < nr; ++j) sub(i, j) = a(rest[i], rest[j]) * tau;
    const Mat block = expm(sub);
    Mat out(size, size);
    for (int i = 0; i < size; ++i) out(i, i) = std::exp(a(i, i) * tau);
    for (int i = 0; i < nr; ++i)
        for (int j = 0; j < nr; ++j) out(rest[i], rest[j]) = block(i, j);
    return out;
}

Mat top_left(const Mat& m, int n) {
    Mat out(n, n);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) out(i, j) = m(i, j);
    return out;
}
}  // namespace

int monodromy(const Hybrid& h, const std::vector<double>& x0, bool in_l, bool in_r, std::vector<double> iso,
              const double* events, int n_events, double t0, double t_end, double omega, double amp, double phase,
              Mat& jac, std::vector<double>& x_end) {
    const int n = static_cast<int>(x0.size());
    double t = t0;
    std::vector<double> xa(n + 3, 0.0);
    for (int i = 0; i < n; ++i) xa[i] = x0[i];
    xa[n] = std::sin(omega * t + phase);
    xa[n + 1] = std::cos(omega * t + phase);
    xa[n + 2] = 1.0;
    jac = Mat::identity(n);
    Mat a = augmented(h, in_l, in_r, iso, omega, amp);
    for (int e = 0; e <= n_events; ++e) {
        const double t_ev = e < n_events ? events[3 * e] : t_end;
        const Mat step = exponential(a, t_ev - t);
        xa = matvec(step, xa);
        jac = matmul(top_left(step, n), jac);
        t = t_ev;
        if (e == n_events) break;
        const int action = static_cast<int>(events[3 * e + 1]), index = static_cast<int>(events[3 * e + 2]);
        std::vector<double> x(xa.begin(), xa.begin() + n);
        const std::vector<double> f_before = matvec(a, xa);
        bool nl = in_l, nr = in_r;
        std::vector<double> new_iso = iso;
        next_mode(action, index, nl, nr, new_iso, x, f_before[1]);
        const Mat a_after = augmented(h, nl, nr, new_iso, omega, amp);
        const std::vector<double> f_after = matvec(a_after, xa);
        const std::vector<double> grad = guard_gradient(h, action, index, n);
        double rate = 0.0;
        for (int i = 0; i < n; ++i) rate += grad[i] * f_before[i];
        if (rate == 0.0) {  // (tangent: no saltation, unless the field does not jump)
            for (int i = 0; i < n; ++i) {
                if (f_after[i] != f_before[i]) {
                    x_end.assign(xa.begin(), xa.begin() + n);
                    return e;
                }
            }
        } else {
            Mat jump = Mat::identity(n);
            for (int i = 0; i < n; ++i)
                for (int j = 0; j < n; ++j) jump(i, j) += (f_after[i] - f_before[i]) * grad[j] / rate;
            jac = matmul(jump, jac);
        }
        after_event(h, action, index, x);
        for (int i = 0; i < n; ++i) xa[i] = x[i];
        in_l = nl;
        in_r = nr;
        iso = new_iso;
        a = a_after;
    }
    x_end.assign(xa.begin(), xa.begin() + n);
    return -1;
}

}  // namespace pounding
