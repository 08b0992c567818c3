// `plmap draw MAP --element T -o FILE.svg|png` and `plmap draw MAP --view3d -o FILE.svg|png`:
// pictures of a map (paper Figs. 1-3). SVG is written by the library; PNG by converting that SVG
// with rsvg-convert (Debian package librsvg2-bin), if it is installed.

#include "cli_common.hpp"
#include "progress_bar.hpp"

#include <plmap/core/errors.hpp>
#include <plmap/core/io/atomic_file.hpp>
#include <plmap/core/io/map_file.hpp>
#include <plmap/core/io/svg_drawing.hpp>

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <iostream>
#include <optional>
#include <sstream>
#include <vector>

extern char** environ;

namespace plmap::cli {

namespace {

constexpr const char* png_converter = "rsvg-convert";

struct DrawOptions {
  ProgressMode progress = ProgressMode::automatic;
  std::string file;
  std::string output;
  std::optional<Index> element;
  bool view3d = false;
  double azimuth = 35.0;
  double elevation = 25.0;
  std::string up = "z";
  double width = 900.0;
  double height = 700.0;
  double element_width = 560.0;
  double zoom = 1.0;
  bool node_labels = false;
  bool no_legend = false;
  bool closure = false;
  bool element_labels = false;
  bool no_domain_edges = false;
};

/// The full path of `program` on PATH, if it is there and executable.
std::optional<std::filesystem::path> find_on_path(const std::string& program) {
  const char* path = std::getenv("PATH");
  if (path == nullptr) return std::nullopt;
  std::stringstream dirs(path);
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    if (dir.empty()) continue;
    const std::filesystem::path candidate = std::filesystem::path(dir) / program;
    if (::access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return std::nullopt;
}

/// Runs a program without a shell (file names need no quoting) and returns its exit status.
int run_program(const std::filesystem::path& program, const std::vector<std::string>& arguments) {
  std::vector<char*> argv;
  std::vector<std::string> storage{program.string()};
  storage.insert(storage.end(), arguments.begin(), arguments.end());
  for (auto& s : storage) argv.push_back(s.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (::posix_spawn(&pid, program.c_str(), nullptr, nullptr, argv.data(), environ) != 0)
    throw Error("could not start " + program.string());
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) throw Error("lost track of " + program.string());
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128;
}

/// Converts the SVG to PNG next to `output` and renames it over `output`, so that a failed
/// conversion leaves an existing file untouched. The temporary files are removed in every case.
void write_png(const std::string& svg, const std::filesystem::path& output, double zoom) {
  namespace fs = std::filesystem;
  const auto converter = find_on_path(png_converter);
  if (!converter)
    throw Error(output.string() + ": writing PNG needs the program rsvg-convert (Debian package "
                "librsvg2-bin), which is not on PATH; install it, or write an .svg file");
  const fs::path parent = output.has_parent_path() ? output.parent_path() : fs::path(".");
  if (!fs::is_directory(parent))
    throw Error(output.string() + ": directory " + parent.string() + " does not exist");
  remove_stale_temporaries(output);
  const TemporaryFile svg_file(output, ".svg");
  TemporaryFile png_file(output, ".png");
  write_svg_file(svg_file.path(), svg);
  const int status = run_program(*converter, {"--zoom", std::to_string(zoom), "--format", "png",
                                              "--output", png_file.path().string(),
                                              svg_file.path().string()});
  if (status != 0 || !fs::is_regular_file(png_file.path()))
    throw Error(output.string() + ": rsvg-convert failed (exit status " + std::to_string(status) + ")");
  std::error_code error;
  fs::rename(png_file.path(), output, error);
  if (error) throw Error(output.string() + ": cannot replace the file: " + error.message());
  png_file.release();
}

template <int d>
std::string draw(const PlMap<d>& map, const DrawOptions& o) {
  if (o.element) {
    ElementDrawingOptions options;
    options.element_width = o.element_width;
    options.legend = !o.no_legend;
    options.node_labels = o.node_labels;
    return draw_element_graph_svg(map, *o.element, options);
  }
  MapViewOptions options;
  options.azimuth_degrees = o.azimuth;
  options.elevation_degrees = o.elevation;
  options.up_axis = o.up;
  options.width = o.width;
  options.height = o.height;
  options.legend = !o.no_legend;
  options.closure_edges = o.closure;
  options.element_labels = o.element_labels;
  options.domain_edges = !o.no_domain_edges;
  return draw_map_view_svg(map, options);
}

int run_draw(const DrawOptions& o) {
  check_output_file(o.output, OutputKind::picture, {{"MAP", o.file}});
  require_readable_file(o.file);
  const std::string ext = lower_extension(o.output);
  if (ext == ".png" && !find_on_path(png_converter))
    throw Error(o.output + ": writing PNG needs the program rsvg-convert (Debian package "
                "librsvg2-bin), which is not on PATH; install it, or write an .svg file");
  const AnyPlMap any = load_map_showing_progress(o.file, o.progress);
  const std::string svg = std::visit([&](const auto& map) { return draw(map, o); }, any);
  if (ext == ".svg")
    write_svg_file(o.output, svg);
  else
    write_png(svg, o.output, o.zoom);
  std::cout << "wrote " << o.output << '\n';
  return exit_code::success;
}

}  // namespace

void register_draw(CLI::App& app, Action& action) {
  auto o = std::make_shared<DrawOptions>();
  CLI::App* cmd = app.add_subcommand(
      "draw",
      "Draw a map as an SVG or PNG picture. --element T: the plane graph on S1 element T in its "
      "reference coordinates (paper Fig. 3): S2-edge preimages solid, closure edges dashed, "
      "regions coloured by S2 element, nodes marked by type (corner filled disc, touching open "
      "square, intersection filled diamond, ghost open circle, interior dot). --view3d: S1 "
      "shaded in 3-D with the preimage of S2's edge graph drawn on it (paper Fig. 2); for "
      "curves, S1 and S2 in the plane with each node joined to its image (paper Fig. 1). PNG "
      "output needs rsvg-convert (Debian package librsvg2-bin).");
  cmd->add_option("MAP", o->file, "Map file (.plmap)")->required();
  cmd->add_option("-o,--output", o->output, "Picture to write, .svg or .png (replaced atomically)")
      ->required();
  CLI::Option* element =
      cmd->add_option("--element,-e", o->element, "Draw the graph on this S1 element (0-based)");
  CLI::Option* view = cmd->add_flag("--view3d", o->view3d, "Draw the whole map (3-D view of S1)");
  element->excludes(view);
  cmd->add_option("--azimuth", o->azimuth,
                  "--view3d: camera azimuth in degrees, counter-clockwise about +z from +x")
      ->capture_default_str();
  cmd->add_option("--elevation", o->elevation,
                  "--view3d: camera elevation in degrees above the xy plane")
      ->check(CLI::Range(-90.0, 90.0))
      ->capture_default_str();
  cmd->add_option("--up", o->up,
                  "--view3d: the world axis pointing up in the picture: x, y, z, -x, -y or -z")
      ->check(CLI::IsMember({"x", "y", "z", "-x", "-y", "-z"}))
      ->capture_default_str();
  cmd->add_option("--width", o->width, "--view3d: image width in pixels")
      ->check(CLI::Range(100.0, 20000.0))
      ->capture_default_str();
  cmd->add_option("--height", o->height, "--view3d: image height in pixels")
      ->check(CLI::Range(100.0, 20000.0))
      ->capture_default_str();
  cmd->add_option("--element-width", o->element_width,
                  "--element: width of the element drawing in pixels (legend not included)")
      ->check(CLI::Range(150.0, 20000.0))
      ->capture_default_str();
  cmd->add_flag("--labels", o->node_labels, "--element: write each node's index next to it");
  cmd->add_flag("--closure", o->closure, "--view3d: also draw the closure edges (dashed)");
  cmd->add_flag("--element-labels", o->element_labels,
                "--view3d: write each S1 element's index on it (to pick one for --element)");
  cmd->add_flag("--no-domain-edges", o->no_domain_edges,
                "--view3d: do not outline S1's triangles");
  cmd->add_flag("--no-legend", o->no_legend, "Leave out the legend");
  cmd->add_option("--zoom", o->zoom, "PNG only: scale factor of the pixel size")
      ->check(CLI::Range(0.1, 20.0))
      ->capture_default_str();
  add_progress_options(*cmd, o->progress);
  cmd->callback([o, &action] {
    if (!o->element && !o->view3d)
      throw CLI::RequiredError("--element T or --view3d");
    action = [o] { return run_draw(*o); };
  });
}

}  // namespace plmap::cli
