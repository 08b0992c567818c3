#pragma once
/// \file
/// Lengths, simplex measures and normals of world vectors that neither overflow nor underflow.
///
/// A plain norm() squares the coordinates and the norm of a cross product squares products of
/// two: from coordinates of about 1e77 (or below 1e-77) on those fourth powers leave the range of
/// doubles and an area becomes infinite or zero although it is representable. These functions
/// first divide by a power of two near the largest coordinate (exact, so for inputs of ordinary
/// size the results are bit for bit those of the plain formulas) and multiply back at the end.
/// plmap supports surfaces whose measures are normal doubles (see Surface).

#include <plmap/core/types.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <limits>

namespace plmap {

/// The power of two at or just below the largest absolute coordinate of the vectors; 1 if they
/// are all zero or not finite. For a normal largest coordinate that is the number with its
/// mantissa bits cleared; only subnormal ones take the library calls ilogb and ldexp, which cost
/// about as much as the measure they scale (3 % of a projection's instructions: every element
/// measure and normal, the image measures, the adjacency of a surface being read).
template <int d>
double power_of_two_scale(std::initializer_list<WorldPoint<d>> vectors) {
  double largest = 0.0;
  for (const auto& v : vectors) largest = std::max(largest, v.cwiseAbs().maxCoeff());
  if (!(largest > 0.0) || !std::isfinite(largest)) return 1.0;
  if (largest >= std::numeric_limits<double>::min())
    return std::bit_cast<double>(std::bit_cast<std::uint64_t>(largest) & 0x7ff0000000000000ULL);
  return std::ldexp(1.0, std::ilogb(largest));
}

/// Euclidean length of a world vector.
template <int d>
double scaled_length(const WorldPoint<d>& v) {
  const double s = power_of_two_scale<d>({v});
  return (v / s).norm() * s;
}

/// Measure of a simplex in units of unit^d, and the unit: {measure / unit^d, unit}. The measure
/// is the product, which the caller may form once it knows the result is representable.
template <int d>
std::pair<double, double> scaled_simplex_measure(const std::array<WorldPoint<d>, d + 1>& c) {
  if constexpr (d == 1) {
    const WorldPoint<1> u = c[1] - c[0];
    const double s = power_of_two_scale<1>({u});
    return {(u / s).norm(), s};
  } else {
    const WorldPoint<2> u = c[1] - c[0], v = c[2] - c[0];
    const double s = power_of_two_scale<2>({u, v});
    return {0.5 * (u / s).cross(v / s).norm(), s};
  }
}

/// Length (d = 1) or area (d = 2) of a simplex given by its world corners.
template <int d>
double simplex_measure(const std::array<WorldPoint<d>, d + 1>& c) {
  const auto [m, s] = scaled_simplex_measure<d>(c);
  return d == 1 ? m * s : m * s * s;
}

}  // namespace plmap
