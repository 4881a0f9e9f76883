// Small dense linear algebra (matrices of a few rows), written here: no library.
#pragma once

#include <cmath>
#include <vector>

namespace pounding {

// a square or rectangular matrix, row-major
struct Mat {
    int rows = 0, cols = 0;
    std::vector<double> a;
    Mat() = default;
    Mat(int r, int c, double fill = 0.0) : rows(r), cols(c), a(static_cast<size_t>(r) * c, fill) {}
    double& operator()(int i, int j) { return a[static_cast<size_t>(i) * cols + j]; }
    double operator()(int i, int j) const { return a[static_cast<size_t>(i) * cols + j]; }
    static Mat identity(int n, double c = 1.0) {
        Mat m(n, n);
        for (int i = 0; i < n; ++i) m(i, i) = c;
        return m;
    }
};

Mat matmul(const Mat& x, const Mat& y);
std::vector<double> matvec(const Mat& x, const std::vector<double>& v);
// x^-1 y by Gaussian elimination with partial pivoting
Mat solve(Mat x, Mat y);
// the same in place (x overwritten by its factor, y by the solution); false, the work left half done, when a
// pivot is not above min_pivot in magnitude (min_pivot < 0: no pivot refused)
bool solve_in_place(Mat& x, Mat& y, double min_pivot);
// exp(a): balanced (a diagonal similarity by powers of 2), then scaling and squaring with the lowest adequate
// diagonal Pade approximant of degree 3 to 13 (Higham 2005)
Mat expm(const Mat& a);

}  // namespace pounding
