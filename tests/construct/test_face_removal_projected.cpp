// remove_faces(PlMap&&) (core/face_removal.hpp) on projected maps, as project() calls it for the
// folded faces and the farther sheet: faces of several regions, closure edges inside faces and
// along element boundaries. The result must follow the rule evaluated by brute force
// (tests/core/face_removal_rule.hpp) and stay a valid map.
#include "../core/face_removal_rule.hpp"
#include "projection_fixtures.hpp"

#include <plmap/construct/project.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

using namespace plmap;

TEST(FaceRemovalProjected, KeepsWhatTheRuleKeeps) {
  // S2 coarser than S1 and shifted: most faces hold several regions joined by closure edges
  const auto s1 = test::grid(12, 12, 0.0, 1.0, 0.0, 1.0, 0.0, false, 0.15);
  const auto s2 = test::grid(5, 4, 0.3, 1.3, 0.2, 1.2, 0.1, true, 0.2);
  const auto r = project<2>(s1, s2, {.normal_check = TargetNormalCheck::facing});
  const PlMap<2>& map = r.map;
  Index closure_entries = 0;
  for (GraphEdgeKind kind : map.data().neighbor_edge_kind) closure_entries += kind == GraphEdgeKind::closure;
  ASSERT_GT(closure_entries, map.node_count());  // the case this test is for
  std::mt19937 random(17);
  for (int round = 0; round < 30; ++round) {
    std::vector<Index> named(1 + round % 6);
    for (Index& g : named) g = static_cast<Index>(random() % static_cast<unsigned>(map.region_count()));
    test::expect_rule_holds(map, named);
  }
}

TEST(FaceRemovalProjected, RegionsGoAloneWhereTheyReachTheElementBoundary) {
  // remove_regions on the same kind of map: the rule's structure holds, every region it takes is
  // one remove_faces takes too (a named part, or the face of a part strictly inside), the named
  // regions go, and on these faces of several regions it keeps some that remove_faces takes.
  const auto s1 = test::grid(12, 12, 0.0, 1.0, 0.0, 1.0, 0.0, false, 0.15);
  const auto s2 = test::grid(5, 4, 0.3, 1.3, 0.2, 1.2, 0.1, true, 0.2);
  const auto r = project<2>(s1, s2, {.normal_check = TargetNormalCheck::facing});
  const PlMap<2>& map = r.map;
  std::mt19937 random(19);
  Index kept_by_regions = 0;
  for (int round = 0; round < 30; ++round) {
    std::vector<Index> named(1 + round % 6);
    for (Index& g : named) g = static_cast<Index>(random() % static_cast<unsigned>(map.region_count()));
    std::vector<char> by_faces, by_regions;
    test::expect_rule_holds(map, named, test::Removal::faces, &by_faces);
    test::expect_rule_holds(map, named, test::Removal::regions, &by_regions);
    for (Index g : named) EXPECT_TRUE(by_regions[static_cast<std::size_t>(g)]) << g;
    for (std::size_t k = 0; k < by_regions.size(); ++k) {
      EXPECT_FALSE(by_regions[k] && !by_faces[k]) << "region " << k << " went with remove_regions only";
      kept_by_regions += by_faces[k] && !by_regions[k];
    }
  }
  EXPECT_GT(kept_by_regions, 0);
}

TEST(FaceRemovalProjected, ARegionStrictlyInsideItsElementTakesItsFace) {
  // A region with no side on its element's boundary would leave a hole strictly inside the
  // element: remove_regions then takes its face, exactly as remove_faces does.
  const auto s1 = test::grid(12, 12, 0.0, 1.0, 0.0, 1.0, 0.0, false, 0.15);
  const auto s2 = test::grid(5, 4, 0.3, 1.3, 0.2, 1.2, 0.1, true, 0.2);
  const auto r = project<2>(s1, s2, {.normal_check = TargetNormalCheck::facing});
  const PlMap<2>& map = r.map;
  const MapData<2>& m = map.data();
  auto on_boundary = [&](Index a, Index b) {
    const LocalPoint<2> p = m.node_position[a], q = m.node_position[b];
    const double eps = 1e-12;
    return (std::abs(p.y()) < eps && std::abs(q.y()) < eps) || (std::abs(p.x()) < eps && std::abs(q.x()) < eps) ||
           (std::abs(p.x() + p.y() - 1) < eps && std::abs(q.x() + q.y() - 1) < eps);
  };
  int inner_in_larger_face = 0;
  for (Index g = 0; g < map.region_count(); ++g) {
    const auto& c = m.region_corners[g];
    if (on_boundary(c[0], c[1]) || on_boundary(c[1], c[2]) || on_boundary(c[2], c[0])) continue;
    FaceRemovalReport by_faces, by_regions;
    const PlMap<2> faces = remove_faces(map, std::span<const Index>(&g, 1), &by_faces);
    const PlMap<2> regions = remove_regions(PlMap<2>(map), std::span<const Index>(&g, 1), &by_regions);
    ASSERT_EQ(regions.data(), faces.data()) << "region " << g;
    EXPECT_EQ(by_regions.partial_faces, 0);
    inner_in_larger_face += by_faces.removed_regions > 1;
  }
  EXPECT_GT(inner_in_larger_face, 0);
}

TEST(FaceRemovalProjected, RemovalsLeaveOnlyTheGraphsTheRegionsDoNotGiveBack) {
  // A projected map stores some graphs its regions would give back (the builder does not derive
  // them to find out); the first removal drops those, and a later removal then looks again only
  // at the elements that lose regions (StoredGraph::known_minimal). After each, the stored graph
  // is the one a map handed the full arrays keeps.
  const auto s1 = test::grid(12, 12, 0.0, 1.0, 0.0, 1.0, 0.0, false, 0.15);
  const auto s2 = test::grid(5, 4, 0.3, 1.3, 0.2, 1.2, 0.1, true, 0.2);
  PlMap<2> map = project<2>(s1, s2, {.normal_check = TargetNormalCheck::facing, .keep_nearer_sheet = false}).map;
  const auto minimal = [](const PlMap<2>& m) { return PlMap<2>(m.domain_ptr(), m.target_ptr(), m.data()).stored_graph(); };
  ASSERT_FALSE(map.stored_graph().known_minimal);
  ASSERT_GT(map.elements_with_stored_graph(), minimal(map).element.size());  // the case this test is for
  std::mt19937 random(23);
  for (int round = 0; round < 6 && map.region_count() > 8; ++round) {
    std::vector<Index> named(1 + round % 3);
    for (Index& g : named) g = static_cast<Index>(random() % static_cast<unsigned>(map.region_count()));
    std::sort(named.begin(), named.end());
    named.erase(std::unique(named.begin(), named.end()), named.end());
    map = remove_regions(std::move(map), std::span<const Index>(named), nullptr, 1 + round % 3);
    EXPECT_TRUE(map.stored_graph().known_minimal) << "round " << round;
    EXPECT_TRUE(map.stored_graph() == minimal(map)) << "round " << round;
    EXPECT_EQ(test::verify_violations(map), "") << "round " << round;
  }
}
