// remove_faces(PlMap&&) (core/face_removal.hpp) on projected maps, as project() calls it for the
// folded faces and the farther sheet: faces of several regions, closure edges inside faces and
// along element boundaries. The result must follow the rule evaluated by brute force
// (tests/core/face_removal_rule.hpp) and stay a valid map.
#include "../core/face_removal_rule.hpp"
#include "projection_fixtures.hpp"

#include <plmap/construct/project.hpp>

#include <gtest/gtest.h>

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
