// One measurement of the projection benchmark against the peers (experiments/peers/README.md):
// builds one input pair in memory from a seed, runs one tool on it once, and prints one JSON line
// with the wall time of the projection, the increase of peak memory over the memory held after
// the input was built, and the covered measure against the exact overlap. run.sh runs each tool
// and input in a separate process, three times, and tabulates the medians.
//
// Usage: bench_projection_peers --tool plmap|psurface|contactmerge --case plane|sphere|femur|femur-offset|circle
//            --size N [--seed S] [--threads T] [--femur femur.off] [--write-inputs PREFIX]
//            [--order as-generated|spatial] [--renumber auto|always|target|never]
//        bench_projection_peers --list-tools
// --size: plane: S1 triangles; sphere: icosphere level; circle: S1 segments; femur*: ignored.
// --threads: plmap only (0 = all cores); the peers are single-threaded.
// --order spatial: both surfaces renumbered along a Morton curve before any tool sees them.
// --renumber: plmap only, ProjectionOptions::renumbering (plmap's own copies in spatial order).
// --write-inputs: also write S1 and S2 to PREFIX_s1.off/.curve and PREFIX_s2.off/.curve (reproducers).

#include "command_line.hpp"
#include "plain_mesh_surface.hpp"
#include "spatial_order.hpp"
#include "tools.hpp"

#include <plmap/core/io/surface_writer.hpp>

#include <fmt/format.h>

#include <string>
#include <vector>

namespace plmap::peers {

namespace {

struct Arguments {
  std::string tool = "plmap", family = "plane", femur, write_inputs;
  std::string order = "as-generated";  ///< or "spatial" (spatial_order.hpp)
  std::string renumber = "auto";       ///< plmap's ProjectionOptions::renumbering
  long size = 2000;
  std::uint64_t seed = 1;
  unsigned threads = 1;
};

/// Writes S1 and S2 as PREFIX_s1.off / PREFIX_s2.off (d = 2) or PREFIX_s1.curve / PREFIX_s2.curve
/// (d = 1), in plmap's own writers, so that `plmap project PREFIX_s1.off PREFIX_s2.off` reproduces
/// a case from the command line (coordinates are written with round-trip precision).
template <int d>
void write_inputs(const std::string& prefix, const SurfacePair<d>& input) {
  const std::string ext = d == 2 ? ".off" : ".curve";
  write_surface<d>(prefix + "_s1" + ext, *to_surface(input.s1));
  write_surface<d>(prefix + "_s2" + ext, *to_surface(input.s2));
}

template <int d>
nlohmann::json measure(const Arguments& args, const SurfacePair<d>& input, double generation_seconds) {
  if (!args.write_inputs.empty()) write_inputs(args.write_inputs, input);
  Measurement clock;
  ToolOutcome outcome;
  if (args.tool == "plmap") {
    outcome = run_plmap<d>(input, args.threads, args.renumber, clock);
#ifdef PLMAP_PEERS_HAVE_PSURFACE
  } else if (args.tool == "psurface") {
    outcome = run_psurface<d>(input, clock);
#endif
#ifdef PLMAP_PEERS_HAVE_CONTACTMERGE
  } else if (args.tool == "contactmerge") {
    outcome = run_contactmerge<d>(input, clock);
#endif
  } else {
    reject_tool(args.tool);
  }
  const double relative_error = (outcome.covered - input.exact_overlap) / input.exact_overlap;
  const double covered_target = outcome.details.value("covered_target", 0.0);
  const double target_relative_error =
      (covered_target - input.exact_target_overlap) / input.exact_target_overlap;
  return {{"tool", args.tool},
          {"threads", args.tool == "plmap" ? args.threads : 1u},
          {"family", input.family},
          {"label", input.label},
          {"size", args.size},
          {"seed", args.seed},
          {"dimension", d},
          {"s1_cells", input.s1.cells.size()},
          {"s2_cells", input.s2.cells.size()},
          {"ok", outcome.ok},
          {"error", outcome.error},
          {"seconds", clock.seconds()},
          {"cpu_seconds", clock.cpu_seconds()},
          {"peak_increase_mib", double(clock.peak_increase_kib()) / 1024.0},
          {"baseline_mib", double(clock.baseline_kib()) / 1024.0},
          {"peak_reset", clock.peak_was_reset()},
          {"covered", outcome.covered},
          {"exact_overlap", input.exact_overlap},
          {"exact_overlap_note", input.exact_overlap_note},
          {"covered_relative_error", relative_error},
          {"covered_target", covered_target},
          {"exact_target_overlap", input.exact_target_overlap},
          {"covered_target_relative_error", target_relative_error},
          {"pieces", outcome.pieces},
          {"generation_seconds", generation_seconds},
          {"details", outcome.details}};
}

/// The tools this build has, for --list-tools.
std::vector<std::string> built_in_tools() {
  std::vector<std::string> tools = {"plmap"};
#ifdef PLMAP_PEERS_HAVE_PSURFACE
  tools.emplace_back("psurface");
#endif
#ifdef PLMAP_PEERS_HAVE_CONTACTMERGE
  tools.emplace_back("contactmerge");
#endif
  return tools;
}

int run(int argc, char** argv) {
  Arguments args;
  for (ArgumentReader a(argc, argv); a.next();) {
    if (a.name() == "--tool") args.tool = a.value();
    else if (a.name() == "--case") args.family = a.value();
    else if (a.name() == "--size") args.size = std::stol(a.value());
    else if (a.name() == "--seed") args.seed = std::stoull(a.value());
    else if (a.name() == "--threads") args.threads = static_cast<unsigned>(std::stoul(a.value()));
    else if (a.name() == "--femur") args.femur = a.value();
    else if (a.name() == "--write-inputs") args.write_inputs = a.value();
    else if (a.name() == "--order") args.order = a.value();
    else if (a.name() == "--renumber") args.renumber = a.value();
    else if (a.name() == "--list-tools") {
      print_tools(built_in_tools());
      return 0;
    } else {
      a.reject();
    }
  }
  if (args.order != "as-generated" && args.order != "spatial")
    throw std::invalid_argument(fmt::format("unknown --order '{}' (as-generated or spatial)", args.order));
  // Only the numbering changes (spatial_order.hpp); the generated inputs have no isolated points.
  auto ordered = [&](auto input) {
    if (args.order == "spatial") {
      input.s1 = spatially_ordered(input.s1);
      input.s2 = spatially_ordered(input.s2);
      input.label += " (spatial order)";
    }
    return input;
  };
  const double t0 = now_seconds();
  nlohmann::json line;
  if (args.family == "circle") {
    const auto input = ordered(concentric_circles(args.size, args.seed));
    line = measure<1>(args, input, now_seconds() - t0);
  } else {
    SurfacePair<2> input;
    if (args.family == "plane") input = facing_planes(args.size, args.seed);
    else if (args.family == "sphere") input = concentric_spheres(static_cast<int>(args.size), args.seed);
    else if (args.family == "femur") input = femur_pair(args.femur, true, args.seed);
    else if (args.family == "femur-offset") input = femur_pair(args.femur, false, args.seed);
    else throw std::invalid_argument(fmt::format("unknown case '{}'", args.family));
    input = ordered(std::move(input));
    line = measure<2>(args, input, now_seconds() - t0);
  }
  print_result_line(line);
  return 0;
}

}  // namespace

}  // namespace plmap::peers

int main(int argc, char** argv) {
  return plmap::peers::run_benchmark("bench_projection_peers", [&] { return plmap::peers::run(argc, argv); });
}
