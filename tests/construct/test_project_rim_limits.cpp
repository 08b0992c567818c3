// With a distance limit m, D ends on the curve where the rays' distance to S2 reaches m (and, with
// negative distances allowed, -m), as it ends on mu = 0 where S2 passes behind S1
// (ProjectionOptions::end_on_rim; construct/src/projection_rim.cpp). The planes here make D a
// strip of the unit square whose bounds are known in closed form; a curved S2 is judged by the
// ray check under the same rules.
#include "rim_fixtures.hpp"

#include <plmap/construct/direction_field.hpp>
#include <plmap/construct/project.hpp>
#include <plmap/core/evaluation.hpp>
#include <plmap/verify/deepest_region_locator.hpp>
#include <plmap/verify/ray_check.hpp>


#include <gtest/gtest.h>

#include <cmath>

using namespace plmap;
using namespace plmap::test;

namespace {

/// S2: a finer jittered grid facing S1 at height 0.1 + 0.06 sin(5x + 1) cos(4y): the curves
/// where the height reaches a limit are closed loops and arcs that cross S1 and S2 elements
/// at every angle.
std::shared_ptr<const Surface<2>> wavy_sheet() {
  return transformed<2>(*grid(23, 23, -0.1, 1.1, -0.1, 1.1, 0.0, true, 0.2), [](const WorldPoint<2>& p) {
    return WorldPoint<2>(p.x(), p.y(), 0.1 + 0.06 * std::sin(5.0 * p.x() + 1.0) * std::cos(4.0 * p.y()));
  });
}

/// S2: a fine jittered grid facing S1 at height 0.1, with a bump up to 0.15 around (0.35, 0.15).
std::shared_ptr<const Surface<2>> sheet_with_a_bump() {
  return transformed<2>(*grid(30, 30, -0.1, 1.1, -0.1, 1.1, 0.0, true, 0.2), [](const WorldPoint<2>& p) {
    const double r2 = (p.x() - 0.35) * (p.x() - 0.35) + (p.y() - 0.15) * (p.y() - 0.15);
    return WorldPoint<2>(p.x(), p.y(), 0.1 + 0.05 * std::exp(-r2 / 0.005));
  });
}

/// D covers exactly `area` of S1 (a closed form), within rounding, and the ray cast under the
/// same rules finds nothing missed and nothing extra.
void expect_exactly(const ProjectionResult<2>& r, const Surface<2>& s1, const ProjectionOptions& rules, double area) {
  EXPECT_EQ(verify_violations(r.map), "");
  EXPECT_NEAR(r.measures.covered_domain, area, 1e-9) << describe_failures(r.report);
  const auto rays = rays_under(r.map, s1, rules);
  EXPECT_EQ(rays.extra, 0u);
  EXPECT_EQ(rays.missed_defects(), 0u);
}

}  // namespace

class ProjectRimAtTheLimit : public ::testing::TestWithParam<double> {};

TEST_P(ProjectRimAtTheLimit, DEndsWhereS2GoesBeyondTheLimit) {
  // S2 lies in front of all of S1; its height reaches the limit at x = x1, so D is x <= x1.
  const double x1 = GetParam();
  const auto s1 = flat_square();
  const auto rules = with_limit(0.25 * (x1 + 0.2));
  const auto r = project<2>(s1, tilted_plane(-0.2), rules);
  EXPECT_GT(r.report.rim_edges, 0);
  expect_exactly(r, *s1, rules, x1);
}

TEST_P(ProjectRimAtTheLimit, WithoutTheRimDEndsAtTheLastS1Edges) {
  const double x1 = GetParam();
  const auto s1 = flat_square();
  auto rules = with_limit(0.25 * (x1 + 0.2));
  rules.end_on_rim = false;
  const auto r = project<2>(s1, tilted_plane(-0.2), rules);
  EXPECT_EQ(verify_violations(r.map), "");
  EXPECT_EQ(r.report.rim_edges, 0);
  EXPECT_LT(r.measures.covered_domain, x1 - 0.01);
  EXPECT_GT(rays_under(r.map, *s1, rules).missed_defects(), 0u);
}

// the limit's curve through S1 elements at three places (0.5 would run along S1 edges)
INSTANTIATE_TEST_SUITE_P(LimitPositions, ProjectRimAtTheLimit, ::testing::Values(0.43, 0.57, 0.77));

TEST(ProjectRimAtBothBounds, DIsTheStripBetweenMuZeroAndTheLimit) {
  // height 0.25 (x - 0.33), limit 0.1: behind S1 left of x = 0.33, beyond the limit right of
  // x = 0.73; D is the strip between, bounded by the two rims.
  const auto s1 = flat_square();
  const auto rules = with_limit(0.1);
  expect_exactly(project<2>(s1, tilted_plane(0.33), rules), *s1, rules, 0.4);
}

TEST(ProjectRimAtBothBounds, WithNegativeDistancesDIsTheStripWithinTheLimitOnBothSides) {
  // height 0.25 (x - 0.51), negative distances allowed down to -0.05: D is |x - 0.51| <= 0.2.
  const auto s1 = flat_square();
  const auto rules = with_limit(0.05, true);
  expect_exactly(project<2>(s1, tilted_plane(0.51), rules), *s1, rules, 0.4);
}

class ProjectRimOnAWavySheet : public ::testing::TestWithParam<double> {};

TEST_P(ProjectRimOnAWavySheet, TheRaysFindNothingMissedAndNothingExtra) {
  // Curved rims at the limit (the height ranges over 0.04..0.16): every point whose ray meets
  // S2 within the limit is in D, and no other.
  const auto s1 = flat_square();
  const auto rules = with_limit(GetParam());
  const auto r = project<2>(s1, wavy_sheet(), rules);
  EXPECT_EQ(verify_violations(r.map), "");
  EXPECT_GT(r.report.rim_edges, 0);
  const auto rays = rays_under(r.map, *s1, rules);
  EXPECT_EQ(rays.extra, 0u);
  EXPECT_EQ(rays.missed_defects(), 0u) << describe_failures(r.report);
}

INSTANTIATE_TEST_SUITE_P(Limits, ProjectRimOnAWavySheet, ::testing::Values(0.07, 0.1, 0.13));

TEST(ProjectRimIsland, AnIslandBeyondTheLimitInsideOneS1ElementCostsOnlyTheIsland) {
  // S1: the unit square in 2 x 2 cells, so the bump's top, beyond the limit 0.12 (a disk of
  // radius about 0.068), lies strictly inside S1 element 0. D is S1 without that disk: the
  // element keeps its regions around the hole the rim encloses (before, the whole element left D).
  const auto s1 = grid(2, 2, 0.0, 1.0, 0.0, 1.0, 0.0);
  const auto rules = with_limit(0.12);
  const auto r = project<2>(s1, sheet_with_a_bump(), rules);
  EXPECT_EQ(verify_violations(r.map), "");
  EXPECT_GT(r.report.rim_edges, 0);
  // the disk's area is pi r^2 with r^2 = 0.005 ln(2.5), up to the PL interpolation of S2
  const double disk = 3.14159265358979 * 0.005 * std::log(2.5);
  EXPECT_NEAR(r.measures.covered_domain, 1.0 - disk, 0.1 * disk);
  const auto rays = rays_under(r.map, *s1, rules);
  EXPECT_EQ(rays.extra, 0u);
  EXPECT_EQ(rays.missed_defects(), 0u) << describe_failures(r.report);
  // the disk's centre is outside D, a point of the same element beside it maps straight up
  DeepestRegion<2> locator;
  auto at = [&](double x, double y) {
    const LocalPoint<2> local(2.0 * x - 2.0 * y, 2.0 * y);  // on element 0: corners (0,0), (.5,0), (.5,.5)
    return evaluate(r.map, SurfacePoint<2>{0, local}, locator);
  };
  EXPECT_FALSE(at(0.35, 0.15).in_domain);
  const Evaluation<2> beside = at(0.45, 0.03);
  ASSERT_TRUE(beside.in_domain);
  EXPECT_NEAR(beside.world.x(), 0.45, 1e-9);
  EXPECT_NEAR(beside.world.y(), 0.03, 1e-9);
}

TEST(ProjectRimWalks, EdgesThatDipIntoTheBandBetweenVerticesBeyondTheLimitAreWalkedFromTheRim) {
  // S1: a fine unit sphere (rays radial); S2: a coarse sphere of radius 1.3 around it, seen from
  // inside. Its vertices lie 0.3 out, beyond the limit 0.25, but its edges, chords, come within
  // 0.2 of S1 half-way: every S2 edge enters the band and leaves it again with neither vertex
  // in it, so no walk from a vertex preimage or S1's boundary (S1 has none) reaches it; only the
  // rim finds it. D is the part of S1 whose ray meets S2 within 0.25: a net around the chords.
  const auto s1 = sphere(4, 1.0);
  const auto rules = with_limit(0.25);
  const auto r = project<2>(s1, sphere(1, 1.3, true, 0.3), rules);
  EXPECT_EQ(verify_violations(r.map), "");
  EXPECT_EQ(r.report.vertex_preimages, 0);
  EXPECT_GT(r.report.edges_partly_inserted, 0);
  // every edge walked from the rim is counted once: no longer outside D
  EXPECT_LE(r.report.edges_inserted + r.report.edges_partly_inserted + r.report.edges_outside, r.report.target_edges);
  const auto rays = rays_under(r.map, *s1, rules);
  EXPECT_GT(rays.in_domain_with_hit, rays.samples / 4);
  EXPECT_EQ(rays.extra, 0u);
  EXPECT_LE(rays.missed_defects(), rays.samples / 1000) << describe_failures(r.report);
}
