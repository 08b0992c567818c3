// `plmap build identity|refine|overlay`: maps between surfaces whose correspondence is known
// without projection (normal projection comes with the construction algorithms).

#include "cli_common.hpp"

#include <plmap/core/errors.hpp>
#include <plmap/core/io/map_file.hpp>
#include <plmap/verify/generators/random_maps.hpp>

#include <iostream>

namespace plmap::cli {

namespace {

/// Refinements larger than this are refused: a typo in --levels should not eat the machine.
constexpr Index max_refined_elements = 20'000'000;

struct BuildOptions {
  std::string surface;
  std::string second_surface;  // overlay only
  std::string output;
  int dimension = 0;
  int levels = 1;
  int random_points = 0;
  std::uint64_t seed = 1;
  bool json = false;
};

template <int d>
int save_and_report(const generators::MapCase<d>& built, const BuildOptions& o) {
  save_map(o.output, *built.map);
  hint_if_large_text_map(o.output);
  Json j;
  j["output"] = o.output;
  j["description"] = built.description;
  j["dimension"] = d;
  j["domain"] = {{"vertices", built.domain->vertex_count()},
                 {"elements", built.domain->element_count()}};
  j["target"] = {{"vertices", built.target->vertex_count()},
                 {"elements", built.target->element_count()}};
  j["nodes"] = built.map->node_count();
  j["regions"] = built.map->region_count();
  print_result(j, o.json);
  return exit_code::success;
}

template <int d>
std::shared_ptr<const Surface<d>> shared(Surface<d>&& s) {
  return std::make_shared<const Surface<d>>(std::move(s));
}

int run_identity(const BuildOptions& o) {
  check_output_file(o.output, OutputKind::map, {{"SURFACE", o.surface}});
  AnySurface any = read_any_surface(o.surface, o.dimension);
  return std::visit(
      [&]<int d>(Surface<d>& s) {
        return save_and_report(generators::identity_map<d>(shared(std::move(s)),
                                                           "identity of " + o.surface),
                               o);
      },
      any);
}

int run_refine(const BuildOptions& o) {
  check_output_file(o.output, OutputKind::map, {{"SURFACE", o.surface}});
  AnySurface any = read_any_surface(o.surface, o.dimension);
  return std::visit(
      [&]<int d>(Surface<d>& s) {
        auto s1 = shared(std::move(s));
        if (o.random_points > 0) {
          generators::Rng rng(o.seed);
          generators::RefinementOptions options;
          options.max_points_per_edge = o.random_points;
          options.max_points_per_element = o.random_points;
          const auto refinement = generators::random_refinement<d>(*s1, options, rng);
          return save_and_report(
              generators::refinement_map<d>(s1, refinement,
                                            "random refinement of " + o.surface + " (up to " +
                                                std::to_string(o.random_points) +
                                                " points per edge/element, seed " +
                                                std::to_string(o.seed) + ")"),
              o);
        }
        const auto refinement = generators::uniform_refinement<d>(*s1, o.levels, max_refined_elements);
        return save_and_report(
            generators::refinement_map<d>(s1, refinement,
                                          "uniform refinement of " + o.surface + ", " +
                                              std::to_string(o.levels) + " levels"),
            o);
      },
      any);
}

int run_overlay(const BuildOptions& o) {
  check_output_file(o.output, OutputKind::map, {{"S1", o.surface}, {"S2", o.second_surface}});
  auto s1 = read_any_surface(o.surface, 2);
  auto s2 = read_any_surface(o.second_surface, 2);
  return save_and_report(
      generators::plane_overlay_map(shared(std::move(std::get<Surface<2>>(s1))),
                                    shared(std::move(std::get<Surface<2>>(s2))),
                                    "overlay of " + o.surface + " and " + o.second_surface),
      o);
}

CLI::App* add_build_command(CLI::App& build, const char* name, const char* help,
                            const std::shared_ptr<BuildOptions>& o) {
  CLI::App* cmd = build.add_subcommand(name, help);
  cmd->add_option("-o,--output", o->output, "Map file to write: .plmapb binary (large maps) or .plmap text; replaced atomically")
      ->required();
  cmd->add_flag("--json", o->json, "Print the summary as JSON");
  return cmd;
}

}  // namespace

void register_build(CLI::App& app, Action& action) {
  CLI::App* build = app.add_subcommand(
      "build",
      "Build a map between surfaces whose correspondence is known, and save it as a .plmap "
      "file. For maps by normal projection between arbitrary surfaces, see `plmap project`.");
  build->require_subcommand(1);

  auto identity = std::make_shared<BuildOptions>();
  CLI::App* id = add_build_command(*build, "identity",
                                   "The identity map of a surface onto itself (S2 = S1).",
                                   identity);
  id->add_option("SURFACE", identity->surface, "The surface S1 = S2")->required();
  add_dimension_option(*id, identity->dimension);
  id->callback([identity, &action] { action = [identity] { return run_identity(*identity); }; });

  auto refine = std::make_shared<BuildOptions>();
  CLI::App* rf = add_build_command(
      *build, "refine",
      "The inclusion map between a surface S1 and a refinement S2 of it (Xi is the identity of "
      "space). Uniform: every segment split into 2^K pieces, every triangle into 4^K. Random "
      "(--random-points): random points on every edge and inside every element, reproducible "
      "from the seed.",
      refine);
  rf->add_option("SURFACE", refine->surface, "The surface S1 to refine")->required();
  add_dimension_option(*rf, refine->dimension);
  rf->add_option("--levels,-k", refine->levels, "Uniform refinement levels K")
      ->check(CLI::Range(0, 20))
      ->capture_default_str();
  rf->add_option("--random-points", refine->random_points,
                 "Random refinement instead: up to this many points per edge and per element")
      ->check(CLI::Range(1, 1000));
  rf->add_option("--seed", refine->seed, "Seed of the random refinement")->capture_default_str();
  rf->callback([refine, &action] { action = [refine] { return run_refine(*refine); }; });

  auto overlay = std::make_shared<BuildOptions>();
  CLI::App* ov = add_build_command(
      *build, "overlay",
      "The identity of the plane between two triangulations of the same planar domain (all "
      "vertices at z = 0, triangles counter-clockwise): S2 edges cross S1 edges, so the map has "
      "intersection, touching and ghost nodes. Quadratic in the edge counts: for surfaces of a "
      "few thousand triangles.",
      overlay);
  ov->add_option("S1", overlay->surface, "The domain triangulation")->required();
  ov->add_option("S2", overlay->second_surface, "The target triangulation")->required();
  ov->callback([overlay, &action] { action = [overlay] { return run_overlay(*overlay); }; });
}

}  // namespace plmap::cli
