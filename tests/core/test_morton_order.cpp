// plmap::morton_order (core/spatial_order.hpp): points sorted along the Z-order curve of their
// box, x's bit before y's at every level, equal codes in index order.
#include <plmap/core/spatial_order.hpp>

#include <gtest/gtest.h>

#include <vector>

using namespace plmap;

TEST(MortonOrder, TheCornersOfASquareComeInZOrder) {
  // the four corners of the unit square, listed in reverse Z order
  const std::vector<WorldPoint<1>> p{{1.0, 1.0}, {1.0, 0.0}, {0.0, 1.0}, {0.0, 0.0}};
  const auto order = morton_order<1>(std::span<const WorldPoint<1>>(p), WorldPoint<1>(0.0, 0.0), WorldPoint<1>(1.0, 1.0));
  // (0,0), (0,1), (1,0), (1,1): the x bit is the more significant of each pair
  EXPECT_EQ(order, (std::vector<Index>{3, 2, 1, 0}));
}

TEST(MortonOrder, QuadrantsComeOneAfterTheOtherAndTiesKeepTheirOrder) {
  // a 4 x 4 x 4 lattice (d = 2 points) listed backwards, and a duplicate of the first point
  std::vector<WorldPoint<2>> p;
  for (int i = 63; i >= 0; --i) p.emplace_back(i % 4, (i / 4) % 4, i / 16);
  p.push_back(p.front());
  const auto order = morton_order<2>(std::span<const WorldPoint<2>>(p), WorldPoint<2>(0, 0, 0), WorldPoint<2>(3, 3, 3));
  ASSERT_EQ(order.size(), p.size());
  // the first eight are the octant nearest the origin: coordinates 0 or 1 only
  for (int i = 0; i < 8; ++i) EXPECT_LE(p[static_cast<std::size_t>(order[i])].maxCoeff(), 1.0) << i;
  // the last two are the corner (3, 3, 3) and its duplicate, in index order
  EXPECT_EQ(order[63], 0);
  EXPECT_EQ(order[64], 64);
}
