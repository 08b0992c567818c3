// merge_coincident_vertices (core/vertex_merging.hpp): vertices at exactly one position become
// one, duplicate elements are kept once, and nothing else changes.
#include <plmap/core/vertex_merging.hpp>


#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace plmap {
namespace {

TEST(VertexMerging, TwoTrianglesOfASoupShareTheirDiagonal) {
  // The unit square as two triangles with corners of their own: vertices 3 and 5 lie where 1 and 2
  // do. Merged, the square has 4 vertices (0, 1, 2 and 4, in that order) and one interior edge.
  const Surface<2> soup({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {3, 4, 5}});
  EXPECT_EQ(soup.edge_count(), 6);
  VertexMergeReport report;
  const Surface<2> s = merge_coincident_vertices(soup, &report);
  EXPECT_EQ(report.merged_vertices, 2);
  EXPECT_EQ(report.duplicate_elements, 0);
  ASSERT_EQ(s.vertex_count(), 4);
  EXPECT_EQ(s.vertex(3), WorldPoint<2>(1, 1, 0));
  ASSERT_EQ(s.element_count(), 2);
  EXPECT_EQ(s.element(0), (ElementCorners<2>{0, 1, 2}));
  EXPECT_EQ(s.element(1), (ElementCorners<2>{1, 3, 2}));
  EXPECT_EQ(s.edge_count(), 5);
  EXPECT_DOUBLE_EQ(s.measure(), 1.0);
}

TEST(VertexMerging, PositionsAreComparedExactly) {
  // -0.0 is the position 0.0; a position one unit in the last place away is another one.
  const double next = std::nextafter(1.0, 2.0);
  const Surface<1> c({{0.0, 0.0}, {1.0, 0.0}, {-0.0, 0.0}, {0.0, 1.0}, {next, 0.0}, {2.0, 0.0}},
                     {{0, 1}, {2, 3}, {4, 5}});
  VertexMergeReport report;
  const Surface<1> s = merge_coincident_vertices(c, &report);
  EXPECT_EQ(report.merged_vertices, 1);  // vertex 2 into vertex 0
  ASSERT_EQ(s.vertex_count(), 5);
  EXPECT_EQ(s.element(1), (ElementCorners<1>{0, 2}));
  EXPECT_EQ(s.element(2), (ElementCorners<1>{3, 4}));
}

TEST(VertexMerging, AnElementListedTwiceIsKeptOnce) {
  // A soup that lists one triangle twice (the second time reversed, with corners of its own) and
  // a third triangle sharing the edge 1-2 through copies of those vertices. Merged, the first two
  // have the same corners, which a surface refuses: the second goes.
  const Surface<2> twice({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}, {0, 1, 0}},
                         {{0, 1, 2}, {5, 4, 3}, {7, 6, 8}});
  VertexMergeReport report;
  const Surface<2> s = merge_coincident_vertices(twice, &report);
  EXPECT_EQ(report.merged_vertices, 5);
  EXPECT_EQ(report.duplicate_elements, 1);
  ASSERT_EQ(s.vertex_count(), 4);
  ASSERT_EQ(s.element_count(), 2);
  EXPECT_EQ(s.element(0), (ElementCorners<2>{0, 1, 2}));
  EXPECT_EQ(s.element(1), (ElementCorners<2>{1, 3, 2}));
}

TEST(VertexMerging, ASurfaceWithoutCoincidentVerticesComesBackUnchanged) {
  const Surface<2> square({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 2, 3}});
  VertexMergeReport report{7, 7};
  const Surface<2> s = merge_coincident_vertices(square, &report);
  EXPECT_EQ(report.merged_vertices, 0);
  EXPECT_EQ(report.duplicate_elements, 0);
  EXPECT_EQ(s.vertices(), square.vertices());
  EXPECT_EQ(s.elements(), square.elements());
}

TEST(VertexMerging, ACurveMayBranchWhereItsCopiesMeet) {
  // Three segments from copies of the origin: merged, one vertex with three segments (curves
  // may be non-manifold).
  const Surface<1> star({{0, 0}, {1, 0}, {0, 0}, {0, 1}, {0, 0}, {-1, 0}}, {{0, 1}, {2, 3}, {4, 5}});
  VertexMergeReport report;
  const Surface<1> s = merge_coincident_vertices(star, &report);
  EXPECT_EQ(report.merged_vertices, 2);
  ASSERT_EQ(s.vertex_count(), 4);
  EXPECT_EQ(s.elements(), (std::vector<ElementCorners<1>>{{0, 1}, {0, 2}, {0, 3}}));
  EXPECT_EQ(s.vertex_elements(0).size(), 3u);
}

}  // namespace
}  // namespace plmap
