// Normal projection when S1 has several sheets over one part of S2: two bodies one above the
// other (d = 2), two arcs one inside the other (d = 1). The nearer sheet maps where both reach
// S2; the farther sheet maps where only it does; the map stays valid.

#include "projection_fixtures.hpp"

#include <plmap/construct/project.hpp>

#include <gtest/gtest.h>

using namespace plmap;
using namespace plmap::test;

namespace {

/// The union of two surfaces (vertices and elements of b renumbered after a's).
template <int d>
std::shared_ptr<const Surface<d>> both(const Surface<d>& a, const Surface<d>& b) {
  std::vector<WorldPoint<d>> v = a.vertices();
  v.insert(v.end(), b.vertices().begin(), b.vertices().end());
  std::vector<ElementCorners<d>> e = a.elements();
  for (auto c : b.elements()) {
    for (Index& i : c) i += a.vertex_count();
    e.push_back(c);
  }
  return std::make_shared<const Surface<d>>(std::move(v), std::move(e));
}

}  // namespace

TEST(ProjectSheets, TheFartherSheetMapsWhereTheNearerOneDoesNotReach) {
  // S1: the unit square at z = 0 and, above its middle, the strip [0.25, 0.75] x [0, 1] at
  // z = 0.5; S2: a plane at z = 1 over both. Under the strip the upper sheet is nearer; the
  // two outer strips of the lower sheet reach S2 too, and their S2 vertices' nearest S1
  // elements (by centroid) all lie on the upper sheet.
  const auto lower = grid(8, 8, 0.0, 1.0, 0.0, 1.0, 0.0, false, 0.1);
  const auto upper = grid(4, 8, 0.25, 0.75, 0.0, 1.0, 0.5, false, 0.1);
  const auto s1 = both<2>(*lower, *upper);
  const auto s2 = grid(11, 11, -0.2, 1.2, -0.2, 1.2, 1.0, true, 0.1);
  for (unsigned threads : {1u, 3u}) {
    const auto r = project<2>(s1, s2, {.threads = threads});
    EXPECT_EQ(verify_violations(r.map), "");
    // Upper strip 0.5, outer strips 0.5, less what the edges crossing the strip's shadow
    // line cannot close (about one S2 cell along each of the two lines).
    EXPECT_GT(r.measures.covered_domain, 0.8) << describe_failures(r.report);
    // S2 vertices over the outer strips have their preimages on the lower sheet.
    Index on_lower = 0;
    for (Index n = 0; n < r.map.node_count(); ++n)
      if (is_target_vertex_preimage(r.map.data().node_type[n]) && r.map.node_element(n) < lower->element_count()) ++on_lower;
    EXPECT_GT(on_lower, 20);
    // those are the second search's (the first one's seeds all lie on the upper sheet)
    EXPECT_GT(r.report.vertices_found_by_ray_hits, 10);
  }
}

TEST(ProjectSheets, AnArcInsideACircleIsHiddenByIt) {
  // S1: the unit circle and, inside it, an arc of radius 0.5 over the angles 45..135 degrees;
  // S2: a circle of radius 2. Normals point outwards, so the arc's rays pass the unit circle
  // and reach the same part of S2 farther away: the arc's pieces leave D, the circle maps whole.
  const auto outer = circle(64, 1.0);
  std::vector<WorldPoint<1>> v;
  std::vector<ElementCorners<1>> e;
  for (int i = 0; i <= 8; ++i) {
    const double a = (45.0 + 90.0 * i / 8) * std::numbers::pi / 180.0;
    v.emplace_back(0.5 * std::cos(a), 0.5 * std::sin(a));
    if (i > 0) e.push_back({i, i - 1});  // counter-clockwise: outward normals
  }
  const Surface<1> arc(std::move(v), std::move(e));
  const auto s1 = both<1>(*outer, arc);
  const auto s2 = circle(80, 2.0, 0.01);
  const auto r = project<1>(s1, s2);
  EXPECT_EQ(verify_violations(r.map), "");
  EXPECT_NEAR(r.measures.covered_domain, outer->measure(), 1e-9);
  for (Index t = outer->element_count(); t < s1->element_count(); ++t)
    EXPECT_EQ(r.map.regions_begin(t), r.map.regions_end(t)) << "arc element " << t;
}
