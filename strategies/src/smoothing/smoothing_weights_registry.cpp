#include <plmap/strategies/smoothing/smoothing_weights_registry.hpp>

#include <plmap/strategies/smoothing/floater_weights.hpp>
#include <plmap/strategies/smoothing/mean_value_weights.hpp>
#include <plmap/strategies/smoothing/uniform_weights.hpp>

#include <plmap/core/errors.hpp>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <array>

namespace plmap {

namespace {
constexpr std::array<std::string_view, 3> names = {"floater", "mean-value", "uniform"};

template <class Model>
AnySmoothingWeights wrap() {
  return [](const Eigen::Vector3d& c, std::span<const Eigen::Vector3d> r) { return Model{}.weights(c, r); };
}
}  // namespace

std::span<const std::string_view> smoothing_weights_names() { return names; }

AnySmoothingWeights make_smoothing_weights(std::string_view name) {
  if (name == "floater") return wrap<FloaterWeights>();
  if (name == "mean-value") return wrap<MeanValueWeights>();
  if (name == "uniform") return wrap<UniformWeights>();
  throw Error(fmt::format("unknown smoothing weights '{}' (valid: {})", name, fmt::join(names, ", ")));
}

}  // namespace plmap
