// split_regions_off_their_rays (construct/src/split_region_rays.hpp) names the regions on the
// listed S2 elements whose sample points' rays meet the element's plane more than half an edge
// from Xi there. On triangle_under_triangle (S2 two units above S1, Xi the vertical lift):
// vertical rays meet S2 exactly at Xi; rays tilted by 0.1 per unit up meet it 0.2 away (inside
// half the mean edge, 0.57); rays at 45 degrees meet it 2 away, and rays parallel to it never.
#include "split_region_rays.hpp"

#include "triangle_under_triangle.hpp"

#include <gtest/gtest.h>

#include <vector>

using namespace plmap;
using plmap::test::triangle_under_triangle;

namespace {

std::vector<Index> named_with(const PlMap<2>& map, const WorldPoint<2>& direction, std::vector<Index> split_targets) {
  const std::vector<WorldPoint<2>> per_vertex(3, direction);
  return projection::split_regions_off_their_rays(map, per_vertex, split_targets, 1);
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

TEST(SplitRegionRays, OnlyRegionsOnTheListedElementsAreJudged) {
  const PlMap<2> map = triangle_under_triangle();
  EXPECT_TRUE(named_with(map, {1, 0, 1}, {}).empty());
  EXPECT_TRUE(named_with(map, {1, 0, 1}, {1}).empty());  // not the region's element
}
