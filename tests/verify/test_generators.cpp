// The random surface and map generators themselves: the surfaces have the shape they promise,
// the same seed gives the same surface, and the overlay generator produces the nodes the paper
// predicts on small cases whose answer is known.

#include <plmap/core/predicates.hpp>
#include <plmap/core/regions.hpp>
#include <plmap/verify/generators/rc_generators.hpp>

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <set>

namespace plmap {
namespace {

using namespace plmap::generators;

double signed_area_xy(const Surface<2>& s, Index t) {
  const auto a = s.corner(t, 0), b = s.corner(t, 1), c = s.corner(t, 2);
  return 0.5 * ((b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x()));
}

void expect_planar_ccw_with_area(const Surface<2>& s, double area) {
  double sum = 0.0;
  for (Index t = 0; t < s.element_count(); ++t) {
    const double a = signed_area_xy(s, t);
    EXPECT_GT(a, 0.0) << "element " << t;
    sum += a;
  }
  EXPECT_NEAR(sum, area, 1e-12);
  for (const auto& v : s.vertices()) EXPECT_EQ(v.z(), 0.0);
}

constexpr double hole_area = (HoleBox::x1 - HoleBox::x0) * (HoleBox::y1 - HoleBox::y0);

TEST(Generators, GridCoversTheSquare) {
  Rng rng(1);
  const Surface<2> s = grid_triangulation({.cells = 4, .jitter = 0.0, .with_hole = false}, rng);
  EXPECT_EQ(s.element_count(), 32);
  EXPECT_EQ(s.vertex_count(), 25);
  expect_planar_ccw_with_area(s, 1.0);
}

TEST(Generators, JitteredGridWithHole) {
  Rng rng(2);
  const Surface<2> s = grid_triangulation({.cells = 8, .jitter = 0.2, .with_hole = true}, rng);
  EXPECT_EQ(s.element_count(), 2 * 64 - 2 * 4);  // the hole is 2 x 2 cells
  expect_planar_ccw_with_area(s, 1.0 - hole_area);
}

TEST(Generators, DelaunayCoversTheDomain) {
  for (bool hole : {false, true}) {
    Rng rng(3);
    const Surface<2> s = delaunay_triangulation(
        {.interior_points = 30, .boundary_points = 6, .grid_points = 5, .with_hole = hole}, rng);
    EXPECT_GE(s.vertex_count(), 30);
    expect_planar_ccw_with_area(s, hole ? 1.0 - hole_area : 1.0);
  }
}

TEST(Generators, SameSeedSameSurface) {
  const PlanarRecipe r{PlanarBase::delaunay, 20, true, false, 77};
  const Surface<2> a = make_planar(r), b = make_planar(r);
  EXPECT_EQ(a.vertices(), b.vertices());
  EXPECT_EQ(a.elements(), b.elements());
  PlanarRecipe other = r;
  other.seed = 78;
  EXPECT_NE(make_planar(other).vertices(), a.vertices());
}

TEST(Generators, HeightFieldKeepsTheTriangulation) {
  Rng rng(4);
  const Surface<2> planar = grid_triangulation({.cells = 3, .jitter = 0.1, .with_hole = false}, rng);
  const Surface<2> lifted = lift_to_height_field(planar, random_height_field(rng));
  EXPECT_EQ(lifted.elements(), planar.elements());
  EXPECT_GT(lifted.measure(), planar.measure());
  EXPECT_TRUE(std::any_of(lifted.vertices().begin(), lifted.vertices().end(),
                          [](const WorldPoint<2>& v) { return v.z() != 0.0; }));
}

TEST(Generators, FinsMakeEdgesWithThreeTriangles) {
  Rng rng(5);
  const Surface<2> sheet = grid_triangulation({.cells = 3, .jitter = 0.0, .with_hole = false}, rng);
  const Surface<2> s = add_fins(sheet, 2, rng);
  EXPECT_EQ(s.element_count(), sheet.element_count() + 2);
  int three = 0;
  for (Index e = 0; e < s.edge_count(); ++e) three += s.edge_elements(e).size() == 3;
  EXPECT_EQ(three, 2);
}

TEST(Generators, SheetsSharingOneVertex) {
  Rng rng(6);
  const Surface<2> a = grid_triangulation({.cells = 2, .jitter = 0.0, .with_hole = false}, rng);
  const Surface<2> b = grid_triangulation({.cells = 3, .jitter = 0.0, .with_hole = false}, rng);
  const Surface<2> s = join_at_corner(a, b);
  EXPECT_EQ(s.vertex_count(), a.vertex_count() + b.vertex_count() - 1);
  EXPECT_EQ(s.element_count(), a.element_count() + b.element_count());
  // The shared vertex has elements of both sheets but no edge joins the two sheets.
  Index shared = invalid_index;
  for (Index v = 0; v < s.vertex_count(); ++v)
    if (s.vertex(v) == WorldPoint<2>(1, 1, 0)) shared = v;
  ASSERT_NE(shared, invalid_index);
  const auto star = s.vertex_elements(shared);
  EXPECT_TRUE(std::any_of(star.begin(), star.end(), [&](Index t) { return t < a.element_count(); }));
  EXPECT_TRUE(std::any_of(star.begin(), star.end(), [&](Index t) { return t >= a.element_count(); }));
  EXPECT_NEAR(s.measure(), a.measure() + b.measure() * std::sqrt(1.5), 1e-12);
}

TEST(Generators, Polylines) {
  Rng rng(7);
  const Surface<1> open = random_open_polyline(5, rng);
  EXPECT_EQ(open.element_count(), 5);
  EXPECT_EQ(open.vertex_count(), 6);
  EXPECT_TRUE(open.is_boundary_vertex(0));
  EXPECT_TRUE(open.is_boundary_vertex(5));

  const Surface<1> closed = random_closed_polyline(6, rng);
  EXPECT_EQ(closed.vertex_count(), 6);
  for (Index v = 0; v < closed.vertex_count(); ++v) EXPECT_EQ(closed.vertex_elements(v).size(), 2u);

  const Surface<1> star = random_star_polyline(4, 3, rng);
  EXPECT_EQ(star.element_count(), 12);
  EXPECT_EQ(star.vertex_elements(0).size(), 4u);  // the centre
}

TEST(Generators, RefinementHasTheSameMeasure) {
  Rng rng(8);
  auto s1 = std::make_shared<const Surface<2>>(
      lift_to_height_field(grid_triangulation({.cells = 3, .jitter = 0.1, .with_hole = false}, rng),
                           random_height_field(rng)));
  const Refinement<2> r = random_refinement<2>(*s1, {.max_points_per_edge = 2, .max_points_per_element = 3}, rng);
  EXPECT_GT(r.refined.element_count(), s1->element_count());
  EXPECT_NEAR(r.refined.measure(), s1->measure(), 1e-12);
  for (Index v = 0; v < r.refined.vertex_count(); ++v) {
    const auto& loc = r.vertex_location[v];
    EXPECT_LT((s1->world_position(loc.point.element, loc.point.local) - r.refined.vertex(v)).norm(), 1e-14);
  }
}

// ---- overlays with a known answer ------------------------------------------------------------------

std::shared_ptr<const Surface<2>> square(bool main_diagonal) {
  std::vector<WorldPoint<2>> v{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  std::vector<ElementCorners<2>> e;
  if (main_diagonal)
    e = {{0, 1, 2}, {0, 2, 3}};
  else
    e = {{0, 1, 3}, {1, 2, 3}};
  return std::make_shared<const Surface<2>>(std::move(v), std::move(e));
}

template <int d>
long count(const PlMap<d>& m, NodeType t) {
  return std::count(m.data().node_type.begin(), m.data().node_type.end(), t);
}

TEST(Generators, OverlayOfCrossedDiagonals) {
  const MapCase<2> c = plane_overlay_map(square(true), square(false));
  // The S2 diagonal crosses the S1 diagonal at the centre: one intersection node, copied on
  // both S1 triangles; no ghosts; four regions.
  EXPECT_EQ(count(*c.map, NodeType::intersection), 2);
  EXPECT_EQ(count(*c.map, NodeType::ghost), 0);
  EXPECT_EQ(c.map->region_count(), 4);
}

TEST(Generators, OverlayOfFineGridOnCoarseGridHasGhostsAtCrossedVertices) {
  Rng rng(9);
  auto fine = std::make_shared<const Surface<2>>(grid_triangulation({.cells = 4, .jitter = 0.0, .with_hole = false}, rng));
  auto coarse = std::make_shared<const Surface<2>>(grid_triangulation({.cells = 2, .jitter = 0.0, .with_hole = false}, rng));
  const MapCase<2> c = plane_overlay_map(fine, coarse);
  // The 25 - 9 fine vertices that are no coarse vertex all lie on coarse edges or inside coarse
  // triangles: ghost nodes. Those on coarse edges (the grid lines and possibly diagonals) are
  // created automatically by the builder.
  std::set<Index> ghost_vertices;
  const auto& m = c.map->data();
  for (Index n = 0; n < c.map->node_count(); ++n)
    if (m.node_type[n] == NodeType::ghost)
      ghost_vertices.insert(fine->element(c.map->node_element(n))[m.node_location[n]]);
  EXPECT_EQ(ghost_vertices.size(), 16u);
  EXPECT_EQ(count(*c.map, NodeType::touching), 0);
  const CoveredMeasure cm = covered_measure(*c.map);
  EXPECT_NEAR(cm.domain, 1.0, 1e-12);
  EXPECT_NEAR(cm.target, 1.0, 1e-12);
}

TEST(Generators, OverlayOfCoarseGridOnFineGridHasTouchingNodes) {
  Rng rng(10);
  auto fine = std::make_shared<const Surface<2>>(grid_triangulation({.cells = 4, .jitter = 0.0, .with_hole = false}, rng));
  auto coarse = std::make_shared<const Surface<2>>(grid_triangulation({.cells = 2, .jitter = 0.0, .with_hole = false}, rng));
  const MapCase<2> c = plane_overlay_map(coarse, fine);
  // Fine vertices at the 12 midpoints of coarse grid-line edges (8 on the boundary, 4 inside)
  // and at the 4 cell centres (on the coarse diagonals) are touching nodes, one copy per
  // incident coarse triangle: 8 * 1 + 4 * 2 + 4 * 2.
  EXPECT_EQ(count(*c.map, NodeType::touching), 24);
  EXPECT_EQ(count(*c.map, NodeType::ghost), 0);  // every coarse vertex is a fine vertex
}

TEST(Generators, OverlayOfNonDyadicGridWithDyadicPoints) {
  // Grid coordinates i/6 are rounded, points of the 1/8 grid are exact: S2 edges pass within
  // rounding distance of S1 vertices. The generator must apply the builder's snapping rule, or
  // the builder sees two crossings at one vertex (this configuration once failed that way).
  Rng rng(2026);
  auto grid = std::make_shared<const Surface<2>>(grid_triangulation({.cells = 6}, rng));
  auto delaunay = std::make_shared<const Surface<2>>(
      delaunay_triangulation({.interior_points = 40, .boundary_points = 8, .grid_points = 6}, rng));
  const MapCase<2> c = plane_overlay_map(grid, delaunay);
  const CoveredMeasure cm = covered_measure(*c.map);
  EXPECT_NEAR(cm.domain, 1.0, 1e-12);
  EXPECT_NEAR(cm.target, 1.0, 1e-12);
}

TEST(Generators, OverlayOfAnEdgeAlongAnEdgeUpToRounding) {
  // S2 has an edge between (5/6, 1/6) and (2/3, 1/3), which lies on S1's diagonal x + y = 1 but
  // for rounding: the first end lies just above it, the second just below. The builder places
  // both ends on S1's diagonal (snapping), so the edge runs along it and crosses nothing; the
  // exact predicates alone see a crossing whose parameters, from a denominator of about 1e-17,
  // once put a node at the diagonal's midpoint 1/3 of the way along the S2 edge (a valid map,
  // but not the identity the overlay promises; property seed 3 of MapComposition.OverlayChains2).
  const double a = 5.0 / 6.0, b = 1.0 / 6.0, c = 4.0 / 6.0, e = 2.0 / 6.0;
  // The configuration this test is about: the ends lie on opposite sides of S1's diagonal.
  const Eigen::Vector2d from(1, 0), to(0, 1);
  ASSERT_EQ(orient2d(from, to, Eigen::Vector2d(a, b)) * orient2d(from, to, Eigen::Vector2d(c, e)), -1);
  auto s2 = std::make_shared<const Surface<2>>(
      std::vector<WorldPoint<2>>{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {a, b, 0}, {c, e, 0}},
      std::vector<ElementCorners<2>>{{0, 1, 4}, {1, 2, 4}, {4, 2, 5}, {5, 2, 3}, {0, 4, 5}, {0, 5, 3}});
  const MapCase<2> m = plane_overlay_map(square(false), s2);
  for (Index n = 0; n < m.map->node_count(); ++n) {
    const WorldPoint<2> place = m.domain->world_position(m.map->node_element(n), m.map->data().node_position[n]);
    const SurfacePoint<2> image = m.map->data().node_image(n);
    EXPECT_LT((m.target->world_position(image.element, image.local) - place).norm(), 1e-12) << "node " << n;
  }
  const CoveredMeasure cm = covered_measure(*m.map);
  EXPECT_NEAR(cm.domain, 1.0, 1e-12);
  EXPECT_NEAR(cm.target, 1.0, 1e-12);
}

TEST(Generators, PolylineOverlayIsExactOnSharedParameters) {
  Rng rng(11);
  auto base = std::make_shared<const Surface<1>>(random_open_polyline(2, rng));
  PolylineSubdivisions sub{base, {{0.5}, {0.25, 0.75}}, {{0.25, 0.5}, {}}};
  const MapCase<1> c = polyline_overlay_map(sub);
  // S1 vertices at 0.25 and 0.75 of the second base segment are ghosts (one by hand, one
  // automatic); 0.5 of the first segment is shared.
  EXPECT_EQ(count(*c.map, NodeType::ghost), 2 * 2);  // two vertices, two copies each
  // First segment: [0, .25], [.25, .5], [.5, 1]; second: the three S1 pieces inside one S2 segment.
  EXPECT_EQ(c.map->region_count(), 6);
  EXPECT_NEAR(covered_measure(*c.map).domain, base->measure(), 1e-12);
}

// ---- the generators keep their promises for all sizes ---------------------------------------------

RC_GTEST_PROP(Generators, PlanarTriangulationsCoverTheirDomain, ()) {
  const PlanarRecipe r = *planar_recipes();
  const Surface<2> s = make_planar(r);
  double area = 0.0;
  for (Index t = 0; t < s.element_count(); ++t) {
    RC_ASSERT(signed_area_xy(s, t) > 0.0);
    area += signed_area_xy(s, t);
  }
  RC_ASSERT(std::abs(area - (r.with_hole ? 1.0 - hole_area : 1.0)) < 1e-12);
}

RC_GTEST_PROP(Generators, TriangleSurfacesAreValidSurfaces, ()) {
  const TriangleSurfaceRecipe r = *triangle_surface_recipes();
  const Surface<2> s = make_triangle_surface(r);  // the constructor validates
  RC_ASSERT(s.element_count() > 0);
  if (r.shape == SheetShape::fins) {
    bool has_fin_edge = false;
    for (Index e = 0; e < s.edge_count(); ++e) has_fin_edge |= s.edge_elements(e).size() == 3;
    RC_ASSERT(has_fin_edge);
  }
}

RC_GTEST_PROP(Generators, CurvesAreValidSurfaces, ()) {
  const CurveRecipe r = *curve_recipes();
  const Surface<1> s = make_curve(r);
  RC_ASSERT(s.element_count() > 0);
  if (r.shape == CurveShape::star) RC_ASSERT(static_cast<int>(s.vertex_elements(0).size()) == r.arms);
}

}  // namespace
}  // namespace plmap
