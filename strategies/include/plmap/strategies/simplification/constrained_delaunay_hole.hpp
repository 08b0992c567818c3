#pragma once
/// \file
/// The constrained Delaunay triangulation of the hole polygon (the paper's choice): a first
/// triangulation by ear clipping (O(n²) ear tests; MinMaxAspectTriangulation when forbidden
/// diagonals block every ear) followed by Lawson flips with the exact in-circle predicate until
/// every diagonal is locally Delaunay. Inside a simple polygon, with the polygon's sides as
/// constraints, that fixed point is the constrained Delaunay triangulation (unique unless four
/// ring vertices are cocircular). Diagonals the caller forbids are never flipped in. The result
/// is listed canonically (each triangle as (i, m, j) with i < m < j, read off from the chord
/// 0-(n-1) inwards), so it depends only on which triangles were found.

#include <plmap/strategies/simplification/hole_triangulation.hpp>

namespace plmap {

struct ConstrainedDelaunayHole {
  std::optional<HoleTriangles> triangulate(std::span<const Eigen::Vector2d> polygon,
                                           const DiagonalAllowed& allowed) const;
};
static_assert(HoleTriangulation<ConstrainedDelaunayHole>);

}  // namespace plmap
