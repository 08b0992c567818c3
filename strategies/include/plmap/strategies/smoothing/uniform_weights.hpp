#pragma once
/// \file
/// Uniform weights 1/k (Tutte's barycentric embedding): ignores the geometry, so every free node
/// lands at the centroid of its neighbours. The baseline the geometric weights are compared with.

#include <plmap/strategies/smoothing/smoothing_weights.hpp>

namespace plmap {

struct UniformWeights {
  std::optional<std::vector<double>> weights(const Eigen::Vector3d& center, std::span<const Eigen::Vector3d> ring) const;
};
static_assert(SmoothingWeights<UniformWeights>);

}  // namespace plmap
