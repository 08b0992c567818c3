#include <plmap/experiment/schema.hpp>

#include <plmap/strategies/point_locator_registry.hpp>
#include <plmap/strategies/simplification/simplification_registry.hpp>
#include <plmap/strategies/smoothing/smoothing_weights_registry.hpp>

#include <algorithm>
#include <cstdlib>
#include <stdexcept>

namespace plmap::experiment {

namespace {

/// Small builders so that each schema below reads as a table.
ParameterSpec integer(std::string name, std::int64_t def, double min, double max, std::string doc) {
  ParameterSpec s;
  s.name = std::move(name), s.type = ParameterType::integer, s.default_value = def;
  s.min = min, s.max = max, s.doc = std::move(doc);
  return s;
}
ParameterSpec real(std::string name, double def, double min, double max, std::string doc) {
  ParameterSpec s;
  s.name = std::move(name), s.type = ParameterType::real, s.default_value = def;
  s.min = min, s.max = max, s.doc = std::move(doc);
  return s;
}
ParameterSpec boolean(std::string name, bool def, std::string doc) {
  ParameterSpec s;
  s.name = std::move(name), s.type = ParameterType::boolean, s.default_value = def;
  s.doc = std::move(doc);
  return s;
}
ParameterSpec text(std::string name, std::string def, std::string doc) {
  ParameterSpec s;
  s.name = std::move(name), s.type = ParameterType::text, s.default_value = std::move(def), s.doc = std::move(doc);
  return s;
}
ParameterSpec required_text(std::string name, std::string doc) {
  ParameterSpec s;
  s.name = std::move(name), s.type = ParameterType::text, s.doc = std::move(doc);
  return s;
}
/// "default" and every locator name of the registry (d = 2, then the d = 1 ones not yet listed),
/// so a new strategy is accepted by configs as soon as it is registered.
std::vector<std::string> locator_choices() {
  std::vector<std::string> names{"default"};
  for (const auto name : point_locator_names<2>()) names.emplace_back(name);
  for (const auto name : point_locator_names<1>())
    if (std::find(names.begin(), names.end(), name) == names.end()) names.emplace_back(name);
  return names;
}

ParameterSpec choice(std::string name, std::optional<std::string> def, std::vector<std::string> choices,
                     std::string noun, std::string doc) {
  ParameterSpec s;
  s.name = std::move(name), s.type = ParameterType::choice;
  if (def) s.default_value = *def;
  s.choices = std::move(choices), s.choice_noun = std::move(noun), s.doc = std::move(doc);
  return s;
}
ParameterSpec seed(std::string doc) {
  ParameterSpec s;
  s.name = "seed", s.type = ParameterType::integer, s.inherits_seed = true;
  s.min = 0, s.max = 9.0e15, s.doc = std::move(doc);
  return s;
}
ParameterSpec only_for(ParameterSpec s, std::string key, std::vector<std::string> values) {
  s.only_when = std::move(key), s.only_when_values = std::move(values);
  return s;
}

constexpr double unbounded = 1e300;

std::vector<std::string> names_of(std::span<const std::string_view> names) {
  return {names.begin(), names.end()};
}

const std::vector<std::string> kInputKinds = {"file",          "cgal",           "grid",
                                              "delaunay",      "bumpy-grid",     "open-polyline",
                                              "closed-polyline", "star-polyline", "contact-pair",
                                              "contact-circles"};

std::vector<std::string> make_step_kinds() {
  std::vector<std::string> kinds = {"build"};
  if (projection_available()) kinds.push_back("project");
  kinds.push_back("evaluate");
  kinds.push_back("check");
  if (peer_benchmark_available()) kinds.push_back("peer_project");
  if (projection_available()) {
    kinds.push_back("simplify");
    kinds.push_back("smooth");
    kinds.push_back("refine");
  }
  if (simplification_benchmark_available()) kinds.push_back("peer_simplify");
  return kinds;
}

ParameterSpec height() {
  return real("height", 0.0, 0.0, unbounded,
              "amplitude of the height field z = height sin(3x) cos(2y) (0: planar)");
}
ParameterSpec z_offset() { return real("z_offset", 0.0, -unbounded, unbounded, "added to every z"); }

}  // namespace

bool projection_available() {
#ifdef PLMAP_EXPERIMENT_HAS_CONSTRUCT
  return true;
#else
  return false;
#endif
}

bool peer_benchmark_available() {
#ifdef PLMAP_EXPERIMENT_PEER_BENCH
  return true;
#else
  return false;
#endif
}

std::string peer_benchmark_program() {
  if (const char* env = std::getenv("PLMAP_PEER_BENCH"); env && *env) return env;
#ifdef PLMAP_EXPERIMENT_PEER_BENCH
  return PLMAP_EXPERIMENT_PEER_BENCH;
#else
  return {};
#endif
}

bool simplification_benchmark_available() {
#ifdef PLMAP_EXPERIMENT_SIMPLIFICATION_BENCH
  return true;
#else
  return false;
#endif
}

std::string simplification_benchmark_program() {
  if (const char* env = std::getenv("PLMAP_SIMPLIFICATION_BENCH"); env && *env) return env;
#ifdef PLMAP_EXPERIMENT_SIMPLIFICATION_BENCH
  return PLMAP_EXPERIMENT_SIMPLIFICATION_BENCH;
#else
  return {};
#endif
}

bool is_contact_input_kind(const std::string& kind) { return kind == "contact-pair" || kind == "contact-circles"; }

std::span<const std::string> input_kinds() { return kInputKinds; }

std::span<const std::string> step_kinds() {
  static const std::vector<std::string> kinds = make_step_kinds();
  return kinds;
}

const std::vector<ParameterSpec>& input_schema(const std::string& kind) {
  static const std::vector<ParameterSpec> file = {
      required_text("path", "surface file (.off .obj .stl .ply .msh .curve), relative to the config"),
      integer("dimension", 0, 0, 2, "1 (curve) or 2 (triangle surface); 0: .curve is 1, else 2")};
  static const std::vector<ParameterSpec> cgal = {
      required_text("mesh", "name of a mesh in libcgal-demo's data/meshes, e.g. \"femur\""),
      integer("simplify_to", 0, 0, unbounded,
              "if > 0, simplify by CGAL edge collapse to about this many triangles")};
  static const std::vector<ParameterSpec> grid = {
      integer("cells", 8, 1, 4096, "cells per side of the unit square (a multiple of 4 with hole)"),
      real("jitter", 0.0, 0.0, 0.2, "vertex jitter as a fraction of the cell size"),
      boolean("hole", false, "cut the hole [0.25,0.5] x [0.5,0.75]"), height(), z_offset(),
      seed("random diagonals and jitter")};
  static const std::vector<ParameterSpec> delaunay = {
      integer("interior_points", 50, 0, 1e7, "random points inside the square"),
      integer("boundary_points", 8, 0, 1e6, "random points on the boundary"),
      integer("grid_points", 0, 0, 1e6, "points from the dyadic grid of spacing 1/8"),
      boolean("hole", false, "cut the hole [0.25,0.5] x [0.5,0.75]"), height(), z_offset(),
      seed("the random points")};
  static const std::vector<ParameterSpec> bumpy = {
      integer("cells", 8, 1, 4096, "an n x n grid of squares, two triangles each, on a gentle height field")};
  static const std::vector<ParameterSpec> open_polyline = {
      integer("segments", 16, 1, 1e7, "segments of an x-monotone polyline from x = 0 to 1"),
      seed("the vertices")};
  static const std::vector<ParameterSpec> closed_polyline = {
      integer("segments", 16, 3, 1e7, "segments of a closed star-shaped polygon"), seed("the vertices")};
  static const std::vector<ParameterSpec> star_polyline = {
      integer("arms", 3, 3, 1e5, "polylines leaving a common (non-manifold) centre"),
      integer("segments_per_arm", 4, 1, 1e6, "segments per arm"), seed("the vertices")};
  // The input pairs of experiments/peers (S1 here; its partner S2 is generated by the
  // peer_project step's benchmark from the same parameters).
  static const std::vector<ParameterSpec> contact_pair = {
      choice("case", "plane", {"plane", "sphere", "femur", "femur-offset"}, "contact pair",
             "plane: facing jittered patches, overlap 0.72; sphere: icosphere levels L and 2^L + 1, "
             "radius 1 and 1.01; femur: a CGAL mesh (`mesh`) against an offset remeshed copy; femur-offset: "
             "against an offset copy (same triangulation)"),
      only_for(text("mesh", "femur",
                    "the mesh of libcgal-demo's data/meshes the femur cases pair with its offset copy "
                    "(e.g. \"bones\", \"armadillo\")"),
               "case", {"femur", "femur-offset"}),
      integer("size", 2000, 1, 1e8, "plane: S1 triangles; sphere: icosphere level (20 * 4^L triangles); femur: ignored"),
      seed("jitter, diagonals, rotation and offsets")};
  static const std::vector<ParameterSpec> contact_circles = {
      integer("segments", 1000, 3, 1e8, "segments of S1 (radius 1); S2 has 1.3 times as many (radius 1.01)"),
      seed("the rotation of S2")};
  if (kind == "file") return file;
  if (kind == "contact-pair") return contact_pair;
  if (kind == "contact-circles") return contact_circles;
  if (kind == "cgal") return cgal;
  if (kind == "grid") return grid;
  if (kind == "delaunay") return delaunay;
  if (kind == "bumpy-grid") return bumpy;
  if (kind == "open-polyline") return open_polyline;
  if (kind == "closed-polyline") return closed_polyline;
  if (kind == "star-polyline") return star_polyline;
  throw std::out_of_range("no input kind " + kind);
}

int input_kind_dimension(const std::string& kind) {
  if (kind == "file") return 0;
  if (kind.ends_with("polyline") || kind == "contact-circles") return 1;
  return 2;
}

const std::vector<ParameterSpec>& step_schema(const std::string& kind) {
  static const std::vector<std::string> randomized = {"subdivision", "refinement", "overlay"};
  static const std::vector<ParameterSpec> build = {
      choice("map", std::nullopt, {"identity", "subdivision", "refinement", "overlay"}, "map kind",
             "identity: S2 = S1; subdivision: every element cut into k x k (d = 1: k) pieces; "
             "refinement: random points on edges and inside elements; overlay: a second, "
             "independent triangulation of the same planar domain (d = 1: subdivision of the "
             "same polyline)"),
      only_for(integer("k", 4, 1, 1000, "subdivisions per element side"), "map", {"subdivision"}),
      only_for(real("jitter", 0.2, 0.0, 0.2, "interior subdivision points move by up to jitter / k"),
               "map", {"subdivision"}),
      only_for(integer("max_points_per_edge", 2, 0, 64, "random points per S1 edge: 0..max"), "map",
               {"refinement"}),
      only_for(integer("max_points_per_element", 3, 0, 256, "random points per S1 element: 0..max"),
               "map", {"refinement"}),
      only_for(integer("overlay_cells", 8, 1, 4096,
                       "d = 2: cells per side of the second triangulation (a grid); d = 1: most "
                       "split points per segment"),
               "map", {"overlay"}),
      only_for(real("overlay_jitter", 0.1, 0.0, 0.2, "d = 2: jitter of the second triangulation"), "map",
               {"overlay"}),
      only_for(seed("random choices of the map"), "map", randomized)};
  static const std::vector<ParameterSpec> project = {
      required_text("target", "name of the input that is S2 (give it run = false)"),
      choice("solver", "newton", {"newton", "ceres"}, "projection solver", "solver of eq. (3) and (4)"),
      real("max_distance", 0.0, 0.0, unbounded, "largest projection distance; 0: no limit"),
      boolean("relative_distance", true, "max_distance is a multiple of S1's bounding-box diagonal"),
      boolean("allow_negative_distance", false, "accept images behind S1"),
      choice("normal_check", "none", {"none", "facing", "aligned"}, "normal check",
             "which target orientations are accepted"),
      choice("renumbering", "auto", {"auto", "always", "target", "never"}, "renumbering",
             "copies in spatial order: auto (S2 when its order is poor), always, target (S2), never"),
      integer("threads", 1, 0, 1024, "worker threads; 0: all hardware threads")};
  static const std::vector<ParameterSpec> evaluate = {
      choice("locator", "default", locator_choices(),
             "point locator",
             "point-location strategy, any registered name; default: the registry's default for the dimension"),
      integer("queries", 100000, 1, 1e9, "random query points, uniform over elements"),
      integer("threads", 1, 0, 1024, "evaluation threads; 0: all hardware threads"),
      seed("the query points")};
  static const std::vector<ParameterSpec> check = {
      boolean("parametrization", false, "also require that the map covers all of S1 and S2"),
      real("max_condition", 0.0, 0.0, unbounded, "regions with kappa above this are violations; 0: none")};
  static const std::vector<ParameterSpec> peer_project = {
      choice("tool", std::nullopt, {"plmap", "contactmerge", "psurface"}, "projection tool",
             "plmap::project, dune-grid-glue's ContactMerge or PSurface 2.0's ContactMapping, run by "
             "experiments/peers' benchmark in a child process on the input's contact pair"),
      integer("threads", 1, 0, 1024, "plmap's threads (0: all hardware threads); the peers are single-threaded"),
      real("timeout_seconds", 1800, 1, 1e6, "a child still running after this long is killed; the run records why"),
      integer("psurface_max_elements", 25000, 0, 1e9,
              "PSurface tests all pairs of elements (hours beyond ~20k): larger S1 are skipped and recorded as such"),
      choice("order", "as-generated", {"as-generated", "spatial"}, "input order",
             "numbering of the pair the tool gets: as generated, or both surfaces renumbered along a Morton "
             "curve (same geometry; shows how much a tool depends on the order of its input)")};
  static const std::vector<ParameterSpec> simplify = {
      integer("target_elements", 0, 0, 1e9, "stop at this many triangles (0: no element target)"),
      real("max_error", 0.0, 0.0, unbounded,
           "refuse steps whose modified Hausdorff distance exceeds this multiple of the mesh's bounding-box "
           "diagonal (0: no bound)"),
      text("oracles", "hausdorff:1,aspect-ratio:0.05,normal-deviation:0.5",
           "error oracles NAME[:WEIGHT], comma-separated (a weighted combination)"),
      real("feature_angle", 60.0, 0.0, 180.0, "edges with a larger dihedral angle (degrees) are feature lines"),
      choice("flattening", "polar-map", names_of(star_flattening_names()), "star flattening", "flattening of a star"),
      choice("hole_triangulation", "constrained-delaunay", names_of(hole_triangulation_names()), "hole triangulation",
             "re-triangulation of the hole"),
      choice("ranking", "exact", {"exact", "estimate"}, "ranking",
             "how removal candidates are queued: by their ranking plan, or by a Hausdorff estimate corrected when "
             "they come up"),
      choice("cut", "per-step", {"per-step", "deferred"}, "cut",
             "when the fine edges are cut along the coarse edges: at every step, or traced once at the end")};
  static const std::vector<ParameterSpec> smooth = {
      integer("sweeps", 1, 1, 1000, "passes over all elements"),
      choice("weights", "floater", names_of(smoothing_weights_names()), "smoothing weights",
             "convex-combination weights"),
      boolean("quadrilaterals", true,
              "also smooth over the quadrilateral of every pair of S1 triangles sharing an edge (false: inside each "
              "element only)")};
  static const std::vector<ParameterSpec> refine = {
      integer("levels", 2, 0, 8, "uniform refinement levels of S1 (each splits every triangle into four)")};
  static const std::vector<ParameterSpec> peer_simplify = {
      choice("tool", std::nullopt, {"plmap", "psurface", "cgal"}, "simplification tool",
             "plmap (simplify + smooth), PSurface 2.0 (point removal + edge relaxation) or CGAL's edge collapse "
             "(the floor, no map), run by experiments/peers' bench_simplification_peers in a child process"),
      integer("target_elements", 500, 1, 1e9, "triangles to simplify to"),
      text("oracles", "hausdorff:1,aspect-ratio:1", "plmap's error oracles NAME[:WEIGHT], comma-separated"),
      choice("ranking", "exact", {"exact", "estimate"}, "ranking", "plmap's queueing of removal candidates"),
      choice("cut", "per-step", {"per-step", "deferred"}, "cut", "plmap's cut of the fine edges: per step or deferred"),
      real("feature_angle", 180.0, 0.0, 180.0,
           "plmap's feature-line angle (180: no sharp features, as PSurface sees an unmarked mesh)"),
      real("psurface_aspect_ratio", 0.5, 0.0, unbounded, "PSurface's QualityRequest aspect-ratio weight"),
      real("psurface_hausdorff", 0.5, 0.0, unbounded, "PSurface's QualityRequest Hausdorff weight"),
      integer("sweeps", 1, 0, 1000, "smoothing sweeps (0: none)"),
      choice("weights", "floater", names_of(smoothing_weights_names()), "smoothing weights", "plmap's smoothing weights"),
      boolean("quadrilaterals", true,
              "plmap's smoothing also over edge quadrilaterals (false: inside each element only)"),
      integer("refine_levels", 2, 0, 6, "refinement levels for the refined surface's quality (0: skip)"),
      real("timeout_seconds", 1800, 1, 1e6, "a child still running after this long is killed; the run records why")};
  if (kind == "build") return build;
  if (kind == "project") return project;
  if (kind == "evaluate") return evaluate;
  if (kind == "check") return check;
  if (kind == "peer_project") return peer_project;
  if (kind == "simplify") return simplify;
  if (kind == "smooth") return smooth;
  if (kind == "refine") return refine;
  if (kind == "peer_simplify") return peer_simplify;
  throw std::out_of_range("no step kind " + kind);
}

const std::vector<MetricSpec>& input_metrics() {
  static const std::vector<MetricSpec> m = {{"dimension", false, "1 or 2"},
                                            {"vertices", false, "vertices of S1"},
                                            {"elements", false, "elements of S1"}};
  return m;
}

const std::vector<MetricSpec>& step_metrics(const std::string& kind) {
  static const std::vector<MetricSpec> build = {
      {"nodes", false, "graph nodes of the map"},
      {"regions", false, "regions (overlaps) of the map"},
      {"regions_per_element", false, "regions / S1 elements"},
      {"target_vertices", false, "vertices of S2"},
      {"target_elements", false, "elements of S2"},
      {"memory_bytes", false, "bytes of the compact form"},
      {"seconds", true, "wall time to build the map"}};
  static const std::vector<MetricSpec> project = {
      {"nodes", false, "graph nodes of the map"},
      {"regions", false, "regions of the map"},
      {"target_elements", false, "elements of S2"},
      {"vertex_preimages", false, "S2 vertices with a preimage"},
      {"edges_inserted", false, "S2 edges inserted completely"},
      {"edges_partly_inserted", false, "S2 edges inserted in pieces"},
      {"edges_not_inserted", false, "S2 edges reported as not inserted"},
      {"renumbered_domain", false, "whether S1 was renumbered in spatial order"},
      {"renumbered_target", false, "whether S2 was renumbered in spatial order"},
      {"covered_fraction", false, "measure of D / measure of S1"},
      {"solver_calls", false, "solver calls (eq. 3 and 4)"},
      {"solver_failures", false, "solver calls that did not converge"},
      {"seconds", true, "wall time of the projection"}};
  static const std::vector<MetricSpec> evaluate = {
      {"in_domain", false, "queries inside D"},
      {"checksum", false, "sum of the image coordinates (a fingerprint of the results)"},
      {"seconds", true, "wall time for all queries"},
      {"ns_per_eval", true, "wall nanoseconds per query"},
      {"evals_per_second", true, "queries per wall second"}};
  static const std::vector<MetricSpec> check = {
      {"ok", false, "no violation"},
      {"violations", false, "number of violations"},
      {"kappa_max", false, "largest condition number of a region"},
      {"kappa_mean", false, "mean condition number"},
      {"seconds", true, "wall time of verify()"}};
  static const std::vector<MetricSpec> peer_project = {
      {"ok", false, "the tool produced its overlaps (false: see error)"},
      {"error", false, "why not: the tool's exception, a time-out or a skip (empty if ok)"},
      {"target_elements", false, "elements of S2"},
      {"label", false, "the benchmark's name of the pair (\"(spatial order)\" appended when renumbered)"},
      {"pieces", false, "regions (plmap) or overlap simplices / primitives (peers)"},
      {"covered_error", false, "(covered - exact) / exact overlap on S1"},
      {"covered_target_error", false, "(covered - exact) / exact overlap on S2"},
      {"peak_mib", true, "peak resident memory during the projection above what the inputs hold (MiB)"},
      {"seconds", true, "wall time of the projection alone"}};
  static const std::vector<MetricSpec> simplify = {
      {"elements", false, "triangles of S1 after simplification"},
      {"vertices", false, "vertices of S1"},
      {"nodes", false, "graph nodes of the map"},
      {"regions", false, "regions of the map"},
      {"hausdorff", false, "modified Hausdorff distance / S2's bounding-box diagonal"},
      {"kappa_max", false, "largest condition number of a region"},
      {"kappa_mean", false, "mean condition number"},
      {"kappa_p99", false, "99th percentile of the condition number"},
      {"coarse_aspect_mean", false, "mean aspect ratio of S1's triangles"},
      {"coarse_aspect_p90", false, "90th percentile of S1's aspect ratio"},
      {"coarse_aspect_max", false, "largest aspect ratio of S1"},
      {"target_reached", false, "the element target was reached"},
      {"seconds", true, "wall time of the simplification"},
      {"peak_mib", true, "peak resident memory of the step above the process's before it (MiB; Linux)"}};
  static const std::vector<MetricSpec> smooth = {
      {"kappa_max_before", false, "largest kappa before smoothing"},
      {"kappa_mean_before", false, "mean kappa before"},
      {"kappa_p99_before", false, "99th percentile of kappa before"},
      {"kappa_max", false, "largest kappa after smoothing"},
      {"kappa_mean", false, "mean kappa after"},
      {"kappa_p99", false, "99th percentile of kappa after"},
      {"hausdorff", false, "modified Hausdorff distance after smoothing / S2's bounding-box diagonal"},
      {"nodes_moved", false, "free nodes moved (last sweep)"},
      {"quadrilaterals_smoothed", false, "quadrilateral steps kept, over all sweeps (0 without quadrilaterals)"},
      {"seconds", true, "wall time of the smoothing"},
      {"peak_mib", true, "peak resident memory of the step above the process's before it (MiB; Linux)"}};
  static const std::vector<MetricSpec> refine = {
      {"elements", false, "triangles of the refined surface"},
      {"distance_max", false, "largest distance to S2 / S2's bounding-box diagonal"},
      {"distance_mean", false, "mean distance to S2 (surface units)"},
      {"coarse_aspect_mean", false, "mean aspect ratio of S1"},
      {"coarse_aspect_p90", false, "90th percentile of S1's aspect ratio"},
      {"coarse_aspect_max", false, "largest aspect ratio of S1"},
      {"refined_aspect_mean", false, "mean aspect ratio of the refined surface"},
      {"refined_aspect_p90", false, "90th percentile of the refined surface's aspect ratio"},
      {"refined_aspect_max", false, "largest aspect ratio of the refined surface"},
      {"seconds", true, "wall time of the refinement"},
      {"peak_mib", true, "peak resident memory of the step above the process's before it (MiB; Linux)"}};
  static const std::vector<MetricSpec> peer_simplify = {
      {"ok", false, "the tool produced its coarse surface (false: see error)"},
      {"error", false, "why not: the tool's exception, a time-out (empty if ok)"},
      {"elements", false, "triangles of the coarse surface"},
      {"hausdorff_before_smoothing", false, "largest node-to-image distance / bounding-box diagonal, before smoothing"},
      {"hausdorff", false, "the same after smoothing (the maps' tools only)"},
      {"quadrilaterals_smoothed", false, "plmap's quadrilateral steps kept in the smoothing (null for the peers)"},
      {"kappa_max_before", false, "largest kappa before smoothing"},
      {"kappa_mean_before", false, "mean kappa before smoothing"},
      {"kappa_p99_before", false, "99th percentile of kappa before smoothing"},
      {"kappa_max", false, "largest kappa after smoothing"},
      {"kappa_mean", false, "mean kappa after smoothing"},
      {"kappa_p99", false, "99th percentile of kappa after smoothing"},
      {"coarse_aspect_mean", false, "mean aspect ratio of the coarse surface"},
      {"coarse_aspect_p90", false, "90th percentile"},
      {"coarse_aspect_max", false, "largest"},
      {"refined_aspect_mean", false, "mean aspect ratio of the coarse surface refined through the map"},
      {"refined_aspect_p90", false, "90th percentile"},
      {"refined_aspect_max", false, "largest"},
      {"seconds", true, "wall time of simplification and smoothing"},
      {"seconds_simplify", true, "wall time of the simplification"},
      {"seconds_smooth", true, "wall time of the smoothing"},
      {"cpu_seconds", true, "CPU time of simplification and smoothing (the fair figure on a loaded machine)"},
      {"cpu_seconds_simplify", true, "CPU time of the simplification"},
      {"cpu_seconds_smooth", true, "CPU time of the smoothing"},
      {"peak_mib", true, "peak resident memory above the input during both (MiB)"}};
  if (kind == "build") return build;
  if (kind == "project") return project;
  if (kind == "evaluate") return evaluate;
  if (kind == "check") return check;
  if (kind == "peer_project") return peer_project;
  if (kind == "simplify") return simplify;
  if (kind == "smooth") return smooth;
  if (kind == "refine") return refine;
  if (kind == "peer_simplify") return peer_simplify;
  throw std::out_of_range("no step kind " + kind);
}

}  // namespace plmap::experiment
