#pragma once
// The pairs and rules the rim tests share (test_project_rim.cpp, test_project_rim_limits.cpp,
// test_project_nearer_sheet.cpp): a flat S1 with vertical rays and a tilted S2 plane, so that
// the rays' distance mu is known in closed form.

#include "projection_fixtures.hpp"

#include <plmap/construct/direction_field.hpp>
#include <plmap/construct/projection_options.hpp>
#include <plmap/verify/ray_check.hpp>

namespace plmap::test {

/// S1: the unit square at z = 0, 10 x 10 cells, normals +z, so its rays are vertical and mu is
/// the height of S2 above S1.
inline std::shared_ptr<const Surface<2>> flat_square() { return grid(10, 10, 0.0, 1.0, 0.0, 1.0, 0.0); }

/// S2: a jittered `cells` x `cells` grid over [-0.1, 1.1]^2 facing S1, on the plane
/// z = 0.25 (x - x0): in front of S1 for x > x0, behind it for x < x0, its height
/// mu(x) = 0.25 (x - x0). Its rims (the lines where mu reaches a bound) cross S1 elements and S2
/// triangles alike.
inline std::shared_ptr<const Surface<2>> tilted_plane(double x0, int cells = 7) {
  return transformed<2>(*grid(cells, cells, -0.1, 1.1, -0.1, 1.1, 0.0, true, 0.2), [x0](const WorldPoint<2>& p) {
    return WorldPoint<2>(p.x(), p.y(), 0.25 * (p.x() - x0));
  });
}

/// Projection options with distance limit `max_distance`.
inline ProjectionOptions with_limit(double max_distance, bool allow_negative = false) {
  ProjectionOptions o;
  o.max_distance = max_distance;
  o.allow_negative_distance = allow_negative;
  return o;
}

/// The ray check of a projection map under the rules it was made with, 20,000 samples.
inline RayCheckReport<2> rays_under(const PlMap<2>& map, const Surface<2>& s1, const ProjectionOptions& rules) {
  RayCheckOptions<2> o;
  o.directions = averaged_vertex_normals(s1);
  o.samples = 20000;
  o.max_distance = rules.max_distance;
  o.allow_negative_distance = rules.allow_negative_distance;
  return check_against_rays(map, o);
}

}  // namespace plmap::test
