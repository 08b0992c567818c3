// White-box tests of the closure's O(k) simplicity shortcut (core/src/element_closure.hpp):
// whenever convex_and_winding_once accepts a face, the pairwise test agrees it is simple, and it
// accepts the convex faces it is meant for.
#include "element_closure.hpp"

#include <plmap/core/predicates.hpp>

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <numbers>

using namespace plmap;

namespace {

/// The O(k^2) test of close_by_faces: no two sides meet except consecutive ones at their vertex.
bool simple_by_pairs(const std::vector<LocalPoint<2>>& p) {
  const int k = static_cast<int>(p.size());
  for (int i = 0; i < k; ++i)
    for (int j = i + 1; j < k; ++j)
      if (segments_cross_properly(p[i], p[(i + 1) % k], p[j], p[(j + 1) % k])) return false;
  return true;
}

bool shortcut(const std::vector<LocalPoint<2>>& p) {
  std::vector<int> poly(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) poly[i] = static_cast<int>(i);
  return detail::convex_and_winding_once(p, poly);
}

/// Vertices at the given angles (in turns) on an ellipse, on a grid of 1/64 so that collinear
/// and axis-parallel sides occur.
std::vector<LocalPoint<2>> on_ellipse(const std::vector<double>& turns) {
  std::vector<LocalPoint<2>> p;
  for (double t : turns) {
    const double a = 2.0 * std::numbers::pi * t;
    p.emplace_back(std::round(32.0 * std::cos(a)) / 64.0 + 0.5, std::round(20.0 * std::sin(a)) / 64.0 + 0.5);
  }
  return p;
}

}  // namespace

TEST(ElementClosure, ShortcutAcceptsConvexFacesAndRejectsStarsAndSpikes) {
  EXPECT_TRUE(shortcut({{0, 0}, {1, 0}, {1, 1}, {0, 1}}));
  EXPECT_TRUE(shortcut({{0, 0}, {0.5, 0}, {1, 0}, {1, 1}, {0, 1}}));  // a straight vertex
  EXPECT_FALSE(shortcut({{0, 0}, {0, 1}, {1, 1}, {1, 0}}));           // clockwise
  // a pentagram: left turns only, but it winds twice
  EXPECT_FALSE(shortcut(on_ellipse({0.0, 0.4, 0.8, 0.2, 0.6})));
  // doubling back along a line: (0,0) -> (1,0) -> (0.5,0) turns by exactly pi
  EXPECT_FALSE(shortcut({{0, 0}, {1, 0}, {0.5, 0}, {0.5, 1}}));
  // a reflex vertex
  EXPECT_FALSE(shortcut({{0, 0}, {1, 0}, {0.5, 0.2}, {1, 1}, {0, 1}}));
}

RC_GTEST_PROP(ElementClosure, ShortcutImpliesSimple, ()) {
  // random vertex sequences on an ellipse: sorted (convex), shuffled or wound several times
  const int k = *rc::gen::inRange(4, 12);
  auto turns = *rc::gen::container<std::vector<double>>(static_cast<std::size_t>(k), rc::gen::map(rc::gen::inRange(0, 1000), [](int i) {
    return i / 1000.0;
  }));
  const int mode = *rc::gen::inRange(0, 3);
  if (mode == 0) std::sort(turns.begin(), turns.end());
  if (mode == 1) {
    std::sort(turns.begin(), turns.end());
    for (std::size_t i = 0; i < turns.size(); i += 2) turns[i] += 1.0;  // every other vertex a turn later
    for (auto& t : turns) t *= 2.0;  // ... and wound twice
  }
  auto p = on_ellipse(turns);
  // distinct vertices, as close_by_faces guarantees before the test
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = i + 1; j < p.size(); ++j) RC_PRE(p[i] != p[j]);
  if (shortcut(p)) RC_ASSERT(simple_by_pairs(p));
  if (mode == 0 && simple_by_pairs(p)) {
    // sorted by angle on a convex curve and simple: convex unless rounding made a right turn
    bool left = true;
    for (int i = 0; i < k; ++i) left = left && orient2d(p[(i + k - 1) % k], p[i], p[(i + 1) % k]) >= 0;
    RC_ASSERT(shortcut(p) == left);
  }
}
