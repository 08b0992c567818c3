// plan_vertex_removal's `storage`: a plan made in the buffers of an earlier, unrelated plan (an
// accepted one with polyline edits, or a refused one) must equal the plan made from scratch,
// field by field; the simplifier reuses every discarded plan this way.

#include <plmap/core/editable_map.hpp>

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>

namespace plmap {
namespace {

/// A hexagon fan around vertex 0 (at the origin), closed by a cap below; vertex 0 is an interior
/// manifold vertex, and the fan is tilted so that removing it moves nodes off the plane.
std::shared_ptr<const Surface<2>> tilted_fan() {
  std::vector<WorldPoint<2>> v = {{0, 0, 0.3}};
  for (int i = 0; i < 6; ++i) {
    const double a = std::numbers::pi / 3 * i + 0.1 * (i % 2);
    v.emplace_back(std::cos(a), std::sin(a), 0.05 * i);
  }
  v.emplace_back(0.0, 0.0, -1.0);
  std::vector<ElementCorners<2>> t;
  for (int i = 0; i < 6; ++i) {
    t.push_back({0, 1 + i, 1 + (i + 1) % 6});
    t.push_back({7, 1 + (i + 1) % 6, 1 + i});
  }
  return std::make_shared<const Surface<2>>(v, t);
}

struct Request {
  std::vector<StarSheet> sheets;
  std::vector<std::vector<Eigen::Vector2d>> flat;
  std::vector<std::vector<std::array<int, 3>>> triangles;
};

Request request_for(const EditableMap& m, Index v, std::vector<std::array<int, 3>> triangles) {
  Request r;
  r.sheets.push_back({m.closed_ring(v), true});
  std::vector<Eigen::Vector2d> flat;
  for (Index w : r.sheets[0].ring) flat.emplace_back(m.position(w)(0), m.position(w)(1));
  r.flat.push_back(std::move(flat));
  r.triangles.push_back(std::move(triangles));
  return r;
}

VertexRemovalPlan plan(const EditableMap& m, const Request& r, PlanExtent extent, VertexRemovalPlan storage = {}) {
  return m.plan_vertex_removal(0, r.sheets, r.flat, r.triangles, extent, std::move(storage));
}

void expect_same(const VertexRemovalPlan& a, const VertexRemovalPlan& b) {
  EXPECT_EQ(a.vertex, b.vertex);
  EXPECT_EQ(a.refusal, b.refusal);
  EXPECT_EQ(a.ring, b.ring);
  EXPECT_EQ(a.old_triangles, b.old_triangles);
  EXPECT_EQ(a.new_triangles, b.new_triangles);
  EXPECT_EQ(a.old_triangle_sheet, b.old_triangle_sheet);
  EXPECT_EQ(a.new_triangle_sheet, b.new_triangle_sheet);
  EXPECT_EQ(a.line_edge, b.line_edge);
  EXPECT_EQ(a.node_domain_positions, b.node_domain_positions);
  EXPECT_EQ(a.node_target_positions, b.node_target_positions);
  EXPECT_EQ(a.max_node_distance, b.max_node_distance);
  ASSERT_EQ(a.relocations.size(), b.relocations.size());
  for (std::size_t i = 0; i < a.relocations.size(); ++i) {
    EXPECT_EQ(a.relocations[i].target_vertex, b.relocations[i].target_vertex);
    EXPECT_EQ(a.relocations[i].new_triangle, b.relocations[i].new_triangle);
    EXPECT_EQ(a.relocations[i].barycentric, b.relocations[i].barycentric);
    EXPECT_EQ(a.relocations[i].edge_parameter, b.relocations[i].edge_parameter);
  }
  ASSERT_EQ(a.polyline_edits.size(), b.polyline_edits.size());
  for (std::size_t i = 0; i < a.polyline_edits.size(); ++i) {
    const auto& x = a.polyline_edits[i];
    const auto& y = b.polyline_edits[i];
    EXPECT_EQ(x.target_edge, y.target_edge);
    EXPECT_TRUE(x.points == y.points);
  }
  EXPECT_EQ(a.triangle_count_at_planning, b.triangle_count_at_planning);
  EXPECT_EQ(a.extent, b.extent);
  EXPECT_EQ(a.blocking_diagonal, b.blocking_diagonal);
  EXPECT_EQ(a.blocking_sheet, b.blocking_sheet);
}

TEST(EditableMapPlanStorage, APlanInReusedBuffersEqualsAFreshOne) {
  const EditableMap m(tilted_fan());
  const Request zigzag = request_for(m, 0, {{0, 1, 2}, {2, 3, 4}, {4, 5, 0}, {0, 2, 4}});
  const Request fan = request_for(m, 0, {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}});
  const Request too_few = request_for(m, 0, {{0, 1, 2}});

  const VertexRemovalPlan full = plan(m, zigzag, PlanExtent::full);
  ASSERT_TRUE(full.accepted()) << to_string(full.refusal);
  ASSERT_FALSE(full.polyline_edits.empty());
  const VertexRemovalPlan other = plan(m, fan, PlanExtent::full);
  ASSERT_TRUE(other.accepted()) << to_string(other.refusal);
  const VertexRemovalPlan refused = plan(m, too_few, PlanExtent::full);
  ASSERT_FALSE(refused.accepted());

  // every pair (earlier plan as storage, request): same as planned from scratch
  const std::array<const VertexRemovalPlan*, 3> earlier{&full, &other, &refused};
  const std::array<const Request*, 3> requests{&zigzag, &fan, &too_few};
  for (std::size_t e = 0; e < earlier.size(); ++e)
    for (std::size_t r = 0; r < requests.size(); ++r)
      for (PlanExtent extent : {PlanExtent::full, PlanExtent::ranking_bound}) {
        SCOPED_TRACE(testing::Message() << "storage " << e << ", request " << r);
        expect_same(plan(m, *requests[r], extent, *earlier[e]), plan(m, *requests[r], extent));
      }
}

// A full plan asked for right after the ranking bound of the same request, with the bound as
// storage, continues from the bound (the simplifier's estimate ranking does this for every
// vertex it removes): it must be the plan made from scratch. The bound of another request, or a
// bound followed by another planning call, must not be continued from.
TEST(EditableMapPlanStorage, AFullPlanContinuedFromItsRankingBoundEqualsAFreshOne) {
  const EditableMap m(tilted_fan());
  const Request zigzag = request_for(m, 0, {{0, 1, 2}, {2, 3, 4}, {4, 5, 0}, {0, 2, 4}});
  const Request fan = request_for(m, 0, {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}});
  for (const auto& [request, other] : {std::pair{&zigzag, &fan}, std::pair{&fan, &zigzag}}) {
    const VertexRemovalPlan fresh = plan(m, *request, PlanExtent::full);
    ASSERT_TRUE(fresh.accepted()) << to_string(fresh.refusal);
    ASSERT_FALSE(fresh.polyline_edits.empty());

    VertexRemovalPlan bound = plan(m, *request, PlanExtent::ranking_bound);
    ASSERT_TRUE(bound.accepted());
    EXPECT_NE(bound.bound_generation, 0u);
    const VertexRemovalPlan continued = plan(m, *request, PlanExtent::full, std::move(bound));
    expect_same(continued, fresh);
    EXPECT_EQ(continued.bound_generation, 0u);

    VertexRemovalPlan other_bound = plan(m, *other, PlanExtent::ranking_bound);
    expect_same(plan(m, *request, PlanExtent::full, std::move(other_bound)), fresh);

    VertexRemovalPlan stale = plan(m, *request, PlanExtent::ranking_bound);
    const VertexRemovalPlan between = plan(m, *other, PlanExtent::ranking_bound);
    ASSERT_TRUE(between.accepted());
    expect_same(plan(m, *request, PlanExtent::full, std::move(stale)), fresh);
  }
}

}  // namespace
}  // namespace plmap
