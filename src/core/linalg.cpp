#include "linalg.hpp"

#include <algorithm>
#include <cmath>

#include <unsupported/Eigen/MatrixFunctions>

namespace pounding {

namespace {
// a diagonal similarity by powers of 2 (exact) that evens the off-diagonal row and column sums: b = D^-1 a D
Mat balance(const Mat& a, std::vector<double>& d) {
    const int n = static_cast<int>(a.rows());
    Mat b = a;
    d.assign(static_cast<size_t>(n), 1.0);
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

}  // namespace

std::vector<double> matvec(const Mat& x, const std::vector<double>& v) {
    std::vector<double> out(static_cast<size_t>(x.rows()), 0.0);
    Eigen::Map<Eigen::VectorXd>(out.data(), x.rows()) =
        x * Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
    return out;
}

bool solve_checked(const Mat& x, Mat& y, double min_pivot) {
    const Eigen::PartialPivLU<Mat> lu(x);
    const Mat& f = lu.matrixLU();  // (U on and above the diagonal, L's multipliers below)
    const Eigen::Index n = f.rows(), m = y.cols();
    for (Eigen::Index i = 0; i < n; ++i)
        if (!(std::abs(f(i, i)) > min_pivot)) return false;
    // the substitutions by hand, in elimination's order (each term subtracted in turn, then a division by the
    // pivot): Eigen's triangular solves multiply by the pivot's reciprocal and sum in blocks, other roundings
    // that a chattering stop amplifies
    y = (lu.permutationP() * y).eval();
    for (Eigen::Index c = 0; c < n; ++c)
        for (Eigen::Index r = c + 1; r < n; ++r) {
            const double l = f(r, c);
            if (l != 0.0)
                for (Eigen::Index j = 0; j < m; ++j) y(r, j) -= l * y(c, j);
        }
    for (Eigen::Index c = n - 1; c >= 0; --c)
        for (Eigen::Index j = 0; j < m; ++j) {
            double acc = y(c, j);
            for (Eigen::Index k = c + 1; k < n; ++k) acc -= f(c, k) * y(k, j);
            y(c, j) = acc / f(c, c);
        }
    return true;
}

Mat expm(const Mat& a) {
    std::vector<double> d;
    const Mat b = balance(a, d);
    Mat x = b.exp();
    for (Eigen::Index i = 0; i < x.rows(); ++i)
        for (Eigen::Index j = 0; j < x.cols(); ++j) x(i, j) *= d[static_cast<size_t>(i)] / d[static_cast<size_t>(j)];
    return x;
}

}  // namespace pounding
