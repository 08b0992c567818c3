// White-box test of finalize's choice of the elements to close again after drops
// (core/src/finalize_rechecks.hpp): every element whose graph a drop touched must be among them,
// or a conflict there would go unnoticed; and nothing else, or finalize would close S1 again.

#include "finalize_rechecks.hpp"

#include <plmap/core/surface.hpp>

#include <gtest/gtest.h>

#include <memory>
#include <vector>

using namespace plmap;
using namespace plmap::detail;

namespace {

/// The unit square cut into 2 x 2 squares, each cut by its diagonal: elements 2 (i + 2 j) and
/// 2 (i + 2 j) + 1 in square (i, j).
std::shared_ptr<const Surface<2>> four_squares() {
  std::vector<WorldPoint<2>> v;
  for (int j = 0; j <= 2; ++j)
    for (int i = 0; i <= 2; ++i) v.push_back({0.5 * i, 0.5 * j, 0.0});
  std::vector<ElementCorners<2>> t;
  auto id = [](int i, int j) { return static_cast<Index>(3 * j + i); };
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      t.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      t.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return std::make_shared<const Surface<2>>(v, t);
}

struct Contents {
  std::shared_ptr<const Surface<2>> s1 = four_squares();
  BuilderOptions options;
  BuilderNodes<2> nodes;
  std::vector<Index> node_at_domain_vertex = std::vector<Index>(9, invalid_index);
  BuilderSegments<2> segments;
  std::vector<char> edge_inserted = std::vector<char>(4, 1);
  BuilderContents<2> in{*s1, *s1, options, nodes, node_at_domain_vertex, segments, edge_inserted};

  Index node_at(PlaceKind kind, Index index) {
    Place<2> place;
    place.kind = kind;
    place.index = index;
    nodes.emplace_back(place, BuilderNodeKind::rim, invalid_index, Support<2>{});
    return static_cast<Index>(nodes.size()) - 1;
  }
  Index segment(bool along_edge, Index where) {
    segments.push_back(Segment{0, 1, 0, along_edge, where});
    return static_cast<Index>(segments.size()) - 1;
  }
};

std::vector<Index> elements_of_edge(const Surface<2>& s, Index e) {
  std::vector<Index> out;
  for (const EdgeIncidence& incidence : s.edge_elements(e)) out.push_back(incidence.element);
  return out;
}

}  // namespace

TEST(FinalizeRechecks, TheElementsAroundEveryDroppedSegmentAndNodeAndThoseThatFailed) {
  Contents c;
  const Surface<2>& s1 = *c.s1;
  const Index diagonal = s1.find_edge(0, 4);  // inside square (0, 0): elements 0 and 1
  const Index middle = s1.find_edge(4, 7);       // between squares (0, 1) and (1, 1): elements 4 and 7
  ASSERT_EQ(elements_of_edge(s1, diagonal), (std::vector<Index>{0, 1}));
  ASSERT_EQ(elements_of_edge(s1, middle), (std::vector<Index>{4, 7}));
  const Index inside_3 = c.segment(false, 3);
  const Index along_diagonal = c.segment(true, diagonal);
  c.segment(false, 2);  // never dropped: element 2 stays out
  const Index rim_on_middle = c.node_at(PlaceKind::edge, middle);
  c.node_at(PlaceKind::element, 5);  // never dropped: element 5 stays out
  DroppedEdges dropped(c.edge_inserted, nullptr, c.segments.size());
  dropped.drop_segments(std::vector<Index>{inside_3, along_diagonal});
  dropped.drop_segments(std::vector<Index>{inside_3});  // dropped before: nothing new
  dropped.drop_rim_node(rim_on_middle, c.nodes.size());
  const std::vector<Index> failed{4, 6};
  EXPECT_EQ(elements_to_close_again(c.in, dropped.take_changes(), failed), (std::vector<Index>{0, 1, 3, 4, 6, 7}));
  // the changes were taken: the next round starts from the failures alone
  EXPECT_EQ(elements_to_close_again(c.in, dropped.take_changes(), failed), failed);
}

TEST(FinalizeRechecks, ARimNodeAtAVertexTouchesItsStar) {
  Contents c;
  const Index at_centre = c.node_at(PlaceKind::vertex, 4);
  DroppedEdges dropped(c.edge_inserted, nullptr, c.segments.size());
  dropped.drop_rim_node(at_centre, c.nodes.size());
  EXPECT_EQ(elements_to_close_again(c.in, dropped.take_changes(), {}), (std::vector<Index>{0, 1, 3, 4, 6, 7}));
}

TEST(FinalizeRechecks, AWholeDroppedEdgeTouchesEveryElement) {
  Contents c;
  DroppedEdges dropped(c.edge_inserted, nullptr, c.segments.size());
  dropped.drop(2, 0);
  EXPECT_EQ(elements_to_close_again(c.in, dropped.take_changes(), {}).size(), 8u);
}

// finalize closes the graphs of these elements before its first full pass (so that a conflict is
// found before that pass assembles anything): an element left out costs a wasted pass, an element
// put in costs one closure.
TEST(FinalizeRechecks, ElementsNextToPiecesThatStopInsideS1AndToRimEdgesAreClosedFirst) {
  Contents c;
  const Surface<2>& s1 = *c.s1;
  auto node = [&](PlaceKind kind, Index index, BuilderNodeKind what) {
    Place<2> place;
    place.kind = kind;
    place.index = index;
    c.nodes.emplace_back(place, what, invalid_index, Support<2>{});
    return static_cast<Index>(c.nodes.size()) - 1;
  };
  auto piece = [&](Index a, Index b, Index target_edge, bool along_edge, Index where) {
    c.segments.push_back(Segment{a, b, target_edge, along_edge, where});
  };
  using K = BuilderNodeKind;
  c.edge_inserted = {edge_complete, edge_partial, edge_partial, edge_partial};
  // S2 edge 1 enters across S1's boundary (edge 2-5) and stops on the interior edge 1-4, through
  // elements 2 and 3: both are closed first.
  const Index q = node(PlaceKind::edge, s1.find_edge(2, 5), K::intersection);
  const Index p = node(PlaceKind::edge, s1.find_edge(1, 5), K::intersection);
  const Index r = node(PlaceKind::edge, s1.find_edge(1, 4), K::intersection);
  piece(q, p, 1, false, 2);
  piece(p, r, 1, false, 3);
  // S2 edge 2 runs from its vertex's preimage (in element 5) out across the boundary (edge 6-7):
  // partly inserted, but nowhere stopped inside S1: element 5 is not.
  const Index u = node(PlaceKind::element, 5, K::vertex_preimage);
  const Index w = node(PlaceKind::edge, s1.find_edge(6, 7), K::intersection);
  piece(u, w, 2, false, 5);
  // S2 edge 3 runs along the interior S1 edge 4-7 from the interior vertex 4 (where it stops) to
  // the boundary vertex 7: both elements at that S1 edge, 4 and 7.
  const Index at_4 = node(PlaceKind::vertex, 4, K::intersection);
  const Index at_7 = node(PlaceKind::vertex, 7, K::intersection);
  piece(at_4, at_7, 3, true, s1.find_edge(4, 7));
  // S2 edge 0 is whole (element 1 is not); a rim edge in element 6 is.
  piece(u, w, 0, false, 1);
  piece(p, r, invalid_index, false, 6);
  EXPECT_EQ(elements_next_to_partial_preimages(c.in, nullptr), (std::vector<Index>{2, 3, 4, 6, 7}));
  // Without S2 edges 1 and 3 and the rim edge, nothing is closed first: S2 edge 2 only leaves S1
  // across its boundary, as on a larger S2.
  c.segments.erase(c.segments.begin() + 5);  // the rim edge
  c.segments.erase(c.segments.begin() + 3);  // S2 edge 3 along 4-7
  c.segments.erase(c.segments.begin(), c.segments.begin() + 2);  // S2 edge 1
  EXPECT_EQ(elements_next_to_partial_preimages(c.in, nullptr), std::vector<Index>{});
}
