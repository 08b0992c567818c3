#pragma once
/// \file
/// Running an experiment: expand the sweep, run the pipeline of every run `repetitions` times
/// (inputs are loaded once per distinct input), record metrics and timings, and write
///
///   DIR/config.toml        the configuration as given
///   DIR/runs.json          the expanded runs (every parameter resolved)
///   DIR/provenance.json
///   DIR/results.jsonl      one JSON object per run
///   DIR/results.csv        the same, flattened
///   DIR/plots/<name>.*     data, gnuplot script, SVG (and PNG)
///   DIR/summary.md
///
///   auto outcome = plmap::experiment::run_experiment(parse_experiment_file("x.toml"), "out");

#include <plmap/experiment/config.hpp>
#include <plmap/experiment/plots.hpp>
#include <plmap/experiment/results.hpp>

#include <plmap/core/progress.hpp>

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace plmap::experiment {

struct RunOptions {
  /// Phase "runs" (counting runs; the detail names the run and its swept values: "run 3/12:
  /// input sphere, evaluate.locator=..."), called before each run and at the end, then phase
  /// "plots" at its start and end. Optional; a callback that throws cancels the experiment.
  ProgressCallback progress;
  PlotOptions plots;
  bool make_plots = true;
  /// If set, replaces [experiment] repetitions (e.g. 1 for a quick look).
  int repetitions_override = 0;
};

struct ExperimentOutcome {
  std::vector<RunResult> rows;
  Provenance provenance;
  std::vector<PlotOutcome> plots;
  std::filesystem::path output_directory;
};

/// Runs every run of the experiment and writes the outputs listed above into `output_dir`
/// (created if needed). Throws ConfigError / plmap::Error naming the run and step that failed.
ExperimentOutcome run_experiment(const ExperimentConfig& config, const std::filesystem::path& output_dir,
                                 const RunOptions& options = {});

/// Runs the pipeline only and returns the rows (no files written, except CGAL meshes extracted
/// into `cache_dir`).
std::vector<RunResult> run_all(const ExperimentConfig& config, const std::filesystem::path& cache_dir,
                               const RunOptions& options = {});

}  // namespace plmap::experiment
