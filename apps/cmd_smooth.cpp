// `plmap smooth MAP -o MAP2`: re-places the S2 vertex preimages inside every S1 element by a
// convex-combination parametrization (paper 3.3.2) and prints κ_Ξ before and after each sweep.

#include "cli_common.hpp"

#include <plmap/construct/smooth.hpp>
#include <plmap/core/errors.hpp>
#include <plmap/core/io/map_file.hpp>
#include <plmap/strategies/smoothing/smoothing_weights_registry.hpp>
#include <plmap/verify/quality.hpp>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

namespace plmap::cli {

namespace {

struct SmoothCommand {
  std::string map, output;
  int sweeps = 1;
  std::string weights = "floater";
  bool json = false;
};

/// κ max, mean and the 99th percentile (verify's quality report; construct/ cannot compute it).
Json kappa_json(const PlMap<2>& map) {
  const QualityReport q = compute_quality(map);
  Json j;
  j["kappa_max"] = q.kappa_max;
  j["kappa_mean"] = q.kappa_mean;
  const auto it = std::find(q.quantile_levels.begin(), q.quantile_levels.end(), 0.99);
  if (it != q.quantile_levels.end()) j["kappa_p99"] = q.quantiles[static_cast<std::size_t>(it - q.quantile_levels.begin())];
  j["degenerate_regions"] = q.degenerate_count;
  return j;
}

int run_smooth(const SmoothCommand& o) {
  // A bad name is a bad command line, refused before the map is read.
  const auto names = smoothing_weights_names();
  if (std::find(names.begin(), names.end(), o.weights) == names.end())
    throw UsageError(fmt::format("--weights: unknown smoothing weights '{}' (valid: {})", o.weights, fmt::join(names, ", ")));
  check_output_file(o.output, OutputKind::map, {{"MAP", o.map}});
  require_readable_file(o.map);
  AnyPlMap any = load_map(o.map);
  if (!std::holds_alternative<PlMap<2>>(any))
    throw Error(fmt::format("{}: smooth needs a map between triangle surfaces (d = 2), this one is between curves", o.map));
  const PlMap<2>& map = std::get<PlMap<2>>(any);

  Json j;
  j["map"] = o.output;
  j["weights"] = o.weights;
  j["before"] = kappa_json(map);
  Json sweeps = Json::array();
  SmoothOptions options;
  options.sweeps = o.sweeps;
  options.weights = o.weights;
  options.after_sweep = [&sweeps](int, const PlMap<2>& m) { sweeps.push_back(kappa_json(m)); };
  const SmoothResult result = smooth(map, options);
  save_map(o.output, result.map);
  hint_if_large_text_map(o.output);

  const SmoothReport& r = result.report;
  j["after"] = sweeps.back();
  for (std::size_t s = 0; s < r.sweeps.size(); ++s) {
    sweeps[s]["nodes_moved"] = r.sweeps[s].nodes_moved;
    sweeps[s]["elements_smoothed"] = r.sweeps[s].elements_smoothed;
    sweeps[s]["max_displacement"] = r.sweeps[s].max_displacement;
  }
  j["sweeps"] = sweeps;
  j["free_nodes"] = r.free_nodes;
  j["uniform_fallback_nodes"] = r.uniform_fallback_nodes;
  Json skipped = Json::object();
  for (const auto& [why, count] : r.skipped_by_reason) skipped[why] = count;
  j["skipped_by_reason"] = skipped;
  j["seconds"] = r.seconds;
  print_result(j, o.json);
  return exit_code::success;
}

}  // namespace

void register_smooth(CLI::App& app, Action& action) {
  auto o = std::make_shared<SmoothCommand>();
  CLI::App* cmd = app.add_subcommand(
      "smooth",
      "Smooth a map (paper 3.3.2): inside every S1 element, re-place the preimages of S2's "
      "vertices by a convex-combination parametrization with the element's boundary fixed, so "
      "that the map gets closer to an isometry. Prints kappa (max, mean, p99) before and after.");
  cmd->add_option("MAP", o->map, "The map file to smooth (.plmap, d = 2)")->required();
  cmd->add_option("-o,--output", o->output, "Map file to write: .plmapb binary (large maps) or .plmap text; replaced atomically")->required();
  cmd->add_option("--sweeps", o->sweeps, "Passes over all elements (per-element smoothing reaches its fixed point in one)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--weights", o->weights, "Smoothing weights: floater, mean-value or uniform")->capture_default_str();
  cmd->add_flag("--json", o->json, "Print the summary as JSON");
  cmd->callback([o, &action] { action = [o] { return run_smooth(*o); }; });
}

}  // namespace plmap::cli
