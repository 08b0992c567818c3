#pragma once
// The distance from a point to a segment (d = 1, in the plane) or a triangle (d = 2, in space):
// the bound of the vertex preimage search below which an element's bounding box makes it a seed
// (projection_vertex_preimages.cpp).

#include <plmap/core/surface.hpp>

#include <algorithm>
#include <array>
#include <cmath>

namespace plmap::projection {

/// Distance from x to the segment a-b (a point if a = b).
template <class Point>
double segment_distance(const Point& x, const Point& a, const Point& b) {
  const Point ab = b - a;
  const double length2 = ab.squaredNorm();
  const double s = length2 > 0.0 ? std::clamp((x - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return (x - (a + s * ab)).norm();
}

/// Distance from x to the simplex with corners c: the segment's, or the triangle's (the distance
/// to its plane where x projects inside it, else the nearest of its sides').
template <int d>
double simplex_distance(const WorldPoint<d>& x, const std::array<WorldPoint<d>, d + 1>& c) {
  if constexpr (d == 1) {
    return segment_distance(x, c[0], c[1]);
  } else {
    const WorldPoint<2> u = c[1] - c[0], v = c[2] - c[0], w = x - c[0];
    const WorldPoint<2> n = u.cross(v);
    const double n2 = n.squaredNorm();
    if (n2 > 0.0) {
      // barycentric coordinates of x's projection onto the plane
      const double b1 = w.cross(v).dot(n) / n2, b2 = u.cross(w).dot(n) / n2;
      if (b1 >= 0.0 && b2 >= 0.0 && b1 + b2 <= 1.0) return std::abs(w.dot(n)) / std::sqrt(n2);
    }
    return std::min({segment_distance(x, c[0], c[1]), segment_distance(x, c[1], c[2]), segment_distance(x, c[2], c[0])});
  }
}

}  // namespace plmap::projection
