#pragma once
/// \file
/// Sweep expansion: every combination (cartesian product) of the [sweep] values, for every input
/// that runs. An axis that names one input (`inputs.<name>.<parameter>`) only multiplies the
/// runs of that input, so no run is repeated with a parameter that does not concern it.
/// Order: sweep groups ([[sweep]] tables) in config order; within a group, inputs in config
/// order; within an input, the first sweep axis varies slowest.

#include <plmap/experiment/config.hpp>

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace plmap::experiment {

/// One run: an input and the pipeline with every parameter resolved.
struct RunSpec {
  int index = 0;        ///< 0-based, over the whole experiment
  int input_index = 0;  ///< into ExperimentConfig::inputs
  ParameterSet input_parameters;
  std::vector<ParameterSet> step_parameters;  ///< one per pipeline step
  /// The configuration columns of this run, flattened: "input.name", "input.kind",
  /// "input.<parameter>", "<step name>.<parameter>"; in config order.
  nlohmann::ordered_json columns;
};

/// Expands the sweep. Throws ConfigError if a combination is invalid (messages name the sweep
/// key and the value's position).
std::vector<RunSpec> expand_runs(const ExperimentConfig& config);

/// Number of runs expand_runs would return.
std::size_t run_count(const ExperimentConfig& config);

}  // namespace plmap::experiment
