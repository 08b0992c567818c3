#pragma once
/// \file
/// Plots through gnuplot (an external program, from Debian's gnuplot package): for each
/// [[plots]] entry a data file, a gnuplot script, an SVG and, if gnuplot has the pngcairo
/// terminal, a PNG. Timing columns are drawn as median with min/max error bars.

#include <plmap/experiment/config.hpp>
#include <plmap/experiment/results.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace plmap::experiment {

struct PlotOutcome {
  std::string name;
  std::vector<std::filesystem::path> images;  ///< written images (relative to the output dir)
  std::string warning;                        ///< why no image was made, or empty
};

struct PlotOptions {
  /// The gnuplot executable: a name looked up in PATH, or a path. Empty: skip all plots.
  std::string gnuplot = "gnuplot";
};

/// Writes plots/<name>.{dat,gp,svg,png} under `output_dir`. Never throws for a missing or failing
/// gnuplot: the outcome carries the warning instead.
std::vector<PlotOutcome> write_plots(const ExperimentConfig& config, const std::vector<RunResult>& rows,
                                     const std::filesystem::path& output_dir,
                                     const PlotOptions& options = {});

/// The full path of an executable found in PATH (or `name` itself if it contains a slash and is
/// executable); empty if not found.
std::filesystem::path find_executable(const std::string& name);

}  // namespace plmap::experiment
