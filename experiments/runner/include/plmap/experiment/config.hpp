#pragma once
/// \file
/// An experiment configuration (TOML, parsed with toml++), checked completely before anything
/// runs: unknown keys, wrong types, values out of range, unknown strategy names, empty sweep
/// lists, missing input files, plots of unknown columns all raise ConfigError naming the key.
///
///   [experiment]  name, description, repetitions, seed, metrics
///   [[inputs]]    surfaces: a file, a mesh of Debian's libcgal-demo, or a generator
///   [[pipeline]]  steps run on every input in order: build | project | evaluate | check
///   [sweep]       "<step>.<parameter>" / "input.<parameter>" / "inputs.<name>.<parameter>"
///                 = [values...]; every combination runs
///   [[sweep]]     several such tables (each may name its `inputs`); their runs follow each other
///   [[plots]]     x, y, group_by, log_x, log_y, reference
///
/// docs/experiments.md is the reference of every key.

#include <plmap/experiment/parameters.hpp>

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace plmap::experiment {

struct InputConfig {
  std::string key;   ///< "inputs[0]", for messages
  std::string name;  ///< unique; default "<kind>" or "<kind><index>" if repeated
  std::string kind;
  bool run = true;   ///< false: only a target of a project step
  int dimension = 2;
  ParameterSet given;       ///< the values written in the config (type-checked)
  ParameterSet parameters;  ///< resolved (defaults filled in), before sweeps
};

struct StepConfig {
  std::string key;   ///< "pipeline[1]"
  std::string name;  ///< unique; default: the step kind
  std::string kind;
  ParameterSet given;       ///< the values written in the config (type-checked)
};

/// One swept parameter: the values every combination takes.
struct SweepAxis {
  std::string key;  ///< as written under [sweep], e.g. "evaluate.locator"
  /// What it changes: step index, or input index (-1: every input that runs).
  enum class Target { step, input } target = Target::step;
  int index = -1;
  std::string parameter;
  std::vector<ParameterValue> values;  ///< validated
};

/// One cartesian product of sweep axes: `[sweep]`, or one table of `[[sweep]]`. Several groups
/// let a config run some combinations without all the others (plmap's thread counts without
/// single-threaded peers at two threads).
struct SweepGroup {
  std::string key;  ///< "sweep" or "sweep[1]", for messages
  std::vector<SweepAxis> axes;
  /// The inputs (indices into ExperimentConfig::inputs) this group runs; empty: every input that
  /// runs.
  std::vector<int> inputs;
};

enum class ReferenceSlope { none, constant, log_n, sqrt_n, n, n_log_n, n_squared };
std::string to_string(ReferenceSlope slope);

struct PlotConfig {
  std::string key;   ///< "plots[0]"
  std::string name;  ///< file stem; default "plot<i>"
  std::string x, y;  ///< column names (configuration columns or metrics)
  /// Columns whose value combinations give one line each; empty: one line.
  std::vector<std::string> group_by;
  bool log_x = false, log_y = false;
  /// Reference curves ("n log n", ...) drawn through the first point of the first line.
  std::vector<ReferenceSlope> references;
  std::string title, x_label, y_label;
};

struct ExperimentConfig {
  std::filesystem::path source;  ///< the config file ("" for text parsed from memory)
  std::string text;              ///< the config as read, copied to the output directory
  std::filesystem::path base_directory;  ///< relative input paths start here
  std::string name;
  std::string description;
  int repetitions = 3;
  std::uint64_t seed = 1;
  std::vector<std::string> metrics;  ///< empty: every metric of the pipeline
  std::vector<InputConfig> inputs;
  std::vector<StepConfig> pipeline;
  /// No group: every running input once. One group per [[sweep]] table ([sweep]: one group).
  std::vector<SweepGroup> sweeps;
  std::vector<PlotConfig> plots;
  /// Line of each key in the config text ("pipeline[1].locator" -> 12), for error messages.
  std::map<std::string, int> key_lines;

  /// The name used in error messages for this config.
  std::string source_name() const { return source.empty() ? std::string("<config>") : source.string(); }
};

/// Reads and checks a config file. Relative input paths are relative to the file's directory.
ExperimentConfig parse_experiment_file(const std::filesystem::path& path);
/// Checks config text; relative input paths are relative to `base_directory`. `source_name`
/// only appears in messages.
ExperimentConfig parse_experiment_text(const std::string& text, const std::string& source_name,
                                       const std::filesystem::path& base_directory);

/// Every metric name the pipeline can record, in pipeline order, and whether it is a timing.
std::vector<std::pair<std::string, bool>> available_metrics(const ExperimentConfig& config);

}  // namespace plmap::experiment
