// The smoothing solves' linear system (construct/src/convex_combination_system.hpp): the dense
// elimination for small systems and the sparse LU for large ones solve the same convex-combination
// systems, agree with each other and with the residual, and refuse singular matrices.

#include "convex_combination_system.hpp"

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <Eigen/Dense>

#include <vector>

namespace plmap {
namespace {

using smoothing::ConvexCombinationSystem;

/// A random convex-combination system: row i is x_i - Σ w_ij x_j with weights of a few random
/// neighbours summing to at most one, strictly less than one in at least one row (a fixed
/// neighbour), as in a smoothing solve. Row i's first neighbour is i - 1 and row 0 has a fixed
/// one, so every row reaches a strictly dominant one: non-singular, like a smoothing system in
/// which every free node is connected to the fixed boundary. Returned dense, with its
/// right-hand side.
struct RandomSystem {
  Eigen::MatrixXd matrix;
  Eigen::MatrixX2d rhs;
};

RandomSystem random_system(int n) {
  RandomSystem s{Eigen::MatrixXd::Identity(n, n), Eigen::MatrixX2d::Zero(n, 2)};
  for (int i = 0; i < n; ++i) {
    const int neighbours = *rc::gen::inRange(1, std::min(n, 7) + 1);
    const bool has_fixed = i == 0 || *rc::gen::arbitrary<bool>();
    std::vector<double> w(static_cast<std::size_t>(neighbours + (has_fixed ? 1 : 0)));
    double total = 0.0;
    for (double& x : w) total += (x = *rc::gen::inRange(1, 1000) / 1000.0);
    for (int k = 0; k < neighbours; ++k) {
      int j = k == 0 && i > 0 ? i - 1 : *rc::gen::inRange(0, n);
      if (j == i) j = (i + 1) % n;
      if (j == i) continue;  // n == 1
      s.matrix(i, j) -= w[static_cast<std::size_t>(k)] / total;
    }
    if (has_fixed) {
      const Eigen::Vector2d fixed(*rc::gen::inRange(-1000, 1000) / 100.0, *rc::gen::inRange(-1000, 1000) / 100.0);
      s.rhs.row(i) += w.back() / total * fixed.transpose();
    }
  }
  return s;
}

/// Feeds the system entry by entry (duplicates split in two, as repeated neighbours add up).
bool solve_with(ConvexCombinationSystem& system, const RandomSystem& s) {
  const int n = static_cast<int>(s.matrix.rows());
  system.reset(n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      if (s.matrix(i, j) == 0.0) continue;
      system.add(i, j, 0.5 * s.matrix(i, j));
      system.add(i, j, 0.5 * s.matrix(i, j));
    }
    system.add_rhs(i, s.rhs.row(i).transpose());
  }
  return system.solve();
}

double residual(const ConvexCombinationSystem& system, const RandomSystem& s) {
  const int n = static_cast<int>(s.matrix.rows());
  Eigen::MatrixX2d x(n, 2);
  for (int i = 0; i < n; ++i) x.row(i) = system.solution(i).transpose();
  return (s.matrix * x - s.rhs).cwiseAbs().maxCoeff();
}

RC_GTEST_PROP(ConvexCombinationSystemProperties, DenseSolvesSmallSystemsLikeAnLU, ()) {
  const int n = *rc::gen::inRange(1, ConvexCombinationSystem::dense_limit + 1);
  const RandomSystem s = random_system(n);
  const Eigen::MatrixX2d expected = s.matrix.fullPivLu().solve(s.rhs);
  ConvexCombinationSystem system;
  RC_ASSERT(solve_with(system, s));
  const double scale = std::max(1.0, s.rhs.cwiseAbs().maxCoeff());
  RC_ASSERT(residual(system, s) <= 1e-9 * scale);
  for (int i = 0; i < n; ++i) RC_ASSERT((system.solution(i) - expected.row(i).transpose()).norm() <= 1e-8 * scale);
}

RC_GTEST_PROP(ConvexCombinationSystemProperties, LargeSystemsGoToTheSparseLU, ()) {
  const int n = *rc::gen::inRange(ConvexCombinationSystem::dense_limit + 1, 3 * ConvexCombinationSystem::dense_limit);
  const RandomSystem s = random_system(n);
  ConvexCombinationSystem system;
  RC_ASSERT(solve_with(system, s));
  RC_ASSERT(residual(system, s) <= 1e-9 * std::max(1.0, s.rhs.cwiseAbs().maxCoeff()));
}

TEST(ConvexCombinationSystem, ReusedObjectSolvesEachSystemFromScratch) {
  ConvexCombinationSystem system;
  // a 2 × 2 system first, then a 1 × 1 one: nothing of the first may leak into the second
  system.reset(2);
  system.add(0, 0, 1.0);
  system.add(0, 1, -0.5);
  system.add(1, 1, 1.0);
  system.add(1, 0, -0.5);
  system.add_rhs(0, Eigen::Vector2d(1.0, 0.0));
  system.add_rhs(1, Eigen::Vector2d(0.0, 1.0));
  ASSERT_TRUE(system.solve());
  EXPECT_NEAR(system.solution(0).x(), 4.0 / 3.0, 1e-15);
  EXPECT_NEAR(system.solution(1).y(), 4.0 / 3.0, 1e-15);
  system.reset(1);
  system.add(0, 0, 2.0);
  system.add_rhs(0, Eigen::Vector2d(3.0, -1.0));
  ASSERT_TRUE(system.solve());
  EXPECT_EQ(system.solution(0), Eigen::Vector2d(1.5, -0.5));
}

TEST(ConvexCombinationSystem, RefusesSingularMatrices) {
  ConvexCombinationSystem system;
  for (int n : {3, ConvexCombinationSystem::dense_limit + 5}) {
    // every row sums to zero and no fixed neighbour: the constant vector is in the kernel
    system.reset(n);
    for (int i = 0; i < n; ++i) {
      system.add(i, i, 1.0);
      system.add(i, (i + 1) % n, -1.0);
    }
    EXPECT_FALSE(system.solve()) << n << " unknowns";
  }
}

}  // namespace
}  // namespace plmap
