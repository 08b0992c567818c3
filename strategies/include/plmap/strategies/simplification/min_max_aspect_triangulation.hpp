#pragma once
/// \file
/// The triangulation of the hole whose worst triangle is best: among all triangulations of the
/// polygon that use only admissible diagonals, one that minimizes the largest aspect ratio
/// (dynamic programming over sub-polygons, O(n^3) for n ring vertices; holes are small). Unlike
/// greedy ear clipping it never runs into a dead end when some diagonals are forbidden.

#include <plmap/strategies/simplification/hole_triangulation.hpp>

namespace plmap {

struct MinMaxAspectTriangulation {
  std::optional<HoleTriangles> triangulate(std::span<const Eigen::Vector2d> polygon,
                                           const DiagonalAllowed& allowed) const;
};
static_assert(HoleTriangulation<MinMaxAspectTriangulation>);

/// Aspect ratio of a planar triangle, longest edge × perimeter / (4√3 × area): 1 for the
/// equilateral triangle, growing without bound for slivers, infinite if degenerate.
double planar_aspect_ratio(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c);

/// True if the segment between polygon vertices i and j is a diagonal of the simple polygon
/// (counter-clockwise): inside it, touching its boundary only at i and j.
bool is_polygon_diagonal(std::span<const Eigen::Vector2d> polygon, int i, int j);

}  // namespace plmap
