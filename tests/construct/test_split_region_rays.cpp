// split_regions_off_their_rays (construct/src/split_region_rays.hpp) names the listed regions
// whose sample points' rays meet their S2 element's plane more than half an edge from Xi there.
// On triangle_under_triangle (S2 two units above S1, Xi the vertical lift): vertical rays meet
// S2 exactly at Xi; rays tilted by 0.1 per unit up meet it 0.2 away (inside half the mean edge,
// 0.57); rays at 45 degrees meet it 2 away, and rays parallel to it never. A ray that meets S2
// close to Xi but past a focal point of the field does not back its region either.
#include "split_region_rays.hpp"

#include "triangle_under_triangle.hpp"

#include <plmap/solvers/focal_points.hpp>

#include <gtest/gtest.h>

#include <array>

#include <limits>
#include <vector>

using namespace plmap;
using plmap::test::triangle_under_triangle;

namespace {

std::vector<Index> named_with(const PlMap<2>& map, const WorldPoint<2>& direction, std::vector<Index> candidates) {
  const std::vector<WorldPoint<2>> per_vertex(3, direction);
  const std::vector<double> reach{std::numeric_limits<double>::infinity()};  // equal directions: no focal point
  return projection::split_regions_off_their_rays(map, per_vertex, reach, candidates, 1);
}

}  // namespace

TEST(SplitRegionRays, RegionsTheRaysMeetFarFromXiAreNamed) {
  const PlMap<2> map = triangle_under_triangle();
  ASSERT_EQ(map.region_count(), 1);
  EXPECT_TRUE(named_with(map, {0, 0, 1}, {0}).empty());
  EXPECT_TRUE(named_with(map, {0.1, 0, 1}, {0}).empty());
  EXPECT_EQ(named_with(map, {1, 0, 1}, {0}), std::vector<Index>{0});
  EXPECT_EQ(named_with(map, {0, -1, 0.2}, {0}), std::vector<Index>{0});
  EXPECT_EQ(named_with(map, {1, 0, 0}, {0}), std::vector<Index>{0});  // parallel to S2: no hit at all
}

TEST(SplitRegionRays, OnlyTheListedRegionsAreJudged) {
  const PlMap<2> map = triangle_under_triangle();
  EXPECT_TRUE(named_with(map, {1, 0, 1}, {}).empty());
}

TEST(SplitRegionRays, RaysThatPassAFocalPointBeforeS2DoNotBackTheirRegion) {
  // directions converging on a point just below S2 (z = 1.9): every ray lands on S2 within 0.06
  // of Xi, but only past the focal point; converging on a point just above S2 (z = 2.1), before it
  const PlMap<2> map = triangle_under_triangle();
  auto named_converging_at = [&](double height) {
    const WorldPoint<2> focus(1.0 / 3.0, 1.0 / 3.0, height);
    std::array<WorldPoint<2>, 3> corners, directions;
    for (int k = 0; k < 3; ++k) {
      corners[k] = map.domain().corner(0, k);
      directions[k] = (focus - corners[k]).normalized();
    }
    const std::vector<double> reach{focal_free_distance<2>(corners, directions)};
    const std::vector<WorldPoint<2>> per_vertex(directions.begin(), directions.end());
    return projection::split_regions_off_their_rays(map, per_vertex, reach, std::vector<Index>{0}, 1);
  };
  EXPECT_EQ(named_converging_at(1.9), std::vector<Index>{0});
  EXPECT_TRUE(named_converging_at(2.1).empty());
}
