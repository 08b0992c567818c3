#pragma once
/// \file
/// Merging vertices that lie at exactly the same position: welding a polygon soup (every element
/// with corners of its own, as CGAL's `boeing.off`) or a seam whose two sides were never stitched.
///
/// Normal projection needs its surfaces stitched: across an unstitched seam no walk continues, and
/// a surface projected onto a copy of itself loses whole elements along it (docs/robustness.md).
/// `plmap project` warns about such vertices; `plmap convert IN OUT --merge-coincident` merges them.
///
/// Positions are compared exactly (0.0 equals -0.0), as the STL reader merges corners: no tolerance
/// decides which vertices are one, so nothing is merged that the file did not place at one point.

#include <plmap/core/surface.hpp>

namespace plmap {

struct VertexMergeReport {
  /// Vertices that took the number of an earlier vertex at the same position.
  Index merged_vertices = 0;
  /// Elements dropped because an earlier element has the same corners after merging (either
  /// orientation): a soup that lists a triangle twice, or both sides of one.
  Index duplicate_elements = 0;
};

/// `s` with every vertex at exactly the position of an earlier vertex replaced by that one, and
/// duplicate elements (the same corners, in any order) kept once. Vertices keep their order (of
/// each group at one position the first stays, the others go); elements keep their order and
/// their corners' order. A surface without coincident vertices comes back unchanged. Throws
/// InvalidSurfaceError if the merged elements do not make a surface (the error names why).
template <int d>
  requires SurfaceDimension<d>
Surface<d> merge_coincident_vertices(const Surface<d>& s, VertexMergeReport* report = nullptr);

extern template Surface<1> merge_coincident_vertices<1>(const Surface<1>&, VertexMergeReport*);
extern template Surface<2> merge_coincident_vertices<2>(const Surface<2>&, VertexMergeReport*);

}  // namespace plmap
