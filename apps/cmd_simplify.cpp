// `plmap simplify FINE -o MAP`: builds a coarse surface S1 and the parametrization of FINE over
// it by point-removal simplification (paper section 3.3.1), and prints what it did.

#include "cli_common.hpp"
#include "kappa_json.hpp"
#include "progress_bar.hpp"

#include <plmap/construct/simplify.hpp>
#include <plmap/construct/simplify_curve.hpp>
#include <plmap/strategies/simplification/simplification_registry.hpp>
#include <plmap/core/errors.hpp>
#include <plmap/core/io/map_file.hpp>
#include <plmap/core/io/surface_writer.hpp>
#include <plmap/verify/quality.hpp>

#include <fmt/format.h>

#include <iostream>

namespace plmap::cli {

namespace {

struct SimplifyCommand {
  std::string fine, output, coarse;
  Index target_elements = 0, target_vertices = 0;
  double max_error = std::numeric_limits<double>::infinity();
  std::vector<std::string> oracles;
  double feature_angle = 60.0;
  std::string flattening = "polar-map", hole_triangulation = "constrained-delaunay", ranking = "exact", cut = "per-step";
  unsigned threads = 0;
  bool json = false;
  ProgressMode progress = ProgressMode::automatic;
};

/// κ_Ξ as `plmap smooth` prints it, and how far the map stretches and shrinks lengths.
Json quality_json(const QualityReport& q) {
  Json j = kappa_json(kappa_summary(q));
  j["stretch_min"] = q.stretch_min;
  j["stretch_max"] = q.stretch_max;
  return j;
}

template <int d>
int report_simplification(const SimplifyCommand& o, const PlMap<d>& map, const SimplifyReport& r, ProgressBar& bar);

int run_simplify(const SimplifyCommand& o) {
  SimplifyOptions options;
  options.target_elements = o.target_elements;
  options.target_vertices = o.target_vertices;
  options.max_error = o.max_error;
  options.feature_angle_degrees = o.feature_angle;
  options.flattening = o.flattening;
  options.hole_triangulation = o.hole_triangulation;
  options.ranking = o.ranking;
  options.cut = o.cut;
  options.builder.threads = o.threads;
  for (const std::string& spec : o.oracles) options.oracles.add_spec(spec);
  // Strategy names are checked before the (possibly long) run.
  (void)make_star_flattening(o.flattening);
  (void)make_hole_triangulation(o.hole_triangulation);

  check_output_file(o.output, OutputKind::map, {{"FINE", o.fine}});
  if (!o.coarse.empty()) {
    check_output_file(o.coarse, OutputKind::surface, {{"FINE", o.fine}});
    if (same_file(o.coarse, o.output))
      throw UsageError(fmt::format("{}: --coarse and -o name the same file", o.coarse));
  }
  // Both outputs are written after the run; a missing directory is found before it, so that a
  // failed write cannot leave one file without the other.
  for (const std::string& out : {o.output, o.coarse}) {
    if (out.empty()) continue;
    const std::filesystem::path parent = std::filesystem::path(out).parent_path();
    if (!parent.empty() && !std::filesystem::is_directory(parent))
      throw Error(fmt::format("{}: cannot write here, the directory {} does not exist", out, parent.string()));
  }
  AnySurface any = read_any_surface(o.fine);
  ProgressBar bar(o.progress);
  options.progress = bar.callback();
  if (std::holds_alternative<Surface<1>>(any)) {
    auto curve = std::make_shared<const Surface<1>>(std::move(std::get<0>(any)));
    const CurveSimplifyResult result =
        naming_the_input(o.fine, [&] { return simplify_curve(curve, std::move(options)); });
    return report_simplification(o, result.map, result.report, bar);
  }
  auto fine = std::make_shared<const Surface<2>>(std::move(std::get<1>(any)));
  const SimplifyResult result = naming_the_input(o.fine, [&] { return simplify(fine, std::move(options)); });
  return report_simplification(o, result.map, result.report, bar);
}

/// A run that stops above its element or vertex target still writes a valid map (exit 0), but
/// the user asked for something else: say on stderr why it stopped, so that the JSON on stdout
/// stays clean and the reason is not only a `false` among thirty fields. Prefixed "note: ", like
/// the "hint: " lines, so that it is not taken for an error ("plmap: ").
void note_missed_target(const SimplifyCommand& o, const SimplifyReport& r) {
  if (r.target_reached || (o.target_elements == 0 && o.target_vertices == 0)) return;
  const std::string asked = o.target_elements > 0
                                ? fmt::format("{} elements, above --target-elements {}", r.elements_after, o.target_elements)
                                : fmt::format("{} vertices, above --target-vertices {}", r.vertices_after, o.target_vertices);
  std::string reasons;
  for (const auto& [why, count] : r.skipped_by_reason)
    reasons += fmt::format("{}{} {}", reasons.empty() ? "" : ", ", why, count);
  std::string line = fmt::format("note: stopped at {}: {} feature corners are never removed", asked,
                                 r.feature_corners);
  line += r.skipped_vertices > 0
              ? fmt::format(" and {} other vertices could not be removed ({})", r.skipped_vertices, reasons)
              : std::string(" and no other vertex is left to remove");
  if (r.feature_corners > 0) line += "; a larger --feature-angle may keep fewer features";
  std::cerr << line << '\n';
}

/// Writes the outputs and prints the summary, for surfaces and curves alike.
template <int d>
int report_simplification(const SimplifyCommand& o, const PlMap<d>& map, const SimplifyReport& r, ProgressBar& bar) {
  if (!o.coarse.empty()) write_surface(o.coarse, map.domain());
  save_map(o.output, map, bar.callback());
  bar.finish();
  hint_if_large_text_map(o.output);

  Json j;
  j["map"] = o.output;
  if (!o.coarse.empty()) j["coarse"] = o.coarse;
  j["elements_before"] = r.elements_before;
  j["elements_after"] = r.elements_after;
  j["vertices_before"] = r.vertices_before;
  j["vertices_after"] = r.vertices_after;
  j["removed_vertices"] = r.removed_vertices;
  j["target_reached"] = r.target_reached;
  j["hausdorff_error"] = r.hausdorff_error;
  j["hausdorff_error_relative"] = r.hausdorff_error_relative;
  j["quality"] = quality_json(compute_quality(map));
  j["regions"] = map.region_count();
  j["feature_edges"] = r.feature_edges;
  j["feature_vertices"] = r.feature_vertices;
  j["feature_corners"] = r.feature_corners;
  j["removed_along_lines"] = r.removed_along_lines;
  j["skipped_vertices"] = r.skipped_vertices;
  Json skipped = Json::object();
  for (const auto& [why, count] : r.skipped_by_reason) skipped[why] = count;
  j["skipped_by_reason"] = skipped;
  j["oracles"] = r.oracles;
  j["flattening"] = r.flattening;
  j["hole_triangulation"] = r.hole_triangulation;
  if (!r.ranking.empty()) {  // surfaces only: a curve's removals are ranked exactly
    j["ranking"] = r.ranking;
    j["full_plans"] = r.full_plans;
    j["requeued"] = r.requeued;
    j["ranking_plans"] = r.ranking_plans;
    j["cut"] = r.cut;
    j["cut_fell_back"] = r.cut_fell_back;
    if (r.cut_fell_back) j["cut_failure"] = r.cut_failure;
  }
  j["feature_angle"] = o.feature_angle;
  j["threads"] = resolved_threads(o.threads);
  j["seconds"] = r.seconds_total;
  j["seconds_by_phase"] = {{"simplify", r.seconds_simplify}, {"finalize", r.seconds_finalize}};
  print_result(j, o.json);
  note_missed_target(o, r);
  return exit_code::success;
}

}  // namespace

void register_simplify(CLI::App& app, Action& action) {
  auto o = std::make_shared<SimplifyCommand>();
  CLI::App* cmd = app.add_subcommand(
      "simplify",
      "Simplify a fine triangle surface (or curve) into a coarse one S1 and build the parametrization "
      "of the fine one over S1 (paper 3.3.1): vertices are removed one at a time, cheapest first by "
      "the error oracles; feature lines (boundary, non-manifold, sharp edges) are kept, vertices on "
      "them are removed only along them, feature corners never.");
  cmd->add_option("FINE", o->fine, "The fine triangle surface or curve S2")->required();
  cmd->add_option("-o,--output", o->output, "Map file to write (S1 -> S2): .plmapb binary (large maps) or .plmap text; replaced atomically")->required();
  cmd->add_option("--coarse", o->coarse, "Also write the coarse surface S1 to this file (any surface format)");
  cmd->add_option("--target-elements", o->target_elements, "Stop at this many triangles (segments for a curve)")
      ->check(positive_number);
  cmd->add_option("--target-vertices", o->target_vertices, "Stop at this many vertices")
      ->check(positive_number);
  cmd->add_option("--max-error", o->max_error,
                  "Refuse steps whose modified Hausdorff distance exceeds this (surface units)")
      ->check(positive_number);
  cmd->add_option("--oracle", o->oracles,
                  "Error oracle NAME[:WEIGHT], repeatable: hausdorff, aspect-ratio, long-edge, "
                  "normal-deviation, self-intersection (default hausdorff:1 aspect-ratio:0.05 "
                  "normal-deviation:0.5)");
  cmd->add_option("--feature-angle", o->feature_angle,
                  "Dihedral angle in degrees above which an edge is a feature (180: none)")
      ->check(CLI::Range(0.0, 180.0))
      ->capture_default_str();
  cmd->add_option("--flattening", o->flattening, "Star flattening: polar-map or plane-projection")
      ->capture_default_str();
  cmd->add_option("--hole-triangulation", o->hole_triangulation,
                  "Re-triangulation: constrained-delaunay or min-max-aspect")
      ->capture_default_str();
  cmd->add_option("--ranking", o->ranking,
                  "Queue removal candidates by their exact ranking plan (exact) or by a cheap "
                  "Hausdorff estimate corrected when they come up (estimate)")
      ->check(CLI::IsMember({"exact", "estimate"}))
      ->capture_default_str();
  cmd->add_option("--cut", o->cut,
                  "Cut the fine edges along the new coarse edges at every step (per-step), or trace "
                  "them once through the final coarse surface, redoing the run per step if the "
                  "trace is not valid (deferred); surfaces only")
      ->check(CLI::IsMember({"per-step", "deferred"}))
      ->capture_default_str();
  add_threads_option(*cmd, o->threads, "Threads of the final closure");
  add_progress_options(*cmd, o->progress);
  cmd->add_flag("--json", o->json, "Print the summary as JSON");
  cmd->callback([o, &action] {
    if (o->target_elements == 0 && o->target_vertices == 0 && !std::isfinite(o->max_error))
      throw CLI::ValidationError("simplify", "give --target-elements, --target-vertices or --max-error");
    action = [o] { return run_simplify(*o); };
  });
}

}  // namespace plmap::cli
