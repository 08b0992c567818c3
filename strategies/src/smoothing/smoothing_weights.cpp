#include <plmap/strategies/smoothing/smoothing_weights.hpp>

#include <cmath>

namespace plmap {

std::optional<std::vector<double>> normalized_positive_weights(std::vector<double> weights) {
  double sum = 0.0;
  for (double w : weights) {
    if (!std::isfinite(w) || !(w > 0.0)) return std::nullopt;
    sum += w;
  }
  if (!std::isfinite(sum) || !(sum > 0.0)) return std::nullopt;
  for (double& w : weights) w /= sum;
  return weights;
}

}  // namespace plmap
