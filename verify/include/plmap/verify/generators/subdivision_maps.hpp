#pragma once
/// \file
/// Maps whose regions are known in advance: S2 is a logical subdivision of S1 in which every S1
/// element is cut into k x k sub-elements (d = 2: the regular subdivision of the triangle into
/// k^2 triangles; d = 1: k segments), interior subdivision points jittered, S2 lifted off S1 by a
/// small wave so that it is not S1 itself. Sub-elements can be dropped from S2, which leaves holes
/// in D ∩ T (a non-convex, possibly disconnected domain on an element). The map is built through
/// MapBuilder (add_vertex_preimage*, add_target_element), exactly as a user would.
///
/// Used by the point-location tests, bench_point_location, psurface_eval and the experiment
/// runner's `refine` step; the sample surfaces below are their inputs.

#include <plmap/core/pl_map.hpp>

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

namespace plmap::generators {

template <int d>
struct SubdivisionMap {
  std::shared_ptr<const Surface<d>> domain;
  std::shared_ptr<const Surface<d>> target;
  std::shared_ptr<const PlMap<d>> map;
  /// Points strictly inside dropped sub-elements (outside D), one per dropped sub-element.
  std::vector<SurfacePoint<d>> holes;
};

/// Which sub-elements to drop: (S1 element, sub-element number on it) -> true to drop.
using DropRule = std::function<bool(Index element, int sub_element)>;

/// The k x k subdivision of every triangle of S1 (d = 2), or of every segment into k pieces
/// (d = 1), interior points moved by up to jitter / k (jitter <= 0.2 keeps every sub-triangle
/// positively oriented), sub-elements dropped by `drop`.
SubdivisionMap<2> subdivision_map(std::shared_ptr<const Surface<2>> s1, int k, double jitter, std::uint64_t seed,
                                  const DropRule& drop = {});
SubdivisionMap<1> subdivision_map(std::shared_ptr<const Surface<1>> s1, int k, double jitter, std::uint64_t seed,
                                  const DropRule& drop = {});

/// Two triangles forming the unit square at z = 0 (counter-clockwise seen from +z).
std::shared_ptr<const Surface<2>> two_triangles();
/// An n x n grid of squares over the unit square, each cut into two triangles, on a gentle
/// height field.
std::shared_ptr<const Surface<2>> bumpy_grid(int n);
/// A zigzag polyline of n segments in the plane.
std::shared_ptr<const Surface<1>> zigzag_curve(int n);

}  // namespace plmap::generators
