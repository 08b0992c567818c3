#include <plmap/strategies/smoothing/uniform_weights.hpp>

namespace plmap {

std::optional<std::vector<double>> UniformWeights::weights(const Eigen::Vector3d&,
                                                           std::span<const Eigen::Vector3d> ring) const {
  if (ring.empty()) return std::nullopt;
  return std::vector<double>(ring.size(), 1.0 / static_cast<double>(ring.size()));
}

}  // namespace plmap
