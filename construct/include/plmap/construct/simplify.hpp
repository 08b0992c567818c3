#pragma once
/// \file
/// Parametrization by surface simplification (paper 3.3.1): from a fine surface S2, build a
/// coarse S1 and the map Ξ: S1 → S2, a parametrization (every S2 vertex has exactly one
/// preimage, the regions' images tile S2).
///
/// Start with S1 = S2 and Ξ = identity; remove S1 vertices one at a time, cheapest first by the
/// error oracles; each step flattens the star (strategy), re-triangulates the hole (strategy),
/// merges and cuts the star's graphs (EditableMap) and is refused if Ξ would become invalid.
/// After every step Ξ is valid. Feature edges (boundary, non-manifold, sharp) form feature
/// lines: a vertex on a line (two feature edges) is removed only along it, feature corners
/// never, so the feature lines of S2 stay chains of S1 edges.
///
///   SimplifyOptions options;
///   options.target_elements = 500;
///   options.oracles.add("hausdorff", 1.0).add("aspect-ratio", 0.05);
///   SimplifyResult result = simplify(fine, options);   // result.map: PlMap<2>, S1 → S2

#include <plmap/core/editable_map.hpp>
#include <plmap/core/map_builder.hpp>
#include <plmap/core/pl_map.hpp>
#include <plmap/core/progress.hpp>
#include <plmap/strategies/simplification/weighted_oracles.hpp>

#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <string>

namespace plmap {

struct SimplifyOptions {
  /// Stop once S1 has at most this many triangles (0: no element target).
  Index target_elements = 0;
  /// Stop once S1 has at most this many vertices (0: no vertex target).
  Index target_vertices = 0;
  /// Refuse every step whose modified Hausdorff distance (largest distance between a node of
  /// the star on S1 and its image on S2) exceeds this, in the surface's units (infinity: no
  /// bound). With no target, simplification runs until no step is admissible.
  double max_error = std::numeric_limits<double>::infinity();
  /// Edges whose dihedral angle (between the two triangle normals) exceeds this, in degrees,
  /// are feature edges, like boundary and non-manifold edges. 180 turns sharp features off.
  /// A feature line that turns by more than this at a vertex has a corner there.
  double feature_angle_degrees = 60.0;
  /// Flattening of the star: "polar-map" (paper) or "plane-projection".
  std::string flattening = "polar-map";
  /// Re-triangulation of the hole: "constrained-delaunay" (paper) or "min-max-aspect".
  std::string hole_triangulation = "constrained-delaunay";
  /// How removal candidates are queued. "exact": by the oracles' cost of a ranking plan
  /// (flattening, hole triangulation, relocated preimages: PlanExtent::ranking_bound), a lower
  /// bound of the full cost, so the removal order is that of ranking every candidate fully.
  /// "estimate": by an estimate that needs no flattening: the Hausdorff oracles' weight times
  /// max(the star's carried node distance, the height of the vertex over its ring's plane), plus
  /// the aspect-ratio oracles' weight times a lower bound of their cost from the star's and the
  /// ring's triangles (other oracles count 0). When such a vertex comes up it gets its ranking
  /// plan; if that cost is above the next queued cost it goes back with it, otherwise it is
  /// planned fully and removed if its full cost is not above the next queued cost (else it goes
  /// back with its full cost). Ranking plans are then made only for candidates that come up,
  /// not for every ring vertex of every removal (3.6-4.8 times fewer on CGAL's meshes); the
  /// order differs from the exact one where the estimate is too high (8-11 % larger Hausdorff
  /// error there).
  std::string ranking = "exact";
  /// When S2's edges are cut along S1's new edges. "per-step": every step cuts the star's S2
  /// edge polylines along its new triangles and refuses the step if they would cross (the
  /// paper's method; every intermediate map is valid). "deferred": the steps only relocate the
  /// S2 vertex preimages; at the end every S2 edge is traced once as a straight segment through
  /// the final S1 and the traced graph is checked (EditOptions::defer_cut). If that check fails,
  /// or the run stopped above its target (the deferred cut refuses steps that would turn an S2
  /// triangle's straight preimage over), the whole run is redone with the per-step cut
  /// (SimplifyReport::cut_fell_back); the oracles known by name start afresh for it, a custom
  /// oracle is handed over as it is (its state must allow a second run). Surfaces only: a curve's
  /// segments have no crossings to cut.
  std::string cut = "per-step";
  /// When nothing is left to remove above the target, the vertices refused because a new
  /// triangle of their hole folded over (fold_over) are tried once more, each with the hole
  /// triangulated again without the folded triangle's diagonals. Surfaces only; false: the run
  /// stops there (as before 2026-12-05).
  bool retry_folded_removals = true;
  /// The error oracles; empty: hausdorff:1, aspect-ratio:0.05, normal-deviation:0.5.
  WeightedOracles oracles;
  EditOptions edit;
  BuilderOptions builder;
  /// Optional. Phase "removing vertices", called every `progress_every` removals and at the
  /// end: counts the triangles removed towards target_elements, else the vertices removed
  /// towards target_vertices, else the vertices removed (total 0: unknown, the error bound
  /// decides). Then phase "finalize" at its start and end. A callback that throws cancels.
  ProgressCallback progress;
  Index progress_every = 100;
};

struct SimplifyReport {
  Index elements_before = 0, elements_after = 0;
  Index vertices_before = 0, vertices_after = 0;
  Index removed_vertices = 0;
  Index removed_along_lines = 0;  ///< of these, vertices removed along a feature line
  Index feature_edges = 0;
  Index feature_vertices = 0;  ///< S2 vertices on feature edges (line vertices and corners)
  /// Feature vertices never removed: on one or more than two feature edges, or where their
  /// line turns by more than the feature angle.
  Index feature_corners = 0;
  /// Largest distance between a node of the final map on S1 and its image on S2 (the modified
  /// Hausdorff distance of the whole map), and that divided by S2's bounding-box diagonal.
  double hausdorff_error = 0.0;
  double hausdorff_error_relative = 0.0;
  /// Live vertices other than feature corners that could not be removed when the run stopped, by the reason
  /// of the last attempt (a RemovalRefusal name, "oracle_veto", "max_error", "flattened_preimage",
  /// or "feature_loop_of_three": a closed feature line down to three vertices keeps them).
  std::map<std::string, Index> skipped_by_reason;
  Index skipped_vertices = 0;
  /// True if the element or vertex target was reached.
  bool target_reached = false;
  std::string oracles, flattening, hole_triangulation, ranking, cut;
  /// With the deferred cut: true if its traced graph failed the check and the run was redone
  /// with the per-step cut (the result is the per-step run's), and why it failed.
  bool cut_fell_back = false;
  std::string cut_failure;
  /// Full plans made when candidates came up, and of these, how many went back into the queue
  /// with their full cost because it was above the queued one.
  Index full_plans = 0, requeued = 0;
  /// Ranking plans made (with the estimate ranking: only for candidates that came up).
  Index ranking_plans = 0;
  double seconds_total = 0.0, seconds_simplify = 0.0, seconds_finalize = 0.0;
};

struct SimplifyResult {
  PlMap<2> map;
  SimplifyReport report;
};

/// Simplifies `fine` and returns S1 (map.domain()) with the parametrization. Throws plmap::Error
/// for options that cannot be met: a target not below the mesh's size, neither target nor error
/// bound, an unknown strategy name.
SimplifyResult simplify(std::shared_ptr<const Surface<2>> fine, SimplifyOptions options = {});

/// The feature edges of a surface by the rules above (boundary, non-manifold, inconsistently
/// oriented neighbours, dihedral angle above the threshold), as a flag per edge.
std::vector<char> feature_edges(const Surface<2>& surface, double feature_angle_degrees);

}  // namespace plmap
