// remove_faces (core/face_removal.hpp): the map on a smaller domain stays a valid map, loses
// exactly the named faces (or a whole element when a face lies strictly inside it), and keeps
// its nodes, graph edges and edge arrays.

#include <plmap/core/errors.hpp>
#include <plmap/core/face_removal.hpp>
#include <plmap/core/map_builder.hpp>
#include <plmap/core/regions.hpp>
#include <plmap/verify/check.hpp>
#include <plmap/verify/generators/subdivision_maps.hpp>

#include <gtest/gtest.h>

#include "../verify_violations.hpp"

#include <algorithm>

using namespace plmap;
using plmap::test::verify_violations;

namespace {

template <int d>
Index graph_edge_entries(const PlMap<d>& map) {
  const auto& kinds = map.data().neighbor_edge_kind;
  return static_cast<Index>(std::count(kinds.begin(), kinds.end(), GraphEdgeKind::target_edge));
}

}  // namespace

TEST(FaceRemoval, AFaceOnTheElementBoundaryLeavesTheRestOfTheElement) {
  // 3 x 3 subdivision of each of two triangles: every sub-triangle is a face of one region.
  const auto sm = generators::subdivision_map(generators::two_triangles(), 3, 0.1, 7);
  const PlMap<2>& map = *sm.map;
  ASSERT_EQ(verify_violations(map), "");
  // region 0 is the sub-triangle at corner 0 of element 0: two of its sides lie on the boundary
  const Index removed = 0;
  const double removed_area = remote_intersection(map, removed).domain_measure();
  FaceRemovalReport report;
  const PlMap<2> smaller = remove_faces(map, std::span<const Index>(&removed, 1), &report);
  EXPECT_EQ(report.removed_faces, 1);
  EXPECT_EQ(report.removed_regions, 1);
  EXPECT_EQ(report.cleared_elements, 0);
  EXPECT_EQ(smaller.region_count(), map.region_count() - 1);
  EXPECT_EQ(smaller.node_count(), map.node_count());
  EXPECT_EQ(graph_edge_entries(smaller), graph_edge_entries(map));  // S2 edges stay
  EXPECT_EQ(smaller.data().edge_node, map.data().edge_node);
  EXPECT_NEAR(covered_measure(smaller).domain, covered_measure(map).domain - removed_area, 1e-14);
  EXPECT_EQ(verify_violations(smaller), "");
}

TEST(FaceRemoval, AFaceStrictlyInsideItsElementTakesTheWholeElement) {
  const auto sm = generators::subdivision_map(generators::two_triangles(), 3, 0.1, 7);
  const PlMap<2>& map = *sm.map;
  // A sub-triangle of element 0 with no side on the element boundary: the "upside-down" one
  // between grid points (1,0), (1,1), (0,1).
  Index inner = invalid_index;
  for (Index r = map.regions_begin(0); r < map.regions_end(0) && inner == invalid_index; ++r) {
    bool boundary_side = false;
    const auto& c = map.data().region_corners[r];
    for (int i = 0; i < 3; ++i) {
      const LocalPoint<2> a = map.data().node_position[c[i]], b = map.data().node_position[c[(i + 1) % 3]];
      boundary_side |= (a.y() == 0 && b.y() == 0) || (a.x() == 0 && b.x() == 0) ||
                       (std::abs(a.x() + a.y() - 1) < 1e-12 && std::abs(b.x() + b.y() - 1) < 1e-12);
    }
    if (!boundary_side) inner = r;
  }
  ASSERT_NE(inner, invalid_index);
  FaceRemovalReport report;
  const PlMap<2> smaller = remove_faces(map, std::span<const Index>(&inner, 1), &report);
  EXPECT_EQ(report.removed_faces, 1);
  EXPECT_EQ(report.cleared_elements, 1);
  EXPECT_EQ(report.removed_regions, map.regions_end(0) - map.regions_begin(0));
  EXPECT_EQ(smaller.regions_begin(0), smaller.regions_end(0));
  EXPECT_EQ(smaller.data().start_region[0], invalid_index);
  EXPECT_EQ(smaller.regions_end(1) - smaller.regions_begin(1), map.regions_end(1) - map.regions_begin(1));
  EXPECT_EQ(verify_violations(smaller), "");
}

namespace {

/// S1: one triangle. S2: a larger sheet whose edge D-C (y = 1/2) cuts S1 into a quadrilateral
/// (mapped into S2 triangle ACD; the closure cuts it into two regions) and a triangle (in DCF).
PlMap<2> quadrilateral_and_triangle_map() {
  auto s1 = std::make_shared<const Surface<2>>(std::vector<WorldPoint<2>>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}},
                                               std::vector<ElementCorners<2>>{{0, 1, 2}});
  // A, B, C, D, E, F
  auto s2 = std::make_shared<const Surface<2>>(
      std::vector<WorldPoint<2>>{{-1, -1, 0}, {3, -1, 0}, {3, 0.5, 0}, {-1, 0.5, 0}, {-1, 3, 0}, {3, 3, 0}},
      std::vector<ElementCorners<2>>{{0, 1, 2}, {0, 2, 3}, {3, 2, 5}, {3, 5, 4}});
  MapBuilder<2> b(s1, s2);
  b.add_ghost_node(0, {1, LocalPoint<2>(0.25, 5.0 / 12.0)});  // (0, 0) in ACD
  b.add_ghost_node(1, {1, LocalPoint<2>(0.5, 1.0 / 6.0)});    // (1, 0) in ACD
  b.add_ghost_node(2, {2, LocalPoint<2>(0.05, 0.2)});         // (0, 1) in DCF
  const Index dc = s2->find_edge(2, 3);
  for (Index e = 0; e < s2->edge_count(); ++e)
    if (e != dc) b.add_edge_outside_domain(e);
  // D-C from C (the smaller index): it crosses S1 edge 1-2 at (1/2, 1/2), then edge 0-2 at (0, 1/2)
  const std::array<EdgeCrossing, 2> crossings = {EdgeCrossing{s1->find_edge(1, 2), 0.5, 0.625},
                                                 EdgeCrossing{s1->find_edge(0, 2), 0.5, 0.75}};
  b.add_edge_piece(dc, crossings, PieceStart::first_crossing, PieceEnd::last_crossing);
  return std::move(b).finalize();
}

Index closure_entries(const PlMap<2>& m) {
  const auto& kinds = m.data().neighbor_edge_kind;
  return static_cast<Index>(std::count(kinds.begin(), kinds.end(), GraphEdgeKind::closure));
}

}  // namespace

TEST(FaceRemoval, AFaceOfSeveralRegionsGoesWhole) {
  const PlMap<2> map = quadrilateral_and_triangle_map();
  ASSERT_EQ(verify_violations(map), "");
  ASSERT_EQ(map.region_count(), 3);
  Index in_quad = invalid_index;
  for (Index r = 0; r < map.region_count(); ++r)
    if (map.data().region_target[r] == 1) in_quad = r;
  ASSERT_NE(in_quad, invalid_index);
  FaceRemovalReport report;
  const PlMap<2> smaller = remove_faces(map, std::span<const Index>(&in_quad, 1), &report);
  EXPECT_EQ(report.removed_faces, 1);
  EXPECT_EQ(report.removed_regions, 2);  // both regions of the quadrilateral
  EXPECT_EQ(report.cleared_elements, 0);
  ASSERT_EQ(smaller.region_count(), 1);
  EXPECT_EQ(smaller.data().region_target[0], 2);
  EXPECT_NEAR(covered_measure(smaller).domain, 0.125, 1e-15);
  // Gone with it: the closure edge across the quadrilateral and its three pieces of the element
  // boundary (boundary pieces are closure edges too), each listed at both ends.
  EXPECT_EQ(closure_entries(smaller), closure_entries(map) - 8);
  EXPECT_EQ(verify_violations(smaller), "");
}

TEST(RegionRemoval, ARegionOfAFaceOnTheElementBoundaryGoesAlone) {
  // remove_regions on the quadrilateral of the test above: either of its two regions goes alone
  // (both have sides on the element boundary), the other stays with its image, and the closure
  // edge between them stays as the edge of D; named together, they are the whole face.
  const PlMap<2> map = quadrilateral_and_triangle_map();
  std::vector<Index> quad;
  for (Index r = 0; r < map.region_count(); ++r)
    if (map.data().region_target[r] == 1) quad.push_back(r);
  ASSERT_EQ(quad.size(), 2u);
  const auto& a = map.data().region_corners[quad[0]];
  const auto& b = map.data().region_corners[quad[1]];
  std::vector<Index> diagonal;  // the two nodes the quadrilateral's regions share
  for (Index n : a)
    if (std::find(b.begin(), b.end(), n) != b.end()) diagonal.push_back(n);
  ASSERT_EQ(diagonal.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    const Index named = quad[k], other = quad[1 - k];
    const double area = remote_intersection(map, named).domain_measure();
    FaceRemovalReport report;
    const PlMap<2> smaller = remove_regions(PlMap<2>(map), std::span<const Index>(&named, 1), &report);
    EXPECT_EQ(report.removed_faces, 1);
    EXPECT_EQ(report.partial_faces, 1);
    EXPECT_EQ(report.removed_regions, 1);
    EXPECT_EQ(report.cleared_elements, 0);
    ASSERT_EQ(smaller.region_count(), 2);
    EXPECT_NEAR(covered_measure(smaller).domain, 0.5 - area, 1e-15);
    EXPECT_NEAR(area + remote_intersection(map, other).domain_measure(), 0.375, 1e-15);
    const auto around = smaller.neighbors(diagonal[0]);
    EXPECT_NE(std::find(around.begin(), around.end(), diagonal[1]), around.end()) << "the diagonal went";
    EXPECT_LT(closure_entries(smaller), closure_entries(map));  // the named region's boundary pieces
    EXPECT_EQ(verify_violations(smaller), "");
  }
  FaceRemovalReport report;
  const PlMap<2> both = remove_regions(PlMap<2>(map), std::span<const Index>(quad), &report);
  EXPECT_EQ(report.removed_faces, 1);
  EXPECT_EQ(report.partial_faces, 0);
  EXPECT_EQ(report.removed_regions, 2);
  EXPECT_EQ(both.data(), remove_faces(map, std::span<const Index>(&quad[0], 1)).data());
}

TEST(FaceRemoval, CurvesLoseTheRegionAndItsGraphEdge) {
  const auto sm = generators::subdivision_map(generators::zigzag_curve(4), 5, 0.2, 3);
  const PlMap<1>& map = *sm.map;
  const std::array<Index, 3> named = {2, 7, 2};  // repeats are fine
  FaceRemovalReport report;
  const PlMap<1> smaller = remove_faces(map, std::span<const Index>(named), &report);
  EXPECT_EQ(report.removed_faces, 2);
  EXPECT_EQ(report.removed_regions, 2);
  EXPECT_EQ(smaller.region_count(), map.region_count() - 2);
  EXPECT_EQ(smaller.data().neighbor.size(), map.data().neighbor.size() - 4);  // two links, both ways
  EXPECT_EQ(verify_violations(smaller), "");
}

TEST(FaceRemoval, NothingNamedChangesNothingAndABadIndexIsAnError) {
  const auto sm = generators::subdivision_map(generators::bumpy_grid(2), 4, 0.15, 5);
  const PlMap<2> same = remove_faces(*sm.map, std::span<const Index>());
  EXPECT_EQ(same.data(), sm.map->data());
  const Index bad = sm.map->region_count();
  EXPECT_THROW(remove_faces(*sm.map, std::span<const Index>(&bad, 1)), InvalidMapError);
}
