#pragma once
/// \file
/// The constrained Delaunay triangulation of the hole polygon (the paper's choice): a first
/// triangulation (MinMaxAspectTriangulation) followed by Lawson flips with the exact in-circle predicate until every diagonal
/// is locally Delaunay. Inside a simple polygon, with the polygon's sides as constraints, that
/// fixed point is the constrained Delaunay triangulation. Diagonals the caller forbids are never
/// flipped in.

#include <plmap/strategies/simplification/hole_triangulation.hpp>

namespace plmap {

struct ConstrainedDelaunayHole {
  std::optional<HoleTriangles> triangulate(std::span<const Eigen::Vector2d> polygon,
                                           const DiagonalAllowed& allowed) const;
};
static_assert(HoleTriangulation<ConstrainedDelaunayHole>);

}  // namespace plmap
