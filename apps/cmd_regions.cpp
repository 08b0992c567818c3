// `plmap regions MAP -o FILE.csv|FILE.vtu` and `plmap export MAP -o DIR`: the regions (remote
// intersections) of a map as a table or for ParaView.

#include "cli_common.hpp"

#include <plmap/core/errors.hpp>
#include <plmap/core/io/map_file.hpp>
#include <plmap/core/io/regions_csv.hpp>
#include <plmap/core/io/vtu_export.hpp>

#include <algorithm>
#include <cctype>
#include <iostream>
#include <random>

namespace plmap::cli {

namespace {

std::string lower_extension(const std::filesystem::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

/// Writes only the regions' VTU file to `output`, atomically: the VTU file set is exported into
/// a scratch directory next to `output` (same file system), and its regions.vtu renamed over
/// `output`. The scratch directory is removed in every case.
template <int d>
void write_regions_vtu(const PlMap<d>& map, const std::filesystem::path& output) {
  namespace fs = std::filesystem;
  const fs::path parent = output.has_parent_path() ? output.parent_path() : fs::path(".");
  if (!fs::is_directory(parent))
    throw Error(output.string() + ": directory " + parent.string() + " does not exist");
  std::random_device entropy;
  // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) about "." + std::string at -O2.
  std::string scratch_name = ".";
  scratch_name += output.filename().string();
  scratch_name += ".tmp";
  scratch_name += std::to_string(entropy() % 1000000);
  const fs::path scratch = parent / scratch_name;
  struct RemoveScratch {
    fs::path path;
    ~RemoveScratch() {
      std::error_code ignored;
      fs::remove_all(path, ignored);
    }
  } cleanup{scratch};
  fs::create_directory(scratch);
  export_vtu(map, scratch);
  fs::rename(scratch / "regions.vtu", output);
}

struct RegionsOptions {
  std::string file;
  std::string output;
};

int run_regions(const RegionsOptions& o) {
  require_readable_file(o.file);
  const std::string ext = lower_extension(o.output);
  if (ext != ".csv" && ext != ".vtu")
    throw Error(o.output + ": unknown output format '" + ext + "'; use .csv or .vtu");
  const AnyPlMap any = load_map(o.file);
  std::visit(
      [&](const auto& map) {
        if (ext == ".csv")
          write_regions_csv(std::filesystem::path(o.output), map);
        else
          write_regions_vtu(map, o.output);
        std::cout << "wrote " << map.region_count() << " regions to " << o.output << '\n';
      },
      any);
  return exit_code::success;
}

struct ExportOptions {
  std::string file;
  std::string directory;
};

int run_export(const ExportOptions& o) {
  require_readable_file(o.file);
  const AnyPlMap any = load_map(o.file);
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
  cmd->callback([o, &action] { action = [o] { return run_export(*o); }; });
}

}  // namespace plmap::cli
