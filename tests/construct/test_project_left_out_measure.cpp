// ProjectionReport::left_out: the measure of S1 outside D, by why (core/src/finalize_assembly.cpp
// for what finalize leaves out, construct/src/project.cpp for the folded and occluded faces).
// The properties of test_project_properties.cpp check on every generated pair that these and the
// covered measure add up to S1's measure; here, a closed form and the thread count.
#include "projection_fixtures.hpp"
#include "rim_fixtures.hpp"

#include <plmap/construct/project.hpp>

#include <gtest/gtest.h>

#include <string>

using namespace plmap;
using namespace plmap::test;

TEST(ProjectLeftOutMeasure, WhatS2DoesNotReachIsOutsideAndMeasuredExactly) {
  // S1 the unit square at z = 0 (normals up), S2 a jittered grid over x in [-0.2, 0.55] facing it
  // at z = 0.1: the vertical rays find S2 over x <= 0.55 only, so D is [0, 0.55] x [0, 1] and
  // the rest of S1, 0.45, lies beyond D's reach
  const auto s1 = flat_square();
  const auto s2 = grid(5, 9, -0.2, 0.55, -0.2, 1.2, 0.1, true, 0.2);
  const ProjectionResult<2> r = project<2>(s1, s2);
  EXPECT_NEAR(r.measures.covered_domain, 0.55, 1e-12);
  EXPECT_NEAR(r.report.left_out.outside, 0.45, 1e-12);
  for (const auto& [name, measure] : r.report.left_out.fields()) {
    if (std::string(name) == "outside") continue;
    EXPECT_EQ(r.report.left_out.*measure, 0.0) << name;
  }
}

TEST(ProjectLeftOutMeasure, TheSameForEveryThreadCount) {
  // the tilted plane with a distance limit: a rim inside S1, faces left out for several reasons
  const auto s1 = flat_square();
  const auto s2 = tilted_plane(0.3);
  ProjectionOptions rules = with_limit(0.1);
  std::optional<ProjectionReport<2>::MeasureLeftOut> first;
  for (unsigned threads : {1u, 2u, 3u}) {
    rules.threads = threads;
    const ProjectionResult<2> r = project<2>(s1, s2, rules);
    const auto& out = r.report.left_out;
    EXPECT_GT(out.outside, 0.0);
    // (written out member by member: a member missing from fields() would show as a difference)
    const double explicit_sum =
        out.outside + out.reversed + out.unmapped + out.enclosed + out.folded + out.unbacked + out.occluded;
    EXPECT_NEAR(r.measures.covered_domain + explicit_sum, r.measures.domain, 1e-12);
    EXPECT_NEAR(out.sum(), explicit_sum, 1e-15);
    if (!first) {
      first = out;
      continue;
    }
    for (const auto& [name, measure] : out.fields()) EXPECT_EQ(out.*measure, (*first).*measure) << name << ", " << threads;
  }
}
