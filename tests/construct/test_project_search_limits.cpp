// ProjectionOptions::search_limits (the limits and slacks of the searches) and the ray search
// that must keep the nearest admissible hit although its seeds lie on a farther sheet.

#include "projection_fixtures.hpp"

#include <plmap/construct/project.hpp>
#include <plmap/core/errors.hpp>

#include <gtest/gtest.h>

#include <algorithm>

namespace plmap {
namespace {

using namespace plmap::test;

TEST(ProjectSearchLimits, OutOfRangeLimitsAreRejectedWithTheirNames) {
  auto s1 = grid(4, 4, 0, 1, 0, 1, 0.0);
  auto s2 = grid(5, 5, 0, 1, 0, 1, 0.1, true);
  auto rejected = [&](auto change) {
    ProjectionOptions o;
    change(o.search_limits);
    try {
      (void)project<2>(s1, s2, o);
    } catch (const Error& e) {
      return std::string(e.what()).find("search limits") != std::string::npos;
    }
    return false;
  };
  EXPECT_TRUE(rejected([](ProjectionSearchLimits& l) { l.seed_walk_steps = 0; }));
  EXPECT_TRUE(rejected([](ProjectionSearchLimits& l) { l.edge_walk_steps = -1; }));
  EXPECT_TRUE(rejected([](ProjectionSearchLimits& l) { l.inside_tolerance = -1e-9; }));
  EXPECT_TRUE(rejected([](ProjectionSearchLimits& l) { l.edge_parameter_slack = 0.5; }));
  EXPECT_TRUE(rejected([](ProjectionSearchLimits& l) { l.second_search_hits = 33; }));
  EXPECT_TRUE(rejected([](ProjectionSearchLimits& l) { l.farther_hit_retry = -1.0; }));
  EXPECT_FALSE(rejected([](ProjectionSearchLimits&) {}));
}

TEST(ProjectSearchLimits, AnEdgeWalkCutShortIsReportedAsWalkLimit) {
  // S2 much coarser than S1: each S2 edge's preimage crosses several S1 edges
  auto s1 = grid(24, 24, 0, 1, 0, 1, 0.0);
  auto s2 = grid(3, 3, -0.05, 1.05, -0.05, 1.05, 0.1, true);
  auto walk_limits = [&](int steps) {
    ProjectionOptions o;
    o.search_limits.edge_walk_steps = steps;
    const auto r = project<2>(s1, s2, o);
    return count_failures(r.report, EdgeFailureReason::walk_limit);
  };
  EXPECT_EQ(walk_limits(0), 0);
  EXPECT_GT(walk_limits(2), 0);
}

TEST(ProjectSearchLimits, ARayKeepsTheNearerSheetAfterItsNeighbourHitAFartherOne) {
  // S2: a far sheet at z = 0.3 over all of S1, and a near sheet at z = 0.05 over x > 0.5 only.
  // The rays of one row of S1 vertices are cast in order of x: those with x < 0.5 hit the far
  // sheet, and the next ray, seeded next to that hit, found the far sheet too and kept it,
  // although the near sheet lies on it first (CGAL's bones pair had four such vertices).
  std::vector<WorldPoint<2>> v;
  std::vector<ElementCorners<2>> e;
  for (const auto& sheet : {grid(9, 9, -0.13, 1.12, -0.11, 1.14, 0.3, true), grid(7, 9, 0.51, 1.13, -0.12, 1.09, 0.05, true)}) {
    const Index base = static_cast<Index>(v.size());
    for (const auto& p : sheet->vertices()) v.push_back(p);
    for (auto t : sheet->elements()) e.push_back({t[0] + base, t[1] + base, t[2] + base});
  }
  auto s2 = std::make_shared<const Surface<2>>(std::move(v), std::move(e));
  auto s1 = grid(10, 10, 0, 1, 0, 1, 0.0);
  const auto r = project<2>(s1, s2, {});
  Index checked = 0;
  for (Index n = 0; n < r.map.node_count(); ++n) {
    if (r.map.data().node_type[n] != NodeType::ghost) continue;
    const WorldPoint<2> p = r.map.node_domain_world(n);
    if (p.x() < 0.55) continue;
    ++checked;
    EXPECT_NEAR(r.map.node_target_world(n).z(), 0.05, 1e-9) << "the ray from " << p.transpose()
                                                            << " took the farther sheet";
  }
  EXPECT_GT(checked, 20);
}

}  // namespace
}  // namespace plmap
