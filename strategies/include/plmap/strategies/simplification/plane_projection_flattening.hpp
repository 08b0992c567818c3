#pragma once
/// \file
/// Flattening by orthogonal projection of the ring onto the plane through the centre normal to
/// the star's area-weighted normal. Cheaper than the polar map and exact for planar stars, but
/// not star-shaped for strongly curved stars (such steps are then refused).

#include <plmap/strategies/simplification/star_flattening.hpp>

namespace plmap {

struct PlaneProjectionFlattening {
  std::optional<std::vector<Eigen::Vector2d>> flatten(const Eigen::Vector3d& center,
                                                      std::span<const Eigen::Vector3d> ring) const;
};
static_assert(StarFlattening<PlaneProjectionFlattening>);

}  // namespace plmap
