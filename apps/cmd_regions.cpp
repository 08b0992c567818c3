// `plmap regions MAP -o FILE.csv|FILE.vtu` and `plmap export MAP -o DIR`: the regions (remote
// intersections) of a map as a table or for ParaView.

#include "cli_common.hpp"
#include "progress_bar.hpp"

#include <plmap/core/errors.hpp>
#include <plmap/core/io/map_file.hpp>
#include <plmap/core/io/regions_csv.hpp>
#include <plmap/core/io/vtu_export.hpp>

#include <iostream>

namespace plmap::cli {

namespace {

struct RegionsOptions {
  std::string file;
  std::string output;
  ProgressMode progress = ProgressMode::automatic;
};

int run_regions(const RegionsOptions& o) {
  check_output_file(o.output, OutputKind::regions, {{"MAP", o.file}});
  require_readable_file(o.file);
  const std::string ext = lower_extension(o.output);
  const AnyPlMap any = load_map_showing_progress(o.file, o.progress);
  std::visit(
      [&](const auto& map) {
        if (ext == ".csv")
          write_regions_csv(std::filesystem::path(o.output), map);
        else
          write_regions_vtu(std::filesystem::path(o.output), map);
        std::cout << "wrote " << map.region_count() << " regions to " << o.output << '\n';
      },
      any);
  return exit_code::success;
}

/// The files export_vtu writes into its directory (an input of that name would be replaced).
const std::vector<std::string> export_vtu_file_names = {
    "domain.vtu", "target.vtu", "graph.vtu", "regions.vtu", "images.vtu", "map.pvd"};

struct ExportOptions {
  std::string file;
  std::string directory;
  ProgressMode progress = ProgressMode::automatic;
};

int run_export(const ExportOptions& o) {
  check_output_directory(o.directory, export_vtu_file_names, {}, {{"MAP", o.file}});
  require_readable_file(o.file);
  const AnyPlMap any = load_map_showing_progress(o.file, o.progress);
  const auto written =
      std::visit([&](const auto& map) { return export_vtu(map, o.directory); }, any);
  for (const auto& path : written) std::cout << "wrote " << path.string() << '\n';
  return exit_code::success;
}

}  // namespace

void register_regions(CLI::App& app, Action& action) {
  auto o = std::make_shared<RegionsOptions>();
  CLI::App* cmd = app.add_subcommand(
      "regions",
      "Write the regions of a map (the remote intersections T1 ∩ Xi^-1(T2) over which mortar "
      "integrals are exact): as a CSV table with local and world coordinates of every corner on "
      "both sides and the measures, or as one VTK .vtu file of the region triangles/segments.");
  cmd->add_option("MAP", o->file, "Map file (.plmap)")->required();
  cmd->add_option("-o,--output", o->output, "Output file, .csv or .vtu (written atomically)")
      ->required();
  add_progress_options(*cmd, o->progress);
  cmd->callback([o, &action] { action = [o] { return run_regions(*o); }; });
}

void register_export(CLI::App& app, Action& action) {
  auto o = std::make_shared<ExportOptions>();
  CLI::App* cmd = app.add_subcommand(
      "export",
      "Export a map for ParaView into a directory: domain.vtu (S1), target.vtu (S2), graph.vtu "
      "(the nodes and graph edges on S1), regions.vtu, images.vtu (the regions placed on S2) "
      "and map.pvd, which opens them together.");
  cmd->add_option("MAP", o->file, "Map file (.plmap)")->required();
  cmd->add_option("-o,--output", o->directory, "Output directory (created if missing)")
      ->required();
  add_progress_options(*cmd, o->progress);
  cmd->callback([o, &action] { action = [o] { return run_export(*o); }; });
}

}  // namespace plmap::cli
