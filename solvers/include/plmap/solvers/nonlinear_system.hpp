#pragma once
/// \file
/// SmallNonlinearSystem: a square system F(x) = 0 of fixed size n with an analytic Jacobian, and
/// SolveResult, what a solver reports about it.
///
/// The systems of normal projection have 2 or 3 unknowns. Their size is a compile-time constant
/// so that every vector and matrix lives on the stack (no allocation in the hot loop).

#include <Eigen/Core>

#include <concepts>

namespace plmap {

template <class S>
concept SmallNonlinearSystem = requires(const S& s, const typename S::Vector& x) {
  { S::size } -> std::convertible_to<int>;
  typename S::Vector;    // Eigen::Matrix<double, size, 1>
  typename S::Jacobian;  // Eigen::Matrix<double, size, size>
  { s.residual(x) } -> std::same_as<typename S::Vector>;
  { s.jacobian(x) } -> std::same_as<typename S::Jacobian>;
  /// A length that sets the scale of the residual (e.g. the element diameter): solvers stop when
  /// |F(x)| <= relative_tolerance * scale(), so the same geometry scaled by 1e-6 or 1e6 behaves
  /// the same.
  { s.scale() } -> std::convertible_to<double>;
};

/// Outcome of one solve.
template <int n>
struct SolveResult {
  Eigen::Matrix<double, n, 1> x = Eigen::Matrix<double, n, 1>::Zero();
  /// True if |F(x)| <= tolerance * scale at the returned x.
  bool converged = false;
  int iterations = 0;
  /// |F(x)| / scale at the returned x (the relative residual).
  double relative_residual = 0.0;
};

}  // namespace plmap
