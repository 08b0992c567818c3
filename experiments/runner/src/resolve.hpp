#pragma once
// Internal: resolving the parameters of an input or step (defaults, bounds, choices, seeds),
// shared by the parser (config.cpp) and the sweep expansion (sweep.cpp).

#include <plmap/experiment/config.hpp>
#include <plmap/experiment/config_error.hpp>
#include <plmap/experiment/schema.hpp>

#include <map>
#include <string>

namespace plmap::experiment::detail {

/// Parameter name -> the key errors name (a sweep value: `sweep."evaluate.threads"[2]`).
using KeyNames = std::map<std::string, std::string>;

/// The spec of `name` in `schema`, or nullptr.
const ParameterSpec* find_spec(const std::vector<ParameterSpec>& schema, const std::string& name);

/// "a, b, c"
std::string join(const std::vector<std::string>& items, const std::string& separator = ", ");

/// The members of an oracle list "hausdorff:1,aspect-ratio:0.5" (spaces around commas allowed).
std::vector<std::string> split_oracles(const std::string& list);

/// Bounds and valid choices of one typed value.
void check_value(const std::string& source, const std::string& key, const ParameterSpec& spec,
                 const ParameterValue& value);

/// The parameters of input `index` with `given` values (the config's, or with sweep values).
ParameterSet resolve_input(const ExperimentConfig& config, int index, const ParameterSet& given,
                           const KeyNames& names = {});

/// The parameters of step `index` run on an input of dimension `dimension`.
ParameterSet resolve_step(const ExperimentConfig& config, int index, const ParameterSet& given,
                          int dimension, const KeyNames& names = {});

}  // namespace plmap::experiment::detail
