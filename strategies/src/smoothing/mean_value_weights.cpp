#include <plmap/strategies/smoothing/mean_value_weights.hpp>

#include <Eigen/Geometry>

namespace plmap {

std::optional<std::vector<double>> MeanValueWeights::weights(const Eigen::Vector3d& center,
                                                             std::span<const Eigen::Vector3d> ring) const {
  const std::size_t k = ring.size();
  if (k < 3) return std::nullopt;
  // tan(α/2) = |a × b| / (|a| |b| + a · b): no trigonometric call, and exact enough for small
  // angles, where 1 − cos α would cancel.
  std::vector<double> half_tan(k);
  for (std::size_t j = 0; j < k; ++j) {
    const Eigen::Vector3d a = ring[j] - center, b = ring[(j + 1) % k] - center;
    half_tan[j] = a.cross(b).norm() / (a.norm() * b.norm() + a.dot(b));
  }
  std::vector<double> w(k);
  for (std::size_t j = 0; j < k; ++j)
    w[j] = (half_tan[(j + k - 1) % k] + half_tan[j]) / (ring[j] - center).norm();
  return normalized_positive_weights(std::move(w));
}

}  // namespace plmap
