#pragma once
// The rim of D (projection, end_on_rim): the projection ends where S2 leaves the band of
// admissible distances, on the curve where the rays' distance to S2 reaches a bound mu0 of the
// band (0 where S2 passes behind S1; there the two surfaces meet and Xi is the identity; or
// +-max_distance). Over an S1 element that curve lies in the flat triangle of the points at
// distance mu0 along its rays (ProjectionContext::corners_at_distance), so it is the
// intersection of such triangles with S2 triangles, and its points are found by straight
// segments piercing triangles, in world coordinates.

#include <plmap/core/types.hpp>

#include <array>
#include <cmath>
#include <optional>

namespace plmap::projection {

/// Where the segment p0 -> p1 passes through the plane of a triangle: the parameter s in [0, 1]
/// along the segment and the barycentric coordinates of that point on the triangle (inside it
/// when all are >= 0).
struct Pierce {
  double s = 0.0;
  std::array<double, 3> barycentric{};
};

/// The barycentric coordinates on triangle `tri` of a point x in its plane, from the triangle's
/// normal n = (tri[1] - tri[0]) x (tri[2] - tri[0]) and its squared norm nn.
inline std::array<double, 3> barycentric_in_plane(const std::array<WorldPoint<2>, 3>& tri, const WorldPoint<2>& n,
                                                  double nn, const WorldPoint<2>& x) {
  const double b0 = n.dot((tri[1] - x).cross(tri[2] - x)) / nn;
  const double b1 = n.dot((tri[2] - x).cross(tri[0] - x)) / nn;
  return {b0, b1, 1.0 - b0 - b1};
}

/// The pierce of segment p0 -> p1 through the plane of triangle `tri`, if the segment reaches
/// that plane and is not (nearly) parallel to it.
inline std::optional<Pierce> segment_through_triangle(const WorldPoint<2>& p0, const WorldPoint<2>& p1,
                                                      const std::array<WorldPoint<2>, 3>& tri) {
  const WorldPoint<2> n = (tri[1] - tri[0]).cross(tri[2] - tri[0]);
  const WorldPoint<2> along = p1 - p0;
  const double nn = n.squaredNorm();
  const double denominator = n.dot(along);
  // parallel (within rounding): no single point
  if (!(std::abs(denominator) > 1e-12 * std::sqrt(nn) * along.norm())) return std::nullopt;
  Pierce p;
  p.s = n.dot(tri[0] - p0) / denominator;
  if (!(p.s >= 0.0 && p.s <= 1.0)) return std::nullopt;
  p.barycentric = barycentric_in_plane(tri, n, nn, p0 + p.s * along);
  return p;
}

/// Whether barycentric coordinates lie inside the triangle by more than `margin` from each side.
inline bool strictly_inside(const std::array<double, 3>& b, double margin) {
  return b[0] > margin && b[1] > margin && b[2] > margin;
}

}  // namespace plmap::projection
