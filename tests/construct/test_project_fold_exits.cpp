// Walks that stop at a fold, or where the S2 edge passes behind S1, and come out of it again
// (fold_reentry.hpp): the stretch of an S2 edge between two such places is reached by no walk
// that starts at a vertex preimage or at S1's boundary, only by a restart after the first.
#include "projection_fixtures.hpp"

#include <plmap/construct/direction_field.hpp>
#include <plmap/construct/project.hpp>
#include <plmap/verify/ray_check.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace plmap;
using namespace plmap::test;

namespace {

/// S1: a flat strip [0, 1] x [0, 0.3] of 20 x 6 cells at z = 0 with two V grooves one cell deep
/// and two cells wide, along y at x = 0.3 and x = 0.7. Its averaged normals turn towards each
/// groove's axis on the groove's walls, so the rays of the wall columns meet about 0.12 above
/// S1 and fold before S2 (z = 0.3); the flat columns' rays are vertical.
std::shared_ptr<const Surface<2>> strip_with_two_grooves() {
  return transformed<2>(*grid(20, 6, 0.0, 1.0, 0.0, 0.3, 0.0), [](const WorldPoint<2>& p) {
    const double depth = std::max({0.0, 0.05 - std::abs(p.x() - 0.3), 0.05 - std::abs(p.x() - 0.7)});
    return WorldPoint<2>(p.x(), p.y(), -depth);
  });
}

/// S2: a plane at z = 0.3 facing S1 of 1 x 2 cells over [x0, 1.1] x [-0.1, 0.4]: every S2 edge
/// over S1 crosses both grooves; it starts at S1's boundary (x0 < 0) or, for the S2 vertices at
/// y = 0.15 with x0 > 0, at their preimages on the flat part before the first groove.
std::shared_ptr<const Surface<2>> plane_over_the_strip(double x0) { return grid(1, 2, x0, 1.1, -0.1, 0.4, 0.3, true); }

struct MiddleBand {
  std::size_t samples = 0, defects = 0;
};

/// The ray-check samples on the flat middle of the strip whose rays reach no other sheet
/// (x in [0.45, 0.55]: the groove walls' rays fan out 0.1 beyond each groove's rim), and how
/// many of them are outside D without a reason the rays give.
MiddleBand middle_band(const ProjectionResult<2>& r, const Surface<2>& s1) {
  RayCheckOptions<2> o;
  o.directions = averaged_vertex_normals(s1);
  o.samples = 20000;
  o.max_listed = o.samples;
  const auto rays = check_against_rays(r.map, o);
  EXPECT_EQ(rays.extra, 0u);
  MiddleBand b;
  b.samples = static_cast<std::size_t>(0.1 * 0.3 / r.measures.domain * static_cast<double>(rays.samples));  // expected
  for (const auto& x : rays.missed_examples)
    if (x.point.x() >= 0.45 && x.point.x() <= 0.55 &&
        (x.reason == MissedReason::not_covered || x.reason == MissedReason::next_to_fold ||
         x.reason == MissedReason::farther_sheet))
      ++b.defects;
  return b;
}

}  // namespace

class ProjectFoldExits : public ::testing::TestWithParam<double> {};

TEST_P(ProjectFoldExits, TheStretchBetweenTwoFoldsIsCovered) {
  // The walk along each S2 edge stops at the first groove, and the walk back from where the
  // edge leaves S1 stops at the second. Between them only the restart where the edge's preimage
  // comes out of the first fold walks it (a restart of the walk from the first vertex or from a
  // boundary entry, or of the walk back after the second fold); without one, the regions of the
  // S2 triangles there are lost (a third of the ~1,800 samples between the grooves from the
  // entries, a tenth from the vertices, see below). With it, the flat part between the grooves
  // is covered whole.
  const auto s1 = strip_with_two_grooves();
  const auto r = project<2>(s1, plane_over_the_strip(GetParam()));
  EXPECT_EQ(verify_violations(r.map), "");
  const MiddleBand b = middle_band(r, *s1);
  EXPECT_EQ(b.defects, 0u) << describe_failures(r.report);
}

TEST_P(ProjectFoldExits, WithoutRestartsTheStretchBetweenTheFoldsIsLost) {
  // The same pair with search_limits.fold_exits = 0: the option switches the restarts off, and
  // much of the flat part between the grooves is then outside D without a reason.
  const auto s1 = strip_with_two_grooves();
  ProjectionOptions o;
  o.search_limits.fold_exits = 0;
  const auto r = project<2>(s1, plane_over_the_strip(GetParam()), o);
  EXPECT_EQ(verify_violations(r.map), "");
  const MiddleBand b = middle_band(r, *s1);
  EXPECT_GT(b.defects, b.samples / 20);
}

// S2 from x = -0.1: every walk starts at a boundary entry; from x = 0.1: the S2 edges through
// the S2 vertices at y = 0.15 start at their preimages.
INSTANTIATE_TEST_SUITE_P(FromEntriesAndFromVertices, ProjectFoldExits, ::testing::Values(-0.1, 0.1));

namespace {

/// S1: the strip of strip_with_two_grooves() with two ridges instead, 0.08 high and 0.32 wide
/// at x = 0.2 and x = 0.8: they reach through S2 (z = 0.05), so the preimage of an S2 edge
/// across the strip passes behind S1 (mu < 0) over each ridge and comes out again beyond it.
/// Their flanks rise at slope 1/2, so the rays at their feet meet only far beyond S2: no fold.
std::shared_ptr<const Surface<2>> strip_with_two_ridges() {
  return transformed<2>(*grid(20, 6, 0.0, 1.0, 0.0, 0.3, 0.0), [](const WorldPoint<2>& p) {
    const double height = std::max({0.0, 0.08 - 0.5 * std::abs(p.x() - 0.2), 0.08 - 0.5 * std::abs(p.x() - 0.8)});
    return WorldPoint<2>(p.x(), p.y(), height);
  });
}

std::shared_ptr<const Surface<2>> low_plane_over_the_strip() { return grid(1, 2, -0.1, 1.1, -0.1, 0.4, 0.05, true); }

}  // namespace

TEST(ProjectWalkRestarts, TheStretchBetweenTwoRidgesThroughS2IsCovered) {
  // As TheStretchBetweenTwoFoldsIsCovered, but the walks stop where the S2 edge passes behind a
  // ridge (distance_limit: the only continuations lie behind S1) instead of at folds, and are
  // restarted there as at folds: the walk from the entry restarts where the edge comes out
  // beyond the first ridge, and the walk back from where the edge leaves S1 keeps its stretch
  // up to the second. Restarted only after folds, the flat part between the ridges lost about
  // a sixth of its samples (316 of ~1,800).
  const auto s1 = strip_with_two_ridges();
  const auto r = project<2>(s1, low_plane_over_the_strip());
  EXPECT_EQ(verify_violations(r.map), "");
  EXPECT_GT(count_failures(r.report, EdgeFailureReason::distance_limit), 0) << describe_failures(r.report);
  EXPECT_EQ(middle_band(r, *s1).defects, 0u) << describe_failures(r.report);
}
