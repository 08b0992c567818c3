#pragma once
/// \file
/// summary.md: the experiment, its provenance, one table row per run (the configuration columns
/// that vary, then the metrics; timings as median [min, max]), and the plots.

#include <plmap/experiment/config.hpp>
#include <plmap/experiment/plots.hpp>
#include <plmap/experiment/results.hpp>

#include <string>
#include <vector>

namespace plmap::experiment {

std::string summary_markdown(const ExperimentConfig& config, const std::vector<RunResult>& rows,
                             const Provenance& provenance, const std::vector<PlotOutcome>& plots);

}  // namespace plmap::experiment
