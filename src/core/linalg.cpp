#include "linalg.hpp"

#include <algorithm>
#include <cmath>

namespace pounding {

namespace {
constexpr double THETA[5] = {1.495585217958292e-2, 2.539398330063230e-1, 9.504178996162932e-1, 2.097847961257068e0,
                             5.371920351148152e0};
constexpr double B3[4] = {120.0, 60.0, 12.0, 1.0};
constexpr double B5[6] = {30240.0, 15120.0, 3360.0, 420.0, 30.0, 1.0};
constexpr double B7[8] = {17297280.0, 8648640.0, 1995840.0, 277200.0, 25200.0, 1512.0, 56.0, 1.0};
constexpr double B9[10] = {17643225600.0, 8821612800.0, 2075673600.0, 302702400.0, 30270240.0,
                           2162160.0,     110880.0,     3960.0,       90.0,        1.0};
constexpr double B13[14] = {64764752532480000.0, 32382376266240000.0, 7771770303897600.0, 1187353796428800.0,
                            129060195264000.0,   10559470521600.0,    670442572800.0,     33522128640.0,
                            1323241920.0,        40840800.0,          960960.0,           16380.0,
                            182.0,               1.0};

// out += c m, in place
Mat& add(Mat& out, double c, const Mat& m) {
    for (size_t i = 0; i < out.a.size(); ++i) out.a[i] += c * m.a[i];
    return out;
}

Mat balance(const Mat& a, std::vector<double>& d) {
    const int n = a.rows;
    Mat b = a;
    d.assign(n, 1.0);
    for (int pass = 0; pass < 64; ++pass) {
        bool done = true;
        for (int i = 0; i < n; ++i) {
            double c = 0.0, r = 0.0;
            for (int j = 0; j < n; ++j) {
                if (j != i) {
                    c += std::abs(b(j, i));
                    r += std::abs(b(i, j));
                }
            }
            if (c == 0.0 || r == 0.0) continue;
            const double s = c + r;
            double f = 1.0;
            while (c < r / 2.0) {
                f *= 2.0;
                c *= 4.0;
            }
            while (c > r * 2.0) {
                f /= 2.0;
                c /= 4.0;
            }
            if ((c + r) / f < 0.95 * s) {
                done = false;
                d[i] *= f;
                for (int j = 0; j < n; ++j) {
                    b(i, j) /= f;
                    b(j, i) *= f;
                }
            }
        }
        if (done) break;
    }
    return b;
}

Mat pade_exponential(Mat a) {
    const int n = a.rows;
    double norm = 0.0;
    for (int j = 0; j < n; ++j) {
        double col = 0.0;
        for (int i = 0; i < n; ++i) col += std::abs(a(i, j));
        norm = std::max(norm, col);
    }
    int s = 0;
    if (norm > THETA[3]) {
        s = std::max(0, static_cast<int>(std::ceil(std::log2(norm / THETA[4]))));
        Mat scaled(n, n);
        a = add(scaled, std::pow(0.5, s), a);
    }
    const Mat a2 = matmul(a, a);
    Mat w, v;
    if (norm <= THETA[0]) {
        const double* b = B3;
        w = Mat::identity(n, b[1]);
        add(w, b[3], a2);
        v = Mat::identity(n, b[0]);
        add(v, b[2], a2);
    } else if (norm <= THETA[1]) {
        const double* b = B5;
        const Mat a4 = matmul(a2, a2);
        w = Mat::identity(n, b[1]);
        add(add(w, b[3], a2), b[5], a4);
        v = Mat::identity(n, b[0]);
        add(add(v, b[2], a2), b[4], a4);
    } else if (norm <= THETA[2]) {
        const double* b = B7;
        const Mat a4 = matmul(a2, a2), a6 = matmul(a4, a2);
        w = Mat::identity(n, b[1]);
        add(add(add(w, b[3], a2), b[5], a4), b[7], a6);
        v = Mat::identity(n, b[0]);
        add(add(add(v, b[2], a2), b[4], a4), b[6], a6);
    } else if (norm <= THETA[3]) {
        const double* b = B9;
        const Mat a4 = matmul(a2, a2), a6 = matmul(a4, a2), a8 = matmul(a6, a2);
        w = Mat::identity(n, b[1]);
        add(add(add(add(w, b[3], a2), b[5], a4), b[7], a6), b[9], a8);
        v = Mat::identity(n, b[0]);
        add(add(add(add(v, b[2], a2), b[4], a4), b[6], a6), b[8], a8);
    } else {
        const double* b = B13;
        const Mat a4 = matmul(a2, a2), a6 = matmul(a4, a2);
        Mat t(n, n);
        add(add(add(t, b[13], a6), b[11], a4), b[9], a2);
        w = matmul(a6, t);
        add(add(add(add(w, b[7], a6), b[5], a4), b[3], a2), 1.0, Mat::identity(n, b[1]));
        Mat t2(n, n);
        add(add(add(t2, b[12], a6), b[10], a4), b[8], a2);
        v = matmul(a6, t2);
        add(add(add(add(v, b[6], a6), b[4], a4), b[2], a2), 1.0, Mat::identity(n, b[0]));
    }
    const Mat u = matmul(a, w);
    Mat lhs = v, rhs = v;
    add(lhs, -1.0, u);
    add(rhs, 1.0, u);
    Mat x = solve(lhs, rhs);
    for (int i = 0; i < s; ++i) x = matmul(x, x);
    return x;
}
}  // namespace

Mat matmul(const Mat& x, const Mat& y) {
    Mat out(x.rows, y.cols);
    for (int i = 0; i < x.rows; ++i)
        for (int p = 0; p < x.cols; ++p) {
            const double xip = x(i, p);
            if (xip != 0.0)
                for (int j = 0; j < y.cols; ++j) out(i, j) += xip * y(p, j);
        }
    return out;
}

std::vector<double> matvec(const Mat& x, const std::vector<double>& v) {
    std::vector<double> out(x.rows, 0.0);
    for (int i = 0; i < x.rows; ++i) {
        double acc = 0.0;
        for (int p = 0; p < x.cols; ++p) acc += x(i, p) * v[p];
        out[i] = acc;
    }
    return out;
}

bool solve_in_place(Mat& lu, Mat& x, double min_pivot) {
    const int n = lu.rows, m = x.cols;
    for (int c = 0; c < n; ++c) {
        int piv = c;
        for (int r = c + 1; r < n; ++r)
            if (std::abs(lu(r, c)) > std::abs(lu(piv, c))) piv = r;
        if (min_pivot >= 0.0 && !(std::abs(lu(piv, c)) > min_pivot)) return false;
        if (piv != c) {
            for (int j = 0; j < n; ++j) std::swap(lu(c, j), lu(piv, j));
            for (int j = 0; j < m; ++j) std::swap(x(c, j), x(piv, j));
        }
        for (int r = c + 1; r < n; ++r) {
            const double f = lu(r, c) / lu(c, c);
            if (f != 0.0) {
                for (int j = c + 1; j < n; ++j) lu(r, j) -= f * lu(c, j);
                for (int j = 0; j < m; ++j) x(r, j) -= f * x(c, j);
            }
        }
    }
    for (int c = n - 1; c >= 0; --c)
        for (int j = 0; j < m; ++j) {
            double acc = x(c, j);
            for (int k = c + 1; k < n; ++k) acc -= lu(c, k) * x(k, j);
            x(c, j) = acc / lu(c, c);
        }
    return true;
}

Mat solve(Mat lu, Mat x) {
    solve_in_place(lu, x, -1.0);
    return x;
}

Mat expm(const Mat& a) {
    std::vector<double> d;
    const Mat b = balance(a, d);
    Mat x = pade_exponential(b);
    for (int i = 0; i < x.rows; ++i)
        for (int j = 0; j < x.cols; ++j) x(i, j) *= d[i] / d[j];
    return x;
}

}  // namespace pounding
