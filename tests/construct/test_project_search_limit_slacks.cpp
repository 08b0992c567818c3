// The search limits that were hard-wired in the projection's walks until the projection was split
// into its phases: retry_seeds, piece_parameter_slack and end_parameter_slack
// (ProjectionSearchLimits). Their defaults keep the maps of before; these tests check that they
// are range-checked and that they reach the walks.

#include "projection_fixtures.hpp"

#include <plmap/construct/project.hpp>
#include <plmap/core/errors.hpp>

#include <gtest/gtest.h>

#include <algorithm>

namespace plmap {
namespace {

using namespace plmap::test;

TEST(ProjectSearchLimitSlacks, OutOfRangeValuesAreRejectedWithTheirNames) {
  auto s1 = grid(4, 4, 0, 1, 0, 1, 0.0);
  auto s2 = grid(5, 5, 0, 1, 0, 1, 0.1, true);
  auto rejected_naming = [&](auto change, const std::string& name) {
    ProjectionOptions o;
    change(o.search_limits);
    try {
      (void)project<2>(s1, s2, o);
    } catch (const Error& e) {
      const std::string what = e.what();
      return what.find("search limits") != std::string::npos && what.find(name) != std::string::npos;
    }
    return false;
  };
  EXPECT_TRUE(rejected_naming([](ProjectionSearchLimits& l) { l.retry_seeds = 0; }, "retry_seeds"));
  EXPECT_TRUE(rejected_naming([](ProjectionSearchLimits& l) { l.retry_seeds = 33; }, "retry_seeds"));
  EXPECT_TRUE(rejected_naming([](ProjectionSearchLimits& l) { l.piece_parameter_slack = -1e-9; },
                              "piece_parameter_slack"));
  EXPECT_TRUE(rejected_naming([](ProjectionSearchLimits& l) { l.piece_parameter_slack = 0.5; },
                              "piece_parameter_slack"));
  EXPECT_TRUE(rejected_naming([](ProjectionSearchLimits& l) { l.end_parameter_slack = -1e-12; },
                              "end_parameter_slack"));
  EXPECT_TRUE(rejected_naming([](ProjectionSearchLimits& l) { l.end_parameter_slack = 0.5; },
                              "end_parameter_slack"));
  EXPECT_FALSE(rejected_naming([](ProjectionSearchLimits&) {}, ""));
}

TEST(ProjectSearchLimitSlacks, AWideEndSlackStopsWalksShortOfTheSecondVertex) {
  // S2 much coarser than S1: each S2 edge's preimage crosses several S1 edges, some of them
  // at edge parameters above 0.6. With end_parameter_slack 0.4 such a crossing counts as the
  // second vertex's image, whose preimage lies elsewhere: the walk ends there.
  auto s1 = grid(24, 24, 0, 1, 0, 1, 0.0);
  auto s2 = grid(3, 3, -0.05, 1.05, -0.05, 1.05, 0.1, true);
  auto endpoint_failures = [&](double slack) {
    ProjectionOptions o;
    o.search_limits.end_parameter_slack = slack;
    const auto r = project<2>(s1, s2, o);
    return count_failures(r.report, EdgeFailureReason::endpoint_without_preimage);
  };
  EXPECT_EQ(endpoint_failures(1e-12), 0);
  EXPECT_GT(endpoint_failures(0.4), 0);
}

TEST(ProjectSearchLimitSlacks, AWidePieceSlackSkipsBoundaryEntriesNearTheEdgeEnds) {
  // S2 wider than S1: its edges enter S1 across S1's boundary. An entry within
  // piece_parameter_slack of either end of its S2 edge is taken for that end vertex, so a slack
  // of nearly one half leaves (almost) no entries.
  auto s1 = grid(12, 12, 0, 1, 0, 1, 0.0);
  auto s2 = grid(5, 5, -0.3, 1.3, -0.3, 1.3, 0.1, true);
  auto entries = [&](double slack) {
    ProjectionOptions o;
    o.search_limits.piece_parameter_slack = slack;
    return project<2>(s1, s2, o).report.boundary_entries;
  };
  const Index by_default = entries(1e-9);
  EXPECT_GT(by_default, 0);
  EXPECT_LT(entries(0.49), by_default);
}

}  // namespace
}  // namespace plmap
