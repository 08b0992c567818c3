#pragma once
/// \file
/// Surface<d>: a d-dimensional simplicial surface in R^(d+1) (d = 1: polyline in the plane,
/// d = 2: triangle surface in space), manifold or not, with or without boundary.

#include <plmap/core/types.hpp>

#include <span>
#include <string>
#include <vector>

namespace plmap {

struct SurfaceRenumbering;

/// Where an edge sits in one of its triangles (d = 2 only).
struct EdgeIncidence {
  Index element;
  int local_edge;  ///< 0, 1 or 2; local edge k joins corners k and (k+1) mod 3
  friend bool operator==(const EdgeIncidence&, const EdgeIncidence&) = default;
};

/// A simplicial surface: vertex positions and elements, plus the adjacency plmap needs.
///
/// Construction validates the input and throws InvalidSurfaceError naming the offending element
/// or vertex: non-finite coordinates, indices out of range, repeated corners, elements of zero
/// measure (relative to the surface's size) and duplicate elements are rejected, and so are
/// surfaces whose element measures are not normal doubles (edge lengths beyond about 1e-150 to
/// 1e150): measures and normals are computed from scaled edge vectors, so every scale inside that
/// range gives the same verdicts and the same relative results.
///
/// A vertex that no element uses (an isolated vertex, common in OFF and PLY files) is kept, so
/// that vertex numbers stay those of the file, but it is not part of the surface: it has no
/// elements, no normal, needs no preimage or image, and the constructions and checks skip it. Non-manifold
/// configurations (an edge with three or more triangles, vertices joining several fans) and
/// boundaries are fine.
///
/// For d = 2, local edge k of a triangle joins corners k and (k+1) mod 3, so walking the local
/// edges in order goes counter-clockwise around the triangle. Global edges are stored with their
/// smaller vertex index first.
template <int d>
  requires SurfaceDimension<d>
class Surface {
 public:
  static constexpr int dimension = d;

  Surface() = default;
  Surface(std::vector<WorldPoint<d>> vertices, std::vector<ElementCorners<d>> elements);

  Index vertex_count() const { return static_cast<Index>(vertices_.size()); }
  Index element_count() const { return static_cast<Index>(elements_.size()); }
  /// Number of edges; for d = 1 the edges are the elements themselves.
  Index edge_count() const;

  const WorldPoint<d>& vertex(Index v) const { return vertices_[v]; }
  const ElementCorners<d>& element(Index t) const { return elements_[t]; }
  const std::vector<WorldPoint<d>>& vertices() const { return vertices_; }
  const std::vector<ElementCorners<d>>& elements() const { return elements_; }

  /// Position of corner k of element t.
  const WorldPoint<d>& corner(Index t, int k) const { return vertices_[elements_[t][k]]; }
  /// World position of a point given by local coordinates on element t.
  /// (Inline: it is part of every evaluation.)
  WorldPoint<d> world_position(Index t, const LocalPoint<d>& xi) const {
    const auto& c = elements_[t];
    const WorldPoint<d>& c0 = vertices_[c[0]];
    WorldPoint<d> x = c0;
    for (int i = 0; i < d; ++i) x += xi(i) * (vertices_[c[i + 1]] - c0);
    return x;
  }
  /// Length (d = 1) or area (d = 2) of element t.
  double element_measure(Index t) const;
  /// Sum of all element measures (computed once, at construction).
  double measure() const { return measure_; }
  /// Unit normal of element t (for d = 1 the segment direction rotated clockwise).
  WorldPoint<d> element_normal(Index t) const;
  /// Length of the longest edge of the surface; the scale for relative tolerances.
  double max_edge_length() const { return max_edge_length_; }
  /// The same surface with every coordinate multiplied by 2^exponent: exact (no rounding unless
  /// coordinates become subnormal), adjacency copied. The constructions work on such a copy of
  /// unit size, so that their arithmetic is the same at every scale of the input.
  Surface scaled_by_power_of_two(int exponent) const;
  /// Axis-aligned bounding box.
  WorldPoint<d> bounding_box_min() const { return box_min_; }
  WorldPoint<d> bounding_box_max() const { return box_max_; }

  /// Elements that have vertex v as a corner, in increasing order.
  std::span<const Index> vertex_elements(Index v) const {
    return {vertex_element_.data() + vertex_element_begin_[v],
            vertex_element_.data() + vertex_element_begin_[v + 1]};
  }
  /// Which corner of element t is vertex v, or -1. (Inline: the map builder asks it millions of
  /// times, to re-express images on S2 elements.)
  int local_corner(Index t, Index v) const {
    const auto& c = elements_[t];
    for (int k = 0; k <= d; ++k)
      if (c[k] == v) return k;
    return -1;
  }

  // ---- edges (d = 2) ----
  /// The two vertices of edge e, smaller index first.
  std::array<Index, 2> edge_vertices(Index e) const
    requires(d == 2)
  {
    return edges_[e];
  }
  /// Global edge index of local edge k of element t.
  Index element_edge(Index t, int k) const
    requires(d == 2)
  {
    return element_edges_[t][k];
  }
  /// The triangles containing edge e (any number: one on the boundary, three or more at
  /// non-manifold edges), in increasing element order.
  std::span<const EdgeIncidence> edge_elements(Index e) const
    requires(d == 2)
  {
    return {edge_incidence_.data() + edge_incidence_begin_[e],
            edge_incidence_.data() + edge_incidence_begin_[e + 1]};
  }
  /// Edge joining vertices a and b, or invalid_index.
  Index find_edge(Index a, Index b) const
    requires(d == 2);
  /// True if local edge k of t runs from the smaller to the larger vertex index.
  bool local_edge_is_forward(Index t, int k) const
    requires(d == 2)
  {
    return elements_[t][k] < elements_[t][(k + 1) % 3];
  }

  /// True when the surface has a vertex shared by no element or an edge/vertex with only one
  /// element; boundary = edges (d = 2) or vertices (d = 1) with exactly one element.
  bool is_boundary_vertex(Index v) const;

 private:
  // renumbered_surface (surface_renumbering.hpp) fills the arrays of a renumbered copy directly
  friend struct SurfaceRenumbering;

  void validate() const;
  void build_adjacency();

  std::vector<WorldPoint<d>> vertices_;
  std::vector<ElementCorners<d>> elements_;
  std::vector<Index> vertex_element_begin_;
  std::vector<Index> vertex_element_;
  // d = 2 only
  std::vector<std::array<Index, 2>> edges_;
  std::vector<std::array<Index, 3>> element_edges_;
  std::vector<Index> edge_incidence_begin_;
  std::vector<EdgeIncidence> edge_incidence_;
  std::vector<bool> boundary_vertex_;

  double max_edge_length_ = 0.0;
  double measure_ = 0.0;
  WorldPoint<d> box_min_ = WorldPoint<d>::Zero();
  WorldPoint<d> box_max_ = WorldPoint<d>::Zero();
};

using Curve = Surface<1>;
using TriangleSurface = Surface<2>;

extern template class Surface<1>;
extern template class Surface<2>;

}  // namespace plmap
