// bench_projection_peers --order spatial: the inputs renumbered along a Morton curve must be the
// same surfaces (same cells as point tuples, corners in their order) with consecutive cells near
// each other, or the benchmark would compare the tools on another input.

#include "peers/spatial_order.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <set>
#include <vector>

namespace plmap::peers {
namespace {

/// An n x n grid of triangles over the unit square (z a gentle bump), cells and points shuffled.
PlainMesh<2> shuffled_grid(int n, std::mt19937_64& rng) {
  PlainMesh<2> mesh;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = double(i) / n, y = double(j) / n;
      mesh.points.push_back({x, y, 0.1 * std::sin(3.0 * x) * std::cos(2.0 * y)});
    }
  auto id = [&](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      mesh.cells.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      mesh.cells.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  std::vector<int> perm(mesh.points.size());
  for (std::size_t i = 0; i < perm.size(); ++i) perm[i] = static_cast<int>(i);
  std::shuffle(perm.begin(), perm.end(), rng);
  PlainMesh<2> out;
  out.points.resize(mesh.points.size());
  for (std::size_t i = 0; i < perm.size(); ++i) out.points[perm[i]] = mesh.points[i];
  for (auto cell : mesh.cells) {
    for (int& c : cell) c = perm[c];
    out.cells.push_back(cell);
  }
  std::shuffle(out.cells.begin(), out.cells.end(), rng);
  return out;
}

using Corner = std::array<double, 3>;
using CellPoints = std::array<Corner, 3>;

/// The cells as point triples, each rotated to start at its smallest corner (a rotation keeps
/// the orientation; a reflection would not compare equal).
std::multiset<CellPoints> cells_as_points(const PlainMesh<2>& mesh) {
  std::multiset<CellPoints> out;
  for (const auto& cell : mesh.cells) {
    CellPoints p{mesh.points[cell[0]], mesh.points[cell[1]], mesh.points[cell[2]]};
    std::rotate(p.begin(), std::min_element(p.begin(), p.end()), p.end());
    out.insert(p);
  }
  return out;
}

double median_step(const PlainMesh<2>& mesh) {
  std::vector<double> steps;
  auto centroid = [&](std::size_t c, int k) {
    return (mesh.points[mesh.cells[c][0]][k] + mesh.points[mesh.cells[c][1]][k] + mesh.points[mesh.cells[c][2]][k]) / 3;
  };
  for (std::size_t c = 1; c < mesh.cells.size(); ++c)
    steps.push_back(std::hypot(centroid(c, 0) - centroid(c - 1, 0), centroid(c, 1) - centroid(c - 1, 1),
                               centroid(c, 2) - centroid(c - 1, 2)));
  std::nth_element(steps.begin(), steps.begin() + steps.size() / 2, steps.end());
  return steps[steps.size() / 2];
}

TEST(SpatialOrder, SameCellsInTheirOrientationWithNeighboursNextToEachOther) {
  std::mt19937_64 rng(7);
  const int n = 60;
  const PlainMesh<2> input = shuffled_grid(n, rng);
  const PlainMesh<2> ordered = spatially_ordered(input);
  ASSERT_EQ(ordered.cells.size(), input.cells.size());
  ASSERT_EQ(ordered.points.size(), input.points.size());
  EXPECT_EQ(cells_as_points(ordered), cells_as_points(input));
  // points numbered by first use: cell 0 uses 0, 1, 2, and no number is skipped
  EXPECT_EQ(ordered.cells[0], (std::array<int, 3>{0, 1, 2}));
  int next = 0;
  for (const auto& cell : ordered.cells)
    for (int c : cell) {
      ASSERT_LE(c, next);
      if (c == next) ++next;
    }
  EXPECT_EQ(next, static_cast<int>(ordered.points.size()));
  // shuffled, consecutive cells lie about a third of the square apart; ordered, about a cell
  const double h = 1.0 / n;
  EXPECT_GT(median_step(input), 10 * h);
  EXPECT_LT(median_step(ordered), 1.5 * h);
}

TEST(SpatialOrder, CurvesKeepTheirSegments) {
  PlainMesh<1> circle;
  const int n = 500;
  for (int i = 0; i < n; ++i) {
    const double angle = 2 * std::numbers::pi * i / n;
    circle.points.push_back({std::cos(angle), std::sin(angle)});
  }
  for (int i = 0; i < n; ++i) circle.cells.push_back({(7 * i) % n, (7 * i + 1) % n});  // scattered order
  const PlainMesh<1> ordered = spatially_ordered(circle);
  ASSERT_EQ(ordered.cells.size(), circle.cells.size());
  std::multiset<std::array<std::array<double, 2>, 2>> a, b;
  for (const auto& c : circle.cells) a.insert({circle.points[c[0]], circle.points[c[1]]});
  for (const auto& c : ordered.cells) b.insert({ordered.points[c[0]], ordered.points[c[1]]});
  EXPECT_EQ(a, b);
}

}  // namespace
}  // namespace plmap::peers
