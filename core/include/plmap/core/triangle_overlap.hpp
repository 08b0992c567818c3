#pragma once
/// \file
/// Area of the intersection of two triangles in the plane: how much two region images overlap on
/// an S2 element (verify's coverage check, and normal projection's choice between two sheets).
///
/// A measurement, not a combinatorial decision: Sutherland–Hodgman clipping in floating point, so
/// the area of two triangles that only share a side or a corner is zero up to rounding, and
/// callers compare it against a tolerance.

#include <Eigen/Core>

#include <array>
#include <utility>

namespace plmap {

/// Area of the intersection of two counter-clockwise triangles (clipping a by the three
/// half-planes of b; at most 9 vertices, no allocation).
inline double triangle_intersection_area(const std::array<Eigen::Vector2d, 3>& a,
                                         const std::array<Eigen::Vector2d, 3>& b) {
  const auto cross = [](const Eigen::Vector2d& u, const Eigen::Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); };
  std::array<Eigen::Vector2d, 12> poly, next;
  int count = 3;
  for (int i = 0; i < 3; ++i) poly[i] = a[i];
  for (int j = 0; j < 3 && count > 0; ++j) {
    const Eigen::Vector2d& p = b[j];
    const Eigen::Vector2d dir = b[(j + 1) % 3] - p;
    int out = 0;
    for (int i = 0; i < count; ++i) {
      const Eigen::Vector2d& cur = poly[i];
      const Eigen::Vector2d& nxt = poly[(i + 1) % count];
      const double sc = cross(dir, cur - p), sn = cross(dir, nxt - p);
      if (sc >= 0) next[out++] = cur;
      if ((sc >= 0) != (sn >= 0)) next[out++] = cur + (nxt - cur) * (sc / (sc - sn));
    }
    count = out;
    std::swap(poly, next);
  }
  double area = 0.0;
  for (int i = 0; i < count; ++i) area += cross(poly[i], poly[(i + 1) % count]);
  return 0.5 * area;
}

}  // namespace plmap
