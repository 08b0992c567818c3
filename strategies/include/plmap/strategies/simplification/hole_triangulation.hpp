#pragma once
/// \file
/// Strategy family "re-triangulation": fills the hole left by a removed vertex (paper 3.3.1).
/// The input is the flattened ring, a simple polygon given counter-clockwise, and a predicate
/// that says whether a diagonal (i, j) may be used (the simplification forbids diagonals that
/// are already S1 edges). A model returns n − 2 counter-clockwise triangles of ring indices, or
/// nothing if it finds no admissible triangulation.
///
/// Models: ConstrainedDelaunayHole (paper, default), MinMaxAspectTriangulation.

#include <Eigen/Core>

#include <array>
#include <concepts>
#include <functional>
#include <optional>
#include <span>
#include <vector>

namespace plmap {

using HoleTriangles = std::vector<std::array<int, 3>>;
using DiagonalAllowed = std::function<bool(int, int)>;

template <class T>
concept HoleTriangulation =
    requires(const T& t, std::span<const Eigen::Vector2d> polygon, const DiagonalAllowed& allowed) {
      { t.triangulate(polygon, allowed) } -> std::same_as<std::optional<HoleTriangles>>;
    };

}  // namespace plmap
