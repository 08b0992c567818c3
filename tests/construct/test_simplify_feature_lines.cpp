// simplify() removes vertices along feature lines (boundary, sharp and non-manifold edges): the
// sides of the line are re-triangulated separately, the line's nodes move onto the new edge,
// corners stay. Deterministic cases here; random meshes in test_simplify_feature_properties.cpp.

#include "simplify_test_support.hpp"

#include <plmap/construct/simplify.hpp>
#include <plmap/verify/check.hpp>
#include <plmap/verify/generators/random_surfaces.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace plmap {
namespace {

using simplify_test::skipped_reasons;

void expect_valid_parametrization_with_features(const SimplifyResult& result, double feature_angle) {
  EXPECT_EQ(simplify_test::parametrization_problems(result, feature_angle), "");
}

/// The unit square cut into n x n jittered cells with random diagonals (verify's generator):
/// its boundary is a feature line with 4 corners.
std::shared_ptr<const Surface<2>> jittered_square(int n, std::uint64_t seed) {
  generators::Rng rng(seed);
  return std::make_shared<const Surface<2>>(generators::grid_triangulation({.cells = n, .jitter = 0.2, .with_hole = false}, rng));
}

/// A book: `pages` rectangular grids (n along the spine, m away from it) around a common spine
/// on the x axis. Every spine edge has `pages` triangles (non-manifold).
std::shared_ptr<const Surface<2>> book(int pages, int n, int m) {
  std::vector<WorldPoint<2>> v;
  std::vector<ElementCorners<2>> t;
  for (int i = 0; i <= n; ++i) v.emplace_back(double(i) / n, 0.0, 0.0);
  for (int p = 0; p < pages; ++p) {
    const double angle = 2.0 * std::numbers::pi * (p + 0.1) / pages;
    const Index first = static_cast<Index>(v.size());
    for (int r = 1; r <= m; ++r)
      for (int i = 0; i <= n; ++i) v.emplace_back(double(i) / n, std::cos(angle) * r / m, std::sin(angle) * r / m);
    auto id = [&](int i, int r) { return r == 0 ? static_cast<Index>(i) : first + (r - 1) * (n + 1) + i; };
    for (int r = 0; r < m; ++r)
      for (int i = 0; i < n; ++i) {
        t.push_back({id(i, r), id(i + 1, r), id(i + 1, r + 1)});
        t.push_back({id(i, r), id(i + 1, r + 1), id(i, r + 1)});
      }
  }
  return std::make_shared<const Surface<2>>(v, t);
}

TEST(SimplifyFeatureLines, BoundaryVerticesAreRemovedAlongTheBoundary) {
  // 8 x 8 cells: 32 boundary vertices. Kept, they allow no fewer than 30 triangles; removed
  // along the boundary, the square comes down towards its 4 corners (where the boundary turns
  // by 90 degrees, more than the feature angle). Vertex removal alone cannot always reach the 2
  // triangles of the corners (a hole whose every diagonal is an S1 edge already), so the test
  // asks for far fewer than 30.
  const auto square = jittered_square(8, 7);
  SimplifyOptions options;
  options.target_elements = 2;
  const SimplifyResult result = simplify(square, options);
  EXPECT_LE(result.report.elements_after, 12) << skipped_reasons(result.report);
  EXPECT_GT(result.report.removed_along_lines, 0);
  EXPECT_EQ(result.report.feature_corners, 4);
  expect_valid_parametrization_with_features(result, options.feature_angle_degrees);
}

TEST(SimplifyFeatureLines, NonManifoldSpineIsSimplifiedAlongItself) {
  // Three pages on a spine of 8 edges: the spine's inner vertices have three half-stars.
  const auto three_pages = book(3, 8, 3);
  SimplifyOptions options;
  // With every feature vertex kept, each page's 22 boundary vertices allowed no fewer than 20
  // triangles, 60 in all.
  options.target_elements = 6;
  const SimplifyResult result = simplify(three_pages, options);
  EXPECT_GT(result.report.removed_along_lines, 0) << skipped_reasons(result.report);
  EXPECT_LE(result.report.elements_after, 45) << skipped_reasons(result.report);
  // The spine's ends are corners (three boundary edges and a spine edge each) and stay; the
  // spine's inner vertices went, so the spine is now one S1 edge carrying all 8 S2 edges.
  const Surface<2>& s1 = result.map.domain();
  Index spine_vertices = 0;
  for (Index w = 0; w < s1.vertex_count(); ++w)
    spine_vertices += s1.vertex(w).y() == 0.0 && s1.vertex(w).z() == 0.0;
  EXPECT_EQ(spine_vertices, 2);
  expect_valid_parametrization_with_features(result, options.feature_angle_degrees);
}

/// A flat annulus: `rings` + 1 circles of `n` vertices each, radii 1 to 3, the circles joined by
/// triangle strips. Both boundary circles turn by 360 / n degrees per vertex: with n >= 7 that is
/// below the default feature angle, so each is a closed feature line without corners.
std::shared_ptr<const Surface<2>> annulus(int n, int rings) {
  std::vector<WorldPoint<2>> v;
  std::vector<ElementCorners<2>> t;
  for (int r = 0; r <= rings; ++r)
    for (int i = 0; i < n; ++i) {
      const double angle = 2.0 * std::numbers::pi * (i + 0.5 * r) / n, radius = 1.0 + 2.0 * r / rings;
      v.emplace_back(radius * std::cos(angle), radius * std::sin(angle), 0.0);
    }
  auto id = [n](int i, int r) { return static_cast<Index>(r * n + (i % n)); };
  for (int r = 0; r < rings; ++r)
    for (int i = 0; i < n; ++i) {
      t.push_back({id(i, r), id(i + 1, r), id(i, r + 1)});
      t.push_back({id(i + 1, r), id(i + 1, r + 1), id(i, r + 1)});
    }
  return std::make_shared<const Surface<2>>(v, t);
}

TEST(SimplifyFeatureLines, ClosedLinesKeepThreeVerticesAndSaySo) {
  // The inner rim comes down to three vertices; then each of them has its line neighbours
  // joined by the rim's third edge, and removing it would collapse the rim onto one edge. The
  // report names that reason for those three (the planner alone would say existing_edge or
  // single_triangle_side). The outer rim stops at four: any of its diagonals passes the inner
  // rim (fold_over).
  const auto ring = annulus(16, 3);
  SimplifyOptions options;
  options.target_elements = 2;
  const SimplifyResult result = simplify(ring, options);
  EXPECT_EQ(result.report.feature_corners, 0);
  EXPECT_FALSE(result.report.target_reached);
  const Surface<2>& s1 = result.map.domain();
  Index inner_rim = 0;
  for (Index w = 0; w < s1.vertex_count(); ++w) inner_rim += std::abs(s1.vertex(w).norm() - 1.0) < 1e-12;
  EXPECT_EQ(inner_rim, 3);
  const auto& why = result.report.skipped_by_reason;
  EXPECT_EQ(why.count("feature_loop_of_three") ? why.at("feature_loop_of_three") : 0, 3) << skipped_reasons(result.report);
  EXPECT_EQ(why.count("existing_edge") + why.count("single_triangle_side"), 0u) << skipped_reasons(result.report);
  expect_valid_parametrization_with_features(result, options.feature_angle_degrees);
}

TEST(SimplifyFeatureLines, ASideOfOneTriangleBlocksTheRemoval) {
  // Vertex 1 on the line 0-1-2: above it two triangles, below it the one triangle (0, 2, 1),
  // which would collapse onto the new edge 0-2.
  std::vector<WorldPoint<2>> v{{0, 0, 0}, {1, 0.5, 0}, {2, 0, 0}, {1, 2, 0}};
  std::vector<ElementCorners<2>> t{{0, 1, 3}, {1, 2, 3}, {0, 2, 1}};
  auto s = std::make_shared<const Surface<2>>(v, t);
  EditableMap m(s);
  const std::vector<StarSheet> sheets = m.line_star_sheets(1, 0, 2);
  ASSERT_EQ(sheets.size(), 2u);
  EXPECT_FALSE(sheets[0].closed);
  EXPECT_EQ(sheets[0].ring.size() + sheets[1].ring.size(), 5u);
  const std::vector<std::vector<Eigen::Vector2d>> flat(2);
  const std::vector<std::vector<std::array<int, 3>>> triangles(2);
  EXPECT_EQ(m.plan_vertex_removal(1, sheets, flat, triangles).refusal, RemovalRefusal::single_triangle_side);
}

TEST(SimplifyFeatureLines, LineNodesLandOnTheNewEdgeAtTheSameParameterFromEverySide) {
  // A sharp crease (a roof, 90 degrees) of 2 x 6 cells per side: removing crease vertices puts
  // the crease's S2 vertices on the coarse crease edge, as touching nodes.
  std::vector<WorldPoint<2>> v;
  std::vector<ElementCorners<2>> t;
  const int n = 6, m = 2;
  for (int r = -m; r <= m; ++r)
    for (int i = 0; i <= n; ++i) v.emplace_back(double(i) / n, double(r) / m, 1.0 - std::abs(double(r)) / m);
  auto id = [](int i, int r) { return static_cast<Index>((r + m) * (n + 1) + i); };
  for (int r = -m; r < m; ++r)
    for (int i = 0; i < n; ++i) {
      t.push_back({id(i, r), id(i + 1, r), id(i + 1, r + 1)});
      t.push_back({id(i, r), id(i + 1, r + 1), id(i, r + 1)});
    }
  auto roof = std::make_shared<const Surface<2>>(v, t);
  SimplifyOptions options;
  options.target_elements = 8;
  const SimplifyResult result = simplify(roof, options);
  EXPECT_LE(result.report.elements_after, 16) << skipped_reasons(result.report);
  Index touching = 0;
  for (Index k = 0; k < result.map.node_count(); ++k) touching += result.map.data().node_type[k] == NodeType::touching;
  EXPECT_GT(touching, 0);
  expect_valid_parametrization_with_features(result, options.feature_angle_degrees);
  // The crease (y = 0, z = 1) keeps its two ends only.
  Index crease = 0;
  for (Index w = 0; w < result.map.domain().vertex_count(); ++w) crease += result.map.domain().vertex(w).y() == 0.0;
  EXPECT_EQ(crease, 2);
}

}  // namespace
}  // namespace plmap
