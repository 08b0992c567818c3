// MapBuilder: D ending inside S1 elements, on a rim of rim nodes and rim edges (the curve where a
// projection reaches its distance limit), instead of at the last S1 edge an S2 edge crosses.
//
// S1 is the unit square split along the diagonal 0-2, S2 the same square split along 1-3, and
// the map is the identity restricted to x <= 0.6: the rim is the line x = 0.6. It crosses S1
// edge 0-1 at (0.6, 0), the S2 edge 1-3 inside S1 element 0 at (0.6, 0.4), where that edge's
// preimage ends, the S1 diagonal at (0.6, 0.6) (image inside S2 element 1) and S1 edge 2-3 at
// (0.6, 1). So D ends inside S1 element 0 and 1, and the exact answer is known everywhere.
#include <plmap/core/errors.hpp>
#include <plmap/core/evaluation.hpp>
#include <plmap/core/io/map_file.hpp>
#include <plmap/core/map_builder.hpp>
#include <plmap/core/regions.hpp>
#include <plmap/verify/check.hpp>
#include <plmap/verify/deepest_region_locator.hpp>

#include <gtest/gtest.h>

#include "../verify_violations.hpp"

#include <algorithm>
#include <filesystem>
#include <memory>
#include <string>

#include <unistd.h>

using namespace plmap;
using plmap::test::verify_violations;

namespace {

std::shared_ptr<const Surface<2>> make_square(std::vector<ElementCorners<2>> elements) {
  std::vector<WorldPoint<2>> v{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  return std::make_shared<const Surface<2>>(std::move(v), std::move(elements));
}

int count_type(const PlMap<2>& m, NodeType t) {
  return static_cast<int>(std::count(m.data().node_type.begin(), m.data().node_type.end(), t));
}

/// The point (x, y) of the unit square as a point of S1 (elements (0, 1, 2) below the diagonal,
/// (0, 2, 3) above it).
SurfacePoint<2> on_s1(double x, double y) {
  if (y <= x) return {0, LocalPoint<2>(x - y, y)};
  return {1, LocalPoint<2>(x, y - x)};
}

/// The point (x, y) as a point of S2 (elements (0, 1, 3) below the diagonal x + y = 1, (1, 2, 3)
/// above it).
SurfacePoint<2> on_s2(double x, double y) {
  if (x + y <= 1.0) return {0, LocalPoint<2>(x, y)};
  return {1, LocalPoint<2>(x + y - 1.0, 1.0 - x)};
}

struct RimMap {
  std::shared_ptr<const Surface<2>> s1 = make_square({{0, 1, 2}, {0, 2, 3}});
  std::shared_ptr<const Surface<2>> s2 = make_square({{0, 1, 3}, {1, 2, 3}});
  MapBuilder<2> builder{s1, s2};

  /// Enters everything but the rim edges; returns the rim nodes in order along x = 0.6.
  std::array<MapBuilder<2>::NodeHandle, 4> enter_nodes_and_pieces() {
    auto& b = builder;
    b.add_vertex_preimage_at_vertex(0, 0);
    b.add_vertex_preimage_at_vertex(3, 3);
    std::array<MapBuilder<2>::NodeHandle, 4> rim{};
    const double ys[4] = {0.0, 0.4, 0.6, 1.0};
    for (int i = 0; i < 4; ++i) rim[i] = b.add_rim_node(on_s1(0.6, ys[i]), on_s2(0.6, ys[i]));
    // S2 edge 0-1 runs along S1 edge 0-1 up to the rim
    b.add_edge_piece(s2->find_edge(0, 1), {}, PieceStart::first_vertex, PieceEnd::rim_node, {.end = rim[0]});
    // S2 edge 1-3 starts on the rim at (0.6, 0.4) (parameter 0.4 from vertex 1), crosses the S1
    // diagonal at (0.5, 0.5) and ends at the preimage of vertex 3
    const EdgeCrossing diagonal{s1->find_edge(0, 2), 0.5, 0.5};
    b.add_edge_piece(s2->find_edge(1, 3), std::span(&diagonal, 1), PieceStart::rim_node, PieceEnd::second_vertex,
                     {.start = rim[1]});
    // S2 edge 2-3 along S1 edge 2-3, from the rim
    b.add_edge_piece(s2->find_edge(2, 3), {}, PieceStart::rim_node, PieceEnd::second_vertex, {.start = rim[3]});
    b.add_edge(s2->find_edge(0, 3));
    b.add_edge_outside_domain(s2->find_edge(1, 2));
    return rim;
  }

  PlMap<2> build() {
    const auto rim = enter_nodes_and_pieces();
    for (int i = 0; i + 1 < 4; ++i) builder.add_rim_edge(rim[i], rim[i + 1]);
    return std::move(builder).finalize();
  }
};

/// A RimMap whose builder drops conflicting edges, with everything entered and the rim x = 0.6
/// joined: the tests below add stray rim edges to it.
std::unique_ptr<RimMap> rim_map_dropping_conflicts() {
  BuilderOptions options;
  options.drop_conflicting_edges = true;
  auto r = std::make_unique<RimMap>();
  r->builder = MapBuilder<2>(r->s1, r->s2, options);
  const auto rim = r->enter_nodes_and_pieces();
  for (int i = 0; i + 1 < 4; ++i) r->builder.add_rim_edge(rim[i], rim[i + 1]);
  return r;
}

}  // namespace

TEST(MapBuilderRim, DEndsOnTheRimInsideTheElements) {
  RimMap r;
  const PlMap<2> map = r.build();
  ASSERT_EQ(verify_violations(map), "");
  // the rim crosses S1 edges 0-1, 0-2 (twice: one copy per element) and 2-3, and ends S2 edge
  // 1-3 inside element 0
  EXPECT_EQ(count_type(map, NodeType::rim_on_edge), 4);
  EXPECT_EQ(count_type(map, NodeType::rim_inside), 1);
  const auto covered = covered_measure(map);
  EXPECT_NEAR(covered.domain, 0.6, 1e-14);
  EXPECT_NEAR(covered.target, 0.6, 1e-14);

  DeepestRegion<2> locator;
  // inside D, on either side of S2's diagonal and on both S1 elements: the identity
  for (const auto& [x, y] : {std::pair{0.3, 0.2}, {0.55, 0.42}, {0.58, 0.1}, {0.2, 0.7}, {0.59, 0.95}, {0.59, 0.59}}) {
    const Evaluation<2> e = evaluate(map, on_s1(x, y), locator);
    ASSERT_TRUE(e.in_domain) << x << ", " << y;
    EXPECT_NEAR(e.world(0), x, 1e-14);
    EXPECT_NEAR(e.world(1), y, 1e-14);
  }
  // beyond the rim, also inside the elements the rim crosses: outside D
  for (const auto& [x, y] : {std::pair{0.62, 0.4}, {0.61, 0.05}, {0.9, 0.3}, {0.65, 0.7}, {0.7, 0.99}})
    EXPECT_FALSE(evaluate(map, on_s1(x, y), locator).in_domain) << x << ", " << y;
}

TEST(MapBuilderRim, TheRimSurvivesBothFileFormats) {
  RimMap r;
  const PlMap<2> map = r.build();
  for (const char* name : {"rim.plmap", "rim.plmapb"}) {
    const auto path = std::filesystem::temp_directory_path() / (std::to_string(::getpid()) + name);
    save_map(path, map);
    const PlMap<2> back = load_map<2>(path, r.s1, r.s2);
    std::filesystem::remove(path);
    EXPECT_EQ(back.data().node_type, map.data().node_type) << name;
    EXPECT_EQ(count_type(back, NodeType::rim_inside), 1) << name;
    EXPECT_EQ(verify_violations(back), "") << name;
    EXPECT_NEAR(covered_measure(back).domain, 0.6, 1e-14) << name;
  }
}

TEST(MapBuilderRim, WithoutTheRimEdgesNoRegionReachesPastTheEndOfThePiece) {
  // The rim edges close D off: without them, the faces on either side of S2 edge 1-3's piece
  // reach the S1 corners beyond the rim, which have no node, so they are no regions, and D ends
  // at the S1 edges instead (less than the 0.6 of the rim).
  RimMap r;
  r.enter_nodes_and_pieces();
  const PlMap<2> map = std::move(r.builder).finalize();
  EXPECT_EQ(verify_violations(map), "");
  EXPECT_LT(covered_measure(map).domain, 0.6 - 0.05);
}

TEST(MapBuilderRim, RejectsBadRimInput) {
  RimMap r;
  auto& b = r.builder;
  b.add_vertex_preimage_at_vertex(0, 0);
  b.add_vertex_preimage_at_vertex(3, 3);
  // a rim node on an S2 vertex is that vertex's preimage
  EXPECT_THROW(b.add_rim_node(on_s1(0.6, 0.2), {0, LocalPoint<2>(1.0, 0.0)}), BuilderError);
  const auto inside = b.add_rim_node(on_s1(0.6, 0.2), on_s2(0.6, 0.2));  // image inside S2 element 0
  const auto on_13 = b.add_rim_node(on_s1(0.6, 0.4), on_s2(0.6, 0.4));
  // a piece can end only at a rim node whose image lies on its S2 edge
  EXPECT_THROW(b.add_edge_piece(r.s2->find_edge(0, 1), {}, PieceStart::first_vertex, PieceEnd::rim_node, {.end = inside}),
               BuilderError);
  EXPECT_THROW(b.add_edge_piece(r.s2->find_edge(0, 1), {}, PieceStart::first_vertex, PieceEnd::rim_node, {}),
               BuilderError);
  EXPECT_THROW(b.add_edge_piece(r.s2->find_edge(0, 3), {}, PieceStart::first_vertex, PieceEnd::rim_node, {.end = 0}),
               BuilderError);  // node 0 is a vertex preimage
  // rim edges join two distinct nodes of one S1 element
  EXPECT_THROW(b.add_rim_edge(inside, inside), BuilderError);
  EXPECT_THROW(b.add_rim_edge(inside, 99), BuilderError);
  const auto upper = b.add_rim_node(on_s1(0.3, 0.9), on_s2(0.3, 0.9));  // inside S1 element 1
  EXPECT_THROW(b.add_rim_edge(on_13, upper), BuilderError);
}

TEST(MapBuilderRim, OnlyTheRimEdgesThatCrossSomethingAreDropped) {
  // A stray rim edge in S1 element 1 from (0.2, 0.7) to (0.35, 0.9) crosses S2 edge 1-3's piece
  // (the line x + y = 1 there), so element 1 cannot be closed. With drop_conflicting_edges only
  // that rim edge goes: the rim x = 0.6 stays whole, and D is the part x <= 0.6 as before. Before,
  // every rim edge on element 1 went, and the faces next to x = 0.6 above the diagonal reached
  // the corner (1, 1), which has no node, and left D.
  const auto holder = rim_map_dropping_conflicts();
  RimMap& r = *holder;
  const auto a = r.builder.add_rim_node(on_s1(0.2, 0.7), on_s2(0.2, 0.7));
  const auto b = r.builder.add_rim_node(on_s1(0.35, 0.9), on_s2(0.35, 0.9));
  r.builder.add_rim_edge(a, b);
  FinalizeReport report;
  const PlMap<2> map = std::move(r.builder).finalize(&report);
  ASSERT_EQ(verify_violations(map), "");
  EXPECT_TRUE(report.dropped_edges.empty());  // no S2 edge's stretch went
  EXPECT_NEAR(covered_measure(map).domain, 0.6, 1e-14);
  DeepestRegion<2> locator;
  for (const auto& [x, y] : {std::pair{0.59, 0.95}, {0.59, 0.59}, {0.2, 0.75}, {0.4, 0.9}}) {
    const Evaluation<2> e = evaluate(map, on_s1(x, y), locator);
    ASSERT_TRUE(e.in_domain) << x << ", " << y;
    EXPECT_NEAR(e.world(0), x, 1e-14);
    EXPECT_NEAR(e.world(1), y, 1e-14);
  }
  EXPECT_FALSE(evaluate(map, on_s1(0.65, 0.7), locator).in_domain);
}

TEST(MapBuilderRim, RimNodesGoWithTheirDroppedRimEdges) {
  // As above, a stray rim edge crosses S2 edge 1-3's piece in S1 element 1 and is dropped, but
  // now its nodes' images lie on the other side of S2's diagonal from where the identity puts
  // them (as where a rim belongs to another sheet of S2). Left in the element, each node kept
  // the face around it from mapping into one S2 triangle, and element 1's whole part of D (0.42
  // of the 0.6) was lost. The nodes now go with their rim edge, and D is x <= 0.6.
  const auto holder = rim_map_dropping_conflicts();
  RimMap& r = *holder;
  const auto a = r.builder.add_rim_node(on_s1(0.2, 0.7), on_s2(0.5, 0.9));   // image beyond x + y = 1
  const auto b = r.builder.add_rim_node(on_s1(0.35, 0.9), on_s2(0.1, 0.3));  // image before it
  r.builder.add_rim_edge(a, b);
  FinalizeReport report;
  const PlMap<2> map = std::move(r.builder).finalize(&report);
  ASSERT_EQ(verify_violations(map), "");
  EXPECT_TRUE(report.dropped_edges.empty());
  EXPECT_EQ(count_type(map, NodeType::rim_inside), 1);  // the end of S2 edge 1-3's piece only
  EXPECT_NEAR(covered_measure(map).domain, 0.6, 1e-14);
  DeepestRegion<2> locator;
  for (const auto& [x, y] : {std::pair{0.2, 0.7}, {0.1, 0.5}, {0.35, 0.9}, {0.5, 0.8}}) {
    const Evaluation<2> e = evaluate(map, on_s1(x, y), locator);
    ASSERT_TRUE(e.in_domain) << x << ", " << y;
    EXPECT_NEAR(e.world(0), x, 1e-14);
    EXPECT_NEAR(e.world(1), y, 1e-14);
  }
}

TEST(MapBuilderRim, PiecesEndingAtARimNodeLeftWithoutRimEndAtTheirLastCrossing) {
  // Two stray rim edges in S1 element 0 cross the rim x = 0.6 below and above (0.6, 0.4), where
  // S2 edge 1-3's piece starts: all four rim edges are dropped, and rim nodes (0.6, 0) and
  // (0.6, 0.4) are left without a rim. They go, with the stretches of S2 edges 0-1 and 1-3 that
  // ended there, and so do the stray nodes: the map stays valid, element 0 (whose faces reach
  // its corners (1, 0) and (1, 1), which have no node) holds no region, and element 1 keeps its
  // part x <= 0.6 (0.5 - 0.08).
  const auto holder = rim_map_dropping_conflicts();
  RimMap& r = *holder;
  for (const auto& [p, q] : {std::pair{std::pair{0.55, 0.1}, std::pair{0.65, 0.3}}, {{0.55, 0.45}, {0.65, 0.55}}}) {
    const auto a = r.builder.add_rim_node(on_s1(p.first, p.second), on_s2(p.first, p.second));
    const auto b = r.builder.add_rim_node(on_s1(q.first, q.second), on_s2(q.first, q.second));
    r.builder.add_rim_edge(a, b);
  }
  FinalizeReport report;
  const PlMap<2> map = std::move(r.builder).finalize(&report);
  ASSERT_EQ(verify_violations(map), "");
  EXPECT_EQ(count_type(map, NodeType::rim_inside), 0);
  EXPECT_NEAR(covered_measure(map).domain, 0.42, 1e-14);
  DeepestRegion<2> locator;
  for (const auto& [x, y] : {std::pair{0.2, 0.7}, {0.59, 0.95}, {0.4, 0.9}}) {
    const Evaluation<2> e = evaluate(map, on_s1(x, y), locator);
    ASSERT_TRUE(e.in_domain) << x << ", " << y;
    EXPECT_NEAR(e.world(0), x, 1e-14);
    EXPECT_NEAR(e.world(1), y, 1e-14);
  }
  for (const auto& [x, y] : {std::pair{0.3, 0.1}, {0.55, 0.5}, {0.65, 0.7}})
    EXPECT_FALSE(evaluate(map, on_s1(x, y), locator).in_domain) << x << ", " << y;
}
