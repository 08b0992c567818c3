#pragma once
/// \file
/// A surface with its elements and vertices renumbered, made from the surface itself instead of
/// by the constructor. Normal projection works on such copies of surfaces whose numbering is in
/// no spatial order (construct/src/spatial_renumbering.hpp).
///
/// Why not the constructor: it validates and derives everything from scratch (a sort of each
/// vertex's edges, one vertex after the other), which was half of the projection's renumbering of
/// a CGAL mesh, all of it on one thread. A permutation of a valid surface is valid, its bounding
/// box and longest edge are the same numbers, and its adjacency is the old one renamed: here it is
/// renamed on up to `threads` threads. The result is nevertheless exactly the surface the
/// constructor makes from the renumbered vertices and elements, array for array (the projection
/// reads edge numbers, and a surface must not depend on how it was made): edges numbered by
/// their (smaller, larger) new vertex numbers, every list in increasing new element order, and
/// the measure summed in the new element order (a sum in another order may differ in its last
/// bits, and the projection reports the measure of the surface it worked on).
/// tests/core/test_surface_renumbering.cpp compares every accessor with the constructor's.

#include <plmap/core/surface.hpp>

#include <span>

namespace plmap {

/// `s` renumbered: element i of the result is element original_element[i] of `s`, its corners
/// in the same order, renamed; vertex j is vertex original_vertex[j] of `s`. Both lists must be
/// permutations (of the element and vertex numbers of `s`), else InvalidSurfaceError. Runs on up
/// to `threads` threads (0: all the process may run on); the result does not depend on them.
template <int d>
  requires SurfaceDimension<d>
Surface<d> renumbered_surface(const Surface<d>& s, std::span<const Index> original_element,
                              std::span<const Index> original_vertex, unsigned threads = 1);

extern template Surface<1> renumbered_surface<1>(const Surface<1>&, std::span<const Index>, std::span<const Index>,
                                                 unsigned);
extern template Surface<2> renumbered_surface<2>(const Surface<2>&, std::span<const Index>, std::span<const Index>,
                                                 unsigned);

}  // namespace plmap
