#pragma once
/// \file
/// Floater's mean-value weights (2003): w_j ∝ (tan(α_{j-1}/2) + tan(α_j/2)) / |q_j − p|, with α_j
/// the angle at the centre p between the spokes to q_j and q_{j+1}, measured on the S2 star in
/// space. Positive for every star whose angles are below π, and they vary smoothly with it.

#include <plmap/strategies/smoothing/smoothing_weights.hpp>

namespace plmap {

struct MeanValueWeights {
  std::optional<std::vector<double>> weights(const Eigen::Vector3d& center, std::span<const Eigen::Vector3d> ring) const;
};
static_assert(SmoothingWeights<MeanValueWeights>);

}  // namespace plmap
