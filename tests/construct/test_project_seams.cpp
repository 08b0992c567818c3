// A surface with a seam (vertices at one position that its elements do not share) projected onto
// an identical copy of itself is the identity: each S2 vertex on the seam takes its preimage on
// the side of the seam whose elements see its star (vertex_star_probe.hpp). Before, the walks
// kept whichever of the two equally near preimages they met first, and on the wrong side the
// edges of the vertex's star had no way across the seam: CGAL's quads_to_stitch.off (two strips
// of quads side by side) projected onto itself lost the whole map, and oblong-shuffled.off (a
// lid cut free on three sides, whose long triangles no seed reached) 18 % of it.
#include "projection_fixtures.hpp"

#include <plmap/construct/project.hpp>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>

using namespace plmap;
using namespace plmap::test;

namespace {

/// Two strips of a grid, [0, 1] x [0, 1] and [0, 1] x [1, 2], each with its own vertices on the
/// line y = 1 between them (and, with `gap`, the upper one moved up by it), moved by a rigid
/// motion so that nothing lies along the axes.
std::shared_ptr<const Surface<2>> two_strips(int cells, double gap = 0.0) {
  const auto lower = grid(cells, cells, 0.0, 1.0, 0.0, 1.0, 0.0);
  const auto upper = grid(cells, cells, 0.0, 1.0, 1.0 + gap, 2.0 + gap, 0.0);
  const Eigen::AngleAxisd turn(0.7, Eigen::Vector3d(1.0, 2.0, 3.0).normalized());
  std::vector<WorldPoint<2>> v;
  std::vector<ElementCorners<2>> e = lower->elements();
  for (const auto& p : lower->vertices()) v.push_back(turn * p + WorldPoint<2>(3.0, -1.0, 2.0));
  for (const auto& p : upper->vertices()) v.push_back(turn * p + WorldPoint<2>(3.0, -1.0, 2.0));
  for (auto t : upper->elements()) {
    for (Index& c : t) c += lower->vertex_count();
    e.push_back(t);
  }
  return std::make_shared<const Surface<2>>(std::move(v), std::move(e));
}

void expect_identity(const ProjectionResult<2>& r, const Surface<2>& s) {
  EXPECT_NEAR(r.measures.covered_domain, s.measure(), 1e-12 * s.measure());
  EXPECT_TRUE(r.report.edges_not_inserted.empty()) << describe_failures(r.report);
  EXPECT_EQ(verify_violations(r.map), "");
  // every element is one region, mapped onto its own copy
  ASSERT_EQ(r.map.region_count(), s.element_count());
  for (Index t = 0; t < s.element_count(); ++t) {
    ASSERT_EQ(r.map.regions_end(t) - r.map.regions_begin(t), 1) << "element " << t;
    EXPECT_EQ(r.map.stored().region_target[r.map.regions_begin(t)], t);
  }
}

/// S1 projected onto a copy of itself (another object) on 1 and 2 threads is the identity.
void expect_identity_onto_a_copy(const std::shared_ptr<const Surface<2>>& s1) {
  const auto s2 = std::make_shared<const Surface<2>>(s1->vertices(), s1->elements());
  for (const unsigned threads : {1u, 2u}) {
    ProjectionOptions o;
    o.threads = threads;
    o.renumbering = SpatialRenumbering::never;
    expect_identity(project<2>(s1, s2, o), *s1);
  }
}

}  // namespace

TEST(ProjectSeams, ASurfaceWithASeamProjectsOntoItsCopyAsTheIdentity) {
  for (const int cells : {1, 4, 9}) {
    SCOPED_TRACE(cells);
    expect_identity_onto_a_copy(two_strips(cells));
  }
}

TEST(ProjectSeams, ALongElementOnTheFarSideOfASeamIsFound) {
  // A fine grid on z = 0 and, standing on its edge x = 1, a lid of two long triangles that
  // shares no vertex with it (its bottom corners are copies of the grid's corners): the eight
  // centroids nearest to a bottom corner of the lid all lie on the grid, and no walk crosses
  // from the grid to the lid. The lid's corners must still take their preimages on the lid
  // (the walks are repeated from every element through the preimage first found), as on CGAL's
  // oblong-shuffled.off.
  const auto fine = grid(10, 10, 0.0, 1.0, 0.0, 1.0, 0.0);
  std::vector<WorldPoint<2>> v = fine->vertices();
  std::vector<ElementCorners<2>> e = fine->elements();
  const Index n = fine->vertex_count();
  v.insert(v.end(), {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}});
  e.push_back({n, n + 1, n + 2});
  e.push_back({n, n + 2, n + 3});
  expect_identity_onto_a_copy(std::make_shared<const Surface<2>>(std::move(v), std::move(e)));
}

TEST(ProjectSeams, ASeamThatIsNoneStillProjects) {
  // The same strips a little apart: no vertex has a twin, and the strips project as before.
  expect_identity_onto_a_copy(two_strips(4, 0.01));
}
