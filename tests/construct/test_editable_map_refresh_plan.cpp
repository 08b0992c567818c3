// EditableMap::refresh_plan: a full plan kept across other removals is refreshed only if it is
// still the plan that planning again (same flattening and triangulation) would make; the
// simplifier applies refreshed plans instead of planning again. Random removals on a bumpy grid:
// whenever refresh_plan says yes, the kept plan must equal a fresh one field by field; both
// answers must occur, and the "no" must include removals that are not neighbours (they can
// still rewrite an S2 edge polyline that runs through the kept plan's star).

#include <plmap/core/editable_map.hpp>
#include <plmap/strategies/simplification/constrained_delaunay_hole.hpp>
#include <plmap/strategies/simplification/polar_map_flattening.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace plmap {
namespace {

std::shared_ptr<const Surface<2>> bumpy_grid(int n) {
  std::vector<WorldPoint<2>> v;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      v.emplace_back(i + 0.23 * std::sin(1.7 * j + 0.4 * i), j + 0.19 * std::cos(1.3 * i - 0.6 * j),
                     0.3 * std::sin(0.9 * i) * std::cos(0.7 * j));
  std::vector<ElementCorners<2>> t;
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const Index a = j * n + i, b = a + 1, c = a + n, d = c + 1;
      if ((i + j) % 2 == 0) {
        t.push_back({a, b, d});
        t.push_back({a, d, c});
      } else {
        t.push_back({a, b, c});
        t.push_back({b, d, c});
      }
    }
  return std::make_shared<const Surface<2>>(v, t);
}

struct Request {
  std::vector<StarSheet> sheets;
  std::vector<std::vector<Eigen::Vector2d>> flat;
  std::vector<HoleTriangles> triangles;
};

/// The inputs the simplifier would give plan_vertex_removal for v, if v's star can be flattened
/// and triangulated.
std::optional<Request> request_for(const EditableMap& m, Index v) {
  std::vector<Index> ring = m.closed_ring(v);
  if (ring.size() < 3) return std::nullopt;
  std::vector<Eigen::Vector3d> positions;
  for (Index w : ring) positions.push_back(m.position(w));
  auto flat = PolarMapFlattening{}.flatten(m.position(v), positions);
  if (!flat) return std::nullopt;
  const DiagonalAllowed allowed = [&](int i, int j) { return !m.has_edge(ring[i], ring[j]); };
  auto triangles = ConstrainedDelaunayHole{}.triangulate(*flat, allowed);
  if (!triangles) return std::nullopt;
  Request r;
  r.sheets.push_back({std::move(ring), true});
  r.flat.push_back(std::move(*flat));
  r.triangles.push_back(std::move(*triangles));
  return r;
}

VertexRemovalPlan plan(const EditableMap& m, Index v, const Request& r) {
  return m.plan_vertex_removal(v, r.sheets, r.flat, r.triangles, PlanExtent::full);
}

bool same(const VertexRemovalPlan& a, const VertexRemovalPlan& b) {
  if (a.vertex != b.vertex || a.refusal != b.refusal || a.ring != b.ring || a.old_triangles != b.old_triangles ||
      a.new_triangles != b.new_triangles || a.node_domain_positions != b.node_domain_positions ||
      a.node_target_positions != b.node_target_positions || a.max_node_distance != b.max_node_distance ||
      a.triangle_count_at_planning != b.triangle_count_at_planning || a.relocations.size() != b.relocations.size() ||
      a.polyline_edits.size() != b.polyline_edits.size())
    return false;
  for (std::size_t i = 0; i < a.relocations.size(); ++i)
    if (a.relocations[i].target_vertex != b.relocations[i].target_vertex ||
        a.relocations[i].new_triangle != b.relocations[i].new_triangle ||
        a.relocations[i].barycentric != b.relocations[i].barycentric)
      return false;
  for (std::size_t i = 0; i < a.polyline_edits.size(); ++i) {
    const auto &x = a.polyline_edits[i], &y = b.polyline_edits[i];
    if (x.target_edge != y.target_edge || x.points != y.points) return false;
  }
  return true;
}

TEST(EditableMapRefreshPlan, ARefreshedPlanEqualsAFreshOne) {
  int refreshed = 0, refused_with_same_star = 0;
  for (unsigned seed : {1u, 2u, 3u, 4u, 5u, 6u}) {
    const int n = 14;
    EditableMap m(bumpy_grid(n));
    std::mt19937 random(seed);
    std::uniform_int_distribution<Index> pick(0, n * n - 1);
    for (int step = 0; step < 400 && m.live_vertex_count() > n; ++step) {
      const Index v = pick(random), u = pick(random);
      if (u == v || !m.is_live_vertex(v) || !m.is_live_vertex(u)) continue;
      const auto rv = request_for(m, v);
      if (!rv) continue;
      const VertexRemovalPlan kept = plan(m, v, *rv);
      if (!kept.accepted()) continue;
      // Another removal in between (sometimes a neighbour of v, mostly not).
      if (const auto ru = request_for(m, u)) {
        const VertexRemovalPlan other = plan(m, u, *ru);
        if (other.accepted()) m.apply(other);
      }
      VertexRemovalPlan candidate = kept;
      const bool star_unchanged = m.closed_ring(v) == rv->sheets[0].ring;
      if (m.refresh_plan(candidate)) {
        ++refreshed;
        ASSERT_TRUE(star_unchanged) << "seed " << seed << ", step " << step;
        EXPECT_TRUE(same(candidate, plan(m, v, *rv))) << "seed " << seed << ", step " << step;
      } else {
        EXPECT_TRUE(same(candidate, kept));  // untouched
        if (star_unchanged && !same(kept, plan(m, v, *rv))) ++refused_with_same_star;
      }
      if (step % 3 == 0) {  // shrink the map so that polylines grow long and cross many stars
        const VertexRemovalPlan fresh = plan(m, v, *rv);
        if (fresh.accepted()) m.apply(fresh);
      }
    }
  }
  EXPECT_GT(refreshed, 50);
  EXPECT_GT(refused_with_same_star, 0);  // the polyline edit counts matter
}

}  // namespace
}  // namespace plmap
