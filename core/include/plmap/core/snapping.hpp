#pragma once
/// \file
/// The snapping rule of plmap (DESIGN.md §3): when a point of a surface given by coordinates is
/// "on" a vertex or an edge of its element. Every construction decides it with these functions,
/// so that the map builder and the constructions that feed it (normal projection, the
/// generators) agree on which nodes are corners, touching nodes or interior nodes.
///
/// The tolerance is in local coordinates, hence relative to the element's size: a barycentric
/// weight at most `tolerance` is zero, and a point at edge parameter at most `tolerance` from an
/// end of the edge is that end vertex. Negative weights larger than −tolerance are rounding and
/// snap to zero as well; whether a more negative weight is an error (a point outside the element)
/// is for the caller to decide before snapping.

#include <plmap/core/types.hpp>

namespace plmap {

/// Barycentric weights with the snapping rule applied: weights <= tolerance become 0, the others
/// are renormalised to sum 1. Requires tolerance < 1 / (d + 1), so that one weight survives.
template <int d>
Barycentric<d> snap_barycentric(Barycentric<d> b, double tolerance) {
  for (int k = 0; k <= d; ++k)
    if (b(k) <= tolerance) b(k) = 0.0;
  b /= b.sum();
  return b;
}

/// Where a point at parameter t of an edge (0 at its first vertex, 1 at its second) lies after
/// snapping.
enum class EdgeSnap { first_vertex, second_vertex, inside };

inline EdgeSnap snap_edge_parameter(double t, double tolerance) {
  if (t <= tolerance) return EdgeSnap::first_vertex;
  if (t >= 1.0 - tolerance) return EdgeSnap::second_vertex;
  return EdgeSnap::inside;
}

}  // namespace plmap
