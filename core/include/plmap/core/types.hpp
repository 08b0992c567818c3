#pragma once
/// \file
/// Basic vocabulary shared by every part of plmap: index type, points in world and local
/// coordinates, and the dimension conventions.
///
/// A d-dimensional surface (d = 1: polyline, d = 2: triangle surface) lives in R^(d+1).
/// Local coordinates on an element with corners c_0..c_d are xi in R^d with
///   x = c_0 + sum_i xi_i (c_{i+1} - c_0),
/// i.e. barycentric coordinates (1 - sum xi, xi_0, ..., xi_{d-1}).

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <limits>

namespace plmap {

/// Index of a vertex, edge, element, node or region. 32 bits keep the flat arrays compact.
using Index = std::int32_t;
inline constexpr Index invalid_index = -1;

template <int d>
concept SurfaceDimension = (d == 1 || d == 2);

/// A point of the ambient space R^(d+1).
template <int d>
using WorldPoint = Eigen::Matrix<double, d + 1, 1>;

/// Local coordinates on an element (see the file comment for the convention).
template <int d>
using LocalPoint = Eigen::Matrix<double, d, 1>;

/// Barycentric coordinates on an element: d+1 numbers summing to one.
template <int d>
using Barycentric = Eigen::Matrix<double, d + 1, 1>;

/// Corner vertex indices of an element.
template <int d>
using ElementCorners = std::array<Index, d + 1>;

template <int d>
Barycentric<d> barycentric_from_local(const LocalPoint<d>& xi) {
  Barycentric<d> b;
  b(0) = 1.0 - xi.sum();
  b.template tail<d>() = xi;
  return b;
}

template <int d>
LocalPoint<d> local_from_barycentric(const Barycentric<d>& b) {
  return b.template tail<d>();
}

/// Local coordinates of corner k of the reference element.
template <int d>
LocalPoint<d> reference_corner(int k) {
  LocalPoint<d> xi = LocalPoint<d>::Zero();
  if (k > 0) xi(k - 1) = 1.0;
  return xi;
}

/// A point on a surface: an element and local coordinates on it.
template <int d>
struct SurfacePoint {
  Index element = invalid_index;
  LocalPoint<d> local = LocalPoint<d>::Zero();
  friend bool operator==(const SurfacePoint&, const SurfacePoint&) = default;
};

/// x^n for a small non-negative n (a dimension): n multiplications, where std::pow takes its
/// general path of logarithms (measurable in the projection's inner loops). Exact for n <= 2,
/// as one rounding is all either way.
constexpr double integer_power(double x, int n) {
  double r = 1.0;
  for (int i = 0; i < n; ++i) r *= x;
  return r;
}

}  // namespace plmap
