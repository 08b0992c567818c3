// The smoothing's fast paths must answer exactly what the general code answers:
// pieces_meet / any_pieces_meet (construct/src/piece_crossings.hpp) against
// segments_cross_properly over all pairs, and frame_scale (construct/src/region_condition.hpp)
// against power_of_two_scale, bit for bit; the exact winding count (direction_precedes) against
// the sum of atan2 turning angles it replaced.

#include "piece_crossings.hpp"
#include "region_condition.hpp"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

namespace plmap::smoothing {
namespace {

bool all_pairs_meet(const std::vector<PlanarSegment>& s) {
  for (std::size_t a = 0; a < s.size(); ++a)
    for (std::size_t b = a + 1; b < s.size(); ++b)
      if (segments_cross_properly(s[a][0], s[a][1], s[b][0], s[b][1])) return true;
  return false;
}

TEST(PieceCrossings, SharedEndpointCases) {
  using V = Eigen::Vector2d;
  // each way two segments can share an end, apart, overlapping beyond it, and touching the other
  EXPECT_FALSE(pieces_meet(V(0, 0), V(2, 0), V(0, 0), V(0, 2)));
  EXPECT_FALSE(pieces_meet(V(0, 0), V(2, 0), V(0, 2), V(0, 0)));
  EXPECT_FALSE(pieces_meet(V(2, 0), V(0, 0), V(0, 0), V(0, 2)));
  EXPECT_FALSE(pieces_meet(V(2, 0), V(0, 0), V(0, 2), V(0, 0)));
  EXPECT_TRUE(pieces_meet(V(0, 0), V(2, 0), V(0, 0), V(1, 0)));   // collinear, overlapping
  EXPECT_TRUE(pieces_meet(V(2, 0), V(0, 0), V(1, 0), V(0, 0)));
  EXPECT_FALSE(pieces_meet(V(0, 0), V(2, 0), V(2, 0), V(3, 0)));  // collinear, end to end
  EXPECT_TRUE(pieces_meet(V(0, 0), V(2, 0), V(1, 0), V(1, 1)));   // T-junction
  EXPECT_TRUE(pieces_meet(V(0, 0), V(2, 2), V(0, 2), V(2, 0)));   // proper crossing
  EXPECT_FALSE(pieces_meet(V(0, 0), V(1, 0), V(0, 1), V(1, 1)));  // parallel
}

// Points on a small integer grid, so that shared endpoints, collinear pieces and touching points
// are frequent: every pair answer and the sweep's answer equal segments_cross_properly's.
RC_GTEST_PROP(PieceCrossings, AgreesWithSegmentsCrossProperly, ()) {
  const auto coordinate = rc::gen::inRange(0, 5);
  const int n = *rc::gen::inRange(0, 12);
  std::vector<PlanarSegment> segments;
  for (int i = 0; i < n; ++i) {
    Eigen::Vector2d p(*coordinate, *coordinate), q(*coordinate, *coordinate);
    if (p == q) q.y() += 1.0;
    segments.push_back({p, q});
  }
  for (std::size_t a = 0; a < segments.size(); ++a)
    for (std::size_t b = 0; b < segments.size(); ++b) {
      if (a == b) continue;
      const auto& s = segments[a];
      const auto& o = segments[b];
      RC_ASSERT(pieces_meet(s[0], s[1], o[0], o[1]) == segments_cross_properly(s[0], s[1], o[0], o[1]));
    }
  std::vector<PieceBox> boxes;
  RC_ASSERT(any_pieces_meet(segments, boxes) == all_pairs_meet(segments));
}

// Pieces on a small grid, each end labelled as an unknown (a few labels, placed at one grid point
// each) or fixed: the sweep that skips pairs sharing an unknown says "meet" exactly when a pair
// not sharing one meets; every pair it skips is one the winding check refuses when it meets
// (both leave the unknown in the same direction).
RC_GTEST_PROP(PieceCrossings, SkippingSharedUnknownsMissesOnlyPairsLeavingTheUnknownTogether, ()) {
  const auto coordinate = rc::gen::inRange(0, 5);
  std::vector<Eigen::Vector2d> unknown_at;  // up to three unknowns, at their own grid points
  for (int u = 0; u < 3; ++u) unknown_at.emplace_back(*coordinate, *coordinate);
  const int n = *rc::gen::inRange(0, 12);
  std::vector<PlanarSegment> segments;
  std::vector<std::array<int, 2>> ends;
  for (int i = 0; i < n; ++i) {
    std::array<int, 2> e{*rc::gen::inRange(-1, 3), *rc::gen::inRange(-1, 3)};
    if (e[0] >= 0 && e[0] == e[1]) e[1] = -1;  // an S2 edge joins two different vertices
    Eigen::Vector2d p = e[0] >= 0 ? unknown_at[e[0]] : Eigen::Vector2d(*coordinate, *coordinate);
    Eigen::Vector2d q = e[1] >= 0 ? unknown_at[e[1]] : Eigen::Vector2d(*coordinate, *coordinate);
    if (p == q) {
      if (e[1] >= 0) continue;  // two unknowns at one point: not a piece the test can build
      q.y() += 1.0;
    }
    segments.push_back({p, q});
    ends.push_back(e);
  }
  bool unshared_meet = false, shared_meet = false;
  for (std::size_t a = 0; a < segments.size(); ++a)
    for (std::size_t b = a + 1; b < segments.size(); ++b) {
      const bool meet = segments_cross_properly(segments[a][0], segments[a][1], segments[b][0], segments[b][1]);
      const auto& x = ends[a];
      const auto& y = ends[b];
      const int shared = x[0] >= 0 && (x[0] == y[0] || x[0] == y[1]) ? x[0] : x[1] >= 0 && (x[1] == y[0] || x[1] == y[1]) ? x[1] : -1;
      if (shared < 0) {
        unshared_meet = unshared_meet || meet;
        continue;
      }
      shared_meet = shared_meet || meet;
      if (meet) {  // both leave the unknown in the same direction
        const Eigen::Vector2d o = unknown_at[shared];
        const Eigen::Vector2d da = (segments[a][0] == o ? segments[a][1] : segments[a][0]) - o;
        const Eigen::Vector2d db = (segments[b][0] == o ? segments[b][1] : segments[b][0]) - o;
        RC_ASSERT(da.x() * db.y() - da.y() * db.x() == 0.0);
        RC_ASSERT(da.dot(db) > 0.0);
      }
    }
  std::vector<PieceBox> boxes;
  RC_ASSERT(pieces_apart_from_shared_ends_meet(segments, ends, boxes) == unshared_meet);
  RC_ASSERT(any_pieces_meet(segments, boxes) == (unshared_meet || shared_meet));
}

TEST(FrameScale, EqualsPowerOfTwoScale) {
  const double tiny = std::numeric_limits<double>::denorm_min();
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<Eigen::Vector3d> cases = {
      {0, 0, 0}, {1, 0, 0}, {-3, 0.5, 2}, {0.75, -1e-300, 0}, {1e300, 1, -1e308}, {tiny, 0, 0},
      {4 * tiny, -tiny, 0}, {std::numeric_limits<double>::min(), 0, 0}, {inf, 1, 0}, {std::nan(""), 1, 0}};
  for (const auto& u : cases)
    for (const auto& v : cases) EXPECT_EQ(frame_scale(u, v), power_of_two_scale<2>({u, v})) << u.transpose() << " / " << v.transpose();
}

RC_GTEST_PROP(FrameScale, EqualsPowerOfTwoScaleOnRandomVectors, ()) {
  const auto component = [] {
    const double mantissa = *rc::gen::inRange(-1000000, 1000000) / 1e6;
    return std::ldexp(mantissa, *rc::gen::inRange(-1070, 1020));
  };
  const Eigen::Vector3d u(component(), component(), component()), v(component(), component(), component());
  RC_ASSERT(frame_scale(u, v) == power_of_two_scale<2>({u, v}));
}

// Random directions on a small integer grid (no zero direction, no two consecutive ones equal):
// exactly one turn fails direction_precedes iff the counter-clockwise turning angles sum to 2π.
RC_GTEST_PROP(DirectionOrder, CountsTheWindingOfTheTurningAngles, ()) {
  const int k = *rc::gen::inRange(2, 9);
  std::vector<Eigen::Vector2d> d;
  for (int i = 0; i < k; ++i) {
    Eigen::Vector2d v(*rc::gen::inRange(-3, 4), *rc::gen::inRange(-3, 4));
    if (v == Eigen::Vector2d::Zero()) v.x() = 1.0;
    d.push_back(v);
  }
  int wraps = 0;
  double turning = 0.0;
  for (int i = 0; i < k; ++i) {
    const Eigen::Vector2d& a = d[static_cast<std::size_t>(i)];
    const Eigen::Vector2d& b = d[static_cast<std::size_t>((i + 1) % k)];
    const int turn = orient2d(Eigen::Vector2d::Zero(), a, b);
    RC_PRE(!(turn == 0 && a.dot(b) > 0.0));  // the step refuses equal directions before
    if (!direction_precedes(a, b, turn)) ++wraps;
    double angle = std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b));
    if (angle <= 0.0) angle += 2.0 * std::numbers::pi;
    turning += angle;
  }
  RC_ASSERT(std::abs(turning - 2.0 * std::numbers::pi * wraps) < 1e-9);
}

}  // namespace
}  // namespace plmap::smoothing
