// The downstream project's own tests: its refinement maps must pass plmap::verify, and verify
// must notice when such a map is wrong.
#include "refinement.hpp"

#include <plmap/core/regions.hpp>
#include <plmap/verify/check.hpp>

#include <gtest/gtest.h>

#include <utility>

namespace {

plmap::VerifyOptions parametrization() {
  plmap::VerifyOptions options;
  options.expect_parametrization = true;  // regions must cover the coarse and the fine surface
  return options;
}

TEST(RefinementMap, UnitSquareIsAVerifiedParametrization) {
  const auto coarse = downstream::unit_square();
  const auto fine = downstream::midpoint_refine(*coarse);
  ASSERT_EQ(fine->element_count(), 8);
  const plmap::PlMap<2> map = downstream::refinement_map(coarse, fine);

  const plmap::VerificationReport report = plmap::verify(map, parametrization());
  EXPECT_TRUE(report.ok()) << plmap::summary(report);
  EXPECT_EQ(map.region_count(), 8);  // one region per fine triangle
  const plmap::CoveredMeasure covered = plmap::covered_measure(map);
  EXPECT_NEAR(covered.domain, 1.0, 1e-14);
  EXPECT_NEAR(covered.target, 1.0, 1e-14);
}

TEST(RefinementMap, ClosedSurfaceInSpaceIsAVerifiedParametrization) {
  const auto coarse = downstream::tetrahedron();
  const auto fine = downstream::midpoint_refine(*coarse);
  const plmap::PlMap<2> map = downstream::refinement_map(coarse, fine);

  const plmap::VerificationReport report = plmap::verify(map, parametrization());
  EXPECT_TRUE(report.ok()) << plmap::summary(report);
  EXPECT_EQ(map.region_count(), 16);
  // Each region is a fine triangle: the map is the identity of the geometry, so every region's
  // corners coincide with their images.
  for (const auto& region : plmap::remote_intersections(map)) {
    EXPECT_NEAR(region.domain_measure(), region.target_measure(), 1e-14);
    for (int i = 0; i < 3; ++i)
      EXPECT_NEAR((region.domain_world[i] - region.target_world[i]).norm(), 0.0, 1e-14);
  }
}

TEST(RefinementMap, VerifyRejectsARegionMappedIntoTheWrongTriangle) {
  const auto coarse = downstream::unit_square();
  const auto fine = downstream::midpoint_refine(*coarse);
  const plmap::PlMap<2> good = downstream::refinement_map(coarse, fine);

  // Send region 0 into a fine triangle on the other side of the square.
  plmap::MapData<2> data = good.data();
  data.region_target[0] = (data.region_target[0] + 5) % fine->element_count();
  const plmap::PlMap<2> broken(good.domain_ptr(), good.target_ptr(), std::move(data));

  const plmap::VerificationReport report = plmap::verify(broken, parametrization());
  EXPECT_FALSE(report.ok());
  EXPECT_GT(report.violation_count(plmap::check_names::map), 0u) << plmap::summary(report);
}

}  // namespace
