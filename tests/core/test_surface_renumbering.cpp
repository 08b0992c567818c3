// plmap::renumbered_surface (core/surface_renumbering.hpp): the copy made by renaming a surface's
// own arrays is exactly the surface the constructor builds from the renumbered vertices and
// elements — every accessor, the edge numbers, the order of every list and the measure to the
// last bit — for random permutations of manifold, non-manifold, holed and isolated-vertex
// surfaces (d = 1 and d = 2), on any number of threads; lists that are no permutation are a
// clean error.
#include <plmap/core/errors.hpp>
#include <plmap/core/surface_renumbering.hpp>
#include <plmap/verify/generators/random_surfaces.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <string>
#include <vector>

using namespace plmap;
namespace gen = plmap::generators;

namespace {

struct Permutation {
  std::vector<Index> element, vertex;  // new -> old
};

Permutation random_permutation(Index elements, Index vertices, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  Permutation p;
  p.element.resize(static_cast<std::size_t>(elements));
  p.vertex.resize(static_cast<std::size_t>(vertices));
  std::iota(p.element.begin(), p.element.end(), 0);
  std::iota(p.vertex.begin(), p.vertex.end(), 0);
  std::shuffle(p.element.begin(), p.element.end(), rng);
  std::shuffle(p.vertex.begin(), p.vertex.end(), rng);
  return p;
}

/// The renumbered surface as any caller would make it: permuted arrays through the constructor.
template <int d>
Surface<d> constructed(const Surface<d>& s, const Permutation& p) {
  std::vector<Index> new_vertex(p.vertex.size());
  for (std::size_t v = 0; v < p.vertex.size(); ++v) new_vertex[static_cast<std::size_t>(p.vertex[v])] = static_cast<Index>(v);
  std::vector<WorldPoint<d>> vertices;
  for (const Index old : p.vertex) vertices.push_back(s.vertex(old));
  std::vector<ElementCorners<d>> elements;
  for (const Index old : p.element) {
    ElementCorners<d> c = s.element(old);
    for (Index& v : c) v = new_vertex[static_cast<std::size_t>(v)];
    elements.push_back(c);
  }
  return Surface<d>(std::move(vertices), std::move(elements));
}

template <int d>
void expect_identical(const Surface<d>& fast, const Surface<d>& built, const std::string& what) {
  SCOPED_TRACE(what);
  ASSERT_EQ(fast.vertex_count(), built.vertex_count());
  ASSERT_EQ(fast.element_count(), built.element_count());
  ASSERT_EQ(fast.edge_count(), built.edge_count());
  EXPECT_EQ(fast.vertices(), built.vertices());
  EXPECT_EQ(fast.elements(), built.elements());
  // exactly: the same numbers summed in the same order, maxima and minima of the same numbers
  EXPECT_EQ(fast.measure(), built.measure());
  EXPECT_EQ(fast.max_edge_length(), built.max_edge_length());
  EXPECT_EQ(fast.bounding_box_min(), built.bounding_box_min());
  EXPECT_EQ(fast.bounding_box_max(), built.bounding_box_max());
  for (Index v = 0; v < fast.vertex_count(); ++v) {
    const auto a = fast.vertex_elements(v), b = built.vertex_elements(v);
    EXPECT_TRUE(std::equal(a.begin(), a.end(), b.begin(), b.end())) << "vertex " << v;
    EXPECT_EQ(fast.is_boundary_vertex(v), built.is_boundary_vertex(v)) << "vertex " << v;
  }
  for (Index t = 0; t < fast.element_count(); ++t) {
    EXPECT_EQ(fast.element_measure(t), built.element_measure(t)) << "element " << t;
    EXPECT_EQ(fast.element_normal(t), built.element_normal(t)) << "element " << t;
  }
  if constexpr (d == 2) {
    for (Index e = 0; e < fast.edge_count(); ++e) {
      EXPECT_EQ(fast.edge_vertices(e), built.edge_vertices(e)) << "edge " << e;
      const auto a = fast.edge_elements(e), b = built.edge_elements(e);
      EXPECT_TRUE(std::equal(a.begin(), a.end(), b.begin(), b.end())) << "edge " << e;
      EXPECT_EQ(fast.find_edge(built.edge_vertices(e)[1], built.edge_vertices(e)[0]), e);
    }
    for (Index t = 0; t < fast.element_count(); ++t)
      for (int k = 0; k < 3; ++k) EXPECT_EQ(fast.element_edge(t, k), built.element_edge(t, k)) << "element " << t << " edge " << k;
  }
}

template <int d>
void expect_renumbered_as_constructed(const Surface<d>& s, const std::string& name, int seeds = 4) {
  for (int seed = 0; seed < seeds; ++seed) {
    const Permutation p = random_permutation(s.element_count(), s.vertex_count(), 1000 + static_cast<std::uint64_t>(seed));
    const Surface<d> built = constructed(s, p);
    for (const unsigned threads : {1u, 2u, 3u})
      expect_identical(renumbered_surface(s, p.element, p.vertex, threads), built,
                       name + ", seed " + std::to_string(seed) + ", threads " + std::to_string(threads));
  }
  // the identity gives the surface itself
  Permutation identity;
  identity.element.resize(static_cast<std::size_t>(s.element_count()));
  identity.vertex.resize(static_cast<std::size_t>(s.vertex_count()));
  std::iota(identity.element.begin(), identity.element.end(), 0);
  std::iota(identity.vertex.begin(), identity.vertex.end(), 0);
  expect_identical(renumbered_surface(s, identity.element, identity.vertex, 2), s, name + ", identity");
}

/// `s` with one vertex that no element uses, put in the middle of the numbering.
template <int d>
Surface<d> with_isolated_vertex(const Surface<d>& s) {
  std::vector<WorldPoint<d>> vertices = s.vertices();
  const auto middle = static_cast<Index>(vertices.size() / 2);
  vertices.insert(vertices.begin() + middle, WorldPoint<d>::Constant(0.25));
  std::vector<ElementCorners<d>> elements = s.elements();
  for (auto& c : elements)
    for (Index& v : c)
      if (v >= middle) ++v;
  return Surface<d>(std::move(vertices), std::move(elements));
}

}  // namespace

TEST(SurfaceRenumbering, TriangleSurfacesAreThoseTheConstructorBuilds) {
  gen::Rng rng(20261205);
  const Surface<2> grid = gen::grid_triangulation({.cells = 12, .jitter = 0.15, .with_hole = true}, rng);
  expect_renumbered_as_constructed(gen::lift_to_height_field(grid, gen::random_height_field(rng)), "holed height field");
  expect_renumbered_as_constructed(gen::add_fins(grid, 5, rng), "fins (edges of three triangles)");
  const Surface<2> delaunay = gen::delaunay_triangulation({.interior_points = 60, .boundary_points = 12}, rng);
  expect_renumbered_as_constructed(gen::join_at_corner(delaunay, grid), "two sheets on one vertex");
  expect_renumbered_as_constructed(with_isolated_vertex(delaunay), "isolated vertex");
  // large enough for every thread to take many items
  expect_renumbered_as_constructed(gen::grid_triangulation({.cells = 96, .jitter = 0.1}, rng), "large grid", 1);
}

TEST(SurfaceRenumbering, CurvesAreThoseTheConstructorBuilds) {
  gen::Rng rng(7);
  expect_renumbered_as_constructed(gen::random_open_polyline(40, rng), "open polyline");
  expect_renumbered_as_constructed(gen::random_closed_polyline(40, rng), "closed polyline");
  expect_renumbered_as_constructed(gen::random_star_polyline(4, 9, rng), "star");
  expect_renumbered_as_constructed(with_isolated_vertex(gen::random_closed_polyline(25, rng)), "isolated vertex");
}

TEST(SurfaceRenumbering, ListsThatAreNoPermutationAreRejected) {
  gen::Rng rng(3);
  const Surface<2> s = gen::grid_triangulation({.cells = 3}, rng);
  Permutation p = random_permutation(s.element_count(), s.vertex_count(), 5);
  Permutation repeated = p;
  repeated.element[1] = repeated.element[0];
  EXPECT_THROW(renumbered_surface(s, repeated.element, repeated.vertex), InvalidSurfaceError);
  Permutation out_of_range = p;
  out_of_range.vertex[2] = s.vertex_count();
  EXPECT_THROW(renumbered_surface(s, out_of_range.element, out_of_range.vertex), InvalidSurfaceError);
  Permutation short_list = p;
  short_list.vertex.pop_back();
  EXPECT_THROW(renumbered_surface(s, short_list.element, short_list.vertex), InvalidSurfaceError);
}
