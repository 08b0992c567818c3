// `plmap experiment run CONFIG -o DIR`: runs a reproducible experiment (docs/experiments.md);
// `plmap experiment check CONFIG`: checks a config and lists its runs without running them.

#include "cli_common.hpp"
#include "progress_bar.hpp"

#ifdef PLMAP_HAS_EXPERIMENT_RUNNER
#include <plmap/experiment/config.hpp>
#include <plmap/experiment/runner.hpp>
#include <plmap/experiment/sweep.hpp>
#endif

#include <iostream>

namespace plmap::cli {

namespace {

struct ExperimentOptions {
  std::string config;
  std::string output;
  int repetitions = 0;
  bool no_plots = false;
  ProgressMode progress = ProgressMode::automatic;
  bool json = false;
  std::string gnuplot = "gnuplot";
};

#ifdef PLMAP_HAS_EXPERIMENT_RUNNER
int run_experiment_command(const ExperimentOptions& o) {
  // What run_experiment writes into the directory (docs/experiments.md, "Output").
  check_output_directory(o.output,
                         {"config.toml", "provenance.json", "runs.json", "results.jsonl",
                          "results.csv", "summary.md"},
                         {"inputs", "plots"}, {{"CONFIG", o.config}});
  require_readable_file(o.config);
  const auto config = experiment::parse_experiment_file(o.config);
  experiment::RunOptions options;
  options.repetitions_override = o.repetitions;
  options.make_plots = !o.no_plots;
  options.plots.gnuplot = o.gnuplot;
  ProgressBar bar(o.progress);
  options.progress = bar.callback();
  const auto outcome = experiment::run_experiment(config, o.output, options);
  bar.finish();
  for (const auto& plot : outcome.plots)
    if (!plot.warning.empty()) std::cerr << "plmap: warning: plot " << plot.name << ": " << plot.warning << '\n';
  nlohmann::json summary = {{"experiment", config.name},
                            {"runs", outcome.rows.size()},
                            {"output", o.output},
                            {"summary", (std::filesystem::path(o.output) / "summary.md").string()}};
  std::size_t images = 0;
  for (const auto& plot : outcome.plots) images += plot.images.size();
  summary["images"] = images;
  print_result(summary, o.json);
  return exit_code::success;
}

int check_experiment_command(const ExperimentOptions& o) {
  require_readable_file(o.config);
  const auto config = experiment::parse_experiment_file(o.config);
  const auto runs = experiment::expand_runs(config);
  if (o.json) {
    nlohmann::json j = {{"experiment", config.name}, {"runs", nlohmann::json::array()}};
    for (const auto& run : runs) j["runs"].push_back(nlohmann::json::parse(run.columns.dump()));
    print_json(j);
  } else {
    std::cout << o.config << ": valid; " << runs.size() << " runs, " << config.repetitions
              << " repetitions each\n";
  }
  return exit_code::success;
}
#else
int unavailable(const ExperimentOptions&) {
  std::cerr << "plmap: this build has no experiment runner (configure with -DPLMAP_BUILD_EXPERIMENTS=ON)\n";
  return exit_code::usage_error;
}
#endif

}  // namespace

void register_experiment(CLI::App& app, Action& action) {
  auto o = std::make_shared<ExperimentOptions>();
  CLI::App* cmd = app.add_subcommand(
      "experiment", "Reproducible experiments described by a TOML config (docs/experiments.md).");
  cmd->require_subcommand(1);

  CLI::App* run = cmd->add_subcommand(
      "run",
      "Run every combination of the config's sweep, record metrics, timings and provenance in "
      "DIR/results.jsonl and DIR/results.csv, draw the plots with gnuplot and write DIR/summary.md.");
  run->add_option("CONFIG", o->config, "Experiment config (.toml)")->required();
  run->add_option("-o,--output", o->output, "Output directory (created if needed)")->required();
  run->add_option("--repetitions", o->repetitions, "Override [experiment] repetitions")
      ->check(positive_number);
  run->add_flag("--no-plots", o->no_plots, "Do not call gnuplot");
  run->add_option("--gnuplot", o->gnuplot, "The gnuplot executable")->capture_default_str();
  add_progress_options(*run, o->progress);
  run->add_flag_callback("-q,--quiet", [o] { o->progress = ProgressMode::never; }, "Same as --no-progress");
  run->add_flag("--json", o->json, "Print the outcome as JSON");

  CLI::App* check = cmd->add_subcommand(
      "check", "Check a config (every key, every sweep combination) and count its runs, without running.");
  check->add_option("CONFIG", o->config, "Experiment config (.toml)")->required();
  check->add_flag("--json", o->json, "Print every run's resolved configuration as JSON");

#ifdef PLMAP_HAS_EXPERIMENT_RUNNER
  run->callback([o, &action] { action = [o] { return run_experiment_command(*o); }; });
  check->callback([o, &action] { action = [o] { return check_experiment_command(*o); }; });
#else
  run->callback([o, &action] { action = [o] { return unavailable(*o); }; });
  check->callback([o, &action] { action = [o] { return unavailable(*o); }; });
#endif
}

}  // namespace plmap::cli
