// triangle_conditioning: kappa of the linear map between two world triangles, the function that
// region_conditioning uses and that the peer benchmarks apply to maps held in another form.

#include <plmap/core/regions.hpp>
#include <plmap/verify/generators/random_surfaces.hpp>
#include <plmap/verify/generators/subdivision_maps.hpp>
#include <plmap/verify/quality.hpp>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>

namespace plmap {
namespace {

TEST(TriangleConditioning, AStretchByTwoAlongOneAxisHasKappaTwoInAnyPlacement) {
  const std::array<WorldPoint<2>, 3> domain = {WorldPoint<2>(0, 0, 0), WorldPoint<2>(1, 0, 0), WorldPoint<2>(0, 1, 0)};
  // the image stretched by 2 along x, then rotated into another plane and moved
  const Eigen::Matrix3d rotation = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  std::array<WorldPoint<2>, 3> image;
  for (int k = 0; k < 3; ++k)
    image[k] = rotation * WorldPoint<2>(2 * domain[k](0), domain[k](1), 0) + WorldPoint<2>(5, -1, 2);
  const RegionConditioning c = triangle_conditioning(domain, image);
  EXPECT_NEAR(c.kappa, 2.0, 1e-12);
  EXPECT_NEAR(c.sigma_max, 2.0, 1e-12);
  EXPECT_NEAR(c.sigma_min, 1.0, 1e-12);
}

TEST(TriangleConditioning, ADegenerateDomainHasInfiniteKappa) {
  const std::array<WorldPoint<2>, 3> line = {WorldPoint<2>(0, 0, 0), WorldPoint<2>(1, 0, 0), WorldPoint<2>(2, 0, 0)};
  const std::array<WorldPoint<2>, 3> image = {WorldPoint<2>(0, 0, 0), WorldPoint<2>(1, 0, 0), WorldPoint<2>(0, 1, 0)};
  EXPECT_TRUE(std::isinf(triangle_conditioning(line, image).kappa));
}

TEST(TriangleConditioning, AgreesWithRegionConditioningOnEveryRegionOfAMap) {
  generators::Rng rng(11);
  auto s1 = std::make_shared<const Surface<2>>(
      generators::grid_triangulation({.cells = 3, .jitter = 0.2, .with_hole = false}, rng));
  const auto built = generators::subdivision_map(s1, 3, 0.2, 5);
  const PlMap<2>& map = *built.map;
  ASSERT_GT(map.region_count(), 0);
  for (Index r = 0; r < map.region_count(); ++r) {
    const RegionConditioning expected = region_conditioning(map, r);
    const RemoteIntersection<2> ri = remote_intersection(map, r);
    const RegionConditioning got = triangle_conditioning(ri.domain_world, ri.target_world);
    EXPECT_GE(got.kappa, 1.0);
    EXPECT_EQ(got.kappa, expected.kappa);
    EXPECT_EQ(got.sigma_min, expected.sigma_min);
  }
}

}  // namespace
}  // namespace plmap
