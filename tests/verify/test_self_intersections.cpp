// Where a surface crosses itself (verify/self_intersections.hpp): pairs of elements that meet
// although they share no vertex, on cases whose answer is known by construction.
#include <plmap/verify/self_intersections.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <utility>
#include <vector>

namespace plmap {
namespace {

using Pairs = std::vector<std::pair<Index, Index>>;

/// The square [0, 1]^2 at height z(x) as n x n cells, two triangles each: in cell (i, j) element
/// 2 (j n + i) has the corners (i, j), (i + 1, j), (i + 1, j + 1) and element 2 (j n + i) + 1 the
/// corners (i, j), (i + 1, j + 1), (i, j + 1). Vertex numbers start at `first`.
void add_sheet(int n, double (*z)(double), std::vector<WorldPoint<2>>& v, std::vector<ElementCorners<2>>& e) {
  const auto first = static_cast<Index>(v.size());
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = double(i) / n;
      v.emplace_back(x, double(j) / n, z(x));
    }
  auto id = [&](int i, int j) { return first + j * (n + 1) + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      e.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      e.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
}

double flat(double) { return 0.0; }
double rising(double x) { return 0.5 * (x - 0.5); }
double falling(double x) { return -0.5 * (x - 0.5); }
double ridge(double x) { return -0.5 * std::abs(x - 0.5); }

}  // namespace

TEST(SelfIntersections, ATrianglePiercingOneElementOfAGridIsOnePair) {
  // The vertical triangle in the plane y = 0.3 crosses z = 0 along x in [0.405, 0.435]: inside
  // element 10 of the 4 x 4 grid (cell (1, 1), below its diagonal), and nowhere else.
  std::vector<WorldPoint<2>> v;
  std::vector<ElementCorners<2>> e;
  add_sheet(4, flat, v, e);
  const auto n = static_cast<Index>(v.size());
  v.emplace_back(0.40, 0.30, -0.1);
  v.emplace_back(0.44, 0.30, -0.1);
  v.emplace_back(0.42, 0.30, 0.1);
  e.push_back({n, n + 1, n + 2});
  const Surface<2> s(std::move(v), std::move(e));
  EXPECT_EQ(self_intersections(s), (Pairs{{10, 32}}));
  EXPECT_EQ(self_intersections(Surface<2>(std::vector<WorldPoint<2>>(s.vertices().begin(), s.vertices().end()),
                                          std::vector<ElementCorners<2>>(s.elements().begin(), s.elements().end() - 1))),
            Pairs{});
}

TEST(SelfIntersections, TwoSheetsCrossingAlongALineMeetInOneColumnOfCells) {
  // z = +-(x - 0.5) / 2 on 5 x 5 cells: they cross along x = 0.5, inside the middle column
  // (cells i = 2); elements elsewhere lie on one side of the other sheet. Every pair found lies
  // in that column, each middle-column element of one sheet meets at least one of the other's,
  // and the answer is the same on one thread and on all.
  std::vector<WorldPoint<2>> v;
  std::vector<ElementCorners<2>> e;
  add_sheet(5, rising, v, e);
  add_sheet(5, falling, v, e);
  const Surface<2> s(std::move(v), std::move(e));
  const Pairs pairs = self_intersections(s, 1);
  ASSERT_FALSE(pairs.empty());
  std::vector<int> met(100, 0);
  for (const auto& [a, b] : pairs) {
    EXPECT_LT(a, 50);
    EXPECT_GE(b, 50);
    EXPECT_EQ((a / 2) % 5, 2) << a;
    EXPECT_EQ(((b - 50) / 2) % 5, 2) << b;
    met[static_cast<std::size_t>(a)] = met[static_cast<std::size_t>(b)] = 1;
  }
  for (int k = 0; k < 100; ++k) {
    if (((k % 50) / 2) % 5 == 2) {
      EXPECT_EQ(met[static_cast<std::size_t>(k)], 1) << k;
    }
  }
  EXPECT_EQ(self_intersections(s, 0), pairs);
}

TEST(SelfIntersections, ASheetBentAlongARidgeDoesNotCrossItself) {
  // The ridge's elements meet only where they share vertices or edges.
  std::vector<WorldPoint<2>> v;
  std::vector<ElementCorners<2>> e;
  add_sheet(6, ridge, v, e);
  EXPECT_EQ(self_intersections(Surface<2>(std::move(v), std::move(e))), Pairs{});
}

TEST(SelfIntersections, CurvesCrossWhereTheirSegmentsDo) {
  // A horizontal polyline at y = 0.5 and a vertical one at x = 0.6, four segments each, with
  // vertices at 0.05 + 0.25 i along them: they cross at (0.6, 0.5), inside segment 2 of the first
  // (x in [0.55, 0.8]) and segment 1 of the second (y in [0.3, 0.55]), which is element 5.
  std::vector<WorldPoint<1>> v;
  std::vector<ElementCorners<1>> e;
  for (int i = 0; i <= 4; ++i) v.emplace_back(0.05 + 0.25 * i, 0.5);
  for (int i = 0; i <= 4; ++i) v.emplace_back(0.6, 0.05 + 0.25 * i);
  for (int i = 0; i < 4; ++i) e.push_back({i, i + 1});
  for (int i = 0; i < 4; ++i) e.push_back({5 + i, 6 + i});
  EXPECT_EQ(self_intersections(Surface<1>(v, e)), (Pairs{{2, 5}}));
  // the vertical one moved beyond the horizontal one's end: no crossing
  for (int i = 5; i <= 9; ++i) v[static_cast<std::size_t>(i)].x() = 1.2;
  EXPECT_EQ(self_intersections(Surface<1>(v, e)), Pairs{});
}

TEST(SelfIntersections, FlatSheetsAndStraightCurvesAreSearchedOverTheAxesTheySpan) {
  // The candidate boxes leave out an axis along which the surface does not extend; pairs that
  // only overlap within the surface's plane or line must still be found.
  // A small triangle lying in the plane z = 0 of the flat 4 x 4 grid, strictly inside element 10
  // (cell (1, 1), below its diagonal y = x): they overlap in the plane and share no vertex.
  std::vector<WorldPoint<2>> v;
  std::vector<ElementCorners<2>> e;
  add_sheet(4, flat, v, e);
  const auto n = static_cast<Index>(v.size());
  v.emplace_back(0.40, 0.26, 0.0);
  v.emplace_back(0.44, 0.26, 0.0);
  v.emplace_back(0.43, 0.29, 0.0);
  e.push_back({n, n + 1, n + 2});
  EXPECT_EQ(self_intersections(Surface<2>(v, e)), (Pairs{{10, 32}}));
  // lifted off the plane, it meets nothing
  for (Index k = n; k < n + 3; ++k) v[static_cast<std::size_t>(k)].z() = 0.01;
  EXPECT_EQ(self_intersections(Surface<2>(v, e)), Pairs{});

  // On the line y = 0: segments [0, 1], [1, 2], [2, 3] and a separate segment [1.5, 2.5], which
  // overlaps the second and the third.
  std::vector<WorldPoint<1>> c;
  std::vector<ElementCorners<1>> s;
  for (int i = 0; i <= 3; ++i) c.emplace_back(double(i), 0.0);
  c.emplace_back(1.5, 0.0);
  c.emplace_back(2.5, 0.0);
  s = {{0, 1}, {1, 2}, {2, 3}, {4, 5}};
  EXPECT_EQ(self_intersections(Surface<1>(c, s)), (Pairs{{1, 3}, {2, 3}}));
  // moved beyond the end of the line, it meets nothing
  c[4].x() = 3.5;
  c[5].x() = 4.5;
  EXPECT_EQ(self_intersections(Surface<1>(c, s)), Pairs{});
}

TEST(SelfIntersections, MoreCandidatesThanOneBatchAreAllDecided) {
  // 1500 parallel segments P_i: y = x + i h and 1500 parallel segments Q_j: y = 2 + j h - 3x, on
  // x in [0, 1], h = 1e-3, each its own component. Every box overlaps every other (4.5M candidate
  // pairs, several of the search's batches); P_i meets Q_j at x = (2 + (j - i) h) / 4, inside
  // both, and parallel segments never meet: exactly the 2.25M pairs (P_i, Q_j).
  constexpr int n = 1500;
  constexpr double h = 1e-3;
  std::vector<WorldPoint<1>> v;
  std::vector<ElementCorners<1>> e;
  for (int i = 0; i < n; ++i) {
    v.emplace_back(0.0, i * h);
    v.emplace_back(1.0, 1.0 + i * h);
  }
  for (int j = 0; j < n; ++j) {
    v.emplace_back(0.0, 2.0 + j * h);
    v.emplace_back(1.0, -1.0 + j * h);
  }
  for (Index k = 0; k < 2 * n; ++k) e.push_back({2 * k, 2 * k + 1});
  const Pairs pairs = self_intersections(Surface<1>(v, e));
  ASSERT_EQ(pairs.size(), std::size_t{n} * n);
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const Index i = static_cast<Index>(k / n), j = static_cast<Index>(k % n);
    if (pairs[k] != std::make_pair(i, n + j)) {
      ADD_FAILURE() << "pair " << k << " is (" << pairs[k].first << ", " << pairs[k].second << ")";
      break;
    }
  }
}

}  // namespace plmap
