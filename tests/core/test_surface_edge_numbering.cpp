// Surface<2>'s edge numbering is part of what maps store (intersection nodes name S2 edges by
// number, in map files too), so building the edges faster must not renumber them: edges in
// (smaller vertex, larger vertex) order, each edge's incidences in element order. Compared here
// with the plain definition (one sort of all (a, b, element, local edge) records) on grids,
// Delaunay triangulations and non-manifold surfaces with fins.

#include <plmap/core/surface.hpp>
#include <plmap/verify/generators/random_surfaces.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <tuple>
#include <vector>

namespace plmap {
namespace {

void expect_edges_by_definition(const Surface<2>& s) {
  struct Record {
    Index a, b, t;
    int k;
  };
  std::vector<Record> records;
  for (Index t = 0; t < s.element_count(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const Index u = s.elements()[t][k], w = s.elements()[t][(k + 1) % 3];
      records.push_back({std::min(u, w), std::max(u, w), t, k});
    }
  }
  std::sort(records.begin(), records.end(),
            [](const Record& x, const Record& y) { return std::tie(x.a, x.b, x.t) < std::tie(y.a, y.b, y.t); });
  Index e = -1;
  std::size_t incidences = 0;
  for (std::size_t i = 0; i < records.size(); ++i) {
    if (i == 0 || records[i].a != records[i - 1].a || records[i].b != records[i - 1].b) {
      ++e;
      ASSERT_LT(e, s.edge_count());
      EXPECT_EQ(s.edge_vertices(e), (std::array<Index, 2>{records[i].a, records[i].b})) << "edge " << e;
      incidences = 0;
    }
    ASSERT_LT(incidences, s.edge_elements(e).size()) << "edge " << e;
    EXPECT_EQ(s.edge_elements(e)[incidences].element, records[i].t) << "edge " << e;
    EXPECT_EQ(s.edge_elements(e)[incidences].local_edge, records[i].k) << "edge " << e;
    EXPECT_EQ(s.element_edge(records[i].t, records[i].k), e);
    ++incidences;
  }
  EXPECT_EQ(e + 1, s.edge_count());
}

TEST(SurfaceEdgeNumbering, IsTheSortedOrderOfVertexPairsAndElements) {
  for (std::uint64_t seed = 0; seed < 20; ++seed) {
    generators::Rng rng(seed);
    generators::GridOptions grid;
    grid.cells = 4 + static_cast<int>(seed % 5) * 4;
    grid.jitter = 0.1;
    grid.with_hole = seed % 2 == 1;
    const Surface<2> sheet = generators::grid_triangulation(grid, rng);
    expect_edges_by_definition(sheet);
    expect_edges_by_definition(generators::add_fins(sheet, 3, rng));  // edges of 3+ triangles
    generators::DelaunayOptions delaunay;
    expect_edges_by_definition(generators::delaunay_triangulation(delaunay, rng));
  }
}

}  // namespace
}  // namespace plmap
