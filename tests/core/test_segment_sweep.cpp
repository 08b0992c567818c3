// any_segments_cross (the sweep along x) must answer exactly what the all-pairs loop of
// segments_cross_properly answers, including touching, collinear and shared-endpoint cases.

#include <plmap/core/segment_sweep.hpp>

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <vector>

namespace plmap {
namespace {

bool all_pairs_cross(const std::vector<PlanarSegment>& s) {
  for (std::size_t a = 0; a < s.size(); ++a)
    for (std::size_t b = a + 1; b < s.size(); ++b)
      if (segments_cross_properly(s[a][0], s[a][1], s[b][0], s[b][1])) return true;
  return false;
}

TEST(SegmentSweep, Examples) {
  using V = Eigen::Vector2d;
  std::vector<PlanarSegment> fan{{V(0, 0), V(1, 0)}, {V(0, 0), V(0, 1)}, {V(0, 0), V(1, 1)}};
  EXPECT_FALSE(any_segments_cross(fan));  // meet only at a common endpoint
  std::vector<PlanarSegment> cross{{V(0, 0), V(2, 2)}, {V(5, 5), V(6, 6)}, {V(0, 2), V(2, 0)}};
  EXPECT_TRUE(any_segments_cross(cross));
  std::vector<PlanarSegment> touch{{V(0, 0), V(2, 0)}, {V(1, 0), V(1, 3)}};  // T-junction
  EXPECT_TRUE(any_segments_cross(touch));
  std::vector<PlanarSegment> overlap{{V(0, 0), V(2, 0)}, {V(1, 0), V(3, 0)}};  // collinear overlap
  EXPECT_TRUE(any_segments_cross(overlap));
  std::vector<PlanarSegment> apart{{V(0, 0), V(1, 0)}, {V(1.5, -1), V(1.5, 1)}, {V(0, 1), V(1, 1)}};
  EXPECT_FALSE(any_segments_cross(apart));
  std::vector<PlanarSegment> vertical_touch{{V(1, 0), V(1, 2)}, {V(0, 1), V(1, 1)}};  // ends on a vertical segment
  EXPECT_TRUE(any_segments_cross(vertical_touch));
}

// Points on a small integer grid, so that shared endpoints, collinear pieces and touching
// points are frequent.
RC_GTEST_PROP(SegmentSweep, AgreesWithAllPairs, ()) {
  const auto coordinate = rc::gen::inRange(0, 6);
  const int n = *rc::gen::inRange(0, 12);
  std::vector<PlanarSegment> segments;
  for (int i = 0; i < n; ++i) {
    Eigen::Vector2d p(*coordinate, *coordinate), q(*coordinate, *coordinate);
    if (p == q) q.x() += 1.0;
    segments.push_back({p, q});
  }
  const bool expected = all_pairs_cross(segments);
  RC_ASSERT(any_segments_cross(segments) == expected);
}

}  // namespace
}  // namespace plmap
