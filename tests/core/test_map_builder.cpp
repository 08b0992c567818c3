// Unit tests of the map factory (MapBuilder) on small hand-made configurations where the
// expected graph is known exactly.
#include <plmap/core/errors.hpp>
#include <plmap/core/map_builder.hpp>
#include <plmap/core/regions.hpp>
#include <plmap/verify/check.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

using namespace plmap;

namespace {

std::shared_ptr<const Surface<2>> make_surface(std::vector<WorldPoint<2>> v,
                                               std::vector<ElementCorners<2>> e) {
  return std::make_shared<const Surface<2>>(std::move(v), std::move(e));
}

WorldPoint<2> P(double x, double y) { return {x, y, 0.0}; }

// Unit square split along the diagonal 0-2.
std::shared_ptr<const Surface<2>> square_diag02() {
  return make_surface({P(0, 0), P(1, 0), P(1, 1), P(0, 1)}, {{0, 1, 2}, {0, 2, 3}});
}
// Unit square split along the other diagonal 1-3.
std::shared_ptr<const Surface<2>> square_diag13() {
  return make_surface({P(0, 0), P(1, 0), P(1, 1), P(0, 1)}, {{0, 1, 3}, {1, 2, 3}});
}

int count_type(const PlMap<2>& m, NodeType t) {
  return static_cast<int>(std::count(m.data().node_type.begin(), m.data().node_type.end(), t));
}

}  // namespace

TEST(MapBuilder, IdentityMapHasOneRegionPerElement) {
  auto s = square_diag02();
  MapBuilder<2> b(s, s);
  for (Index v = 0; v < s->vertex_count(); ++v) b.add_vertex_preimage_at_vertex(v, v);
  for (Index t = 0; t < s->element_count(); ++t) b.add_target_element(t);
  const PlMap<2> m = std::move(b).finalize();
  EXPECT_EQ(m.region_count(), 2);
  EXPECT_EQ(m.node_count(), 6);  // three corner copies per element
  EXPECT_EQ(count_type(m, NodeType::corner), 6);
  EXPECT_EQ(m.data().orientation, 1);
  for (Index r = 0; r < m.region_count(); ++r) {
    const auto ri = remote_intersection(m, r);
    EXPECT_EQ(ri.domain_element, ri.target_element);
    for (int i = 0; i < 3; ++i) EXPECT_EQ(ri.domain_local[i], ri.target_local[i]);
  }
  const auto c = covered_measure(m);
  EXPECT_DOUBLE_EQ(c.domain, 1.0);
  EXPECT_DOUBLE_EQ(c.target, 1.0);
  // every corner has both other corners as neighbours, all along S2 edges
  for (Index n = 0; n < m.node_count(); ++n) {
    ASSERT_EQ(m.neighbors(n).size(), 2u);
    for (Index i = m.data().neighbor_begin[n]; i < m.data().neighbor_begin[n + 1]; ++i)
      EXPECT_EQ(m.data().neighbor_edge_kind[i], GraphEdgeKind::target_edge);
  }
  // edge arrays hold the two corners, from corner k to corner k+1
  for (Index t = 0; t < 2; ++t)
    for (int k = 0; k < 3; ++k) {
      const auto en = m.edge_nodes(t, k);
      ASSERT_EQ(en.size(), 2u);
      EXPECT_EQ(m.data().node_location[en[0]], k);
      EXPECT_EQ(m.data().node_location[en[1]], (k + 1) % 3);
    }
}

TEST(MapBuilder, InteriorNodeSplitsElementIntoThreeRegions) {
  auto s1 = make_surface({P(0, 0), P(1, 0), P(0, 1)}, {{0, 1, 2}});
  auto s2 = make_surface({P(0, 0), P(1, 0), P(0, 1), P(0.25, 0.25)}, {{0, 1, 3}, {1, 2, 3}, {2, 0, 3}});
  MapBuilder<2> b(s1, s2);
  for (Index v = 0; v < 3; ++v) b.add_vertex_preimage_at_vertex(v, v);
  b.add_vertex_preimage(3, {0, LocalPoint<2>(0.25, 0.25)});
  for (Index t = 0; t < 3; ++t) b.add_target_element(t);
  const PlMap<2> m = std::move(b).finalize();
  EXPECT_EQ(m.region_count(), 3);
  EXPECT_EQ(count_type(m, NodeType::interior), 1);
  const auto c = covered_measure(m);
  EXPECT_NEAR(c.domain, 0.5, 1e-15);
  EXPECT_NEAR(c.target, 0.5, 1e-15);
  // the interior node sees all three corners, counter-clockwise
  const Index interior = 3;
  ASSERT_EQ(m.data().node_type[interior], NodeType::interior);
  EXPECT_EQ(m.neighbors(interior).size(), 3u);
}

TEST(MapBuilder, CrossingDiagonalsMakeIntersectionNodes) {
  auto s1 = square_diag02();
  auto s2 = square_diag13();
  MapBuilder<2> b(s1, s2);
  for (Index v = 0; v < 4; ++v) b.add_vertex_preimage_at_vertex(v, v);
  const Index diag13 = s2->find_edge(1, 3);
  const Index diag02 = s1->find_edge(0, 2);
  for (Index e = 0; e < s2->edge_count(); ++e) {
    if (e == diag13) {
      const EdgeCrossing c{diag02, 0.5};
      b.add_edge(e, std::span(&c, 1));
    } else {
      b.add_edge(e);
    }
  }
  const PlMap<2> m = std::move(b).finalize();
  EXPECT_EQ(count_type(m, NodeType::intersection), 2);  // one copy per S1 triangle
  EXPECT_EQ(m.region_count(), 4);
  const auto c = covered_measure(m);
  EXPECT_NEAR(c.domain, 1.0, 1e-15);
  EXPECT_NEAR(c.target, 1.0, 1e-15);
  // the intersection node maps to the centre of the square
  for (Index n = 0; n < m.node_count(); ++n)
    if (m.data().node_type[n] == NodeType::intersection) {
      EXPECT_NEAR((m.node_target_world(n) - P(0.5, 0.5)).norm(), 0.0, 1e-15);
      EXPECT_NEAR((m.node_domain_world(n) - P(0.5, 0.5)).norm(), 0.0, 1e-15);
    }
}

TEST(MapBuilder, EdgeThroughAnS1VertexCreatesAGhostNodeAndRunsAlongEdges) {
  // S1: unit square with a centre vertex (4 triangles); S2: unit square, diagonal 0-2, which runs
  // along the S1 edges 0-4 and 4-2 through the centre vertex 4.
  auto s1 = make_surface({P(0, 0), P(1, 0), P(1, 1), P(0, 1), P(0.5, 0.5)},
                         {{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}});
  auto s2 = square_diag02();
  MapBuilder<2> b(s1, s2);
  for (Index v = 0; v < 4; ++v) b.add_vertex_preimage_at_vertex(v, v);
  const Index diag = s2->find_edge(0, 2);
  for (Index e = 0; e < s2->edge_count(); ++e) {
    if (e == diag) {
      const EdgeCrossing c{s1->find_edge(0, 4), 1.0};
      b.add_edge(e, std::span(&c, 1));
    } else {
      b.add_edge(e);
    }
  }
  const PlMap<2> m = std::move(b).finalize();
  EXPECT_EQ(count_type(m, NodeType::ghost), 4);  // the centre, once per S1 triangle
  EXPECT_EQ(m.region_count(), 4);
  const auto c = covered_measure(m);
  EXPECT_NEAR(c.domain, 1.0, 1e-15);
  EXPECT_NEAR(c.target, 1.0, 1e-15);
  for (Index n = 0; n < m.node_count(); ++n)
    if (m.data().node_type[n] == NodeType::ghost) {
      EXPECT_NEAR((m.node_target_world(n) - P(0.5, 0.5)).norm(), 0.0, 1e-15);
    }
}

TEST(MapBuilder, PartialCoverageLeavesTheRestOutsideD) {
  // S2 covers only the lower-right triangle of S1's first element.
  auto s1 = square_diag02();
  auto s2 = make_surface({P(0, 0), P(1, 0), P(1, 0.5)}, {{0, 1, 2}});
  MapBuilder<2> b(s1, s2);
  b.add_vertex_preimage_at_vertex(0, 0);
  b.add_vertex_preimage_at_vertex(1, 1);
  b.add_vertex_preimage(2, {0, LocalPoint<2>(0.5, 0.5)});  // on S1 edge 1-2
  b.add_target_element(0);
  const PlMap<2> m = std::move(b).finalize();
  EXPECT_EQ(m.region_count(), 1);
  EXPECT_EQ(count_type(m, NodeType::touching), 1);
  EXPECT_NEAR(covered_measure(m).domain, 0.25, 1e-15);
  EXPECT_EQ(m.data().start_region[1], invalid_index);
}

TEST(MapBuilder, RejectsInconsistentInput) {
  auto s = square_diag02();
  {
    MapBuilder<2> b(s, s);
    b.add_vertex_preimage_at_vertex(0, 0);
    EXPECT_THROW(b.add_vertex_preimage_at_vertex(0, 1), BuilderError);  // second preimage
    EXPECT_THROW(b.add_vertex_preimage_at_vertex(1, 0), BuilderError);  // vertex taken
    EXPECT_THROW(b.add_vertex_preimage_at_vertex(7, 1), BuilderError);  // no such S2 vertex
    EXPECT_THROW(b.add_target_element(0), BuilderError);                 // missing preimages
    EXPECT_THROW(b.add_vertex_preimage(1, {0, LocalPoint<2>(2.0, 0.0)}), BuilderError);
    EXPECT_THROW(b.add_vertex_preimage(1, {0, LocalPoint<2>(NAN, 0.0)}), BuilderError);
  }
  {
    // S2's diagonal 1-3 inserted without its crossing with S1's diagonal 0-2
    auto s2 = square_diag13();
    MapBuilder<2> b(s, s2);
    for (Index v = 0; v < 4; ++v) b.add_vertex_preimage_at_vertex(v, v);
    EXPECT_THROW(b.add_edge(s2->find_edge(1, 3)), BuilderError);
  }
}

TEST(MapBuilder, PolylineWithGhostNode) {
  auto s1 = std::make_shared<const Surface<1>>(
      std::vector<WorldPoint<1>>{{0, 0}, {1, 0}, {2, 0}}, std::vector<ElementCorners<1>>{{0, 1}, {1, 2}});
  auto s2 = std::make_shared<const Surface<1>>(
      std::vector<WorldPoint<1>>{{0, 0}, {0.5, 0}, {2, 0}}, std::vector<ElementCorners<1>>{{0, 1}, {1, 2}});
  MapBuilder<1> b(s1, s2);
  b.add_vertex_preimage_at_vertex(0, 0);
  b.add_vertex_preimage(1, {0, LocalPoint<1>(0.5)});
  b.add_vertex_preimage_at_vertex(2, 2);
  b.add_edge(0);
  const VertexCrossing through{1};
  b.add_edge(1, std::span(&through, 1));
  const PlMap<1> m = std::move(b).finalize();
  EXPECT_EQ(m.region_count(), 3);
  const auto c = covered_measure(m);
  EXPECT_NEAR(c.domain, 2.0, 1e-15);
  EXPECT_NEAR(c.target, 2.0, 1e-15);
  int ghosts = 0;
  for (Index n = 0; n < m.node_count(); ++n)
    if (m.data().node_type[n] == NodeType::ghost) {
      ++ghosts;
      EXPECT_NEAR((m.node_target_world(n) - WorldPoint<1>(1, 0)).norm(), 0.0, 1e-15);
    }
  EXPECT_EQ(ghosts, 2);
}

TEST(MapBuilder, EdgePiecesCoverUpToTheDomainBoundary) {
  // S2 is a triangle A B C with B outside the unit square S1; the edges A-B and B-C leave S1
  // through its right side x = 1, so they are inserted as pieces up to that boundary.
  auto s1 = square_diag02();
  auto s2 = make_surface({P(0.3, 0.2), P(1.5, 0.2), P(0.3, 0.7)}, {{0, 1, 2}});
  MapBuilder<2> b(s1, s2);
  b.add_vertex_preimage(0, {0, LocalPoint<2>(0.1, 0.2)});  // A = c0 + 0.1 (c1 - c0) + 0.2 (c2 - c0)
  b.add_vertex_preimage(2, {1, LocalPoint<2>(0.3, 0.4)});  // C on element (0, 2, 3)
  const Index right = s1->find_edge(1, 2), diag = s1->find_edge(0, 2);
  const double s_bc = (1.5 - 1.0) / 1.2;          // where B-C enters S1
  const double s_x = 1.3 / 1.7;                   // where B-C crosses the diagonal
  const double x_diag = 1.5 - 1.2 * s_x;
  {
    const EdgeCrossing exit{right, 0.2, (1.0 - 0.3) / 1.2};
    b.add_edge_piece(s2->find_edge(0, 1), std::span(&exit, 1), PieceStart::first_vertex, PieceEnd::last_crossing);
  }
  {
    const std::array<EdgeCrossing, 2> path{EdgeCrossing{right, 0.2 + 0.5 * s_bc, s_bc},
                                           EdgeCrossing{diag, x_diag, s_x}};
    b.add_edge_piece(s2->find_edge(1, 2), path, PieceStart::first_crossing, PieceEnd::second_vertex);
  }
  {
    const EdgeCrossing through{diag, 0.3};
    b.add_edge(s2->find_edge(0, 2), std::span(&through, 1));
  }
  EXPECT_THROW(b.add_edge(s2->find_edge(0, 1)), BuilderError);  // already inserted in pieces
  const PlMap<2> m = std::move(b).finalize();
  const double expected = 0.7 * (0.5 + 0.5 * s_bc) / 2.0;  // trapezoid x in [0.3, 1]
  const auto c = covered_measure(m);
  EXPECT_NEAR(c.domain, expected, 1e-14);
  EXPECT_NEAR(c.target, expected, 1e-14);
  EXPECT_EQ(count_type(m, NodeType::ghost), 0);
  EXPECT_EQ(count_type(m, NodeType::intersection), 2 + 2 * 2);  // two on x = 1, two diagonal crossings twice
}

// finalize() closes most elements by tracing the graph's faces; a graph part that floats inside
// a face (here a whole S2 triangle inside one S1 element, touching no S1 edge) is not a plain
// tiling, so that element goes through the constrained triangulation instead. Both must give
// the same kind of result: one region per S2 triangle, neighbours in ccw order.
TEST(MapBuilder, TargetTriangleFloatingInsideAnElement) {
  auto s1 = square_diag02();
  auto s2 = make_surface({P(0.5, 0.2), P(0.8, 0.2), P(0.8, 0.5)}, {{0, 1, 2}});
  MapBuilder<2> b(s1, s2);
  b.add_vertex_preimage(0, {0, LocalPoint<2>(0.3, 0.2)});  // element 0 is (0,0),(1,0),(1,1)
  b.add_vertex_preimage(1, {0, LocalPoint<2>(0.6, 0.2)});
  b.add_vertex_preimage(2, {0, LocalPoint<2>(0.3, 0.5)});
  b.add_target_element(0);
  const PlMap<2> m = std::move(b).finalize();
  ASSERT_EQ(m.region_count(), 1);
  EXPECT_EQ(count_type(m, NodeType::interior), 3);
  EXPECT_NEAR(covered_measure(m).domain, 0.045, 1e-15);
  EXPECT_NEAR(covered_measure(m).target, 0.045, 1e-15);
  // each of the three nodes sees the two others, along S2 edges
  for (Index n = 0; n < m.node_count(); ++n) {
    ASSERT_EQ(m.neighbors(n).size(), 2u) << "node " << n;
    for (Index i = m.data().neighbor_begin[n]; i < m.data().neighbor_begin[n + 1]; ++i)
      EXPECT_EQ(m.data().neighbor_edge_kind[i], GraphEdgeKind::target_edge);
  }
  const auto ri = remote_intersection(m, 0);
  const LocalPoint<2> a = ri.domain_local[1] - ri.domain_local[0];
  const LocalPoint<2> c = ri.domain_local[2] - ri.domain_local[0];
  EXPECT_NEAR(a.x() * c.y() - a.y() * c.x(), 0.09, 1e-15);  // counter-clockwise corners
}

// Nodes on an element edge with no graph edge inside that element: the element's face is a
// polygon with a run of collinear vertices (here it touches a missing corner, so it lies outside
// D), which the ear clipping must cut without degenerate triangles. The other element carries a
// fan whose triangles each become one region.
TEST(MapBuilder, CollinearNodesOnAnEdgeAreHandledOnBothSides) {
  auto s1 = square_diag02();  // elements (0,1,2) and (0,2,3); the diagonal is S1 edge 0-2
  const int k = 8;
  std::vector<WorldPoint<2>> v{P(0, 0), P(1, 0), P(1, 1)};
  for (int i = 1; i < k; ++i) v.push_back(P(i / double(k), i / double(k)));
  auto diagonal = [&](int i) -> Index { return i == 0 ? 0 : (i == k ? 2 : 2 + i); };
  std::vector<ElementCorners<2>> e;
  for (int i = 0; i < k; ++i) e.push_back({1, diagonal(i + 1), diagonal(i)});
  auto s2 = make_surface(std::move(v), std::move(e));
  MapBuilder<2> b(s1, s2);
  for (Index q = 0; q < 3; ++q) b.add_vertex_preimage_at_vertex(q, q);
  // on element 0, local (xi, eta) is the point (xi + eta, eta): the diagonal is xi = 0
  for (int i = 1; i < k; ++i) b.add_vertex_preimage(diagonal(i), {0, LocalPoint<2>(0.0, i / double(k))});
  for (Index t = 0; t < s2->element_count(); ++t) b.add_target_element(t);
  const PlMap<2> m = std::move(b).finalize();
  EXPECT_EQ(m.region_count(), k);
  EXPECT_EQ(count_type(m, NodeType::touching), 2 * (k - 1));  // one copy on each side
  EXPECT_NEAR(covered_measure(m).domain, 0.5, 1e-15);
  EXPECT_NEAR(covered_measure(m).target, 0.5, 1e-15);
  for (Index r = 0; r < m.region_count(); ++r) {
    const auto ri = remote_intersection(m, r);
    EXPECT_EQ(ri.domain_element, 0);
    const LocalPoint<2> a = ri.domain_local[1] - ri.domain_local[0];
    const LocalPoint<2> c = ri.domain_local[2] - ri.domain_local[0];
    EXPECT_NEAR(a.x() * c.y() - a.y() * c.x(), 1.0 / k, 1e-12) << "region " << r;
  }
  EXPECT_EQ(m.data().start_region[1], invalid_index);
}

// finalize() closes and assembles blocks of elements on several threads and concatenates them;
// the result must be the same map, array for array, whatever the thread count.
TEST(MapBuilder, ResultDoesNotDependOnTheThreadCount) {
  const int n = 16;  // 512 triangles: enough for several blocks
  std::vector<WorldPoint<2>> v;
  std::vector<ElementCorners<2>> e;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) v.push_back(P(i / double(n), j / double(n)));
  auto id = [&](int i, int j) { return static_cast<Index>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      e.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      e.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  auto s1 = make_surface(v, e);
  // S2: the same square grid cut along the other diagonals, so edges cross inside elements.
  std::vector<ElementCorners<2>> e2;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      e2.push_back({id(i, j), id(i + 1, j), id(i, j + 1)});
      e2.push_back({id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  auto s2 = make_surface(v, e2);
  auto build = [&](unsigned threads) {
    BuilderOptions options;
    options.threads = threads;
    MapBuilder<2> b(s1, s2, options);
    for (Index q = 0; q < s2->vertex_count(); ++q) b.add_vertex_preimage_at_vertex(q, q);
    // the diagonal (i+1, j) - (i, j+1) of S2 crosses S1's diagonal (i, j) - (i+1, j+1) in its middle
    for (Index edge = 0; edge < s2->edge_count(); ++edge) {
      const auto ends = s2->edge_vertices(edge);
      const LocalPoint<2> a = s2->vertex(ends[0]).head<2>(), c = s2->vertex(ends[1]).head<2>();
      if ((c - a).x() * (c - a).y() >= 0) {
        b.add_edge(edge);
        continue;
      }
      const int i = static_cast<int>(std::lround(std::min(a.x(), c.x()) * n));
      const int j = static_cast<int>(std::lround(std::min(a.y(), c.y()) * n));
      const Index crossed = s1->find_edge(id(i, j), id(i + 1, j + 1));
      EdgeCrossing x;
      x.domain_edge = crossed;
      x.domain_parameter = 0.5;
      b.add_edge(edge, std::span<const EdgeCrossing>(&x, 1));
    }
    return std::move(b).finalize();
  };
  const PlMap<2> one = build(1), three = build(3);
  const auto& a = one.data();
  const auto& c = three.data();
  ASSERT_EQ(one.region_count(), 4 * n * n);  // every S1 triangle is cut in two
  EXPECT_EQ(a.node_begin, c.node_begin);
  EXPECT_EQ(a.node_type, c.node_type);
  EXPECT_EQ(a.node_target, c.node_target);
  EXPECT_EQ(a.neighbor_begin, c.neighbor_begin);
  EXPECT_EQ(a.neighbor, c.neighbor);
  EXPECT_EQ(a.edge_node_begin, c.edge_node_begin);
  EXPECT_EQ(a.edge_node, c.edge_node);
  EXPECT_EQ(a.region_begin, c.region_begin);
  EXPECT_EQ(a.region_corners, c.region_corners);
  EXPECT_EQ(a.region_neighbors, c.region_neighbors);
  EXPECT_EQ(a.region_target, c.region_target);
  EXPECT_EQ(a.start_region, c.start_region);
  for (std::size_t r = 0; r < a.region_map.size(); ++r) ASSERT_EQ(a.region_map[r], c.region_map[r]) << r;
  EXPECT_NEAR(covered_measure(three).domain, 1.0, 1e-12);
  // With more threads than the machine has, the blocks of the threads that start late are
  // partly closed by those that finished first (work stealing), differently from run to run:
  // still the same map, every time.
  for (int repeat = 0; repeat < 8; ++repeat) EXPECT_TRUE(build(8).data() == a) << "repeat " << repeat;
}

// Conflicts in several blocks of the closing pass: once an element fails anywhere, every block
// only collects failures (the parts are discarded); the drops, the report and the map must still
// be the same for every thread count. S1 is 240 separate triangles, S2 puts two vertices inside
// each, swapped (so that edges cross) on three triangles far apart: in the first, middle and last
// block.
TEST(MapBuilder, DroppedConflictsDoNotDependOnTheThreadCount) {
  const Index copies = 240;
  const std::array<Index, 3> swapped = {5, 121, 233};
  std::vector<WorldPoint<2>> v1, v2;
  std::vector<ElementCorners<2>> e1, e2;
  for (Index c = 0; c < copies; ++c) {
    const double x = 2.0 * c;
    v1.insert(v1.end(), {P(x, 0), P(x + 1, 0), P(x, 1)});
    e1.push_back({3 * c, 3 * c + 1, 3 * c + 2});
    const Index o = 5 * c;
    v2.insert(v2.end(), {P(x, 0), P(x + 1, 0), P(x, 1), P(x + 0.2, 0.2), P(x + 0.4, 0.4)});
    for (const auto& t : std::vector<ElementCorners<2>>{{0, 1, 3}, {1, 4, 3}, {1, 2, 4}, {2, 3, 4}, {2, 0, 3}})
      e2.push_back({o + t[0], o + t[1], o + t[2]});
  }
  auto s1 = make_surface(v1, e1);
  auto s2 = make_surface(v2, e2);
  auto build = [&](unsigned threads, FinalizeReport& report, bool drop = true) {
    BuilderOptions options;
    options.threads = threads;
    options.drop_conflicting_edges = drop;
    MapBuilder<2> b(s1, s2, options);
    for (Index c = 0; c < copies; ++c) {
      for (Index k = 0; k < 3; ++k) b.add_vertex_preimage_at_vertex(5 * c + k, 3 * c + k);
      const bool swap = std::find(swapped.begin(), swapped.end(), c) != swapped.end();
      b.add_vertex_preimage(5 * c + 3, {c, swap ? LocalPoint<2>(0.4, 0.4) : LocalPoint<2>(0.2, 0.2)});
      b.add_vertex_preimage(5 * c + 4, {c, swap ? LocalPoint<2>(0.2, 0.2) : LocalPoint<2>(0.4, 0.4)});
    }
    for (Index t = 0; t < s2->element_count(); ++t) b.add_target_element(t);
    return std::move(b).finalize(&report);
  };
  FinalizeReport report1;
  const PlMap<2> one = build(1, report1);
  // the conflicts are dropped where they are, and only there
  ASSERT_FALSE(report1.dropped_edges.empty());
  std::vector<Index> elements = report1.dropped_edge_element;
  std::sort(elements.begin(), elements.end());
  elements.erase(std::unique(elements.begin(), elements.end()), elements.end());
  EXPECT_EQ(elements, std::vector<Index>(swapped.begin(), swapped.end()));
  EXPECT_EQ(one.regions_end(0) - one.regions_begin(0), 5);  // an element without conflict keeps all five
  for (unsigned threads : {2u, 3u, 3u, 3u, 8u, 8u, 8u}) {  // repeated: the work stealing differs from run to run
    FinalizeReport report;
    const PlMap<2> other = build(threads, report);
    EXPECT_EQ(report.dropped_edges, report1.dropped_edges) << threads << " threads";
    EXPECT_EQ(report.dropped_edge_element, report1.dropped_edge_element) << threads << " threads";
    EXPECT_TRUE(one.data() == other.data()) << threads << " threads";
  }
  // Without drop_conflicting_edges finalize throws the error of the first element that fails,
  // whatever the thread count and however the elements were split among the threads.
  auto error_of = [&](unsigned threads) -> std::string {
    FinalizeReport report;
    try {
      (void)build(threads, report, false);
    } catch (const BuilderError& e) {
      return e.what();
    }
    return "no error";
  };
  const std::string first = error_of(1);
  EXPECT_NE(first, "no error");
  EXPECT_NE(first.find("element 5"), std::string::npos) << first;
  for (unsigned threads : {2u, 3u, 8u, 8u, 8u}) EXPECT_EQ(error_of(threads), first) << threads << " threads";
}

// Inconsistent input, as a folding projection produces it: two S2 vertex preimages are swapped,
// so the preimage of S2 edge 0-3 runs through the preimage of vertex 4 and other edges cross.
// By default finalize() refuses; with drop_conflicting_edges it leaves out the S2 edges
// involved, reports them, and keeps the rest of the map.
TEST(MapBuilder, ConflictingEdgesAreRejectedOrDropped) {
  auto s1 = make_surface({P(0, 0), P(1, 0), P(0, 1)}, {{0, 1, 2}});
  auto s2 = make_surface({P(0, 0), P(1, 0), P(0, 1), P(0.2, 0.2), P(0.4, 0.4)},
                         {{0, 1, 3}, {1, 4, 3}, {1, 2, 4}, {2, 3, 4}, {2, 0, 3}});
  auto enter = [&](MapBuilder<2>& b) {
    for (Index q = 0; q < 3; ++q) b.add_vertex_preimage_at_vertex(q, q);
    b.add_vertex_preimage(3, {0, LocalPoint<2>(0.4, 0.4)});  // swapped with vertex 4
    b.add_vertex_preimage(4, {0, LocalPoint<2>(0.2, 0.2)});
    for (Index t = 0; t < s2->element_count(); ++t) b.add_target_element(t);
  };
  {
    MapBuilder<2> b(s1, s2);
    enter(b);
    EXPECT_THROW((void)std::move(b).finalize(), BuilderError);
  }
  BuilderOptions options;
  options.drop_conflicting_edges = true;
  MapBuilder<2> b(s1, s2, options);
  enter(b);
  FinalizeReport report;
  const PlMap<2> m = std::move(b).finalize(&report);
  ASSERT_FALSE(report.dropped_edges.empty());
  EXPECT_EQ(report.dropped_edges.size(), report.dropped_edge_element.size());
  const Index e03 = s2->find_edge(0, 3);
  EXPECT_NE(std::find(report.dropped_edges.begin(), report.dropped_edges.end(), e03), report.dropped_edges.end());
  for (Index t : report.dropped_edge_element) EXPECT_EQ(t, 0);
  // what is left are regions of S2 triangles none of whose edges was dropped
  EXPECT_LT(m.region_count(), 5);
  for (Index r = 0; r < m.region_count(); ++r)
    for (int k = 0; k < 3; ++k) {
      const Index e = s2->element_edge(m.data().region_target[r], k);
      EXPECT_EQ(std::find(report.dropped_edges.begin(), report.dropped_edges.end(), e), report.dropped_edges.end());
    }
  EXPECT_LT(covered_measure(m).domain, 0.5);
}

// d = 1: S2 vertex 2's preimage lies between those of vertices 0 and 1, so the preimage of
// segment 0-1 passes over it (a fold). By default finalize() refuses; with
// drop_conflicting_edges segment 0 is left out and reported, segment 1 stays.
TEST(MapBuilder, PolylineSegmentOverAnotherNodeIsRejectedOrDropped) {
  auto s1 = std::make_shared<const Surface<1>>(std::vector<WorldPoint<1>>{{0, 0}, {1, 0}},
                                               std::vector<ElementCorners<1>>{{0, 1}});
  auto s2 = std::make_shared<const Surface<1>>(std::vector<WorldPoint<1>>{{0, 0}, {0.8, 0}, {0.4, 0}},
                                               std::vector<ElementCorners<1>>{{0, 1}, {1, 2}});
  auto enter = [&](MapBuilder<1>& b) {
    b.add_vertex_preimage_at_vertex(0, 0);
    b.add_vertex_preimage(1, {0, LocalPoint<1>(0.8)});
    b.add_vertex_preimage(2, {0, LocalPoint<1>(0.4)});
    b.add_target_element(0);
    b.add_target_element(1);
  };
  {
    MapBuilder<1> b(s1, s2);
    enter(b);
    EXPECT_THROW((void)std::move(b).finalize(), BuilderError);
  }
  BuilderOptions options;
  options.drop_conflicting_edges = true;
  MapBuilder<1> b(s1, s2, options);
  enter(b);
  FinalizeReport report;
  const PlMap<1> m = std::move(b).finalize(&report);
  ASSERT_EQ(report.dropped_edges, std::vector<Index>{0});
  ASSERT_EQ(m.region_count(), 1);
  EXPECT_EQ(m.data().region_target[0], 1);
  EXPECT_NEAR(covered_measure(m).domain, 0.4, 1e-15);
}

// d = 1: a segment whose preimage runs against the map's orientation (the projection folded
// there) is not a region, as for the faces of triangle surfaces: S1 is [0, 2], S2 three
// separate segments, two entered along S1's direction and one (C-D) against it.
TEST(MapBuilder, PolylinePiecesAgainstTheMapsOrientationAreNotRegions) {
  auto s1 = std::make_shared<const Surface<1>>(std::vector<WorldPoint<1>>{{0, 0}, {1, 0}, {2, 0}},
                                               std::vector<ElementCorners<1>>{{0, 1}, {1, 2}});
  auto s2 = std::make_shared<const Surface<1>>(
      std::vector<WorldPoint<1>>{{0, 1}, {1, 1}, {2, 1}, {3, 1}, {4, 1}, {5, 1}},
      std::vector<ElementCorners<1>>{{0, 1}, {2, 3}, {4, 5}});
  auto enter = [&](MapBuilder<1>& b) {
    b.add_vertex_preimage(0, {0, LocalPoint<1>(0.1)});  // A-B forwards on element 0
    b.add_vertex_preimage(1, {0, LocalPoint<1>(0.4)});
    b.add_vertex_preimage(2, {0, LocalPoint<1>(0.9)});  // C-D backwards on element 0
    b.add_vertex_preimage(3, {0, LocalPoint<1>(0.6)});
    b.add_vertex_preimage(4, {1, LocalPoint<1>(0.2)});  // E-F forwards on element 1
    b.add_vertex_preimage(5, {1, LocalPoint<1>(0.7)});
    for (Index s = 0; s < 3; ++s) b.add_edge(s);
  };
  {
    MapBuilder<1> b(s1, s2);
    enter(b);
    FinalizeReport report;
    const PlMap<1> m = std::move(b).finalize(&report);
    EXPECT_EQ(report.reversed_faces, 1);
    EXPECT_EQ(m.data().orientation, 1);  // two pieces against one
    ASSERT_EQ(m.region_count(), 2);
    EXPECT_EQ(m.data().region_target[0], 0);
    EXPECT_EQ(m.data().region_target[1], 2);
    EXPECT_NEAR(covered_measure(m).domain, 0.3 + 0.5, 1e-15);
    // the nodes of the left-out piece stay, without graph neighbours
    for (Index n = m.nodes_begin(0); n < m.nodes_end(0); ++n) {
      if (m.data().node_target[n] == 2 || m.data().node_target[n] == 3) {
        EXPECT_TRUE(m.neighbors(n).empty());
      }
    }
  }
  BuilderOptions reversed;
  reversed.orientation = -1;
  MapBuilder<1> b(s1, s2, reversed);
  enter(b);
  const PlMap<1> m = std::move(b).finalize();
  ASSERT_EQ(m.region_count(), 1);
  EXPECT_EQ(m.data().region_target[0], 1);
}

// d = 2: three separate S2 triangles drawn inside the two triangles of the unit square, one of
// them with its corners in clockwise order. Its face maps with the orientation opposite to the
// other two and is not a region; the report counts it.
TEST(MapBuilder, AFaceMappedAgainstTheMapsOrientationIsNotARegionAndIsCounted) {
  auto s1 = square_diag02();  // triangles (0, 1, 2) below the diagonal, (0, 2, 3) above
  std::vector<WorldPoint<2>> v;
  std::vector<ElementCorners<2>> e;
  for (int k = 0; k < 3; ++k) {
    v.insert(v.end(), {P(3 * k, 0), P(3 * k + 1, 0), P(3 * k, 1)});
    e.push_back({3 * k, 3 * k + 1, 3 * k + 2});
  }
  auto s2 = make_surface(std::move(v), std::move(e));
  // element 0: local (x, y) with x + y < 1; triangle 0 counter-clockwise, triangle 1 clockwise
  // in element 0, triangle 2 counter-clockwise in element 1
  const std::array<std::array<LocalPoint<2>, 3>, 3> at = {{
      {LocalPoint<2>(0.1, 0.1), LocalPoint<2>(0.3, 0.1), LocalPoint<2>(0.1, 0.3)},
      {LocalPoint<2>(0.5, 0.1), LocalPoint<2>(0.5, 0.3), LocalPoint<2>(0.7, 0.1)},
      {LocalPoint<2>(0.1, 0.1), LocalPoint<2>(0.3, 0.1), LocalPoint<2>(0.1, 0.3)},
  }};
  MapBuilder<2> b(s1, s2);
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < 3; ++i) b.add_vertex_preimage(3 * k + i, {k == 2 ? 1 : 0, at[k][i]});
  for (Index t = 0; t < 3; ++t) b.add_target_element(t);
  FinalizeReport report;
  const PlMap<2> m = std::move(b).finalize(&report);
  EXPECT_EQ(m.data().orientation, 1);
  EXPECT_EQ(report.reversed_faces, 1);
  ASSERT_EQ(m.region_count(), 2);
  EXPECT_EQ(m.data().region_target[0], 0);
  EXPECT_EQ(m.data().region_target[1], 2);
  EXPECT_NEAR(covered_measure(m).target, 1.0, 1e-15);  // two of the three S2 triangles
}

namespace {

// S2 over the single S1 triangle (0,0), (1,0), (0,1): its corners 0, 1, 2 and an inner triangle
// 3, 4, 5 joined to them by six triangles (the inner one only `with_inner`, else S2 has a hole
// there). Every vertex maps to its own position; `missing` S2 edges are not inserted.
PlMap<2> annulus_over_one_triangle(bool with_inner, const std::vector<std::array<Index, 2>>& missing,
                                   FinalizeReport& report) {
  auto s1 = make_surface({P(0, 0), P(1, 0), P(0, 1)}, {{0, 1, 2}});
  const std::vector<WorldPoint<2>> v = {P(0, 0), P(1, 0), P(0, 1), P(0.2, 0.2), P(0.5, 0.2), P(0.2, 0.5)};
  std::vector<ElementCorners<2>> e = {{0, 1, 4}, {0, 4, 3}, {1, 2, 5}, {1, 5, 4}, {2, 0, 3}, {2, 3, 5}};
  if (with_inner) e.push_back({3, 4, 5});
  auto s2 = make_surface(v, std::move(e));
  MapBuilder<2> b(s1, s2);
  for (Index q = 0; q < 3; ++q) b.add_vertex_preimage_at_vertex(q, q);
  for (Index q = 3; q < 6; ++q) b.add_vertex_preimage(q, {0, LocalPoint<2>(v[q].x(), v[q].y())});
  for (Index k = 0; k < s2->edge_count(); ++k)
    if (std::none_of(missing.begin(), missing.end(),
                     [&](const std::array<Index, 2>& ends) { return s2->find_edge(ends[0], ends[1]) == k; }))
      b.add_edge(k);
  return std::move(b).finalize(&report);
}

std::string violations_of(const PlMap<2>& map) {
  std::string text;
  for (const auto& check : verify(map).checks)
    for (const auto& v : check.violations) text += check.name + "/" + v.rule + ": " + v.message + "\n";
  return text;
}

}  // namespace

// A face left out of D that lies strictly inside its element, whose boundary the regions cover
// (an S2 edge between S2 vertices inside the element is missing: the quadrilateral 0-4-5-3
// touches the element boundary only at a corner), would leave a hole that verify rejects
// (region_tiling: a fully covered element must be covered entirely). The element leaves D whole,
// as remove_faces clears an element whose removed face lies strictly inside it. Normal projection
// of a coarse copy onto the fine bones mesh wrote such maps.
TEST(MapBuilder, AnUnmappedFaceStrictlyInsideAFullyCoveredElementTakesTheElement) {
  FinalizeReport report;
  const PlMap<2> m = annulus_over_one_triangle(true, {{3, 4}}, report);
  EXPECT_EQ(report.unmapped_faces, 1);
  EXPECT_EQ(m.region_count(), 0);
  EXPECT_EQ(covered_measure(m).domain, 0.0);
  EXPECT_EQ(count_type(m, NodeType::interior), 3);  // the graph stays
  EXPECT_EQ(violations_of(m), "");
}

// The same gap where S2 has a hole (no inner triangle) is D's hole, not a missing region: the
// element keeps the six regions around it.
TEST(MapBuilder, AHoleOfS2StrictlyInsideAnElementKeepsTheRegionsAroundIt) {
  FinalizeReport report;
  const PlMap<2> m = annulus_over_one_triangle(false, {}, report);
  EXPECT_EQ(report.unmapped_faces, 1);
  EXPECT_EQ(m.region_count(), 6);
  EXPECT_NEAR(covered_measure(m).domain, 0.5 - 0.045, 1e-15);
  EXPECT_EQ(violations_of(m), "");
}

// A gap that reaches the element boundary (without the S2 edge 0-4, the face 0-1-4-3 has the
// side 0-1 on it) leaves the other regions.
TEST(MapBuilder, AnUnmappedFaceOnTheElementBoundaryLeavesTheOtherRegions) {
  FinalizeReport report;
  const PlMap<2> m = annulus_over_one_triangle(true, {{0, 4}}, report);
  EXPECT_EQ(report.unmapped_faces, 1);
  EXPECT_EQ(m.region_count(), 5);
  EXPECT_EQ(violations_of(m), "");
}

// A preimage through an S1 vertex whose ghost node (a ray hit) maps off the S2 edge would make
// graph edges labelled with that edge whose ends lie on no common S2 edge (verify's
// unlabelled_target_edge). Normal projection of boeing.off onto itself wrote such maps: its
// patches are not stitched, and a vertex's ray hit lies on a coincident copy of the edge. The
// builder refuses the preimage, before it has made any of its nodes.
TEST(MapBuilder, APreimageThroughAGhostNodeThatMapsOffTheEdgeIsRefused) {
  auto s1 = square_diag02();  // triangles (0, 1, 2) and (0, 2, 3)
  // S2 element 0 = (0, 1, 2) holds the edge; element 1, apart, the ghost's image
  auto s2 = make_surface({P(0, 0), P(1, 0), P(0, 1), P(3, 0), P(4, 0), P(3, 1)}, {{0, 1, 2}, {3, 4, 5}});
  MapBuilder<2> b(s1, s2);
  b.add_vertex_preimage(0, {1, LocalPoint<2>(0.2, 0.5)});  // inside S1 triangle (0, 2, 3)
  b.add_vertex_preimage(1, {0, LocalPoint<2>(0.5, 0.2)});  // inside S1 triangle (0, 1, 2)
  b.add_ghost_node(0, {1, LocalPoint<2>(0.2, 0.2)});
  // S2 edge 0-1 passes S1 vertex 0, the start of S1 edge 0-2
  const EdgeCrossing through_vertex{s1->find_edge(0, 2), 0.0};
  EXPECT_THROW(b.add_edge(s2->find_edge(0, 1), std::span(&through_vertex, 1)), BuilderError);
  const PlMap<2> m = std::move(b).finalize();
  EXPECT_EQ(count_type(m, NodeType::ghost), 2);  // one copy per S1 triangle at vertex 0
  EXPECT_EQ(count_type(m, NodeType::intersection), 0);
  EXPECT_EQ(violations_of(m), "");
}
