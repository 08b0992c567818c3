// Isolated vertices (issue 12, defect 2): a vertex that no element uses is kept in the vertex
// list (vertex numbers stay those of the file) but is not part of the surface. The generators
// give it no preimage and no node, and their maps equal those of the surface without it. Before,
// `vertex_elements(v).front()` on its empty star crashed the identity, refinement and overlay
// generators.
#include <plmap/core/errors.hpp>
#include <plmap/core/map_builder.hpp>
#include <plmap/verify/check.hpp>
#include <plmap/verify/generators/random_maps.hpp>

#include <gtest/gtest.h>

#include <memory>

namespace plmap {
namespace {

/// The square [0, 1]^2 at z = 0 as n x n cells, two counter-clockwise triangles each.
Surface<2> square(int n, std::vector<WorldPoint<2>> extra_vertices = {}) {
  std::vector<WorldPoint<2>> v;
  std::vector<ElementCorners<2>> e;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) v.emplace_back(double(i) / n, double(j) / n, 0.0);
  auto id = [n](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      e.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      e.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  v.insert(v.end(), extra_vertices.begin(), extra_vertices.end());
  return Surface<2>(std::move(v), std::move(e));
}

template <int d>
void expect_same_regions(const PlMap<d>& a, const PlMap<d>& b) {
  EXPECT_EQ(a.data().region_corners, b.data().region_corners);
  EXPECT_EQ(a.data().region_target, b.data().region_target);
  EXPECT_EQ(a.data().node_type, b.data().node_type);
  EXPECT_EQ(a.data().node_target, b.data().node_target);
}

template <int d>
void expect_valid(const PlMap<d>& map, bool parametrization = true) {
  const auto report = verify(map, VerifyOptions{.expect_parametrization = parametrization});
  EXPECT_TRUE(report.ok()) << report.checks.size();
  for (const auto& check : report.checks)
    for (const auto& v : check.violations) ADD_FAILURE() << check.name << "/" << v.rule << ": " << v.message;
}

TEST(IsolatedVertices, IdentityMapSkipsThem) {
  // one isolated vertex off the surface, one exactly on an edge of it
  auto with = std::make_shared<const Surface<2>>(square(2, {{0.3, 0.3, 1.0}, {0.25, 0.0, 0.0}}));
  auto without = std::make_shared<const Surface<2>>(square(2));
  const auto c = generators::identity_map<2>(with);
  expect_valid(*c.map);
  expect_same_regions(*c.map, *generators::identity_map<2>(without).map);
  ASSERT_EQ(c.target_vertex_preimage.size(), 11u);
  EXPECT_EQ(c.target_vertex_preimage[9].element, invalid_index);
}

TEST(IsolatedVertices, RefinementsKeepThemIsolated) {
  auto with = std::make_shared<const Surface<2>>(square(2, {{0.3, 0.3, 1.0}}));
  generators::Rng rng(7);
  const auto refinement = generators::random_refinement<2>(*with, {.max_points_per_edge = 1, .max_points_per_element = 1}, rng);
  EXPECT_TRUE(refinement.refined.vertex_elements(9).empty());
  const auto c = generators::refinement_map<2>(with, refinement);
  expect_valid(*c.map);
  const auto uniform = generators::refinement_map<2>(with, generators::uniform_refinement<2>(*with, 1, 1000));
  expect_valid(*uniform.map);
}

TEST(IsolatedVertices, PlaneOverlaySkipsThemInEitherSurface) {
  // S1's isolated vertex lies exactly on an S2 edge (before: a read out of bounds), and off the
  // plane (it is no part of S1, so S1 is still planar); S2's lies inside S1.
  auto s1 = std::make_shared<const Surface<2>>(square(2, {{1.0 / 3.0, 0.5, 0.0}, {0.2, 0.2, 3.0}}));
  auto s1_plain = std::make_shared<const Surface<2>>(square(2));
  auto s2 = std::make_shared<const Surface<2>>(square(3, {{0.4, 0.45, 0.0}}));
  auto s2_plain = std::make_shared<const Surface<2>>(square(3));
  const auto c = generators::plane_overlay_map(s1, s2);
  expect_valid(*c.map);
  expect_same_regions(*c.map, *generators::plane_overlay_map(s1_plain, s2_plain).map);
  EXPECT_EQ(c.target_vertex_preimage[16].element, invalid_index);
}

TEST(IsolatedVertices, PolylineOverlaySkipsThem) {
  auto base = std::make_shared<const Surface<1>>(std::vector<WorldPoint<1>>{{0.0, 0.0}, {1.0, 0.0}, {2.0, 1.0}, {5.0, 5.0}},
                                                 std::vector<ElementCorners<1>>{{0, 1}, {1, 2}});
  generators::Rng rng(3);
  const auto sub = generators::random_subdivisions(base, 3, rng);
  expect_valid(*generators::polyline_overlay_map(sub).map);
  expect_valid(*generators::identity_map<1>(base).map);
}

TEST(IsolatedVertices, TheBuilderRefusesThemWithAMessageThatSaysWhy) {
  auto s = std::make_shared<const Surface<2>>(square(1, {{0.3, 0.3, 1.0}}));
  MapBuilder<2> builder(s, s);
  try {
    builder.add_vertex_preimage_at_vertex(4, 0);
    ADD_FAILURE() << "accepted a preimage of an isolated S2 vertex";
  } catch (const BuilderError& e) {
    EXPECT_NE(std::string(e.what()).find("S2 vertex 4 is isolated"), std::string::npos) << e.what();
  }
  try {
    builder.add_vertex_preimage_at_vertex(0, 4);
    ADD_FAILURE() << "accepted a node on an isolated S1 vertex";
  } catch (const BuilderError& e) {
    EXPECT_NE(std::string(e.what()).find("S1 vertex 4 is isolated"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace plmap
