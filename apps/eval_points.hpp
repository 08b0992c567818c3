#pragma once
// `plmap eval MAP --points FILE`: evaluation (or inverse evaluation, --inverse) at the user's
// points, read from a text table or .npy and written as CSV, JSON, .npy or raw float64
// (docs/algorithms/evaluation.md, "Points from a file").

#include "progress_bar.hpp"

#include "cli_common.hpp"

#include <string>

namespace plmap::cli {

struct EvalPointsOptions {
  std::string map_file;
  std::string points_file;
  std::string points_kind;  ///< "local", "world" or empty (from the header, else local)
  std::string output;       ///< empty: CSV on stdout
  std::string locator;      ///< empty: the default of the map's dimension
  bool inverse = false;
  unsigned threads = 0;
  bool json = false;  ///< the summary printed when writing to a file
  ProgressMode progress = ProgressMode::automatic;  ///< of loading the map
};

/// The output formats by extension: ".csv", ".json", ".npy", ".bin" (raw float64).
bool is_known_points_output(const std::string& path);

int run_eval_points(const EvalPointsOptions& options);

}  // namespace plmap::cli
