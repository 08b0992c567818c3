// `plmap smooth MAP -o MAP2`: re-places the S2 vertex preimages inside every S1 element by a
// convex-combination parametrization (paper 3.3.2) and prints κ_Ξ before and after each sweep.

#include "cli_common.hpp"
#include "kappa_json.hpp"
#include "progress_bar.hpp"

#include <plmap/construct/smooth.hpp>
#include <plmap/core/errors.hpp>
#include <plmap/core/io/map_file.hpp>
#include <plmap/strategies/smoothing/smoothing_weights_registry.hpp>

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
  bool no_quadrilaterals = false;
  bool no_element_pass = false;
  ProgressMode progress = ProgressMode::automatic;
};

/// κ_Ξ's distribution from the smoothing's own per-region κ, with verify's statistics
/// (construct/ does not depend on verify/).
KappaSummary summarize_kappa(std::span<const double> region_kappas) { return kappa_summary(kappa_statistics(region_kappas)); }

int run_smooth(const SmoothCommand& o) {
  // A bad name is a bad command line, refused before the map is read.
  const auto names = smoothing_weights_names();
  if (std::find(names.begin(), names.end(), o.weights) == names.end())
    throw UsageError(fmt::format("--weights: unknown smoothing weights '{}' (valid: {})", o.weights, fmt::join(names, ", ")));
  if (o.no_quadrilaterals && o.no_element_pass)
    throw UsageError("--no-quadrilaterals and --no-element-pass together leave nothing to smooth");
  check_output_file(o.output, OutputKind::map, {{"MAP", o.map}});
  require_readable_file(o.map);
  ProgressBar bar(o.progress);
  AnyPlMap any = load_map(o.map, bar.callback());
  if (!std::holds_alternative<PlMap<2>>(any))
    throw Error(fmt::format("{}: smooth needs a map between triangle surfaces (d = 2), this one is between curves", o.map));
  const PlMap<2>& map = std::get<PlMap<2>>(any);

  Json j;
  j["map"] = o.output;
  j["weights"] = o.weights;
  SmoothOptions options;
  options.sweeps = o.sweeps;
  options.weights = o.weights;
  options.quadrilaterals = !o.no_quadrilaterals;
  options.elements = !o.no_element_pass;
  options.summarize_kappa = summarize_kappa;
  options.progress = bar.callback();
  const SmoothResult result = naming_the_input(o.map, [&] { return smooth(map, options); });
  save_map(o.output, result.map, bar.callback());
  bar.finish();
  hint_if_large_text_map(o.output);

  const SmoothReport& r = result.report;
  j["before"] = kappa_json(*r.kappa_before);
  Json sweeps = Json::array();
  for (const SmoothSweepReport& s : r.sweeps) {
    Json sj = kappa_json(*s.kappa);
    sj["nodes_moved"] = s.nodes_moved;
    sj["elements_smoothed"] = s.elements_smoothed;
    sj["max_displacement"] = s.max_displacement;
    sj["quadrilaterals_smoothed"] = s.quadrilaterals_smoothed;
    sj["quad_nodes_moved"] = s.quad_nodes_moved;
    sj["nodes_crossed"] = s.nodes_crossed;
    sj["quad_max_displacement"] = s.quad_max_displacement;
    sj["quad_uniform_fallbacks"] = s.quad_uniform_fallbacks;
    Json qs = Json::object();
    for (const auto& [why, count] : s.quadrilaterals_skipped_by_reason) qs[why] = count;
    sj["quadrilaterals_skipped_by_reason"] = qs;
    sj["quadrilateral_pass_rejected"] = s.quadrilateral_pass_rejected;
    sj["quadrilateral_attempts"] = s.quadrilateral_attempts;
    sj["quadrilateral_pass_refused_by_kappa"] = s.quadrilateral_pass_refused_by_kappa;
    sj["elements_shortened"] = s.elements_shortened;
    sweeps.push_back(sj);
  }
  j["after"] = sweeps.back();
  j["sweeps"] = sweeps;
  j["quadrilaterals"] = options.quadrilaterals;
  j["element_pass"] = options.elements;
  if (!r.quadrilaterals_not_applicable.empty()) j["quadrilaterals_not_applicable"] = r.quadrilaterals_not_applicable;
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
      "Smooth a map (paper 3.3.2): inside every S1 element, then over the quadrilateral of every "
      "pair of S1 triangles sharing an edge (preimages may cross it), re-place the preimages of "
      "S2's vertices by a convex-combination parametrization, so that the map gets closer to an "
      "isometry. Prints kappa (max, mean, quantiles, histogram) before and after each sweep.");
  cmd->add_option("MAP", o->map, "The map file to smooth (.plmap, d = 2)")->required();
  cmd->add_option("-o,--output", o->output, "Map file to write: .plmapb binary (large maps) or .plmap text; replaced atomically")->required();
  cmd->add_option("--sweeps", o->sweeps, "Passes over all elements and edges (the paper: fewer than ten suffice)")
      ->check(positive_number)
      ->capture_default_str();
  cmd->add_option("--weights", o->weights, "Smoothing weights: floater, mean-value or uniform")->capture_default_str();
  cmd->add_flag("--no-quadrilaterals", o->no_quadrilaterals,
                "Smooth inside each element only (the preimages never cross an S1 edge)");
  cmd->add_flag("--no-element-pass", o->no_element_pass,
                "Smooth over the quadrilaterals only (they re-place every preimage inside them)");
  add_progress_options(*cmd, o->progress);
  cmd->add_flag("--json", o->json, "Print the summary as JSON");
  cmd->callback([o, &action] { action = [o] { return run_smooth(*o); }; });
}

}  // namespace plmap::cli
