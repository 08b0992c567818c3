#pragma once
/// \file
/// Run-time choice of the flattening and re-triangulation strategies of the simplification by
/// name (command line, experiment configs). The step runs once per removed vertex, so a
/// std::function per step costs nothing measurable next to the step itself.

#include <plmap/strategies/simplification/hole_triangulation.hpp>
#include <plmap/strategies/simplification/star_flattening.hpp>

#include <functional>
#include <span>
#include <string_view>

namespace plmap {

using AnyStarFlattening =
    std::function<std::optional<std::vector<Eigen::Vector2d>>(const Eigen::Vector3d&, std::span<const Eigen::Vector3d>)>;
using AnyHoleTriangulation =
    std::function<std::optional<HoleTriangles>(std::span<const Eigen::Vector2d>, const DiagonalAllowed&)>;

/// "polar-map" (default), "plane-projection". Throws plmap::Error listing the names otherwise.
AnyStarFlattening make_star_flattening(std::string_view name);
std::span<const std::string_view> star_flattening_names();

/// The flattening of the half-stars of a vertex on a feature line (an open fan from one line
/// neighbour to the other), by the same names. Both give the half-disk polar map
/// (PolarMapFlattening::flatten_half): a plane projection cannot put the removed vertex on the
/// segment between its line neighbours, which the removal along the line needs.
AnyStarFlattening make_half_star_flattening(std::string_view name);

/// "constrained-delaunay" (default), "min-max-aspect". Throws plmap::Error otherwise.
AnyHoleTriangulation make_hole_triangulation(std::string_view name);
std::span<const std::string_view> hole_triangulation_names();

}  // namespace plmap
