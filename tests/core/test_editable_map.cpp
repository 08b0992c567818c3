// EditableMap: the identity start, one planned removal, and the refusals that keep Ξ valid.

#include <plmap/core/editable_map.hpp>
#include <plmap/core/errors.hpp>
#include <plmap/verify/check.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace plmap {
namespace {

/// A flat hexagon fan around vertex 0 (at the origin), closed by a cap below so that every ring
/// edge has two triangles; vertex 0 is an interior manifold vertex.
std::shared_ptr<const Surface<2>> fan_with_cap() {
  std::vector<WorldPoint<2>> v = {{0, 0, 0}};
  for (int i = 0; i < 6; ++i) {
    const double a = std::numbers::pi / 3 * i + 0.1 * (i % 2);
    v.emplace_back(std::cos(a), std::sin(a), 0.0);
  }
  v.emplace_back(0.0, 0.0, -1.0);  // apex of the cap
  std::vector<ElementCorners<2>> t;
  for (int i = 0; i < 6; ++i) {
    t.push_back({0, 1 + i, 1 + (i + 1) % 6});
    t.push_back({7, 1 + (i + 1) % 6, 1 + i});
  }
  return std::make_shared<const Surface<2>>(v, t);
}

std::vector<Eigen::Vector2d> flat_ring(const EditableMap& m, const std::vector<Index>& ring) {
  std::vector<Eigen::Vector2d> out;
  for (Index w : ring) out.emplace_back(m.position(w)(0), m.position(w)(1));
  return out;
}

TEST(EditableMap, StartsAsTheIdentity) {
  const EditableMap m(fan_with_cap());
  EXPECT_EQ(m.live_triangle_count(), 12);
  const PlMap<2> map = m.to_map();
  EXPECT_EQ(map.region_count(), 12);
  VerifyOptions v;
  v.expect_parametrization = true;
  EXPECT_TRUE(verify(map, v).ok());
}

TEST(EditableMap, RemovingTheCentreMovesItsPreimageIntoANewTriangle) {
  EditableMap m(fan_with_cap());
  const std::vector<Index> ring = m.closed_ring(0);
  ASSERT_EQ(ring.size(), 6u);
  const auto flat = flat_ring(m, ring);
  // The zig-zag triangulation with the middle triangle 0-2-4, which contains the centre.
  const std::vector<std::array<int, 3>> triangles = {{0, 1, 2}, {2, 3, 4}, {4, 5, 0}, {0, 2, 4}};
  const VertexRemovalPlan plan = m.plan_vertex_removal(0, flat, triangles);
  ASSERT_TRUE(plan.accepted()) << to_string(plan.refusal);
  EXPECT_EQ(plan.relocations.size(), 1u);
  EXPECT_NEAR(plan.max_node_distance, 0.0, 1e-12);  // flat star: nodes stay in the plane
  m.apply(plan);
  EXPECT_FALSE(m.is_live_vertex(0));
  EXPECT_EQ(m.live_triangle_count(), 10);
  const PlMap<2> map = m.to_map();
  VerifyOptions v;
  v.expect_parametrization = true;
  const auto report = verify(map, v);
  EXPECT_TRUE(report.ok()) << summary(report);
  EXPECT_EQ(map.domain().element_count(), 10);
}

TEST(EditableMap, RefusesStepsThatWouldBreakTheMap) {
  const EditableMap m(fan_with_cap());
  const std::vector<Index> ring = m.closed_ring(0);
  const auto flat = flat_ring(m, ring);
  // wrong number of triangles
  const std::vector<std::array<int, 3>> too_few = {{0, 1, 2}};
  EXPECT_EQ(m.plan_vertex_removal(0, flat, too_few).refusal, RemovalRefusal::no_triangulation);
  // clockwise triangle
  const std::vector<std::array<int, 3>> clockwise = {{0, 2, 1}, {2, 3, 4}, {4, 5, 0}, {0, 2, 4}};
  EXPECT_EQ(m.plan_vertex_removal(0, flat, clockwise).refusal, RemovalRefusal::no_triangulation);
  // a flattening that is not star-shaped (the ring in reverse order)
  std::vector<Eigen::Vector2d> reversed(flat.rbegin(), flat.rend());
  const std::vector<std::array<int, 3>> fan = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}};
  EXPECT_EQ(m.plan_vertex_removal(0, reversed, fan).refusal, RemovalRefusal::flattening_not_simple);
  // the apex of the cap: its ring edges already exist on the other side (diagonals are S1 edges)
  const std::vector<Index> apex_ring = m.closed_ring(7);
  ASSERT_EQ(apex_ring.size(), 6u);
  std::vector<Eigen::Vector2d> apex_flat;
  for (int i = 0; i < 6; ++i) apex_flat.emplace_back(std::cos(-i * std::numbers::pi / 3), std::sin(-i * std::numbers::pi / 3));
  // apex ring runs clockwise seen from above; as given, the flattening is counter-clockwise
  const VertexRemovalPlan p = m.plan_vertex_removal(7, apex_flat, fan);
  EXPECT_FALSE(p.accepted());
  // applying a refused plan is an error, and changes nothing
  EXPECT_THROW(EditableMap(fan_with_cap()).apply(p), Error);
}

TEST(EditableMap, TheFanVertexOnADiagonalIsNamedAsTheBlockingDiagonal) {
  // A regular hexagon: its centre lies on the long diagonal 0-3 of a fan from ring vertex 0.
  std::vector<WorldPoint<2>> v = {{0, 0, 0}};
  for (int i = 0; i < 6; ++i) v.emplace_back(std::cos(std::numbers::pi / 3 * i), std::sin(std::numbers::pi / 3 * i), 0.0);
  v.emplace_back(0.0, 0.0, -1.0);
  std::vector<ElementCorners<2>> t;
  for (int i = 0; i < 6; ++i) {
    t.push_back({0, 1 + i, 1 + (i + 1) % 6});
    t.push_back({7, 1 + (i + 1) % 6, 1 + i});
  }
  const EditableMap m(std::make_shared<const Surface<2>>(v, t));
  const std::vector<Index> ring = m.closed_ring(0);
  const std::vector<std::array<int, 3>> fan = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}};
  const VertexRemovalPlan p = m.plan_vertex_removal(0, flat_ring(m, ring), fan);
  EXPECT_EQ(p.refusal, RemovalRefusal::node_on_new_edge);
  EXPECT_EQ(p.blocking_diagonal, (std::array<int, 2>{0, 3}));
}

}  // namespace
}  // namespace plmap
