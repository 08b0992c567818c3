// One measurement of the simplification benchmark against the peers (README.md, "Simplification
// against the peers"): reads a triangle mesh, runs one tool on it once — plmap (simplify + smooth),
// PSurface 2.0 (point removal + edge relaxation) or CGAL's edge collapse (the floor, no map) —
// and prints one JSON line: wall time of the simplification and of the smoothing, the increase of
// peak memory over both, the CPU time of both (the fair figure on a loaded machine), the final
// element count, and, measured with plmap's own code on every
// tool's result, the modified Hausdorff distance (relative to the mesh's bounding-box diagonal),
// kappa of the regions before and after smoothing, and the aspect-ratio distributions of the
// coarse surface and of its refinement through the map.
//
// Usage: bench_simplification_peers --tool plmap|psurface|cgal --mesh FILE.off --target N
//            [--oracle NAME[:WEIGHT]]... [--ranking exact|estimate] [--cut per-step|deferred] [--feature-angle DEG] [--sweeps K] [--weights NAME]
//            [--no-quadrilaterals] [--refine-levels L] [--psurface-aspect-ratio W] [--psurface-hausdorff W]
//        bench_simplification_peers --list-tools
// Exit 2 with one line on stderr for bad arguments or an unreadable mesh.

#include "command_line.hpp"
#include "simplification_tools.hpp"

#include <plmap/core/io/surface_reader.hpp>

#include <fmt/format.h>

#include <string>
#include <vector>

namespace plmap::peers {

namespace {

/// The tools this build has, for --list-tools.
std::vector<std::string> built_in_tools() {
  std::vector<std::string> tools = {"plmap", "cgal"};
#ifdef PLMAP_PEERS_HAVE_PSURFACE
  tools.emplace_back("psurface");
#endif
  return tools;
}

int run(int argc, char** argv) {
  SimplificationRequest request;
  std::string tool = "plmap", mesh;
  bool oracles_given = false;
  for (ArgumentReader a(argc, argv); a.next();) {
    if (a.name() == "--tool") tool = a.value();
    else if (a.name() == "--mesh") mesh = a.value();
    else if (a.name() == "--target") request.target_elements = Index(std::stoll(a.value()));
    else if (a.name() == "--oracle") {
      if (!oracles_given) request.oracles.clear();
      oracles_given = true;
      request.oracles.push_back(a.value());
    } else if (a.name() == "--feature-angle") request.feature_angle_degrees = std::stod(a.value());
    else if (a.name() == "--ranking") request.ranking = a.value();
    else if (a.name() == "--cut") request.cut = a.value();
    else if (a.name() == "--sweeps") request.smooth_sweeps = std::stoi(a.value());
    else if (a.name() == "--weights") request.smoothing_weights = a.value();
    else if (a.name() == "--no-quadrilaterals") request.smooth_quadrilaterals = false;
    else if (a.name() == "--refine-levels") request.refine_levels = std::stoi(a.value());
    else if (a.name() == "--psurface-aspect-ratio") request.psurface_aspect_ratio = std::stod(a.value());
    else if (a.name() == "--psurface-hausdorff") request.psurface_hausdorff = std::stod(a.value());
    else if (a.name() == "--list-tools") {
      print_tools(built_in_tools());
      return 0;
    } else {
      a.reject();
    }
  }
  if (mesh.empty()) throw std::invalid_argument("--mesh FILE is required");
  const double t0 = now_seconds();
  request.fine = std::make_shared<const Surface<2>>(read_surface<2>(mesh));
  const double reading = now_seconds() - t0;
  if (request.target_elements < 1 || request.target_elements >= request.fine->element_count())
    throw std::invalid_argument(fmt::format("--target {} must be between 1 and the mesh's {} triangles",
                                            request.target_elements, request.fine->element_count()));
  Measurement clock;
  SimplificationOutcome outcome;
  if (tool == "plmap") outcome = simplify_with_plmap(request, clock);
  else if (tool == "cgal") outcome = simplify_with_cgal(request, clock);
#ifdef PLMAP_PEERS_HAVE_PSURFACE
  else if (tool == "psurface") outcome = simplify_with_psurface(request, clock);
#endif
  else reject_tool(tool);
  nlohmann::json line = {{"tool", tool},
                         {"mesh", mesh},
                         {"input_elements", request.fine->element_count()},
                         {"target_elements", request.target_elements},
                         {"ok", outcome.ok},
                         {"error", outcome.error},
                         {"seconds", outcome.seconds_simplify + outcome.seconds_smooth},
                         {"seconds_simplify", outcome.seconds_simplify},
                         {"seconds_smooth", outcome.seconds_smooth},
                         {"cpu_seconds", outcome.cpu_simplify + outcome.cpu_smooth},
                         {"cpu_seconds_simplify", outcome.cpu_simplify},
                         {"cpu_seconds_smooth", outcome.cpu_smooth},
                         {"peak_increase_mib", double(clock.peak_increase_kib()) / 1024.0},
                         {"baseline_mib", double(clock.baseline_kib()) / 1024.0},
                         {"peak_reset", clock.peak_was_reset()},
                         {"reading_seconds", reading}};
  line.update(outcome.figures);
  print_result_line(line);
  return 0;
}

}  // namespace

}  // namespace plmap::peers

int main(int argc, char** argv) {
  return plmap::peers::run_benchmark("bench_simplification_peers", [&] { return plmap::peers::run(argc, argv); });
}
