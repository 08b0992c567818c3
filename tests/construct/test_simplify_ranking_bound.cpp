// The ranking bound of a vertex removal (PlanExtent::ranking_bound), by which simplify() ranks
// its candidates, against the full plan on the same flattening and triangulation: it refuses
// nothing the full plan accepts, plans the same new triangles and relocations, and its largest
// node distance is never above the full plan's (so the oracles' cost is a lower bound, which
// the lazy re-ranking of simplify() relies on). It cannot be applied.

#include <plmap/core/editable_map.hpp>
#include <plmap/core/errors.hpp>
#include <plmap/strategies/simplification/simplification_registry.hpp>
#include <plmap/verify/generators/closed_surfaces.hpp>

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <numeric>
#include <optional>

namespace plmap {
namespace {

/// The full plan and the ranking bound of removing v, on one flattening and triangulation.
struct PlanPair {
  VertexRemovalPlan full, bound;
};

std::optional<PlanPair> plan_both(const EditableMap& map, Index v, const AnyStarFlattening& flatten,
                                  const AnyHoleTriangulation& triangulate) {
  const std::vector<Index> ring = map.closed_ring(v);
  if (ring.size() < 3) return std::nullopt;
  std::vector<Eigen::Vector3d> positions;
  for (Index w : ring) positions.push_back(map.position(w));
  const auto flat = flatten(map.position(v), positions);
  if (!flat) return std::nullopt;
  const auto triangles = triangulate(*flat, [&](int i, int j) { return !map.has_edge(ring[i], ring[j]); });
  if (!triangles) return std::nullopt;
  return PlanPair{map.plan_vertex_removal(v, *flat, *triangles, PlanExtent::full),
                  map.plan_vertex_removal(v, *flat, *triangles, PlanExtent::ranking_bound)};
}

/// Empty if the bound is consistent with the full plan; otherwise what is wrong.
std::string bound_violation(const PlanPair& p) {
  if (p.full.accepted() && !p.bound.accepted()) return std::string("the bound refuses: ") + to_string(p.bound.refusal);
  if (!p.bound.accepted()) return p.full.refusal == p.bound.refusal ? "" : "a different refusal";
  if (p.bound.new_triangles != p.full.new_triangles) return "other new triangles";
  if (p.bound.relocations.size() != p.full.relocations.size()) return "other relocations";
  if (!p.bound.polyline_edits.empty()) return "the bound cut polylines";
  if (p.full.accepted() && p.bound.max_node_distance > p.full.max_node_distance)
    return "bound distance " + std::to_string(p.bound.max_node_distance) + " above the full plan's " +
           std::to_string(p.full.max_node_distance);
  return "";
}

TEST(SimplifyRankingBound, IsALowerBoundOfTheFullPlanThroughoutASimplification) {
  const AnyStarFlattening flatten = make_star_flattening("polar-map");
  const AnyHoleTriangulation triangulate = make_hole_triangulation("constrained-delaunay");
  // rc::check reports a counterexample but does not fail the test by itself.
  EXPECT_TRUE(rc::check([&](std::uint32_t seed) {
    const int subdivisions = *rc::gen::inRange(1, 3);
    const double jitter = *rc::gen::inRange(0, 25) / 100.0;
    generators::Rng rng(seed);
    auto s2 = std::make_shared<const Surface<2>>(generators::icosphere({subdivisions, jitter}, rng));
    EditableMap map(s2);
    std::vector<Index> order(s2->vertex_count());
    std::iota(order.begin(), order.end(), Index{0});
    const int rounds = *rc::gen::inRange(1, static_cast<int>(order.size()) - 4);
    std::size_t cursor = 0;
    for (int round = 0; round < rounds; ++round) {
      // Check a few live vertices, then remove the first one the full plan accepts.
      std::shuffle(order.begin(), order.end(), rng);
      std::optional<VertexRemovalPlan> step;
      int checked = 0;
      for (cursor = 0; cursor < order.size() && checked < 4; ++cursor) {
        const Index v = order[cursor];
        if (!map.is_live_vertex(v)) continue;
        const auto pair = plan_both(map, v, flatten, triangulate);
        if (!pair) continue;
        ++checked;
        RC_ASSERT(bound_violation(*pair) == "");
        if (pair->bound.accepted()) {
          RC_ASSERT_THROWS_AS(map.apply(pair->bound), Error);
        }
        if (!step && pair->full.accepted()) step = pair->full;
      }
      if (!step) break;
      map.apply(*step);
    }
  }));
}

TEST(SimplifyRankingBound, MissesTheCrossingsOfALateCoarseStar) {
  // After most of a bumpy sphere is removed, the S2 edges crossing a star make the full plan's
  // distance exceed the bound somewhere: the bound is a strict lower bound, not a copy.
  const AnyStarFlattening flatten = make_star_flattening("polar-map");
  const AnyHoleTriangulation triangulate = make_hole_triangulation("constrained-delaunay");
  generators::Rng rng(7);
  auto s2 = std::make_shared<const Surface<2>>(generators::icosphere({2, 0.2}, rng));
  EditableMap map(s2);
  bool strictly_below = false;
  for (int round = 0; round < 120; ++round) {
    std::optional<VertexRemovalPlan> step;
    for (Index v = 0; v < s2->vertex_count(); ++v) {
      if (!map.is_live_vertex(v)) continue;
      const auto pair = plan_both(map, v, flatten, triangulate);
      if (!pair) continue;
      EXPECT_EQ(bound_violation(*pair), "") << "vertex " << v << " round " << round;
      if (pair->full.accepted() && pair->bound.max_node_distance < pair->full.max_node_distance) strictly_below = true;
      if (!step && pair->full.accepted()) step = pair->full;
    }
    if (!step) break;
    map.apply(*step);
  }
  EXPECT_TRUE(strictly_below);
}

}  // namespace
}  // namespace plmap
