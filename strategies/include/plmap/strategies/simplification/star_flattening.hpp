#pragma once
/// \file
/// Strategy family "flattening" (DESIGN.md §2): maps the star of an S1 vertex into the plane
/// before its removal (paper 3.3.1, Fig. 7). Given the vertex position and its ring
/// (counter-clockwise), a model returns one planar position per ring vertex with the removed
/// vertex at the origin; each star triangle is then mapped affinely onto its fan triangle.
/// It returns nothing when it cannot flatten the star (a zero-length spoke, a zero angle).
///
/// Models: PolarMapFlattening (paper, default), PlaneProjectionFlattening.

#include <Eigen/Core>

#include <concepts>
#include <optional>
#include <span>
#include <vector>

namespace plmap {

template <class F>
concept StarFlattening = requires(const F& f, const Eigen::Vector3d& center, std::span<const Eigen::Vector3d> ring) {
  { f.flatten(center, ring) } -> std::same_as<std::optional<std::vector<Eigen::Vector2d>>>;
};

}  // namespace plmap
