// NearestElements (construct/src/element_index.hpp) answers the seed searches of normal
// projection from the centroids kept from an earlier, wider kd-tree query. The projection's
// result depends on the seeds and their order, so its answers must be the tree's exactly: the
// same elements in the same order, also where centroids tie (regular polygons and grids, queries
// on symmetry axes) and where the kept centroids do not cover the answer.
#include "../../construct/src/element_index.hpp"
#include "projection_fixtures.hpp"

#include <gtest/gtest.h>

#include <numbers>

using namespace plmap;
using plmap::projection::ElementIndex;
using plmap::projection::NearestElements;

namespace {

/// Runs the query points through NearestElements in chunks (as the projection does), compares
/// every answer with the tree's, and returns how many answers came from kept centroids.
template <int d>
std::size_t expect_same_as_tree(const ElementIndex<d>& index, const std::vector<WorldPoint<d>>& points, int k,
                         std::size_t chunk = 256) {
  std::size_t from_kept = 0;
  for (std::size_t begin = 0; begin < points.size(); begin += chunk) {
    NearestElements<d> nearest(index);
    for (std::size_t i = begin; i < std::min(points.size(), begin + chunk); ++i) {
      std::array<std::uint32_t, 32> got, expected;
      std::array<double, 32> unused;
      const int n = nearest.nearest(points[i], k, got);
      const int m = index.nearest(points[i], k, expected.data(), unused.data());
      EXPECT_EQ(n, m) << "query " << i;
      for (int j = 0; j < std::min(n, m); ++j) EXPECT_EQ(got[j], expected[j]) << "query " << i << ", neighbour " << j;
    }
    from_kept += nearest.answers_from_kept();
  }
  return from_kept;
}

}  // namespace

TEST(NearestElements, AnswersAsTheTreeAlongARegularPolygon) {
  // a regular polygon: centroids tie exactly for queries on its symmetry axes
  const auto s1 = test::circle(2000, 1.0);
  const ElementIndex<1> index(*s1);
  for (const double radius : {1.0, 0.999, 1.02}) {
    std::vector<WorldPoint<1>> points;
    for (int i = 0; i < 2600; ++i) {
      // every 13th query lies exactly on a vertex or centroid direction of the polygon
      const double a = 2.0 * std::numbers::pi * (i % 13 == 0 ? std::floor(i / 1.3) / 2000.0 : i / 2600.0);
      points.emplace_back(radius * std::cos(a), radius * std::sin(a));
    }
    for (const int k : {1, 8, 20, 32}) {
      const std::size_t from_kept = expect_same_as_tree<1>(index, points, k);
      if (k == 8) {
        EXPECT_GT(from_kept, points.size() / 2) << "radius " << radius;  // the shortcut is taken
      }
    }
  }
}

TEST(NearestElements, AnswersAsTheTreeForJumpsAndSmallSurfaces) {
  const auto s1 = test::circle(500, 1.0);
  const ElementIndex<1> index(*s1);
  std::vector<WorldPoint<1>> points;
  // jumps across the circle and back, far points, and the centre (all centroids tie)
  for (int i = 0; i < 300; ++i) {
    const double a = 2.0 * std::numbers::pi * ((i * 37) % 300) / 300.0;
    points.emplace_back((i % 3 == 0 ? 5.0 : 1.0) * std::cos(a), std::sin(a));
  }
  points.emplace_back(0.0, 0.0);
  expect_same_as_tree<1>(index, points, 8);
  // fewer elements than a wide query takes
  const auto small = test::circle(12, 1.0);
  const ElementIndex<1> small_index(*small);
  expect_same_as_tree<1>(small_index, points, 8);
}

TEST(NearestElements, AnswersAsTheTreeOnAGridSurface) {
  // an unjittered grid: many exact ties between centroids
  std::vector<WorldPoint<2>> v;
  std::vector<ElementCorners<2>> e;
  const int n = 40;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) v.emplace_back(i, j, 0.0);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i;
      e.push_back({a, a + 1, a + n + 2});
      e.push_back({a, a + n + 2, a + n + 1});
    }
  const Surface<2> grid(std::move(v), std::move(e));
  const ElementIndex<2> index(grid);
  std::vector<WorldPoint<2>> points;
  for (int j = 0; j < 2 * n; ++j)
    for (int i = 0; i < 2 * n; ++i) points.emplace_back(0.5 * i, 0.5 * j, (i + j) % 3 == 0 ? 0.0 : 0.25);
  expect_same_as_tree<2>(index, points, 8);
}
