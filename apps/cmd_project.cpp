// `plmap project S1 S2 -o MAP`: builds the map from S1 onto S2 by normal projection (paper
// section 3.2) and prints what was covered and what could not be inserted.

#include "cli_common.hpp"
#include "directions_file.hpp"
#include "progress_bar.hpp"
#include "release_at_exit.hpp"
#include "surface_pair.hpp"

#include <plmap/construct/project.hpp>
#include <plmap/construct/projection_report_json.hpp>
#include <plmap/core/errors.hpp>
#include <plmap/core/io/map_file.hpp>
#include <plmap/core/regions.hpp>
#include <plmap/solvers/solver_kind.hpp>
#include <plmap/verify/facts_json.hpp>
#include <plmap/verify/self_intersections.hpp>

#include <fmt/format.h>

#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>

namespace plmap::cli {

namespace {

struct ProjectCommand {
  std::string s1, s2, output, directions_file, solver = "newton", normal_check = "none", renumber = "auto";
  double max_distance = std::numeric_limits<double>::infinity();
  bool relative_distance = false, allow_negative = false, json = false, no_rim = false, no_fold_rim = false;
  unsigned threads = 0;
  int dimension = 0;
  std::size_t max_listed = 20;
  ProgressMode progress = ProgressMode::automatic;
};

SpatialRenumbering renumbering_from(const std::string& name) {
  if (const auto r = spatial_renumbering_from_name(name)) return *r;
  throw Error(fmt::format("unknown renumbering '{}' (valid: auto, always, target, never)", name));
}

template <int d>
int run(const ProjectCommand& o, Surface<d>&& s1_surface, Surface<d>&& s2_surface) {
  auto s1 = std::make_shared<const Surface<d>>(std::move(s1_surface));
  auto s2 = std::make_shared<const Surface<d>>(std::move(s2_surface));
  // Unstitched seams: the rays of a seam's two sides meet S2 at one point, and a projection of a
  // surface onto itself lost half of two triangles that share a diagonal's position but not its
  // vertices (and all of CGAL's quads_to_stitch). Said before the work, not refused: the rest of
  // the map is still right.
  for (const auto& [name, surface] : {std::pair{"S1", s1.get()}, std::pair{"S2", s2.get()}})
    if (const Index n = coincident_vertex_count(*surface); n > 0)
      std::cerr << "warning: " << name << " has " << n << " vertices at the position of another vertex (seams whose "
                << "sides are not stitched together); the map may leave out elements along them: merge such "
                << "vertices first (plmap convert IN OUT --merge-coincident)\n";
  ProjectionOptions options;
  options.solver = o.solver;
  options.max_distance = o.max_distance;
  options.max_distance_is_relative = o.relative_distance;
  options.allow_negative_distance = o.allow_negative;
  options.end_on_rim = !o.no_rim;
  options.fold_rim = !o.no_fold_rim;
  options.normal_check = normal_check_named(o.normal_check);
  options.threads = o.threads;
  options.renumbering = renumbering_from(o.renumber);
  if (!o.directions_file.empty()) options.directions = read_directions(o.directions_file, d, s1->vertex_count());

  ProgressBar bar(o.progress);
  options.progress = bar.callback();
  ProjectionResult<d> result = project<d>(s1, s2, options);
  save_map(o.output, result.map, bar.callback());
  bar.finish();
  hint_if_large_text_map(o.output);
  // An empty map is a valid answer, but most often the rays went the wrong way: S2 lies behind
  // S1 (or inside it, for closed surfaces whose normals point out).
  if (!o.allow_negative && result.measures.domain > 0.0 && result.measures.covered_domain == 0.0)
    std::cerr << "hint: no part of S1 was mapped: no ray along S1's directions (its averaged normals unless "
                 "--directions is given) meets S2 in front of S1; if S2 lies behind S1, try --allow-negative\n";

  const auto& r = result.report;
  // Where S2 crosses itself (overlapping bodies in one file), the nearest hit jumps from one sheet
  // to the other, and the faces beside the crossing map into no one S2 element. Looked for only
  // when such faces cost more than 1 % of S1: the test takes about a quarter of a projection's
  // time (0.26 s on the armadillo pair, whose unmapped faces are 0.1 % of S1 and S2 does not
  // cross itself).
  std::optional<std::size_t> s2_crossings;
  if (d == 2 && r.left_out.unmapped > 0.01 * result.measures.domain) {
    s2_crossings = self_intersections(*s2, o.threads).size();
    if (*s2_crossings > 0)
      std::cerr << "note: S2 crosses itself: " << *s2_crossings << " pairs of its elements meet without sharing a "
                << "vertex (overlapping bodies, or a sheet folded through another); the map leaves out the faces "
                << "beside such crossings, where the nearest hit jumps between sheets (`plmap check MAP "
                << "--against-rays N` reports that area as target_crosses_itself)\n";
  }
  Json j;
  j["map"] = o.output;
  j.update(projection_report_json(result, o.max_listed));
  if (s2_crossings) j["target_self_intersecting_pairs"] = *s2_crossings;
  j["solver"] = o.solver;
  j["threads"] = resolved_threads(o.threads);
  print_result(j, o.json);
  release_at_exit(std::move(result));
  return exit_code::success;
}

int run_project(const ProjectCommand& o) {
  // the names are checked before the inputs are read: a misspelt option should not cost a minute
  // of reading two large surfaces first
  solver_kind_from_string(o.solver);
  normal_check_named(o.normal_check);
  renumbering_from(o.renumber);
  check_output_file(o.output, OutputKind::map,
                    {{"S1", o.s1}, {"S2", o.s2}, {"--directions", o.directions_file}});
  auto [a, b] = read_surface_pair(o.s1, o.s2, o.dimension, o.threads);
  if (a.index() != b.index())
    throw Error(fmt::format("{} is a {}-dimensional surface but {} is {}-dimensional", o.s1,
                            a.index() + 1, o.s2, b.index() + 1));
  if (a.index() == 0)
    return run<1>(o, std::move(std::get<0>(a)), std::move(std::get<0>(b)));
  return run<2>(o, std::move(std::get<1>(a)), std::move(std::get<1>(b)));
}

}  // namespace

void register_project(CLI::App& app, Action& action) {
  auto o = std::make_shared<ProjectCommand>();
  CLI::App* cmd = app.add_subcommand(
      "project",
      "Build the map from S1 onto S2 by normal projection along a direction field on S1 "
      "(default: averaged vertex normals). S2 edges that leave S1 are inserted up to S1's "
      "boundary; edges that cannot be inserted are listed with the reason.");
  cmd->add_option("S1", o->s1, "Domain surface (the map is stored on it)")->required();
  cmd->add_option("S2", o->s2, "Target surface")->required();
  cmd->add_option("-o,--output", o->output, "Map file to write: .plmapb binary (large maps) or .plmap text; replaced atomically")->required();
  cmd->add_option("--directions", o->directions_file,
                  "Text file with one projection direction per S1 vertex (d+1 numbers a line)");
  cmd->add_option("--solver", o->solver, "Solver of the projection equations: newton or ceres")
      ->capture_default_str();
  add_threads_option(*cmd, o->threads, "Worker threads; the result does not depend on it");
  cmd->add_option("--max-distance", o->max_distance, "Largest projection distance |mu|")
      ->check(positive_number);
  cmd->add_flag("--relative-distance", o->relative_distance,
                "--max-distance is a multiple of S1's bounding-box diagonal");
  cmd->add_flag("--no-rim", o->no_rim,
                "Where S2 passes behind S1 or beyond --max-distance, end D at the last S1 edge a walk crosses "
                "instead of on the curve where the distance reaches that bound (the behaviour before rim nodes)");
  cmd->add_flag("--no-fold-rim", o->no_fold_rim,
                "Where a walk stops at a fold, end its piece at the last S1 edge it crosses and start the piece "
                "beyond the fold at its first, instead of joining both sheets on one curve (the behaviour before "
                "2026-12-07)");
  cmd->add_flag("--allow-negative", o->allow_negative,
                "Also accept images behind S1 (penetrating contact), down to -max-distance");
  cmd->add_option("--normal-check", o->normal_check,
                  "Accept images by S2's normal: none, facing (contact pairs) or aligned")
      ->capture_default_str();
  cmd->add_option("--renumber", o->renumber,
                  "Work on copies renumbered in spatial order: auto (S2, when its consecutive elements lie far "
                  "apart, as in most meshes written by other tools), always (S1 and S2), target (S2) or never. "
                  "The map is in the input's numbering either way")
      ->capture_default_str();
  cmd->add_option("--max-listed", o->max_listed, "Edges not inserted listed in the output")
      ->capture_default_str();
  add_dimension_option(*cmd, o->dimension);
  add_progress_options(*cmd, o->progress);
  cmd->add_flag("--json", o->json, "Print the summary as JSON");
  cmd->callback([o, &action] { action = [o] { return run_project(*o); }; });
}

}  // namespace plmap::cli
