// BuilderOptions::split_unmapped_faces: the triangles of a face whose nodes share no S2 element
// (an S2 edge's preimage that would split it is inserted only in part) stay in D where their own
// corners map into one S2 element with the map's orientation (core/src/finalize_closure.cpp,
// split_unmapped_face; finalize_assembly.cpp, number_regions).
#include <plmap/core/map_builder.hpp>
#include <plmap/core/regions.hpp>
#include <plmap/verify/check.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <string>
#include <vector>

using namespace plmap;

namespace {

WorldPoint<2> P(double x, double y) { return {x, y, 0.0}; }

std::shared_ptr<const Surface<2>> make_surface(std::vector<WorldPoint<2>> v, std::vector<ElementCorners<2>> e) {
  return std::make_shared<const Surface<2>>(std::move(v), std::move(e));
}

/// A builder of the identity from S1, the unit square cut by its diagonal 0-2 into A = (0, 1, 2)
/// and B = (0, 2, 3), onto an S2 whose vertices 0-3 are the square's corners and vertex 4 lies at
/// (0.6, 0.3), over A: those five preimages are added.
MapBuilder<2> identity_on_square(std::shared_ptr<const Surface<2>> s1, std::shared_ptr<const Surface<2>> s2,
                                 bool split) {
  BuilderOptions options;
  options.split_unmapped_faces = split;
  MapBuilder<2> b(std::move(s1), std::move(s2), options);
  for (Index v = 0; v < 4; ++v) b.add_vertex_preimage_at_vertex(v, v);
  b.add_vertex_preimage(4, {0, LocalPoint<2>(0.3, 0.3)});  // (u + v, v) on A
  return b;
}

/// S1 the unit square, cut by its diagonal 0-2 into A = (0, 1, 2) and B = (0, 2, 3). S2 the same
/// square with two more vertices p = (0.6, 0.3) (over A) and q = (0.3, 0.6) (over B) and six
/// triangles; its edge p-q crosses the diagonal at c = (0.45, 0.45). Xi is the identity. Every S2
/// edge is inserted whole but p-q, of which only the piece from p to c is (as a walk that stops at
/// S1's edge would leave it). On B the face 0-c-2-q then has nodes on four S2 vertices: unmapped.
/// Its closure has the one diagonal c-q, and the triangles 0-c-q and c-2-q map into the S2
/// elements 0-p-q and p-2-q.
struct HalfInsertedEdge {
  std::shared_ptr<const Surface<2>> s1 = make_surface({P(0, 0), P(1, 0), P(1, 1), P(0, 1)}, {{0, 1, 2}, {0, 2, 3}});
  static constexpr Index p = 4, q = 5;
  std::shared_ptr<const Surface<2>> s2 =
      make_surface({P(0, 0), P(1, 0), P(1, 1), P(0, 1), P(0.6, 0.3), P(0.3, 0.6)},
                   {{0, 1, p}, {1, 2, p}, {0, p, q}, {p, 2, q}, {2, 3, q}, {3, 0, q}});

  PlMap<2> map(bool split, FinalizeReport& report) const {
    MapBuilder<2> b = identity_on_square(s1, s2, split);
    b.add_vertex_preimage(q, {1, LocalPoint<2>(0.3, 0.3)});  // (u, u + v) on B
    const Index pq = s2->find_edge(p, q);
    for (Index k = 0; k < s2->edge_count(); ++k)
      if (k != pq) b.add_edge(k);
    const EdgeCrossing c{s1->find_edge(0, 2), 0.45, 0.5};
    b.add_edge_piece(pq, std::span(&c, 1), PieceStart::first_vertex, PieceEnd::last_crossing);
    return std::move(b).finalize(&report);
  }
  Index element(Index a, Index b, Index c) const {
    for (Index t : s2->vertex_elements(a))
      if (s2->local_corner(t, b) >= 0 && s2->local_corner(t, c) >= 0) return t;
    return invalid_index;
  }
};

std::string violations_of(const PlMap<2>& map) {
  std::string text;
  for (const auto& check : verify(map).checks)
    for (const auto& v : check.violations) text += check.name + "/" + v.rule + ": " + v.message + "\n";
  return text;
}

/// Xi is the identity in these fixtures: every region corner maps where it lies.
void expect_identity_on_region_corners(const PlMap<2>& m) {
  for (Index r = 0; r < m.region_count(); ++r)
    for (Index n : m.data().region_corners[r]) {
      const WorldPoint<2> x = m.domain().world_position(m.node_element(n), m.data().node_position[n]);
      EXPECT_NEAR((m.node_target_world(n) - x).norm(), 0.0, 1e-14) << "region " << r << " node " << n;
    }
}

/// Areas of the two triangles of the unmapped face: 0-c-q and c-2-q.
constexpr double area_0cq = 0.0675, area_c2q = 0.0825;

}  // namespace

TEST(MapBuilderSplitFaces, WithoutTheOptionTheUnmappedFaceLeavesD) {
  const HalfInsertedEdge fixture;
  FinalizeReport report;
  const PlMap<2> m = fixture.map(false, report);
  EXPECT_EQ(violations_of(m), "");
  EXPECT_EQ(report.unmapped_faces, 1);
  EXPECT_TRUE(report.split_targets.empty());
  EXPECT_NEAR(covered_measure(m).domain, 1.0 - area_0cq - area_c2q, 1e-15);
  EXPECT_NEAR(report.left_out.unmapped, area_0cq + area_c2q, 1e-15);
}

TEST(MapBuilderSplitFaces, ItsTrianglesThatMapIntoOneElementStay) {
  const HalfInsertedEdge fixture;
  FinalizeReport report;
  const PlMap<2> m = fixture.map(true, report);
  EXPECT_EQ(violations_of(m), "");
  EXPECT_EQ(report.unmapped_faces, 1);  // the face is counted; its triangles became regions
  EXPECT_EQ(report.left_out.unmapped, 0.0);
  const auto covered = covered_measure(m);
  EXPECT_NEAR(covered.domain, 1.0, 1e-15);
  EXPECT_NEAR(covered.target, 1.0, 1e-15);
  std::vector<Index> expected = {fixture.element(0, HalfInsertedEdge::p, HalfInsertedEdge::q),
                                 fixture.element(HalfInsertedEdge::p, 2, HalfInsertedEdge::q)};
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(report.split_targets, expected);
  EXPECT_TRUE(report.regions_split_off_outside_faces.empty());  // unmapped, not outside
  // Xi is the identity on the split triangles as on the rest: q's preimage and c map where they lie
  expect_identity_on_region_corners(m);
}

namespace {

/// A face whose own closure splits badly: S1 as above; S2 the square with p = (0.6, 0.3) over A
/// and q = (0.05, 0.95), r = (0.15, 0.55), s = (0.65, 0.75) over B, in ten triangles, among them
/// (p, q, r) and (p, s, q) on the two sides of edge p-q. Xi is the identity; p-q is inserted
/// only from p to where it crosses the diagonal (c, at a quarter of the edge). On B the face bounded by
/// the pieces of p-r and p-s, by r-q-s and by the diagonal is a convex hexagon c1, c, c2, s, q, r
/// with nodes on four S2 vertices: unmapped. Its Delaunay triangulation (c1 c r, c c2 s, c s r,
/// s q r) has two triangles with corners on both sides of the missing stretch c-q, which no one
/// S2 element holds; flipping s-r to c-q gives c s q in (p, s, q) and c q r in (p, q, r).
struct GapInAHexagon {
  std::shared_ptr<const Surface<2>> s1 = make_surface({P(0, 0), P(1, 0), P(1, 1), P(0, 1)}, {{0, 1, 2}, {0, 2, 3}});
  static constexpr Index p = 4, q = 5, r = 6, s = 7;
  std::shared_ptr<const Surface<2>> s2 = make_surface(
      {P(0, 0), P(1, 0), P(1, 1), P(0, 1), P(0.6, 0.3), P(0.05, 0.95), P(0.15, 0.55), P(0.65, 0.75)},
      {{0, 1, p}, {1, 2, p}, {0, p, r}, {p, q, r}, {p, s, q}, {p, 2, s}, {2, 3, s}, {s, 3, q}, {q, 3, r}, {r, 3, 0}});

  PlMap<2> map(FinalizeReport& report) const {
    MapBuilder<2> b = identity_on_square(s1, s2, true);
    b.add_vertex_preimage(q, {1, LocalPoint<2>(0.05, 0.9)});  // (u, u + v) on B
    b.add_vertex_preimage(r, {1, LocalPoint<2>(0.15, 0.4)});
    b.add_vertex_preimage(s, {1, LocalPoint<2>(0.65, 0.1)});
    const Index pq = s2->find_edge(p, q), pr = s2->find_edge(p, r), ps = s2->find_edge(p, s);
    for (Index k = 0; k < s2->edge_count(); ++k)
      if (k != pq && k != pr && k != ps) b.add_edge(k);
    // p + eta (x - p) meets the diagonal y = x: for x = r at eta = 3/7, (2.85/7, 2.85/7); for
    // x = s at eta = 3/4, (0.6375, 0.6375); for x = q at eta = 1/4, (0.4625, 0.4625)
    const Index diagonal = s1->find_edge(0, 2);
    const EdgeCrossing c1{diagonal, 2.85 / 7.0, 3.0 / 7.0}, c2{diagonal, 0.6375, 0.75};
    b.add_edge(pr, std::span(&c1, 1));
    b.add_edge(ps, std::span(&c2, 1));
    const EdgeCrossing c{diagonal, 0.4625, 0.25};
    b.add_edge_piece(pq, std::span(&c, 1), PieceStart::first_vertex, PieceEnd::last_crossing);
    return std::move(b).finalize(&report);
  }
};

}  // namespace

TEST(MapBuilderSplitFaces, AnUnmappedFaceIsRetriangulatedSoThatItsTrianglesMapIntoOneElement) {
  const GapInAHexagon fixture;
  FinalizeReport report;
  const PlMap<2> m = fixture.map(report);
  EXPECT_EQ(violations_of(m), "");
  EXPECT_EQ(report.unmapped_faces, 1);
  // the whole hexagon stays: with B's Delaunay triangles c s r and s q r it would not
  EXPECT_EQ(report.left_out.unmapped, 0.0);
  const auto covered = covered_measure(m);
  EXPECT_NEAR(covered.domain, 1.0, 1e-15);
  EXPECT_NEAR(covered.target, 1.0, 1e-15);
  expect_identity_on_region_corners(m);
}

namespace {

/// A face at a corner without a node. S1 the unit square as above (A = (0, 1, 2), B = (0, 2, 3));
/// S2 the quadrilateral 0 = (0, 0), 1 = (1, 0), b = (1, 0.9), a = (0, 0.5) in the triangles
/// (0, 1, b) and (0, b, a): it does not reach S1's corners 2 and 3, which get no node. Xi is the
/// identity. Every S2 edge is inserted whole but b-a, of which only the piece from b to where it
/// crosses the diagonal (c = (5/6, 5/6), at a sixth of the edge) is (as a walk that stops at a
/// fold would leave it). On B the one face 0, c, 2, 3, a touches the corners without a node, so
/// it lies outside D's reach; of its closure, the triangle 0-c-a maps into the S2 element
/// (0, b, a), which its split keeps.
struct CornerWithoutNode {
  std::shared_ptr<const Surface<2>> s1 = make_surface({P(0, 0), P(1, 0), P(1, 1), P(0, 1)}, {{0, 1, 2}, {0, 2, 3}});
  static constexpr Index b = 2, a = 3;
  std::shared_ptr<const Surface<2>> s2 =
      make_surface({P(0, 0), P(1, 0), P(1, 0.9), P(0, 0.5)}, {{0, 1, b}, {0, b, a}});

  PlMap<2> map(bool split, FinalizeReport& report) const {
    BuilderOptions options;
    options.split_unmapped_faces = split;
    MapBuilder<2> builder(s1, s2, options);
    builder.add_vertex_preimage_at_vertex(0, 0);
    builder.add_vertex_preimage_at_vertex(1, 1);
    builder.add_vertex_preimage(b, {0, LocalPoint<2>(0.1, 0.9)});  // (u + v, v) on A, on its edge 1-2
    builder.add_vertex_preimage(a, {1, LocalPoint<2>(0.0, 0.5)});  // (u, u + v) on B, on its edge 3-0
    const Index ba = s2->find_edge(b, a);
    for (Index k = 0; k < s2->edge_count(); ++k)
      if (k != ba) builder.add_edge(k);
    const EdgeCrossing c{s1->find_edge(0, 2), 5.0 / 6.0, 1.0 / 6.0};
    builder.add_edge_piece(ba, std::span(&c, 1), PieceStart::first_vertex, PieceEnd::last_crossing);
    return std::move(builder).finalize(&report);
  }
};

/// Areas: S2 (all of it is the image of the square's part below b-a), and the triangle 0-c-a.
constexpr double area_s2 = 0.7, area_0ca = 5.0 / 24.0;

}  // namespace

TEST(MapBuilderSplitFaces, WithoutTheOptionAFaceAtACornerWithoutANodeLeavesD) {
  const CornerWithoutNode fixture;
  FinalizeReport report;
  const PlMap<2> m = fixture.map(false, report);
  EXPECT_EQ(violations_of(m), "");
  EXPECT_EQ(report.unmapped_faces, 0);  // outside, not unmapped
  EXPECT_TRUE(report.split_targets.empty());
  EXPECT_NEAR(covered_measure(m).domain, area_s2 - area_0ca, 1e-15);
  EXPECT_NEAR(report.left_out.outside, 1.0 - area_s2 + area_0ca, 1e-15);
}

TEST(MapBuilderSplitFaces, AFaceAtACornerWithoutANodeKeepsItsTrianglesThatMapIntoOneElement) {
  const CornerWithoutNode fixture;
  FinalizeReport report;
  const PlMap<2> m = fixture.map(true, report);
  EXPECT_EQ(violations_of(m), "");
  EXPECT_EQ(report.unmapped_faces, 0);
  // all of S2 is covered now; only the part of the square beyond b-a stays outside
  const auto covered = covered_measure(m);
  EXPECT_NEAR(covered.domain, area_s2, 1e-15);
  EXPECT_NEAR(covered.target, area_s2, 1e-15);
  EXPECT_NEAR(report.left_out.outside, 1.0 - area_s2, 1e-15);
  EXPECT_EQ(report.split_targets, std::vector<Index>{1});  // the S2 element (0, b, a)
  // the region split off is listed (the projection tests it against its rays): the one of
  // element B on the S2 element (0, b, a)
  ASSERT_EQ(report.regions_split_off_outside_faces.size(), 1u);
  const Index split = report.regions_split_off_outside_faces[0];
  EXPECT_EQ(m.data().region_target[split], 1);
  EXPECT_TRUE(m.regions_begin(1) <= split && split < m.regions_end(1));
  expect_identity_on_region_corners(m);
}
