#pragma once
/// \file
/// Run-time choice of the smoothing weights by name (command line, experiment configs). They are
/// computed once per free node and solve, so a std::function costs nothing measurable.

#include <plmap/strategies/smoothing/smoothing_weights.hpp>

#include <functional>
#include <span>
#include <string_view>

namespace plmap {

using AnySmoothingWeights =
    std::function<std::optional<std::vector<double>>(const Eigen::Vector3d&, std::span<const Eigen::Vector3d>)>;

/// "floater" (default, shape-preserving), "mean-value", "uniform". Throws plmap::Error listing
/// the names otherwise.
AnySmoothingWeights make_smoothing_weights(std::string_view name);
std::span<const std::string_view> smoothing_weights_names();

}  // namespace plmap
