// The linear system of one smoothing solve; see convex_combination_system.hpp.

#include "convex_combination_system.hpp"

#include <Eigen/SparseLU>

#include <cmath>
#include <utility>

namespace plmap::smoothing {

void ConvexCombinationSystem::reset(int unknowns) {
  n_ = unknowns;
  dense_ = unknowns <= dense_limit;
  const auto n = static_cast<std::size_t>(unknowns);
  if (dense_)
    matrix_.assign(n * n, 0.0);
  else
    triplets_.clear();
  rhs_.assign(n, Eigen::Vector2d::Zero());
}

void ConvexCombinationSystem::add(int row, int col, double value) {
  if (dense_)
    matrix_[static_cast<std::size_t>(row) * static_cast<std::size_t>(n_) + static_cast<std::size_t>(col)] += value;
  else
    triplets_.emplace_back(row, col, value);
}

void ConvexCombinationSystem::add_rhs(int row, const Eigen::Vector2d& value) { rhs_[static_cast<std::size_t>(row)] += value; }

bool ConvexCombinationSystem::solve() {
  const bool ok = dense_ ? solve_dense() : solve_sparse();
  if (!ok) return false;
  for (const Eigen::Vector2d& x : solution_)
    if (!x.allFinite()) return false;
  return true;
}

bool ConvexCombinationSystem::solve_dense() {
  const auto n = static_cast<std::size_t>(n_);
  double* a = matrix_.data();
  const auto at = [a, n](std::size_t i, std::size_t j) -> double& { return a[i * n + j]; };
  // Gaussian elimination with partial pivoting, in place; zero multipliers are skipped, which
  // keeps the sparse rows (a node's few neighbours) cheap until fill-in reaches them.
  for (std::size_t k = 0; k < n; ++k) {
    std::size_t pivot = k;
    for (std::size_t i = k + 1; i < n; ++i)
      if (std::abs(at(i, k)) > std::abs(at(pivot, k))) pivot = i;
    if (!(std::abs(at(pivot, k)) > 0.0)) return false;
    if (pivot != k) {
      for (std::size_t j = k; j < n; ++j) std::swap(at(k, j), at(pivot, j));
      std::swap(rhs_[k], rhs_[pivot]);
    }
    const double inverse = 1.0 / at(k, k);
    for (std::size_t i = k + 1; i < n; ++i) {
      const double factor = at(i, k) * inverse;
      if (factor == 0.0) continue;
      at(i, k) = 0.0;
      for (std::size_t j = k + 1; j < n; ++j) at(i, j) -= factor * at(k, j);
      rhs_[i] -= factor * rhs_[k];
    }
  }
  solution_.resize(n);
  for (std::size_t k = n; k-- > 0;) {
    Eigen::Vector2d sum = rhs_[k];
    for (std::size_t j = k + 1; j < n; ++j) sum -= at(k, j) * solution_[j];
    solution_[k] = sum / at(k, k);
  }
  return true;
}

bool ConvexCombinationSystem::solve_sparse() {
  Eigen::SparseMatrix<double> matrix(n_, n_);
  matrix.setFromTriplets(triplets_.begin(), triplets_.end());
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  lu.compute(matrix);
  if (lu.info() != Eigen::Success) return false;
  Eigen::MatrixX2d rhs(n_, 2);
  for (int i = 0; i < n_; ++i) rhs.row(i) = rhs_[static_cast<std::size_t>(i)].transpose();
  const Eigen::MatrixX2d x = lu.solve(rhs);
  if (lu.info() != Eigen::Success) return false;
  solution_.resize(static_cast<std::size_t>(n_));
  for (int i = 0; i < n_; ++i) solution_[static_cast<std::size_t>(i)] = x.row(i).transpose();
  return true;
}

}  // namespace plmap::smoothing
