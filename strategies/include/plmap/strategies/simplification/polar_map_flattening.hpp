#pragma once
/// \file
/// The polar map of paper 3.3.1 (after Eck et al.): the star is cut open along its first spoke
/// and laid out so that the angles at the centre are scaled by a = 2π / (sum of angles) and the
/// spoke lengths r become r^a. It is conformal at the centre, and its image is star-shaped with
/// respect to the origin whenever every scaled angle is below π.

#include <plmap/strategies/simplification/star_flattening.hpp>

namespace plmap {

struct PolarMapFlattening {
  std::optional<std::vector<Eigen::Vector2d>> flatten(const Eigen::Vector3d& center,
                                                      std::span<const Eigen::Vector3d> ring) const;
};
static_assert(StarFlattening<PolarMapFlattening>);

}  // namespace plmap
