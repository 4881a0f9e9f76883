// Small dense linear algebra (matrices of a few rows) on Eigen: its dense matrices, LU solve and matrix
// exponential (Higham's scaling and squaring), preceded here by a balancing.
#pragma once

#include <Eigen/Dense>
#include <vector>

namespace pounding {

// a square or rectangular matrix, row-major (as the core's arrays and numpy's are)
using Mat = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// x v
std::vector<double> matvec(const Mat& x, const std::vector<double>& v);
// x^-1 y by LU with partial pivoting; false when a pivot of x is not above min_pivot in magnitude (y then
// not solved)
bool solve_checked(const Mat& x, Mat& y, double min_pivot);
// exp(a): balanced (a diagonal similarity by powers of 2, so that a badly scaled matrix, the augmented
// system's units of length, velocity and force side by side, keeps its small entries' digits), then
// Eigen's scaling and squaring with the lowest adequate Pade approximant (Higham 2005)
Mat expm(const Mat& a);

}  // namespace pounding
