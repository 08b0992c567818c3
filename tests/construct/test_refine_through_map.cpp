// refine_through_map(): the refined surface has the expected size, its vertices lie on S2, and
// for a parametrization of a sphere its distance to S2 falls with the levels at the rate of a
// piecewise-linear interpolant (about 4x per level) until S2's own resolution is reached.

#include <plmap/construct/refine_through_map.hpp>
#include <plmap/construct/simplify.hpp>
#include <plmap/core/errors.hpp>
#include <plmap/verify/generators/closed_surfaces.hpp>

#include <gtest/gtest.h>

namespace plmap {
namespace {

const PlMap<2>& simplified_sphere() {
  static const PlMap<2> map = [] {
    generators::Rng rng(7);
    auto fine = std::make_shared<const Surface<2>>(generators::icosphere({3, 0.0}, rng));
    SimplifyOptions options;
    options.target_elements = 40;
    return simplify(fine, options).map;
  }();
  return map;
}

TEST(RefineThroughMap, SizesAndVerticesOnTheTarget) {
  const PlMap<2>& map = simplified_sphere();
  const Surface<2>& s1 = map.domain();
  for (int levels : {0, 1, 2}) {
    const RefineResult r = refine_through_map(map, {levels});
    const int n = 1 << levels;
    EXPECT_EQ(r.report.elements, s1.element_count() * n * n);
    // closed surface: V1 + E1 (n - 1) + T1 (n - 1)(n - 2) / 2
    EXPECT_EQ(r.report.vertices, s1.vertex_count() + s1.edge_count() * (n - 1) + s1.element_count() * (n - 1) * (n - 2) / 2);
    // On the icosphere: inside the unit sphere, outside the sphere through its face centroids.
    for (const auto& x : r.surface.vertices()) {
      EXPECT_LE(x.norm(), 1.0 + 1e-12);
      EXPECT_GE(x.norm(), 0.99);
    }
  }
}

TEST(RefineThroughMap, DistanceToTheSphereFallsLikeAPiecewiseLinearInterpolant) {
  const PlMap<2>& map = simplified_sphere();
  std::vector<double> distance;
  for (int levels : {0, 1, 2}) distance.push_back(refine_through_map(map, {levels}).report.distance_max);
  EXPECT_GT(distance[0] / distance[1], 2.5) << distance[0] << " " << distance[1] << " " << distance[2];
  EXPECT_GT(distance[1] / distance[2], 2.5) << distance[1] << " " << distance[2];
}

TEST(RefineThroughMap, RejectsLevelsOutOfRange) {
  EXPECT_THROW((void)refine_through_map(simplified_sphere(), {-1}), Error);
  EXPECT_THROW((void)refine_through_map(simplified_sphere(), {9}), Error);
}

}  // namespace
}  // namespace plmap
