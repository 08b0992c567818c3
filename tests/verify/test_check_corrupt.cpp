// Deliberately corrupted copies of valid maps: each defect is caught, by the check that owns it.

#include "test_check_support.hpp"

#include <plmap/verify/check.hpp>

#include <gtest/gtest.h>

namespace plmap {
namespace {

using namespace plmap::test;

template <int d>
void expect_caught(const PlMap<d>& map, std::string_view check, std::string_view rule) {
  const VerificationReport report = verify(map);
  EXPECT_FALSE(report.ok());
  EXPECT_GT(report.violation_count(check, rule), 0u)
      << "expected " << check << "/" << rule << "\n" << summary(report);
  // The violation names what it is about.
  const CheckResult* c = report.find(check);
  ASSERT_NE(c, nullptr);
  const auto it = std::find_if(c->violations.begin(), c->violations.end(),
                               [&](const Violation& v) { return v.rule == rule; });
  ASSERT_NE(it, c->violations.end());
  EXPECT_EQ(it->check, check);
  EXPECT_FALSE(it->message.empty());
  EXPECT_TRUE(it->element != invalid_index || it->node != invalid_index ||
              it->region != invalid_index || it->target_element != invalid_index);
}

TEST(VerifyCorrupt, SwappedNeighboursBreakTheCyclicOrder) {
  const PlMap<2> base = midpoint_refinement();
  const Index n = node_with_target(base, 0, 3, NodeType::touching);
  ASSERT_EQ(base.neighbors(n).size(), 4u);
  const PlMap<2> bad = modified<2>(base, [&](MapData<2>& m) {
    std::swap(m.neighbor[m.neighbor_begin[n]], m.neighbor[m.neighbor_begin[n] + 1]);
    std::swap(m.neighbor_edge_kind[m.neighbor_begin[n]], m.neighbor_edge_kind[m.neighbor_begin[n] + 1]);
  });
  expect_caught(bad, "structure", "ccw_order");
}

TEST(VerifyCorrupt, AsymmetricNeighbours) {
  const PlMap<2> base = midpoint_refinement();
  const PlMap<2> bad = modified<2>(base, [&](MapData<2>& m) {
    auto lists = neighbor_lists(m);
    lists[0].pop_back();
    set_neighbor_lists(m, lists);
  });
  expect_caught(bad, "structure", "neighbor_symmetry");
}

TEST(VerifyCorrupt, MovedNodeNoLongerOnItsEdge) {
  const PlMap<2> base = midpoint_refinement();
  const Index n = node_with_target(base, 0, 4, NodeType::touching);
  const PlMap<2> bad = modified<2>(base, [&](MapData<2>& m) { m.node_position[n] = lp<2>(0.4, 0.4); });
  expect_caught(bad, "structure", "node_position");
}

TEST(VerifyCorrupt, EdgeArrayOutOfOrder) {
  const PlMap<2> bad = modified<2>(midpoint_refinement(), [](MapData<2>& m) {
    std::reverse(m.edge_node.begin() + m.edge_node_begin[0], m.edge_node.begin() + m.edge_node_begin[1]);
  });
  expect_caught(bad, "structure", "edge_array");
}

TEST(VerifyCorrupt, CopyOnSharedEdgeWithADifferentImage) {
  const PlMap<2> base = centre_fan();
  const Index n = node_with_target(base, 1, 4, NodeType::touching);
  const PlMap<2> bad = modified<2>(base, [&](MapData<2>& m) {
    m.node_image_local[n] = lp<2>(0.3, 0.3);  // still inside its S2 element, but elsewhere
  });
  expect_caught(bad, "structure", "copies_agree");
}

TEST(VerifyCorrupt, CopyOnSharedVertexWithADifferentTarget) {
  const PlMap<2> base = centre_fan();
  const Index n = node_with_target(base, 1, 3, NodeType::corner);
  const Index other = node_with_target(base, 1, 0, NodeType::corner);
  const PlMap<2> bad = modified<2>(base, [&](MapData<2>& m) {
    m.node_target[other] = 3;  // vertex 0's copy in element 1 claims S2 vertex 3
    (void)n;
  });
  expect_caught(bad, "structure", "copies_agree");
}

TEST(VerifyCorrupt, ReversedRegion) {
  const PlMap<2> bad = modified<2>(midpoint_refinement(), [](MapData<2>& m) {
    std::swap(m.region_corners[3][1], m.region_corners[3][2]);
  });
  expect_caught(bad, "plane_graph", "region_orientation");
}

TEST(VerifyCorrupt, CrossingGraphEdges) {
  // Add the graph edge corner 0 -> midpoint of edge 1, which crosses the edge between the
  // midpoints of edges 0 and 2; neighbour lists stay symmetric and counter-clockwise.
  const PlMap<2> base = midpoint_refinement();
  const Index c0 = node_with_target(base, 0, 0, NodeType::corner);
  const Index m12 = node_with_target(base, 0, 4, NodeType::touching);
  const PlMap<2> bad = modified<2>(base, [&](MapData<2>& m) {
    auto lists = neighbor_lists(m);
    lists[c0].push_back({m12, GraphEdgeKind::closure});
    lists[m12].push_back({c0, GraphEdgeKind::closure});
    set_neighbor_lists(m, lists);
    sort_neighbor_lists(m);
  });
  EXPECT_EQ(check_structure(bad).violation_count(), 0u) << summary(check_structure(bad));
  expect_caught(bad, "plane_graph", "edge_crossing");
}

TEST(VerifyCorrupt, RegionNeighbourMissing) {
  const PlMap<2> base = midpoint_refinement();
  const PlMap<2> bad = modified<2>(base, [](MapData<2>& m) {
    for (auto& nb : m.region_neighbors[3]) nb = invalid_index;
  });
  expect_caught(bad, "plane_graph", "region_adjacency");
}

TEST(VerifyCorrupt, MissingRegionInAFullyCoveredElement) {
  const PlMap<2> bad = modified<2>(midpoint_refinement(), [](MapData<2>& m) {
    m.region_corners.pop_back();
    m.region_neighbors.pop_back();
    m.region_target.pop_back();
    m.region_map.pop_back();
    m.region_begin[1] = 3;
    for (auto& nb : m.region_neighbors)
      for (auto& q : nb)
        if (q == 3) q = invalid_index;
  });
  expect_caught(bad, "plane_graph", "region_tiling");
}

TEST(VerifyCorrupt, WrongRegionTarget) {
  const PlMap<2> bad = modified<2>(centre_fan(), [](MapData<2>& m) { m.region_target[0] = 2; });
  expect_caught(bad, "map", "region_corner_image");
}

TEST(VerifyCorrupt, DuplicatedVertexPreimage) {
  const PlMap<2> base = midpoint_refinement();
  const Index n = node_with_target(base, 0, 4, NodeType::touching);
  const PlMap<2> bad = modified<2>(base, [&](MapData<2>& m) { m.node_target[n] = 3; });
  expect_caught(bad, "map", "vertex_preimage_unique");
}

TEST(VerifyCorrupt, FoldOver) {
  const PlMap<2> bad = modified<2>(centre_fan(), [](MapData<2>& m) { m.orientation = -1; });
  expect_caught(bad, "map", "fold_over");
}

TEST(VerifyCorrupt, GraphEdgeThatIsNoTargetEdge) {
  // The midpoint of edge 2 claims to be S2 vertex 4: its graph edge to corner 0 (marked as an S2
  // edge preimage) now joins S2 vertices 0 and 4, which share no S2 edge.
  const PlMap<2> base = midpoint_refinement();
  const Index n = node_with_target(base, 0, 5, NodeType::touching);
  const PlMap<2> bad = modified<2>(base, [&](MapData<2>& m) { m.node_target[n] = 4; });
  expect_caught(bad, "minimal_embedding", "unlabelled_target_edge");
}

TEST(VerifyCorrupt, TwoSegmentsOfOneTargetEdgeInOneElement) {
  // d = 1: the labels of graph edges come from their endpoints' targets; when two consecutive
  // graph edges carry the same S2 segment, its preimage passes through an S2 vertex preimage.
  const PlMap<1> base = curve_refinement();
  const PlMap<1> bad = modified<1>(base, [](MapData<1>& m) {
    // Element 0: nodes 0 (S2 vertex 0), 1 (S2 vertex 1), 2 (S2 vertex 2). Make node 0 claim S2
    // vertex 2: edges 0-1 and 1-2 now both join S2 vertices 1 and 2, i.e. S2 segment 1.
    m.node_target[0] = 2;
  });
  expect_caught(bad, "minimal_embedding", "not_minimal");
}

TEST(VerifyCorrupt, DiscontinuityAcrossSharedEdge) {
  const PlMap<2> bad = modified<2>(centre_fan(), [](MapData<2>& m) {
    m.region_map[m.region_begin[1]](0, 2) += 1e-3;  // shift one region's image
  });
  expect_caught(bad, "continuity", "shared_boundary_mismatch");
}

TEST(VerifyCorrupt, OverlappingImages) {
  // Both S1 triangles map onto S2 element 0.
  const PlMap<2> bad = modified<2>(identity_square(), [](MapData<2>& m) {
    m.region_target[1] = m.region_target[0];
    m.region_map[1] = m.region_map[0];
  });
  expect_caught(bad, "coverage", "image_overlap");
}

TEST(VerifyCorrupt, IndexOutOfRangeSkipsTheOtherChecks) {
  const PlMap<2> bad = modified<2>(centre_fan(), [](MapData<2>& m) { m.node_target[0] = 99; });
  const VerificationReport report = verify(bad);
  EXPECT_GT(report.violation_count("structure", "index_range"), 0u) << summary(report);
  EXPECT_TRUE(report.find("map")->skipped);
  // A single check run alone reports the index problem too, instead of reading out of range.
  const VerificationReport alone = check_map(bad);
  EXPECT_GT(alone.violation_count("structure", "index_range"), 0u);
  ASSERT_NE(alone.find("map"), nullptr);
  EXPECT_TRUE(alone.find("map")->skipped);
}

TEST(VerifyCorrupt, CurveNeighboursOutOfOrder) {
  const PlMap<1> base = curve_refinement();
  const Index n = node_with_target(base, 0, 1, NodeType::interior);
  const PlMap<1> bad = modified<1>(base, [&](MapData<1>& m) {
    std::swap(m.neighbor[m.neighbor_begin[n]], m.neighbor[m.neighbor_begin[n] + 1]);
  });
  expect_caught(bad, "structure", "ccw_order");
}

TEST(VerifyCorrupt, CurveGhostCopiesDisagree) {
  const PlMap<1> base = curve_with_ghost();
  const PlMap<1> bad = modified<1>(base, [](MapData<1>& m) {
    const Index ghost = m.node_begin[1];  // element 1's copy of the ghost at S1 vertex 1
    m.node_image_local[ghost](0) += 0.1;
  });
  expect_caught(bad, "structure", "copies_agree");
  expect_caught(bad, "map", "region_corner_image");
}

TEST(VerifyCorrupt, CurveDiscontinuity) {
  const PlMap<1> bad = modified<1>(curve_with_ghost(), [](MapData<1>& m) {
    m.region_map[m.region_begin[1]](0, 1) += 0.01;
  });
  expect_caught(bad, "continuity", "shared_boundary_mismatch");
}

TEST(VerifyCorrupt, CurveOverlappingImages) {
  const PlMap<1> bad = modified<1>(curve_refinement(), [](MapData<1>& m) {
    m.region_target[2] = m.region_target[1];
    m.region_map[2] = m.region_map[1];
  });
  expect_caught(bad, "coverage", "image_overlap");
}

}  // namespace
}  // namespace plmap
