// `plmap refine MAP --levels K -o OUT`: refines S1 uniformly and moves every new vertex to its
// image under the map (the remesher of paper section 5); prints the distance to S2 and the
// triangle quality.

#include "cli_common.hpp"
#include "progress_bar.hpp"

#include <plmap/construct/refine_through_map.hpp>
#include <plmap/core/errors.hpp>
#include <plmap/core/io/map_file.hpp>
#include <plmap/core/io/surface_writer.hpp>

#include <fmt/format.h>

namespace plmap::cli {

namespace {

struct RefineCommand {
  std::string map, output;
  int levels = 1;
  bool json = false;
  ProgressMode progress = ProgressMode::automatic;
};

Json quality_json(const AspectRatioSummary& q) {
  return {{"min", q.min}, {"mean", q.mean}, {"p50", q.p50}, {"p90", q.p90}, {"p99", q.p99}, {"max", q.max}};
}

int run_refine(const RefineCommand& o) {
  check_output_file(o.output, OutputKind::surface, {{"MAP", o.map}});
  require_readable_file(o.map);
  ProgressBar bar(o.progress);
  AnyPlMap any = load_map(o.map, bar.callback());
  if (!std::holds_alternative<PlMap<2>>(any))
    throw Error(fmt::format("{}: refine needs a map between triangle surfaces (d = 2), this one is between curves", o.map));
  RefineOptions options;
  options.levels = o.levels;
  options.progress = bar.callback();
  const RefineResult result =
      naming_the_input(o.map, [&] { return refine_through_map(std::get<PlMap<2>>(any), options); });
  write_surface(o.output, result.surface);
  bar.finish();
  const RefineReport& r = result.report;
  Json j;
  j["output"] = o.output;
  j["levels"] = r.levels;
  j["vertices"] = r.vertices;
  j["elements"] = r.elements;
  j["distance_max"] = r.distance_max;
  j["distance_mean"] = r.distance_mean;
  j["distance_max_relative"] = r.distance_max_relative;
  j["aspect_ratio_refined"] = quality_json(r.refined_quality);
  j["aspect_ratio_coarse"] = quality_json(r.coarse_quality);
  j["seconds"] = r.seconds;
  print_result(j, o.json);
  return exit_code::success;
}

}  // namespace

void register_refine(CLI::App& app, Action& action) {
  auto o = std::make_shared<RefineCommand>();
  CLI::App* cmd = app.add_subcommand(
      "refine",
      "Refine the domain surface S1 of a map uniformly and move every vertex to its image on S2 "
      "(for a parametrization built by `simplify`: a remeshing of S2 with S1's connectivity). "
      "Prints the distance of the result to S2 and its triangle quality (aspect ratio, 1 = "
      "equilateral).");
  cmd->add_option("MAP", o->map, "Map file (.plmap) of triangle surfaces; must be a parametrization")->required();
  cmd->add_option("-o,--output", o->output, "Surface file to write (any surface format), replaced atomically")
      ->required();
  cmd->add_option("--levels", o->levels, "Levels of uniform refinement (each splits a triangle into 4)")
      ->check(CLI::Range(0, 8))
      ->capture_default_str();
  add_progress_options(*cmd, o->progress);
  cmd->add_flag("--json", o->json, "Print the summary as JSON");
  cmd->callback([o, &action] { action = [o] { return run_refine(*o); }; });
}

}  // namespace plmap::cli
