// Sweep expansion: the cartesian product of the [sweep] axes, per input.

#include "resolve.hpp"

#include <plmap/experiment/sweep.hpp>

#include <fmt/format.h>

namespace plmap::experiment {

namespace {

/// The axes that change runs of input `input`.
std::vector<const SweepAxis*> axes_for(const ExperimentConfig& config, int input) {
  std::vector<const SweepAxis*> axes;
  for (const auto& axis : config.sweep)
    if (axis.target == SweepAxis::Target::step || axis.index == -1 || axis.index == input) axes.push_back(&axis);
  return axes;
}

std::size_t combinations(const std::vector<const SweepAxis*>& axes) {
  std::size_t n = 1;
  for (const auto* a : axes) n *= a->values.size();
  return n;
}

int file_dimension(const ParameterSet& p) {
  const auto dim = p.integer("dimension");
  if (dim != 0) return int(dim);
  return std::filesystem::path(p.text("path")).extension() == ".curve" ? 1 : 2;
}

}  // namespace

std::size_t run_count(const ExperimentConfig& config) {
  std::size_t n = 0;
  for (int i = 0; i < int(config.inputs.size()); ++i)
    if (config.inputs[i].run) n += combinations(axes_for(config, i));
  return n;
}

std::vector<RunSpec> expand_runs(const ExperimentConfig& config) {
  std::vector<RunSpec> runs;
  for (int i = 0; i < int(config.inputs.size()); ++i) {
    const InputConfig& input = config.inputs[i];
    if (!input.run) continue;
    const auto axes = axes_for(config, i);
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
        const std::string name = fmt::format("sweep.\"{}\"[{}]", axis.key, choice[a]);
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
      runs.push_back(std::move(run));
    }
  }
  return runs;
}

}  // namespace plmap::experiment
