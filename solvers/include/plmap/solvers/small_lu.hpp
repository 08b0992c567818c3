#pragma once
/// \file
/// solve_with_partial_pivoting: A x = b for a fixed-size 2x2 or 3x3 matrix, computed with exactly
/// the floating-point operations of Eigen::PartialPivLU<Matrix<double, n, n>>(A).solve(b), so the
/// result is the same to the last bit.
///
/// The projection solves such systems millions of times (every start value and Newton step of
/// eq. 3 and 4, every ghost ray). Eigen's PartialPivLU is written for any size: its compute()
/// also takes the matrix's 1-norm and builds a permutation matrix, and its factorisation runs
/// through a strided generic kernel; that made these tiny solves the largest single cost of the
/// projection phases. The maps must not change with a faster solve, so this one repeats Eigen's
/// algorithm step by step (Eigen 3.4, partial_lu_impl::unblocked_lu and the unrolled triangular
/// solves): the pivot is the first largest |a(i, k)| at or below the diagonal; a zero pivot
/// column is left as it is; the multipliers are divided, not multiplied by a reciprocal; the
/// trailing update subtracts one product per entry; the forward and back substitutions sum
/// their two products left to right. tests/solvers/test_small_lu.cpp compares it bit for bit
/// with Eigen on random, tied, singular and non-finite matrices.

#include <Eigen/Core>

#include <cmath>
#include <utility>

namespace plmap {

template <int n>
  requires(n == 2 || n == 3)
Eigen::Matrix<double, n, 1> solve_with_partial_pivoting(Eigen::Matrix<double, n, n> a, Eigen::Matrix<double, n, 1> b) {
  // factorisation P A = L U in place: L below the diagonal (unit diagonal), U on and above
  for (int k = 0; k < n - 1; ++k) {
    int pivot = k;
    double biggest = std::abs(a(k, k));
    for (int i = k + 1; i < n; ++i) {
      const double candidate = std::abs(a(i, k));
      if (candidate > biggest) {
        biggest = candidate;
        pivot = i;
      }
    }
    if (biggest != 0.0) {
      if (pivot != k) {
        a.row(k).swap(a.row(pivot));
        std::swap(b(k), b(pivot));  // P b, transposition by transposition as Eigen applies them
      }
      for (int i = k + 1; i < n; ++i) a(i, k) /= a(k, k);
    }
    for (int j = k + 1; j < n; ++j)
      for (int i = k + 1; i < n; ++i) a(i, j) -= a(i, k) * a(k, j);
  }
  // L y = P b (unit diagonal), then U x = y
  if constexpr (n == 2) {
    b(1) -= a(1, 0) * b(0);
    b(1) /= a(1, 1);
    b(0) -= a(0, 1) * b(1);
    b(0) /= a(0, 0);
  } else {
    b(1) -= a(1, 0) * b(0);
    b(2) -= a(2, 0) * b(0) + a(2, 1) * b(1);
    b(2) /= a(2, 2);
    b(1) -= a(1, 2) * b(2);
    b(1) /= a(1, 1);
    b(0) -= a(0, 1) * b(1) + a(0, 2) * b(2);
    b(0) /= a(0, 0);
  }
  return b;
}

}  // namespace plmap
