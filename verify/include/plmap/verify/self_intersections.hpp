#pragma once
/// \file
/// Where a surface crosses itself: pairs of elements that meet although they share no vertex.
///
/// Contact and mortar inputs are boundaries of bodies, which do not cross themselves; a surface
/// that does (overlapping bodies joined in one file, such as CGAL's `bones.off`, or an offset copy
/// folded over itself at a crease) has no continuous normal projection across the crossing: the
/// nearest hit jumps from one sheet to the other there. `plmap info` counts such pairs, and the
/// ray check names the area they cost (MissedReason::target_crosses_itself).
///
/// The candidates are the pairs of elements whose bounding boxes meet (CGAL's box intersection,
/// one sweep over all boxes); whether two elements meet is decided with CGAL's exact predicates. Elements that share a vertex are not compared (they meet
/// there by construction; a fold through a shared vertex is not reported). Curves (d = 1): two
/// segments that cross or overlap in the plane.

#include <plmap/core/surface.hpp>

#include <utility>
#include <vector>

namespace plmap {

/// The pairs (a, b), a < b, of elements of s that meet and share no vertex, sorted; searched on
/// up to `threads` threads (0: all), with the same answer for every count.
template <int d>
  requires SurfaceDimension<d>
std::vector<std::pair<Index, Index>> self_intersections(const Surface<d>& s, unsigned threads = 0);

extern template std::vector<std::pair<Index, Index>> self_intersections<1>(const Surface<1>&, unsigned);
extern template std::vector<std::pair<Index, Index>> self_intersections<2>(const Surface<2>&, unsigned);

}  // namespace plmap
