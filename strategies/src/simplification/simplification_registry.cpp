#include <plmap/strategies/simplification/simplification_registry.hpp>

#include <plmap/strategies/simplification/min_max_aspect_triangulation.hpp>
#include <plmap/strategies/simplification/constrained_delaunay_hole.hpp>
#include <plmap/strategies/simplification/plane_projection_flattening.hpp>
#include <plmap/strategies/simplification/polar_map_flattening.hpp>

#include <plmap/core/errors.hpp>

#include <fmt/format.h>

#include <array>

namespace plmap {

namespace {
constexpr std::array<std::string_view, 2> flattenings = {"polar-map", "plane-projection"};
constexpr std::array<std::string_view, 2> triangulations = {"constrained-delaunay", "min-max-aspect"};

template <class Model>
AnyStarFlattening wrap_flattening() {
  return [](const Eigen::Vector3d& c, std::span<const Eigen::Vector3d> r) { return Model{}.flatten(c, r); };
}
template <class Model>
AnyHoleTriangulation wrap_triangulation() {
  return [](std::span<const Eigen::Vector2d> p, const DiagonalAllowed& a) { return Model{}.triangulate(p, a); };
}
}  // namespace

std::span<const std::string_view> star_flattening_names() { return flattenings; }
std::span<const std::string_view> hole_triangulation_names() { return triangulations; }

AnyStarFlattening make_star_flattening(std::string_view name) {
  if (name == "polar-map") return wrap_flattening<PolarMapFlattening>();
  if (name == "plane-projection") return wrap_flattening<PlaneProjectionFlattening>();
  throw Error(fmt::format("unknown flattening '{}' (valid: {})", name, fmt::join(flattenings, ", ")));
}

AnyStarFlattening make_half_star_flattening(std::string_view name) {
  make_star_flattening(name);  // the same names are valid
  return [](const Eigen::Vector3d& c, std::span<const Eigen::Vector3d> r) { return PolarMapFlattening{}.flatten_half(c, r); };
}

AnyHoleTriangulation make_hole_triangulation(std::string_view name) {
  if (name == "constrained-delaunay") return wrap_triangulation<ConstrainedDelaunayHole>();
  if (name == "min-max-aspect") return wrap_triangulation<MinMaxAspectTriangulation>();
  throw Error(fmt::format("unknown hole triangulation '{}' (valid: {})", name, fmt::join(triangulations, ", ")));
}

}  // namespace plmap
