// regions_with_folded_corners (construct/src/folded_regions.hpp) names the regions with a corner
// whose ray passes a focal point of its element's direction field before reaching the node's
// image. One S1 triangle under one S2 triangle two units above it: with converging directions
// that meet one unit up, every corner's ray is folded and the region is named; with equal
// directions (no focal point at any distance, the elements the test skips) nothing is named.
#include "folded_regions.hpp"

#include "triangle_under_triangle.hpp"

#include <plmap/solvers/focal_points.hpp>

#include <gtest/gtest.h>

#include <array>
#include <limits>
#include <vector>

using namespace plmap;
using plmap::test::triangle_under_triangle;

namespace {

std::vector<Index> named_with(const PlMap<2>& map, const std::array<WorldPoint<2>, 3>& directions) {
  std::array<WorldPoint<2>, 3> corners;
  for (int k = 0; k < 3; ++k) corners[k] = map.domain().corner(0, k);
  const std::vector<double> reach{focal_free_distance<2>(corners, directions)};
  const std::vector<WorldPoint<2>> per_vertex(directions.begin(), directions.end());
  return projection::regions_with_folded_corners<2>(map, per_vertex, reach, 1);
}

}  // namespace

TEST(FoldedRegions, RaysPastTheirFocalPointAreNamedAndParallelRaysAreNot) {
  const PlMap<2> map = triangle_under_triangle();
  ASSERT_EQ(map.region_count(), 1);
  const WorldPoint<2> focus(1.0 / 3.0, 1.0 / 3.0, 1.0);  // below S2
  std::array<WorldPoint<2>, 3> converging;
  for (int k = 0; k < 3; ++k) converging[k] = (focus - map.domain().corner(0, k)).normalized();
  EXPECT_EQ(named_with(map, converging), std::vector<Index>{0});

  const std::array<WorldPoint<2>, 3> parallel = {WorldPoint<2>(0, 0, 1), WorldPoint<2>(0, 0, 1), WorldPoint<2>(0, 0, 1)};
  std::array<WorldPoint<2>, 3> corners;
  for (int k = 0; k < 3; ++k) corners[k] = map.domain().corner(0, k);
  EXPECT_EQ(focal_free_distance<2>(corners, parallel), std::numeric_limits<double>::infinity());
  EXPECT_TRUE(named_with(map, parallel).empty());
}
