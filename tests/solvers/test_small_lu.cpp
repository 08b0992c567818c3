// solve_with_partial_pivoting (solvers/small_lu.hpp) must give Eigen's PartialPivLU solution to
// the last bit: the projection uses it in place of Eigen, and the maps must not change. Compared
// on random matrices of many scales, on matrices with tied pivot candidates (the first one wins),
// on singular ones (zero pivots, the same infinities and NaNs) and on non-finite input.
#include <plmap/solvers/small_lu.hpp>

#include <Eigen/LU>
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

using namespace plmap;

namespace {

template <int n>
bool same_bits(const Eigen::Matrix<double, n, 1>& a, const Eigen::Matrix<double, n, 1>& b) {
  for (int i = 0; i < n; ++i) {
    if (std::isnan(a(i)) && std::isnan(b(i))) continue;  // NaN payloads are not compared
    if (std::bit_cast<std::uint64_t>(a(i)) != std::bit_cast<std::uint64_t>(b(i))) return false;
  }
  return true;
}

template <int n>
void expect_like_eigen(const Eigen::Matrix<double, n, n>& a, const Eigen::Matrix<double, n, 1>& b) {
  const Eigen::Matrix<double, n, 1> expected = Eigen::PartialPivLU<Eigen::Matrix<double, n, n>>(a).solve(b);
  const Eigen::Matrix<double, n, 1> got = solve_with_partial_pivoting<n>(a, b);
  EXPECT_TRUE(same_bits<n>(expected, got)) << "A =\n"
                                           << a << "\nb = " << b.transpose() << "\nEigen " << expected.transpose()
                                           << "\nhere  " << got.transpose();
}

template <int n>
Eigen::Matrix<double, n, n> random_matrix(int exponent) {
  Eigen::Matrix<double, n, n> a;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) a(i, j) = *rc::gen::inRange(-100000, 100001) / 1000.0 * std::pow(10.0, exponent);
  return a;
}

}  // namespace

RC_GTEST_PROP(SmallLu, SameBitsAsEigenOnRandomSystems, ()) {
  const int exponent = *rc::gen::inRange(-8, 9);
  const auto a3 = random_matrix<3>(exponent);
  const Eigen::Vector3d b3 = random_matrix<3>(exponent).col(0);
  RC_ASSERT(same_bits<3>(Eigen::PartialPivLU<Eigen::Matrix3d>(a3).solve(b3), solve_with_partial_pivoting<3>(a3, b3)));
  const auto a2 = random_matrix<2>(exponent);
  const Eigen::Vector2d b2 = random_matrix<2>(exponent).col(0);
  RC_ASSERT(same_bits<2>(Eigen::PartialPivLU<Eigen::Matrix2d>(a2).solve(b2), solve_with_partial_pivoting<2>(a2, b2)));
}

RC_GTEST_PROP(SmallLu, SameBitsAsEigenWithSmallIntegerEntries, ()) {
  // entries from a small set: tied pivot candidates, zero columns and singular matrices are common
  const auto entry = [] { return static_cast<double>(*rc::gen::inRange(-2, 3)); };
  Eigen::Matrix3d a3;
  Eigen::Vector3d b3;
  for (int i = 0; i < 9; ++i) a3(i) = entry();
  for (int i = 0; i < 3; ++i) b3(i) = entry();
  RC_ASSERT(same_bits<3>(Eigen::PartialPivLU<Eigen::Matrix3d>(a3).solve(b3), solve_with_partial_pivoting<3>(a3, b3)));
  Eigen::Matrix2d a2;
  Eigen::Vector2d b2;
  for (int i = 0; i < 4; ++i) a2(i) = entry();
  for (int i = 0; i < 2; ++i) b2(i) = entry();
  RC_ASSERT(same_bits<2>(Eigen::PartialPivLU<Eigen::Matrix2d>(a2).solve(b2), solve_with_partial_pivoting<2>(a2, b2)));
}

TEST(SmallLu, TiesSingularAndNonFiniteMatricesLikeEigen) {
  Eigen::Matrix3d tied;
  tied << 1, 2, 3, -1, 5, 6, 1, 8, 10;  // |a(0,0)| = |a(1,0)| = |a(2,0)|: the first one is the pivot
  expect_like_eigen<3>(tied, Eigen::Vector3d(1, 2, 3));
  Eigen::Matrix3d zero_column;
  zero_column << 0, 2, 3, 0, 5, 6, 0, 8, 10;
  expect_like_eigen<3>(zero_column, Eigen::Vector3d(1, 2, 3));
  Eigen::Matrix3d rank_one;
  rank_one << 1, 2, 3, 2, 4, 6, 3, 6, 9;
  expect_like_eigen<3>(rank_one, Eigen::Vector3d(1, 2, 3));
  expect_like_eigen<3>(Eigen::Matrix3d::Zero(), Eigen::Vector3d(0, 0, 0));
  Eigen::Matrix3d with_nan = tied;
  with_nan(1, 0) = std::numeric_limits<double>::quiet_NaN();
  expect_like_eigen<3>(with_nan, Eigen::Vector3d(1, 2, 3));
  Eigen::Matrix3d with_infinity = tied;
  with_infinity(2, 1) = std::numeric_limits<double>::infinity();
  expect_like_eigen<3>(with_infinity, Eigen::Vector3d(1, 2, 3));
  Eigen::Matrix2d parallel;
  parallel << 1, 2, 2, 4;
  expect_like_eigen<2>(parallel, Eigen::Vector2d(1, 1));
  Eigen::Matrix2d swapped;
  swapped << 0, 1, 1, 0;
  expect_like_eigen<2>(swapped, Eigen::Vector2d(3, -7));
}
