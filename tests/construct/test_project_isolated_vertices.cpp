// Normal projection with isolated vertices (issue 12, defect 2): a vertex no element uses is not
// part of its surface. An isolated S2 vertex gets no preimage (before: `vertex_elements(q)
// .front()` on its empty star), an isolated S1 vertex casts no ray and carries no ghost node,
// whatever direction it is given. The map equals the map without them.
#include "projection_fixtures.hpp"

#include <plmap/construct/project.hpp>

#include <gtest/gtest.h>

using namespace plmap;
using namespace plmap::test;

namespace {

template <int d>
std::shared_ptr<const Surface<d>> with_extra_vertices(const Surface<d>& s, std::vector<WorldPoint<d>> extra) {
  auto v = s.vertices();
  v.insert(v.end(), extra.begin(), extra.end());
  return std::make_shared<const Surface<d>>(std::move(v), s.elements());
}

TEST(ProjectIsolatedVertices, TheyAreSkippedAndTheMapIsThatOfTheSurfacesWithoutThem) {
  auto s1 = grid(3, 3, 0.0, 1.0, 0.0, 1.0, 0.0, false, 0.1);
  auto s2 = grid(4, 4, 0.0, 1.0, 0.0, 1.0, 0.2, false, 0.1);
  // S2's isolated vertex lies right above S1 (it would have a preimage), S1's right below S2
  auto s1_iso = with_extra_vertices<2>(*s1, {WorldPoint<2>(0.4, 0.4, 0.0)});
  auto s2_iso = with_extra_vertices<2>(*s2, {WorldPoint<2>(0.6, 0.55, 0.2), WorldPoint<2>(0.3, 0.3, 0.1)});
  ProjectionOptions o;
  o.directions = constant_directions(*s1_iso, WorldPoint<2>(0.0, 0.0, 1.0));
  const auto r = project<2>(s1_iso, s2_iso, o);
  o.directions = constant_directions(*s1, WorldPoint<2>(0.0, 0.0, 1.0));
  const auto plain = project<2>(s1, s2, o);
  EXPECT_EQ(verify_violations(r.map), "");
  EXPECT_EQ(r.map.data().node_type, plain.map.data().node_type);
  EXPECT_EQ(r.map.data().node_target, plain.map.data().node_target);
  EXPECT_EQ(r.map.data().region_corners, plain.map.data().region_corners);
  EXPECT_EQ(r.map.data().region_target, plain.map.data().region_target);
  EXPECT_EQ(r.report.vertex_preimages, plain.report.vertex_preimages);
  EXPECT_EQ(r.report.ghost_nodes, plain.report.ghost_nodes);
  EXPECT_NEAR(r.measures.covered_domain, 1.0, 1e-9);
  // averaged normals: the isolated S1 vertex has none and is skipped as well
  const auto averaged = project<2>(s1_iso, s2_iso);
  EXPECT_EQ(verify_violations(averaged.map), "");
  EXPECT_EQ(averaged.map.data().region_target, project<2>(s1, s2).map.data().region_target);
}

TEST(ProjectIsolatedVertices, CurvesToo) {
  auto inner = circle(12, 1.0), outer = circle(17, 1.5, 0.1);
  auto inner_iso = with_extra_vertices<1>(*inner, {WorldPoint<1>(0.1, 0.2)});
  auto outer_iso = with_extra_vertices<1>(*outer, {WorldPoint<1>(1.2, 0.0)});
  const auto r = project<1>(inner_iso, outer_iso);
  EXPECT_EQ(verify_violations(r.map), "");
  EXPECT_EQ(r.map.data().region_target, project<1>(inner, outer).map.data().region_target);
}

}  // namespace
