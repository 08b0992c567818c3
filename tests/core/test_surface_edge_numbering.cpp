// Surface<2>'s edge numbering is part of what maps store (intersection nodes name S2 edges by
// number, in map files too), so building the edges faster must not renumber them: edges in
// (smaller vertex, larger vertex) order, each edge's incidences in element order. Compared here
// with the plain definition (one sort of all (a, b, element, local edge) records) on grids,
// Delaunay triangulations and non-manifold surfaces with fins. Duplicate triangles, now found
// through the edges, must be reported as sorting all triangles reported them.

#include <plmap/core/errors.hpp>
#include <plmap/core/surface.hpp>
#include <plmap/verify/generators/random_surfaces.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
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

/// The message of duplicate triangles by its definition: the elements sorted by their sorted
/// vertex triple (then number), the first two equal neighbours.
std::string duplicate_message_by_definition(const std::vector<ElementCorners<2>>& elements) {
  std::vector<std::pair<std::array<Index, 3>, Index>> keys;
  for (Index t = 0; t < static_cast<Index>(elements.size()); ++t) {
    auto k = elements[t];
    std::sort(k.begin(), k.end());
    keys.push_back({k, t});
  }
  std::sort(keys.begin(), keys.end());
  for (std::size_t i = 1; i < keys.size(); ++i) {
    if (keys[i].first == keys[i - 1].first) {
      return "elements " + std::to_string(keys[i - 1].second) + " and " + std::to_string(keys[i].second) +
             " have the same three vertices";
    }
  }
  return "";
}

TEST(SurfaceEdgeNumbering, DuplicateTrianglesAreReportedAsBySortingThem) {
  generators::Rng rng(5);
  generators::GridOptions grid;
  grid.cells = 6;
  const Surface<2> sheet = generators::grid_triangulation(grid, rng);
  // Copies (in either orientation) of elements of several groups, some twice, appended in an
  // order that differs from their vertex order.
  const std::vector<std::vector<Index>> copies = {{40}, {40, 3}, {3, 40, 3}, {17, 5, 30}, {70, 2}};
  for (const auto& copy : copies) {
    std::vector<ElementCorners<2>> elements = sheet.elements();
    for (const Index t : copy) {
      const ElementCorners<2> e = elements[t];
      elements.push_back(elements.size() % 2 == 0 ? e : ElementCorners<2>{e[1], e[0], e[2]});
    }
    const std::string expected = duplicate_message_by_definition(elements);
    ASSERT_FALSE(expected.empty());
    try {
      const Surface<2> s(sheet.vertices(), elements);
      ADD_FAILURE() << "duplicate triangles were accepted";
    } catch (const InvalidSurfaceError& e) {
      EXPECT_EQ(std::string(e.what()), expected);
    }
  }
}

/// The message of duplicate segments by its definition: the segments sorted by their sorted
/// vertex pair (then number), the first two equal neighbours.
std::string duplicate_segment_message_by_definition(const std::vector<ElementCorners<1>>& elements) {
  std::vector<std::pair<std::array<Index, 2>, Index>> keys;
  for (Index t = 0; t < static_cast<Index>(elements.size()); ++t)
    keys.push_back({{std::min(elements[t][0], elements[t][1]), std::max(elements[t][0], elements[t][1])}, t});
  std::sort(keys.begin(), keys.end());
  for (std::size_t i = 1; i < keys.size(); ++i)
    if (keys[i].first == keys[i - 1].first)
      return "elements " + std::to_string(keys[i - 1].second) + " and " + std::to_string(keys[i].second) +
             " join the same two vertices";
  return "";
}

TEST(SurfaceEdgeNumbering, DuplicateSegmentsAreReportedAsBySortingThem) {
  // A closed polygon of 12 vertices plus chords from vertex 0 (a junction of degree 8), then
  // copies of some segments in either orientation, appended out of order.
  std::vector<WorldPoint<1>> vertices;
  for (int i = 0; i < 12; ++i) vertices.emplace_back(std::cos(0.5 * i), std::sin(0.5 * i));
  std::vector<ElementCorners<1>> base;
  for (Index i = 0; i < 12; ++i) base.push_back({i, (i + 1) % 12});
  for (Index i = 3; i < 9; ++i) base.push_back({i, 0});
  const std::vector<std::vector<Index>> copies = {{5}, {16, 2}, {2, 16, 2}, {11, 13, 0}, {7, 17}};
  for (const auto& copy : copies) {
    std::vector<ElementCorners<1>> elements = base;
    for (const Index t : copy) {
      const ElementCorners<1> e = elements[t];
      elements.push_back(elements.size() % 2 == 0 ? e : ElementCorners<1>{e[1], e[0]});
    }
    const std::string expected = duplicate_segment_message_by_definition(elements);
    ASSERT_FALSE(expected.empty());
    try {
      const Surface<1> s(vertices, elements);
      ADD_FAILURE() << "duplicate segments were accepted";
    } catch (const InvalidSurfaceError& e) {
      EXPECT_EQ(std::string(e.what()), expected);
    }
  }
  EXPECT_NO_THROW(Surface<1>(vertices, base));
}

}  // namespace
}  // namespace plmap
