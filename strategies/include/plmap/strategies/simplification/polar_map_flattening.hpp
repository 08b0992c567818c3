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
  /// The half-star of a vertex on a feature line (an open fan, ring from one line neighbour to
  /// the other) laid out on the upper half-disk: angles scaled by π / (sum of angles), spoke
  /// lengths kept (relative to the longest), the first ring vertex on the positive x axis and
  /// the last on the negative one. Keeping the lengths (no power) places the two line
  /// neighbours at the same relative distances in every half-star of the vertex, so all sides
  /// of the line agree where its nodes go on the new edge (the 1-d polar map of the line).
  std::optional<std::vector<Eigen::Vector2d>> flatten_half(const Eigen::Vector3d& center,
                                                           std::span<const Eigen::Vector3d> ring) const;
};
static_assert(StarFlattening<PolarMapFlattening>);

}  // namespace plmap
