// `plmap convert IN OUT`: reads a surface in any readable format and writes it in the format
// named by OUT's extension; a map file (text .plmap or binary .plmapb) is rewritten in the map
// format OUT's extension names.

#include "cli_common.hpp"

#include <plmap/core/errors.hpp>
#include <plmap/core/io/map_file.hpp>
#include <plmap/core/io/surface_writer.hpp>
#include <plmap/core/vertex_merging.hpp>

#include <fmt/format.h>

#include <iostream>
#include <map>
#include <optional>
#include <type_traits>

namespace plmap::cli {

namespace {

struct ConvertOptions {
  std::string input;
  std::string output;
  int dimension = 0;
  std::string encoding = "default";
  std::string gmsh_version = "4.1";
  bool merge_coincident = false;
};

int convert_map(const ConvertOptions& o) {
  check_output_file(o.output, OutputKind::map, {{"IN", o.input}});
  std::visit(
      [&](const auto& map) {
        save_map(o.output, map);
        std::cout << "wrote " << o.output << ": map of " << map.node_count() << " nodes, "
                  << map.region_count() << " regions\n";
      },
      load_map(o.input));
  hint_if_large_text_map(o.output);
  return exit_code::success;
}

int run_convert(const ConvertOptions& o) {
  require_readable_file(o.input);
  if (looks_like_map_file(o.input)) {
    if (o.merge_coincident)
      throw UsageError(fmt::format("--merge-coincident merges the vertices of a surface; {} is a map file", o.input));
    return convert_map(o);
  }
  SurfaceWriteOptions options;
  static const std::map<std::string, Encoding> encodings = {
      {"default", Encoding::format_default},
      {"ascii", Encoding::ascii},
      {"binary", Encoding::binary},
      {"binary-big-endian", Encoding::binary_big_endian}};
  options.encoding = encodings.at(o.encoding);  // CLI11 checked the name
  options.gmsh_version = o.gmsh_version == "2.2" ? GmshVersion::v2_2 : GmshVersion::v4_1;
  // Fail on an unknown output extension before reading a possibly large input.
  check_output_file(o.output, OutputKind::surface, {{"IN", o.input}});
  std::visit(
      [&](const auto& read) {
        using SurfaceType = std::decay_t<decltype(read)>;
        VertexMergeReport merged;
        // (merged into a new surface only when asked: a plain conversion writes what it read)
        const std::optional<SurfaceType> welded =
            o.merge_coincident ? std::optional<SurfaceType>(merge_coincident_vertices(read, &merged)) : std::nullopt;
        const SurfaceType& surface = welded ? *welded : read;
        write_surface(o.output, surface, options);
        std::cout << "wrote " << o.output << ": " << surface.vertex_count() << " vertices, "
                  << surface.element_count() << (surface.dimension == 1 ? " segments" : " triangles");
        if (o.merge_coincident)
          std::cout << " (merged " << merged.merged_vertices << " vertices into others at their position, dropped "
                    << merged.duplicate_elements << " duplicate " << (surface.dimension == 1 ? "segments" : "triangles")
                    << ")";
        std::cout << '\n';
      },
      read_any_surface(o.input, o.dimension));
  return exit_code::success;
}

}  // namespace

void register_convert(CLI::App& app, Action& action) {
  auto o = std::make_shared<ConvertOptions>();
  CLI::App* cmd = app.add_subcommand(
      "convert",
      "Convert a surface between file formats: reads .off .obj .stl .ply .msh .curve (format "
      "from the extension, else from the content) and writes the format named by OUT's "
      "extension. A map file is converted between text (.plmap) and binary (.plmapb) the same "
      "way. OUT is replaced only once it is completely written.");
  cmd->add_option("IN", o->input, "Input surface")->required();
  cmd->add_option("OUT", o->output, "Output surface")->required();
  add_dimension_option(*cmd, o->dimension);
  cmd->add_option("--encoding", o->encoding,
                  "Number encoding: default (binary for STL and PLY, ASCII otherwise), ascii, "
                  "binary, binary-big-endian (PLY)")
      ->check(CLI::IsMember({"default", "ascii", "binary", "binary-big-endian"}))
      ->capture_default_str();
  cmd->add_option("--gmsh-version", o->gmsh_version, "Gmsh MSH version written: 2.2 or 4.1")
      ->check(CLI::IsMember({"2.2", "4.1"}))
      ->capture_default_str();
  cmd->add_flag("--merge-coincident", o->merge_coincident,
               "Merge vertices at exactly the same position into one (the first of them), and keep "
               "elements with the same corners once: welds a polygon soup or an unstitched seam, "
               "which `plmap project` warns about. Surfaces only.");
  cmd->callback([o, &action] { action = [o] { return run_convert(*o); }; });
}

}  // namespace plmap::cli
