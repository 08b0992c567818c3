#pragma once
// Normal projection on copies of S1 and S2 numbered along a space-filling curve, when the
// caller's numbering is in no spatial order (issue 14, item 3; docs/projection.md, "The order
// of the input").
//
// Why: every phase of the projection steps from an element to its neighbours (seed walks, edge
// walks, the closure of one element after the other). CGAL's meshes, and meshes remeshed by most
// tools, list their triangles in no spatial order: the centroids of consecutive triangles lie
// about 50 edge lengths apart, and a triangle's neighbours sit in other cache lines and pages
// than the triangle. Numbered in the Morton order of their centroids, the same surfaces project
// about 30 % faster (docs/benchmarks.md). The map is then expressed on the caller's surfaces:
// every element keeps its corners in their order, so every local and barycentric coordinate of
// the map stays as it is, and only numbers change (S1 elements regroup the per-element arrays;
// S2 elements, vertices and edges are renamed).
//
// The copies are made only when an order is poor (ProjectionOptions::renumbering), so surfaces
// generated in rows or by subdivision project on themselves, as before.

#include <plmap/construct/projection_options.hpp>
#include <plmap/construct/projection_result.hpp>
#include <plmap/core/surface.hpp>

#include <memory>
#include <vector>

namespace plmap::projection {

/// A surface, or its copy renumbered along a space-filling curve, with the way back.
template <int d>
struct RenumberedSurface {
  std::shared_ptr<const Surface<d>> surface;
  /// For each element (vertex) of the copy, the caller's number; both empty when `surface` is
  /// the caller's own.
  std::vector<Index> original_element;
  std::vector<Index> original_vertex;
  bool renumbered() const { return !original_element.empty(); }
};

/// How far apart the centroids of consecutive elements lie: the median over (at most 8192,
/// evenly spread) consecutive pairs, in units of the typical element size (the d-th root of the
/// mean element measure). About 0.5–1 for surfaces generated in rows or by subdivision, about 50
/// for CGAL's meshes; 0 for fewer than two elements.
template <int d>
double consecutive_element_spacing(const Surface<d>& s);

/// Above this spacing the order counts as poor (ProjectionOptions::renumbering = automatic).
inline constexpr double poor_order_spacing = 4.0;

/// The surface with its elements in the Morton order of their centroids (within its bounding
/// box) and its vertices in the order those elements first use them (vertices no element uses
/// last, in their order). Every element keeps its corners in their order. On up to `threads`
/// threads (0: all the process may run on); the copy does not depend on them.
template <int d>
RenumberedSurface<d> spatially_renumbered(const Surface<d>& s, unsigned threads = 1);

/// Which surfaces the projection works on renumbered copies of.
struct RenumberingChoice {
  bool domain = false, target = false;
};

/// always: both; target: S2 (and S1 with it when they are one object); never: neither;
/// automatic: S2 when its consecutive_element_spacing exceeds poor_order_spacing, unless S1 and
/// S2 are one object (the identity). S2's numbers are renamed in the finished map in place; S1's
/// order is the order of every per-element array of the map, so renumbering S1 means a gather of
/// the whole map into the caller's order, which on the armadillo pair costs about what S1's order
/// saves (docs/benchmarks.md, "The order of the input").
template <int d>
RenumberingChoice renumbering_choice(const Surface<d>& s2, bool s1_is_s2, SpatialRenumbering rule);

/// `s` as given, or its copy in spatial order (made on up to `threads` threads).
template <int d>
RenumberedSurface<d> renumbered_or_kept(const std::shared_ptr<const Surface<d>>& s, bool renumber, unsigned threads = 1);

/// The options for surfaces numbered as `s1`: the per-vertex directions follow S1's vertices.
template <int d>
ProjectionOptions options_for_renumbered(ProjectionOptions options, const RenumberedSurface<d>& s1);

/// The result of projecting `s1.surface` onto `s2.surface`, expressed on the caller's surfaces
/// `original1` and `original2`: S1 elements back in their order (nodes and regions regrouped,
/// the node and region numbers they hold shifted), S2 elements, vertices and edges renamed, and
/// the report's element and edge numbers (and edge parameters, which run from an edge's
/// smaller-numbered vertex) translated. A surface that was not renumbered keeps its numbers.
/// S2's numbers are renamed on up to `threads` threads; the result does not depend on them.
template <int d>
ProjectionResult<d> in_original_numbering(ProjectionResult<d> result, const RenumberedSurface<d>& s1,
                                          const RenumberedSurface<d>& s2,
                                          const std::shared_ptr<const Surface<d>>& original1,
                                          const std::shared_ptr<const Surface<d>>& original2, unsigned threads = 1);

}  // namespace plmap::projection
