#pragma once
/// \file
/// Ear clipping that always cuts the admissible ear with the best shape (largest smallest
/// angle ratio, i.e. the smallest aspect ratio) first. O(n^2) per hole, and holes are small.

#include <plmap/strategies/simplification/hole_triangulation.hpp>

namespace plmap {

struct BestAspectEarClipping {
  std::optional<HoleTriangles> triangulate(std::span<const Eigen::Vector2d> polygon,
                                           const DiagonalAllowed& allowed) const;
};
static_assert(HoleTriangulation<BestAspectEarClipping>);

/// Aspect ratio of a planar triangle, longest edge × perimeter / (4√3 × area): 1 for the
/// equilateral triangle, growing without bound for slivers, infinite if degenerate.
double planar_aspect_ratio(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c);

}  // namespace plmap
