// An S2 edge that passes behind S1 and comes out in front of it again (a ridge of S1 reaching
// through S2, as where two bones of CGAL's bones.off nearly touch): the walk along its preimage
// ends on the rim where the edge enters S1, and a new piece starts at a rim node where it comes
// out (construct/src/projection_edge_walks.cpp, find_rim_reentry). Before, the new piece started
// only at the first S1 edge crossing beyond, and the faces between that crossing and the rim
// mapped into two S2 triangles and left D.
#include "projection_fixtures.hpp"
#include "rays_along_normals.hpp"

#include <plmap/construct/direction_field.hpp>
#include <plmap/construct/project.hpp>
#include <plmap/verify/ray_check.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <tuple>

using namespace plmap;
using namespace plmap::test;

namespace {

/// S1: the unit square, `cells` x `cells`, lifted to a ridge along y at x = 0.5 (height 0.12,
/// Gaussian of the given width); averaged normals, which fan out over the ridge (no focal point
/// in front).
std::shared_ptr<const Surface<2>> ridge(int cells, double width) {
  return transformed<2>(*grid(cells, cells, 0.0, 1.0, 0.0, 1.0, 0.0, false, 0.2), [width](const WorldPoint<2>& p) {
    const double u = (p.x() - 0.5) / width;
    return WorldPoint<2>(p.x(), p.y(), 0.12 * std::exp(-u * u));
  });
}

/// S2: a coarse jittered grid at z = 0.05 facing S1, whose edges (about 0.37 long) span the
/// ridge: they pass behind S1 over its top (|x - 0.5| < 0.935 width, one or two S1 elements)
/// and in front of it on both sides.
std::shared_ptr<const Surface<2>> plane_through_the_ridge(int cells) {
  return grid(cells, cells, -0.05, 1.05, -0.05, 1.05, 0.05, true, 0.2);
}

/// The map is valid, has rim edges, claims nothing the rays miss, and misses nothing the rays
/// find that is not justified (no defect, in particular nothing `not_covered`).
template <class Result>
void expect_rim_map_complete(const Result& r, const Surface<2>& s1) {
  EXPECT_EQ(verify_violations(r.map), "");
  EXPECT_GT(r.report.rim_edges, 0);
  const auto rays = rays_along_normals(r.map, s1);
  EXPECT_EQ(rays.extra, 0u);
  EXPECT_EQ(rays.missed_by_reason[static_cast<std::size_t>(MissedReason::not_covered)], 0u)
      << describe_failures(r.report);
  EXPECT_EQ(rays.missed_defects(), 0u);
}

}  // namespace

class ProjectRimReentry : public ::testing::TestWithParam<std::tuple<int, double, int>> {};

TEST_P(ProjectRimReentry, EdgesThatComeOutFromBehindS1GoOnFromTheRim) {
  const auto [s1_cells, width, s2_cells] = GetParam();
  const auto s1 = ridge(s1_cells, width);
  // Without the re-entry, the walk from the first vertex went on only from the next S1 edge
  // crossing beyond the ridge, reached the second vertex, and so no walk back from there ran:
  // 924 (10 cells, width 0.1) and 1029 (14 cells, width 0.08) of the 20,000 samples were not
  // covered. Now none is.
  expect_rim_map_complete(project<2>(s1, plane_through_the_ridge(s2_cells)), *s1);
}

INSTANTIATE_TEST_SUITE_P(CoarseS2, ProjectRimReentry,
                         ::testing::Values(std::tuple{10, 0.1, 3}, std::tuple{14, 0.08, 3}));

namespace {

/// S1: [0, 2] x [0, 1], 20 x 10 cells, with a wide ridge at x = 0.7 (width 0.3: S2 passes behind
/// it over 0.56 in x, farther than the re-entry search reaches from either side) and a narrow
/// one at x = 1.45 (width 0.08).
std::shared_ptr<const Surface<2>> wide_and_narrow_ridge() {
  return transformed<2>(*grid(20, 10, 0.0, 2.0, 0.0, 1.0, 0.0, false, 0.2), [](const WorldPoint<2>& p) {
    const double u = (p.x() - 0.7) / 0.3, v = (p.x() - 1.45) / 0.08;
    return WorldPoint<2>(p.x(), p.y(), 0.12 * std::exp(-u * u) + 0.12 * std::exp(-v * v));
  });
}

}  // namespace

class ProjectRimReentryBackwards : public ::testing::TestWithParam<double> {};

// S2's edges run from x = x0 (their first vertex) across both ridges to 2 - x0. The walk from
// the first vertex (or from where the edge enters S1) stops on the wide ridge's rim and finds no
// way out; the walk back from the other end (from the second vertex's preimage, x0 > 0, or from
// where the edge leaves S1, x0 < 0) stops on the narrow ridge's rim. The stretch between the two
// ridges is reached only by the walk back going on where the edge comes out from behind the
// narrow ridge. Before, that walk went on only from the next S1 edge crossing, and the faces
// between it and the rim mapped into two S2 triangles and left D.
TEST_P(ProjectRimReentryBackwards, WalksBackGoOnFromTheRimToo) {
  const double x0 = GetParam();
  const auto s1 = wide_and_narrow_ridge();
  const auto s2 = grid(1, 3, x0, 2.0 - x0, -0.05, 1.05, 0.05, true);
  // Before: 1,041 (x0 = 0.05) and 1,756 (x0 = -0.05) of the 20,000 samples not covered.
  expect_rim_map_complete(project<2>(s1, s2), *s1);
}

INSTANTIATE_TEST_SUITE_P(BothEnds, ProjectRimReentryBackwards, ::testing::Values(0.05, -0.05));
