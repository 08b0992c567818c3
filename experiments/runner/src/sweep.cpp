// Sweep expansion: per sweep group, the cartesian product of its axes, per input.

#include "resolve.hpp"

#include <plmap/experiment/sweep.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <map>

namespace plmap::experiment {

namespace {

/// The axes of `group` that change runs of input `input`.
std::vector<const SweepAxis*> axes_for(const SweepGroup& group, int input) {
  std::vector<const SweepAxis*> axes;
  for (const auto& axis : group.axes)
    if (axis.target == SweepAxis::Target::step || axis.index == -1 || axis.index == input) axes.push_back(&axis);
  return axes;
}

std::size_t combinations(const std::vector<const SweepAxis*>& axes) {
  std::size_t n = 1;
  for (const auto* a : axes) n *= a->values.size();
  return n;
}

/// Whether `group` runs input `input` (which has run = true).
bool runs_input(const SweepGroup& group, int input) {
  return group.inputs.empty() || std::find(group.inputs.begin(), group.inputs.end(), input) != group.inputs.end();
}

/// Without [sweep] every running input runs once: one group without axes.
std::vector<SweepGroup> groups_of(const ExperimentConfig& config) {
  if (!config.sweeps.empty()) return config.sweeps;
  return {SweepGroup{.key = "sweep", .axes = {}, .inputs = {}}};
}

int file_dimension(const ParameterSet& p) {
  const auto dim = p.integer("dimension");
  if (dim != 0) return int(dim);
  return std::filesystem::path(p.text("path")).extension() == ".curve" ? 1 : 2;
}

}  // namespace

std::size_t run_count(const ExperimentConfig& config) {
  std::size_t n = 0;
  for (const SweepGroup& group : groups_of(config))
    for (int i = 0; i < int(config.inputs.size()); ++i)
      if (config.inputs[i].run && runs_input(group, i)) n += combinations(axes_for(group, i));
  return n;
}

std::vector<RunSpec> expand_runs(const ExperimentConfig& config) {
  std::vector<RunSpec> runs;
  std::map<std::string, std::string> first_of;  // a run's columns -> which group and run made them first
  for (const SweepGroup& group : groups_of(config))
    for (int i = 0; i < int(config.inputs.size()); ++i) {
      const InputConfig& input = config.inputs[i];
      if (!input.run || !runs_input(group, i)) continue;
      const auto axes = axes_for(group, i);
      const std::size_t count = combinations(axes);
      for (std::size_t combination = 0; combination < count; ++combination) {
        // Mixed-radix digits of `combination`, the first axis varying slowest.
        std::vector<std::size_t> choice(axes.size());
        std::size_t rest = combination;
        for (std::size_t a = axes.size(); a-- > 0;) {
          choice[a] = rest % axes[a]->values.size();
          rest /= axes[a]->values.size();
        }
        ParameterSet input_given = input.given;
        detail::KeyNames input_names;
        std::vector<ParameterSet> step_given;
        std::vector<detail::KeyNames> step_names(config.pipeline.size());
        for (const auto& step : config.pipeline) step_given.push_back(step.given);
        for (std::size_t a = 0; a < axes.size(); ++a) {
          const SweepAxis& axis = *axes[a];
          const std::string name = fmt::format("{}.\"{}\"[{}]", group.key, axis.key, choice[a]);
          if (axis.target == SweepAxis::Target::input) {
            input_given.set(axis.parameter, axis.values[choice[a]]);
            input_names[axis.parameter] = name;
          } else {
            step_given[axis.index].set(axis.parameter, axis.values[choice[a]]);
            step_names[axis.index][axis.parameter] = name;
          }
        }
        RunSpec run;
        run.index = int(runs.size());
        run.input_index = i;
        run.input_parameters = detail::resolve_input(config, i, input_given, input_names);
        const int dimension = input.kind == "file" ? file_dimension(run.input_parameters) : input.dimension;
        run.columns["input.name"] = input.name;
        run.columns["input.kind"] = input.kind;
        for (const auto& [k, v] : run.input_parameters.entries()) run.columns["input." + k] = to_json(v);
        for (int s = 0; s < int(config.pipeline.size()); ++s) {
          run.step_parameters.push_back(detail::resolve_step(config, s, step_given[s], dimension, step_names[s]));
          for (const auto& [k, v] : run.step_parameters.back().entries())
            run.columns[config.pipeline[s].name + "." + k] = to_json(v);
        }
        // A run two groups both make would be measured twice and counted twice in the summary.
        const std::string where = fmt::format("run {} ({}, input \"{}\")", run.index + 1, group.key, input.name);
        if (const auto [it, fresh] = first_of.emplace(run.columns.dump(), where); !fresh)
          throw ConfigError(config.source_name(), group.key,
                            fmt::format("{} repeats {} with the same parameters", where, it->second));
        runs.push_back(std::move(run));
      }
    }
  return runs;
}

}  // namespace plmap::experiment
