// The mortar mass matrix of examples/mortar_mass_matrix, assembled over the regions of small
// hand-built overlay maps (Xi = identity of the plane), against exact values:
// - sum of all entries = measure of the domain;
// - row sums = integrals of the S1 hat functions, column sums = those of the S2 hat functions;
// - for identical meshes, the standard P1 mass matrix;
// - d = 1: every entry against an independent integration over the merged breakpoints.
// The random overlays of verify's generators are covered in tests/verify/test_generated_maps_mortar.cpp.

#include "../../examples/mortar_mass_matrix/mortar_mass_matrix.hpp"

#include <plmap/core/map_builder.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

namespace plmap {
namespace {

constexpr double tol = 1e-14;

template <int d>
void expect_mortar_identities(const PlMap<d>& map) {
  const Eigen::MatrixXd m = mortar::mortar_mass_matrix(map);
  const auto e = mortar::mortar_identity_errors<d>(m, map.domain(), map.target());
  EXPECT_LT(e.total, tol);
  EXPECT_LT(e.row_sums, tol);
  EXPECT_LT(e.column_sums, tol);
  EXPECT_GE(m.minCoeff(), 0.0);  // products of hat functions are non-negative
}

std::shared_ptr<const Surface<2>> grid(int n) {
  std::vector<WorldPoint<2>> v;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) v.push_back({double(i) / n, double(j) / n, 0.0});
  std::vector<ElementCorners<2>> e;
  auto id = [n](int i, int j) { return Index(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      e.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      e.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return std::make_shared<const Surface<2>>(std::move(v), std::move(e));
}

/// The unit square split along its anti-diagonal (1, 0)-(0, 1).
std::shared_ptr<const Surface<2>> anti_diagonal_square() {
  return std::make_shared<const Surface<2>>(
      std::vector<WorldPoint<2>>{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}},
      std::vector<ElementCorners<2>>{{0, 1, 3}, {1, 2, 3}});
}

/// Crossing of an S2 edge with the S1 edge a-b at fraction t from a (converted to the builder's
/// convention of measuring from the smaller vertex index).
EdgeCrossing across(const Surface<2>& s1, Index a, Index b, double t) {
  EdgeCrossing c;
  c.domain_edge = s1.find_edge(a, b);
  c.domain_parameter = a < b ? t : 1.0 - t;
  return c;
}

/// Passing through S1 vertex v, given as the end of any S1 edge at v.
EdgeCrossing through(const Surface<2>& s1, Index v, Index neighbour) {
  return across(s1, v, neighbour, 0.0);
}

TEST(MortarMassMatrix, IdenticalGridsGiveTheP1MassMatrix) {
  const auto s = grid(3);
  MapBuilder<2> b(s, s);
  for (Index v = 0; v < s->vertex_count(); ++v) b.add_vertex_preimage_at_vertex(v, v);
  for (Index t = 0; t < s->element_count(); ++t) b.add_target_element(t);
  const PlMap<2> map = std::move(b).finalize();
  expect_mortar_identities(map);
  const Eigen::MatrixXd difference = mortar::mortar_mass_matrix(map) - mortar::p1_mass_matrix(*s);
  EXPECT_LT(difference.cwiseAbs().maxCoeff(), tol);
  // and the P1 mass matrix itself: corner (0,0) of a 3 x 3 grid touches two triangles of area 1/18
  EXPECT_NEAR(mortar::p1_mass_matrix(*s)(0, 0), 2 * (1.0 / 18) / 6, tol);
}

TEST(MortarMassMatrix, GridAgainstAntiDiagonalSquare) {
  // S1: 2 x 2 grid with diagonals (i, j)-(i+1, j+1); S2: one square cut along x + y = 1.
  // The S2 diagonal crosses two S1 diagonals and passes the centre vertex (automatic ghost);
  // the S2 boundary edges pass the S1 edge midpoints.
  const auto s1 = grid(2);  // vertex (i, j) = 3 j + i
  const auto s2 = anti_diagonal_square();
  MapBuilder<2> b(s1, s2);
  b.add_vertex_preimage_at_vertex(0, 0);
  b.add_vertex_preimage_at_vertex(1, 2);
  b.add_vertex_preimage_at_vertex(2, 8);
  b.add_vertex_preimage_at_vertex(3, 6);
  const Surface<2>& g = *s1;
  // S2 edges are listed from their smaller-index vertex.
  const std::vector<EdgeCrossing> bottom{through(g, 1, 0)};                 // 0 -> 1
  const std::vector<EdgeCrossing> right{through(g, 5, 2)};                  // 1 -> 2
  const std::vector<EdgeCrossing> top{through(g, 7, 6)};                    // 2 -> 3
  const std::vector<EdgeCrossing> left{through(g, 3, 0)};                   // 0 -> 3
  const std::vector<EdgeCrossing> diagonal{across(g, 1, 5, 0.5), through(g, 4, 0),
                                           across(g, 3, 7, 0.5)};          // 1 -> 3
  b.add_edge(s2->find_edge(0, 1), bottom);
  b.add_edge(s2->find_edge(1, 2), right);
  b.add_edge(s2->find_edge(2, 3), top);
  b.add_edge(s2->find_edge(0, 3), left);
  b.add_edge(s2->find_edge(1, 3), diagonal);
  const PlMap<2> map = std::move(b).finalize();

  // Ghost nodes (all created by the builder) sit at the four edge midpoints and the centre.
  std::set<Index> ghost_vertices;
  for (Index n = 0; n < map.node_count(); ++n)
    if (map.data().node_type[n] == NodeType::ghost)
      ghost_vertices.insert(g.element(map.node_element(n))[map.data().node_location[n]]);
  EXPECT_EQ(ghost_vertices, (std::set<Index>{1, 3, 4, 5, 7}));
  expect_mortar_identities(map);

  // Symmetry of the configuration under (x, y) -> (y, x): S1 vertex (i, j) <-> (j, i), S2 vertex
  // 1 <-> 3; the matrix must be invariant.
  const Eigen::MatrixXd m = mortar::mortar_mass_matrix(map);
  auto swap1 = [](Index v) { return Index(3 * (v % 3) + v / 3); };
  auto swap2 = [](Index v) { return v == 1 ? Index(3) : v == 3 ? Index(1) : v; };
  for (Index i = 0; i < 9; ++i)
    for (Index j = 0; j < 4; ++j) EXPECT_NEAR(m(i, j), m(swap1(i), swap2(j)), tol) << i << ", " << j;
}

// ---- d = 1 -------------------------------------------------------------------------------------

/// Hat function of vertex `v` of a polyline on the x-axis, evaluated at x.
double hat(const Surface<1>& s, Index v, double x) {
  for (Index t : s.vertex_elements(v)) {
    const double a = s.corner(t, 0).x(), b = s.corner(t, 1).x();
    if (x >= std::min(a, b) && x <= std::max(a, b)) return s.element(t)[0] == v ? (b - x) / (b - a) : (x - a) / (b - a);
  }
  return 0.0;
}

TEST(MortarMassMatrix, SubdivisionsOfASegmentMatchDirectIntegration) {
  // S1: [0, 1] split at 0.25 and 0.5; S2: split at 1/3. Both on the x-axis, left to right.
  auto s1 = std::make_shared<const Surface<1>>(
      std::vector<WorldPoint<1>>{{0, 0}, {1, 0}, {0.25, 0}, {0.5, 0}},
      std::vector<ElementCorners<1>>{{0, 2}, {2, 3}, {3, 1}});
  auto s2 = std::make_shared<const Surface<1>>(std::vector<WorldPoint<1>>{{0, 0}, {1, 0}, {1.0 / 3, 0}},
                                               std::vector<ElementCorners<1>>{{0, 2}, {2, 1}});
  MapBuilder<1> b(s1, s2);
  b.add_vertex_preimage_at_vertex(0, 0);
  b.add_vertex_preimage_at_vertex(1, 1);
  b.add_vertex_preimage(2, {1, LocalPoint<1>((1.0 / 3 - 0.25) / 0.25)});
  const std::vector<VertexCrossing> first{{2, 0.25 / (1.0 / 3)}};
  const std::vector<VertexCrossing> second{{3, (0.5 - 1.0 / 3) / (2.0 / 3)}};
  b.add_edge(0, first);
  b.add_edge(1, second);
  const PlMap<1> map = std::move(b).finalize();
  expect_mortar_identities(map);

  // Independent oracle: Simpson on every piece between merged breakpoints (exact for the
  // quadratic products of two hat functions).
  const std::vector<double> breaks{0.0, 0.25, 1.0 / 3, 0.5, 1.0};
  const Eigen::MatrixXd m = mortar::mortar_mass_matrix(map);
  for (Index i = 0; i < s1->vertex_count(); ++i)
    for (Index j = 0; j < s2->vertex_count(); ++j) {
      double exact = 0.0;
      for (std::size_t k = 0; k + 1 < breaks.size(); ++k) {
        const double a = breaks[k], c = breaks[k + 1], mid = 0.5 * (a + c);
        auto f = [&](double x) { return hat(*s1, i, x) * hat(*s2, j, x); };
        exact += (c - a) / 6 * (f(a) + 4 * f(mid) + f(c));
      }
      EXPECT_NEAR(m(i, j), exact, tol) << "M(" << i << ", " << j << ")";
    }
}

}  // namespace
}  // namespace plmap
