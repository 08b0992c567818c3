// `plmap info FILE`: what a surface or map file holds.

#include "cli_common.hpp"
#include "progress_bar.hpp"

#include <plmap/core/io/map_file.hpp>
#include <plmap/verify/facts_json.hpp>
#include <plmap/verify/self_intersections.hpp>

namespace plmap::cli {

namespace {

struct InfoOptions {
  std::string file;
  int dimension = 0;
  bool json = false;
  bool quality = true;
  ProgressMode progress = ProgressMode::automatic;
};

int run_info(const InfoOptions& o) {
  require_readable_file(o.file);
  Json j;
  j["file"] = o.file;
  if (looks_like_map_file(o.file)) {
    j["kind"] = "map";
    std::visit([&](const auto& map) { j.update(map_facts_json(map, o.quality)); }, load_map_showing_progress(o.file, o.progress));
  } else {
    j["kind"] = "surface";
    std::visit(
        [&](const auto& surface) {
          j.update(surface_facts_json(surface));
          // (not for the surfaces inside a map: the test costs about a quarter of a projection)
          j["self_intersecting_pairs"] = self_intersections(surface).size();
        },
        read_any_surface(o.file, o.dimension));
  }
  print_result(j, o.json);
  return exit_code::success;
}

}  // namespace

void register_info(CLI::App& app, Action& action) {
  auto o = std::make_shared<InfoOptions>();
  CLI::App* cmd = app.add_subcommand(
      "info",
      "Describe a surface or map file. Surfaces: vertex/element/edge counts, dimension, measure "
      "(length or area), bounding box, boundary and non-manifold counts, coincident vertices, and the "
      "pairs of elements that cross each other without sharing a vertex (the surface intersects "
      "itself). Maps (.plmap): both surfaces, node counts by type, regions, covered measure and the "
      "distribution of the condition number kappa.");
  cmd->add_option("FILE", o->file, "Surface (.off .obj .stl .ply .msh .curve) or map (.plmap)")
      ->required();
  add_dimension_option(*cmd, o->dimension);
  cmd->add_flag("--json", o->json, "Print JSON instead of text");
  cmd->add_flag("!--no-quality", o->quality, "Maps: skip the kappa statistics");
  add_progress_options(*cmd, o->progress);
  cmd->callback([o, &action] { action = [o] { return run_info(*o); }; });
}

}  // namespace plmap::cli
