// `plmap generate grid|delaunay|polyline`: small reproducible example surfaces (the generators
// of verify/), for the demo, the tests and for trying the other commands.

#include "cli_common.hpp"

#include <plmap/core/errors.hpp>
#include <plmap/core/io/surface_writer.hpp>
#include <plmap/verify/generators/random_surfaces.hpp>

#include <iostream>

namespace plmap::cli {

namespace {

struct GenerateOptions {
  std::string output;
  std::uint64_t seed = 1;
  // grid
  int cells = 4;
  double jitter = 0.0;
  bool hole = false;
  bool lift = false;
  // delaunay
  int interior_points = 20;
  int boundary_points = 4;
  int grid_points = 0;
  // polyline
  int segments = 8;
  bool closed = false;
};

template <int d>
int write_generated(const Surface<d>& surface, const GenerateOptions& o) {
  check_output_file(o.output, OutputKind::surface, {});
  write_surface(o.output, surface);
  std::cout << "wrote " << o.output << ": " << surface.vertex_count() << " vertices, "
            << surface.element_count() << (d == 1 ? " segments" : " triangles") << '\n';
  return exit_code::success;
}

Surface<2> maybe_lift(Surface<2> planar, const GenerateOptions& o, generators::Rng& rng) {
  if (!o.lift) return planar;
  return generators::lift_to_height_field(planar, generators::random_height_field(rng));
}

int run_grid(const GenerateOptions& o) {
  generators::Rng rng(o.seed);
  generators::GridOptions options;
  options.cells = o.cells;
  options.jitter = o.jitter;
  options.with_hole = o.hole;
  if (o.hole && o.cells % 4 != 0)
    throw Error("--hole needs a cell count that is a multiple of 4, got " + std::to_string(o.cells));
  Surface<2> s = generators::grid_triangulation(options, rng);
  return write_generated(maybe_lift(std::move(s), o, rng), o);
}

int run_delaunay(const GenerateOptions& o) {
  generators::Rng rng(o.seed);
  generators::DelaunayOptions options;
  options.interior_points = o.interior_points;
  options.boundary_points = o.boundary_points;
  options.grid_points = o.grid_points;
  options.with_hole = o.hole;
  Surface<2> s = generators::delaunay_triangulation(options, rng);
  return write_generated(maybe_lift(std::move(s), o, rng), o);
}

int run_polyline(const GenerateOptions& o) {
  generators::Rng rng(o.seed);
  if (o.closed && o.segments < 3) throw Error("a closed polyline needs at least 3 segments");
  return write_generated(o.closed ? generators::random_closed_polyline(o.segments, rng)
                                  : generators::random_open_polyline(o.segments, rng),
                         o);
}

CLI::App* add_generate_command(CLI::App& generate, const char* name, const char* help,
                               const std::shared_ptr<GenerateOptions>& o) {
  CLI::App* cmd = generate.add_subcommand(name, help);
  cmd->add_option("-o,--output", o->output,
                  "Surface file to write; the format follows the extension")
      ->required();
  cmd->add_option("--seed", o->seed, "Random seed")->capture_default_str();
  return cmd;
}

}  // namespace

void register_generate(CLI::App& app, Action& action) {
  CLI::App* generate = app.add_subcommand(
      "generate",
      "Write a small reproducible example surface: a triangulated unit square (grid or "
      "Delaunay, optionally with a hole or lifted to a smooth height field) or a plane "
      "polyline. The same seed gives the same file on every platform.");
  generate->require_subcommand(1);

  auto grid = std::make_shared<GenerateOptions>();
  CLI::App* g = add_generate_command(
      *generate, "grid", "Unit square split into cells x cells squares with random diagonals.",
      grid);
  g->add_option("--cells", grid->cells, "Cells per side")
      ->check(CLI::Range(1, 2000))
      ->capture_default_str();
  g->add_option("--jitter", grid->jitter, "Random vertex displacement, in cell sizes (at most 0.2)")
      ->check(CLI::Range(0.0, 0.2))
      ->capture_default_str();
  g->add_flag("--hole", grid->hole, "Cut the hole [0.25,0.5]x[0.5,0.75] (cells a multiple of 4)");
  g->add_flag("--lift", grid->lift, "Lift to a random smooth height field z = h(x, y)");
  g->callback([grid, &action] { action = [grid] { return run_grid(*grid); }; });

  auto delaunay = std::make_shared<GenerateOptions>();
  CLI::App* dl = add_generate_command(
      *generate, "delaunay",
      "Constrained Delaunay triangulation of random points in the unit square.", delaunay);
  dl->add_option("--points", delaunay->interior_points, "Random interior points")
      ->check(CLI::Range(0, 100000))
      ->capture_default_str();
  dl->add_option("--boundary-points", delaunay->boundary_points,
                 "Random points on the square's sides")
      ->check(CLI::Range(0, 10000))
      ->capture_default_str();
  dl->add_option("--grid-points", delaunay->grid_points,
                 "Points on the dyadic grid of spacing 1/8 (shared with grid triangulations)")
      ->check(CLI::Range(0, 81))
      ->capture_default_str();
  dl->add_flag("--hole", delaunay->hole, "Cut the hole [0.25,0.5]x[0.5,0.75]");
  dl->add_flag("--lift", delaunay->lift, "Lift to a random smooth height field z = h(x, y)");
  dl->callback([delaunay, &action] { action = [delaunay] { return run_delaunay(*delaunay); }; });

  auto polyline = std::make_shared<GenerateOptions>();
  CLI::App* pl = add_generate_command(
      *generate, "polyline",
      "A plane polyline: x-monotone from x = 0 to 1, or (--closed) a star-shaped polygon. Write "
      "it as .curve or .msh.",
      polyline);
  pl->add_option("--segments", polyline->segments, "Number of segments")
      ->check(CLI::Range(1, 10000000))
      ->capture_default_str();
  pl->add_flag("--closed", polyline->closed, "Closed polygon around the origin");
  pl->callback([polyline, &action] { action = [polyline] { return run_polyline(*polyline); }; });
}

}  // namespace plmap::cli
