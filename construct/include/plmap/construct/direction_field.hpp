#pragma once
/// \file
/// Direction fields for normal projection: one unit vector per S1 vertex, interpolated linearly
/// over the elements (paper section 3.2).

#include <plmap/core/surface.hpp>

#include <span>
#include <vector>

namespace plmap {

/// Averaged vertex normals: for d = 2 the area-weighted mean of the normals of the triangles
/// around each vertex, for d = 1 the length-weighted mean of the segment normals; normalised.
/// A vertex whose weighted normals cancel (e.g. at a non-manifold fold) gets the normal of its
/// first element. Vertices in no element get the zero vector. Vertices are independent: they are
/// spread over `threads` threads (0: all hardware threads) with the same result for any count.
template <int d>
  requires SurfaceDimension<d>
std::vector<WorldPoint<d>> averaged_vertex_normals(const Surface<d>& surface, unsigned threads = 1);

/// User directions given as d+1 numbers per S1 vertex (flat, vertex-major), normalised. Throws
/// plmap::Error naming the vertex if the count is wrong or a direction is zero or not finite.
template <int d>
  requires SurfaceDimension<d>
std::vector<WorldPoint<d>> directions_from_values(const Surface<d>& surface, std::span<const double> values);

}  // namespace plmap
