// MapBuilder with drop_conflicting_edges: a conflict costs the stretch of the S2 edges involved
// on the S1 element where they conflict, not their whole preimages (issue 14, item 1).

#include <plmap/core/map_builder.hpp>
#include <plmap/core/map_validation.hpp>
#include <plmap/core/regions.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <optional>
#include <vector>

using namespace plmap;

namespace {

WorldPoint<2> P(double x, double y) { return {x, y, 0.0}; }

/// Where the straight segment p -> q of the plane z = 0 properly crosses the edges of a flat S1,
/// in order along it; the target parameter is the parameter along the segment.
std::vector<EdgeCrossing> straight_crossings(const Surface<2>& s1, const WorldPoint<2>& p, const WorldPoint<2>& q) {
  std::vector<EdgeCrossing> out;
  const WorldPoint<2> d = q - p;
  for (Index e = 0; e < s1.edge_count(); ++e) {
    const auto ev = s1.edge_vertices(e);
    const WorldPoint<2> a = s1.vertex(std::min(ev[0], ev[1])), b = s1.vertex(std::max(ev[0], ev[1]));
    const WorldPoint<2> f = b - a;
    const double den = d.x() * f.y() - d.y() * f.x();
    if (den == 0.0) continue;
    const WorldPoint<2> g = a - p;
    const double s = (g.x() * f.y() - g.y() * f.x()) / den;   // along p -> q
    const double lambda = (g.x() * d.y() - g.y() * d.x()) / den;  // along a -> b
    if (s > 1e-9 && s < 1 - 1e-9 && lambda > 1e-9 && lambda < 1 - 1e-9) out.push_back({e, lambda, s});
  }
  std::sort(out.begin(), out.end(), [](const auto& x, const auto& y) { return x.target_parameter < y.target_parameter; });
  return out;
}

/// Barycentric coordinates of p in element t of a flat surface.
std::array<double, 3> barycentric(const Surface<2>& s, Index t, const WorldPoint<2>& p) {
  const WorldPoint<2> a = s.corner(t, 0), b = s.corner(t, 1), c = s.corner(t, 2);
  const double area = (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
  const double u = ((p.x() - a.x()) * (c.y() - a.y()) - (p.y() - a.y()) * (c.x() - a.x())) / area;
  const double v = ((b.x() - a.x()) * (p.y() - a.y()) - (b.y() - a.y()) * (p.x() - a.x())) / area;
  return {1.0 - u - v, u, v};
}

/// The element of a flat surface containing p, and p's local coordinates there (none: outside).
std::optional<SurfacePoint<2>> locate(const Surface<2>& s, const WorldPoint<2>& p) {
  for (Index t = 0; t < s.element_count(); ++t)
    if (const auto w = barycentric(s, t, p); w[0] >= 0 && w[1] >= 0 && w[2] >= 0)
      return SurfacePoint<2>{t, LocalPoint<2>(w[1], w[2])};
  return std::nullopt;
}

/// Regular grid of nx by ny squares over [x0, x0 + nx h] x [y0, y0 + ny k], each cut by its
/// diagonal from lower left to upper right; `shear` moves row j by shear.x() j and column i by
/// shear.y() i, so that the vertices of two such grids are in general position.
std::shared_ptr<const Surface<2>> grid(int nx, int ny, double x0, double y0, double h, double k,
                                       std::array<double, 2> shear = {0.0, 0.0}) {
  std::vector<WorldPoint<2>> v;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) v.push_back(P(x0 + i * h + shear[0] * j, y0 + j * k + shear[1] * i));
  std::vector<ElementCorners<2>> t;
  auto id = [&](int i, int j) { return static_cast<Index>(j * (nx + 1) + i); };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      t.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      t.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return std::make_shared<const Surface<2>>(v, t);
}

/// Enters the map from S1 onto S2 (both flat, S2 covering S1) under which each S2 vertex has
/// the preimage `preimage[q]` (its own position but for the vertices moved), and each S2 edge's
/// preimage is the straight segment between its vertices' preimages, cut off at S1's boundary.
void enter_straight_map(MapBuilder<2>& b, const Surface<2>& s1, const Surface<2>& s2,
                        const std::vector<WorldPoint<2>>& preimage) {
  std::vector<bool> inside(preimage.size());
  for (Index q = 0; q < s2.vertex_count(); ++q)
    if (const auto at = locate(s1, preimage[q])) {
      b.add_vertex_preimage(q, *at);
      inside[q] = true;
    }
  for (Index v = 0; v < s1.vertex_count(); ++v)
    if (const auto image = locate(s2, s1.vertex(v))) b.add_ghost_node(v, *image);
  for (Index e = 0; e < s2.edge_count(); ++e) {
    const auto ev = s2.edge_vertices(e);
    const Index a = std::min(ev[0], ev[1]), c = std::max(ev[0], ev[1]);
    const std::vector<EdgeCrossing> path = straight_crossings(s1, preimage[a], preimage[c]);
    if (inside[a] && inside[c]) b.add_edge(e, path);
    else if (path.empty()) b.add_edge_outside_domain(e);
    else
      b.add_edge_piece(e, path, inside[a] ? PieceStart::first_vertex : PieceStart::first_crossing,
                       inside[c] ? PieceEnd::second_vertex : PieceEnd::last_crossing);
  }
}

}  // namespace

// S1: the strip [0,3] x [0,1], a grid of 12 by 4 squares. S2: a coarse sheared grid (edges
// about 1 long) covering it. The map is the identity but for one S2 vertex, whose preimage is
// moved across the opposite edge of its star: near the moved preimage, the preimages of that
// edge and of the vertex's edges cross, on a few S1 elements only. Dropped whole, those S2
// edges would take every region of their S2 triangles with them; dropped on the elements where
// they conflict, each keeps the rest of its preimage, and its S2 triangles keep regions there.
TEST(MapBuilderConflicts, AConflictDropsOnlyTheStretchOnItsElement) {
  const auto s1 = grid(12, 4, 0.0, 0.0, 0.25, 0.25);
  const auto s2 = grid(4, 2, -0.5, -0.45, 1.0, 0.95, {0.0137, 0.0111});
  std::vector<WorldPoint<2>> preimage;
  for (Index q = 0; q < s2->vertex_count(); ++q) preimage.push_back(s2->vertex(q));
  const Index moved = 7;  // grid vertex (2, 1), at about (1.51, 0.52)
  preimage[moved] = P(2.6, 0.9);  // beyond the S2 edge from (3, 1) to (3, 2), x about 2.52

  {  // the identity itself is exact: S1 is covered once
    MapBuilder<2> b(s1, s2);
    enter_straight_map(b, *s1, *s2, std::vector<WorldPoint<2>>(s2->vertices().begin(), s2->vertices().end()));
    const PlMap<2> m = std::move(b).finalize();
    ASSERT_NEAR(covered_measure(m).domain, 3.0, 1e-12);
  }
  BuilderOptions options;
  options.drop_conflicting_edges = true;
  MapBuilder<2> b(s1, s2, options);
  enter_straight_map(b, *s1, *s2, preimage);
  FinalizeReport report;
  const PlMap<2> m = std::move(b).finalize(&report);
  validate_map_structure(m);
  ASSERT_FALSE(report.dropped_edges.empty());
  const std::vector<RemoteIntersection<2>> regions = remote_intersections(m);
  for (Index e : report.dropped_edges) {
    // a region on an S2 triangle at e, on an S1 element away from where e conflicted
    const bool kept = std::any_of(regions.begin(), regions.end(), [&](const RemoteIntersection<2>& r) {
      for (int k = 0; k < 3; ++k)
        if (s2->element_edge(r.target_element, k) == e) return true;
      return false;
    });
    EXPECT_TRUE(kept) << "S2 edge " << e << " lost every region of its triangles";
  }
  EXPECT_GT(covered_measure(m).domain, 2.0);
}

