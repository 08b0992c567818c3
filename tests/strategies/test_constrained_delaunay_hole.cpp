// The constrained Delaunay hole triangulation after its ear-clipping start: where no diagonal is
// forbidden it is the one constrained Delaunay triangulation (the same triangles as from the
// min-max-aspect start), listed canonically, so the result does not depend on the start, on the
// order of the flips, or on which ring vertex comes first.

#include <plmap/core/predicates.hpp>
#include <plmap/strategies/simplification/constrained_delaunay_hole.hpp>
#include <plmap/strategies/simplification/min_max_aspect_triangulation.hpp>

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace plmap {
namespace {

/// A random star-shaped polygon around the origin (angles increasing, gaps below π, random radii).
std::vector<Eigen::Vector2d> random_star_polygon(int n) {
  std::vector<double> gaps(n);
  double total = 0.0;
  for (double& g : gaps) total += (g = *rc::gen::inRange(20, 100));
  // a gap of π or more (possible for n = 3, e.g. gaps 62, 20, 20) leaves the origin outside the
  // polygon, which may then turn clockwise: not a star polygon around the origin
  RC_PRE(2.0 * *std::max_element(gaps.begin(), gaps.end()) < total);
  std::vector<Eigen::Vector2d> p(n);
  double angle = *rc::gen::inRange(0, 628) / 100.0;
  for (int i = 0; i < n; ++i) {
    const double r = *rc::gen::inRange(20, 100) / 100.0;
    p[i] = {r * std::cos(angle), r * std::sin(angle)};
    angle += 2.0 * std::numbers::pi * gaps[i] / total;
  }
  return p;
}

/// The reference: the min-max-aspect triangulation, flipped (full rescan after every flip) until
/// every flippable diagonal is locally Delaunay; triangles as sorted corner triples, sorted.
HoleTriangles reference_delaunay(std::span<const Eigen::Vector2d> p) {
  HoleTriangles t = *MinMaxAspectTriangulation{}.triangulate(p, [](int, int) { return true; });
  for (bool flipped = true; flipped;) {
    flipped = false;
    for (std::size_t a = 0; a < t.size() && !flipped; ++a)
      for (std::size_t b = 0; b < t.size() && !flipped; ++b)
        for (int m = 0; m < 3 && !flipped; ++m)
          for (int k = 0; k < 3 && !flipped; ++k) {
            const int u = t[a][m], v = t[a][(m + 1) % 3], w = t[a][(m + 2) % 3];
            if (t[b][k] != v || t[b][(k + 1) % 3] != u) continue;
            const int x = t[b][(k + 2) % 3];
            if (incircle(p[u], p[v], p[w], p[x]) > 0 && orient2d(p[x], p[v], p[w]) > 0 && orient2d(p[u], p[x], p[w]) > 0) {
              t[a] = {x, v, w};
              t[b] = {u, x, w};
              flipped = true;
            }
          }
  }
  for (auto& tri : t) std::sort(tri.begin(), tri.end());
  std::sort(t.begin(), t.end());
  return t;
}

HoleTriangles sorted_set(HoleTriangles t) {
  for (auto& tri : t) std::sort(tri.begin(), tri.end());
  std::sort(t.begin(), t.end());
  return t;
}

/// True if t is listed as MinMaxAspectTriangulation lists its result: (i, m, j) with i < m < j,
/// depth first from the chord 0-(n-1), the sub-polygon (m, j) before (i, m).
bool is_canonical(const HoleTriangles& t, int n) {
  std::vector<std::array<int, 2>> stack{{0, n - 1}};
  std::size_t next = 0;
  while (!stack.empty()) {
    const auto [i, j] = stack.back();
    stack.pop_back();
    if (j - i < 2) continue;
    if (next >= t.size() || t[next][0] != i || t[next][2] != j || !(i < t[next][1] && t[next][1] < j)) return false;
    const int m = t[next++][1];
    stack.push_back({i, m});
    stack.push_back({m, j});
  }
  return next == t.size();
}

RC_GTEST_PROP(ConstrainedDelaunayHole, WithoutForbiddenDiagonalsIsTheDelaunayTriangulationListedCanonically, ()) {
  const int n = *rc::gen::inRange(3, 14);
  const auto p = random_star_polygon(n);
  const auto t = ConstrainedDelaunayHole{}.triangulate(p, [](int, int) { return true; });
  RC_ASSERT(t.has_value());
  RC_ASSERT(is_canonical(*t, n));
  RC_ASSERT(sorted_set(*t) == reference_delaunay(p));
}

RC_GTEST_PROP(ConstrainedDelaunayHole, DoesNotDependOnTheFirstRingVertex, ()) {
  const int n = *rc::gen::inRange(4, 14);
  const auto p = random_star_polygon(n);
  const int shift = *rc::gen::inRange(1, n);
  std::vector<Eigen::Vector2d> rotated(n);
  for (int i = 0; i < n; ++i) rotated[i] = p[(i + shift) % n];
  const auto t = *ConstrainedDelaunayHole{}.triangulate(p, [](int, int) { return true; });
  auto u = *ConstrainedDelaunayHole{}.triangulate(rotated, [](int, int) { return true; });
  for (auto& tri : u)
    for (int& c : tri) c = (c + shift) % n;  // back to p's numbering
  RC_ASSERT(sorted_set(t) == sorted_set(u));
}

TEST(ConstrainedDelaunayHole, FallsBackWhenTheEarsLeadToADeadEnd) {
  // A regular hexagon whose only allowed diagonals are 0-2, 2-4, 4-0 (one triangulation) and
  // 5-1. The ear at corner 0 (diagonal 5-1) comes first and leaves the pentagon 1..5 with the
  // single allowed diagonal 2-4: no triangulation. The min-max-aspect start finds the one there is.
  std::vector<Eigen::Vector2d> p(6);
  for (int i = 0; i < 6; ++i) p[i] = {std::cos(i * std::numbers::pi / 3), std::sin(i * std::numbers::pi / 3)};
  const DiagonalAllowed allowed = [](int i, int j) {
    const std::array<int, 2> key{std::min(i, j), std::max(i, j)};
    return key == std::array{0, 2} || key == std::array{2, 4} || key == std::array{0, 4} || key == std::array{1, 5};
  };
  const auto t = ConstrainedDelaunayHole{}.triangulate(p, allowed);
  ASSERT_TRUE(t.has_value());
  EXPECT_EQ(sorted_set(*t), (HoleTriangles{{0, 1, 2}, {0, 2, 4}, {0, 4, 5}, {2, 3, 4}}));
  EXPECT_TRUE(is_canonical(*t, 6));
  EXPECT_FALSE(ConstrainedDelaunayHole{}.triangulate(p, [](int, int) { return false; }).has_value());
}

}  // namespace
}  // namespace plmap
