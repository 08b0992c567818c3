#pragma once
/// \file
/// ProjectionOptions: everything normal projection (project.hpp) can be told, with defaults.

#include <plmap/core/progress.hpp>
#include <plmap/core/projection_rules.hpp>

#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace plmap {

/// Which S2 points may be the image of an S1 point (core/projection_rules.hpp: none, facing,
/// aligned), under the name the projection's options have always used.
using TargetNormalCheck = NormalCheck;

/// Whether normal projection works on copies of S1 and S2 renumbered along a space-filling curve
/// (docs/projection.md, "The order of the input"). The map and the report are always in the
/// caller's numbering; only the time, and ties decided by the order in which candidates are met,
/// depend on it.
enum class SpatialRenumbering {
  /// Renumber S2 when its consecutive elements lie far apart (centroids more than about four
  /// element sizes apart, as in CGAL's meshes), and keep surfaces generated in rows or by
  /// subdivision. S1 is kept: its order is the order of the map's per-element arrays, and
  /// gathering them back into the caller's order costs about what S1's order saves.
  automatic,
  always,  ///< renumber both surfaces
  target,  ///< renumber S2 only, whatever its order
  never,   ///< work on the surfaces as given
};

/// The names the command line, the bindings and experiment configs use: "auto", "always",
/// "target", "never".
constexpr std::string_view to_string(SpatialRenumbering r) {
  switch (r) {
    case SpatialRenumbering::automatic: return "auto";
    case SpatialRenumbering::always: return "always";
    case SpatialRenumbering::target: return "target";
    case SpatialRenumbering::never: return "never";
  }
  return "auto";
}

/// The rule of that name, or nothing.
inline std::optional<SpatialRenumbering> spatial_renumbering_from_name(std::string_view name) {
  for (SpatialRenumbering r : {SpatialRenumbering::automatic, SpatialRenumbering::always, SpatialRenumbering::target,
                               SpatialRenumbering::never})
    if (to_string(r) == name) return r;
  return std::nullopt;
}

/// The limits and slacks of the projection's searches (docs/algorithms/normal-projection.md,
/// "Search limits"). The defaults suit every input tried; they are options so that a search
/// that gives up can be widened without a rebuild. Slacks are in local or edge parameters,
/// hence relative to the element size; lengths are derived from the input's scale.
struct ProjectionSearchLimits {
  /// Elements one seeded walk visits (across S1 for a vertex preimage, across S2 for a ray) before
  /// it gives up; the walk moves towards the most negative barycentric coordinate.
  int seed_walk_steps = 48;
  /// Crossings one walk along an S2 edge may make; 0 (default): 2 |T1| + 16, more than any
  /// preimage of one edge can cross.
  int edge_walk_steps = 0;
  /// A solution counts as inside an element if no barycentric coordinate is below
  /// -inside_tolerance (then it is clamped onto the element).
  double inside_tolerance = 1e-9;
  /// How far outside [0, 1] the S1 edge parameter of a crossing (eq. 4) may lie, and by how
  /// much the S2 edge parameter must grow from one crossing to the next.
  double edge_parameter_slack = 1e-9;
  /// Second search for S2 vertices without a preimage: how many of the nearest ray hits seed it,
  /// and how far (times the largest distance between the hits of two corners of an S1 element
  /// around the hit's vertex) a hit may lie from the vertex.
  int second_search_hits = 4;
  double second_search_reach = 1.5;
  /// A ray whose hit, seeded next to the previous vertex's hit, lies farther along it than that
  /// hit by more than this many times the longest S1 edge at its vertex is cast again from the
  /// elements nearest to the vertex, and the nearer admissible hit is kept.
  double farther_hit_retry = 4.0;
  /// A vertex preimage search all of whose walks stopped at a solver failure (the seeds lie on
  /// elements tangential to the directions) is repeated from this many nearest elements (1..32;
  /// not more than search_seeds: no retry).
  int retry_seeds = 32;
  /// The pieces that the walks along one S2 edge find are disjoint intervals of its parameter;
  /// a walk or boundary entry that starts within this much of where an earlier piece ended is a
  /// re-detection of that piece, and a boundary entry this close to either end of the edge is
  /// the end vertex itself, not an entry.
  double piece_parameter_slack = 1e-9;
  /// A crossing whose S2 edge parameter lies within this of 1 is at the image of the edge's
  /// second vertex: the walk has reached it without finding its preimage.
  double end_parameter_slack = 1e-12;
  /// After a walk along an S2 edge stops at a fold, where the edge passes behind S1 or beyond
  /// max_distance, or where it finds no continuation (any walk: from the first vertex or a boundary
  /// entry forwards, from the second vertex or where the edge leaves S1 backwards), the S1 edges
  /// of the elements within fold_exit_reach rings around the stop (ring r + 1: the elements
  /// sharing a vertex with ring r) are searched, ring by ring, for the point where the edge's
  /// preimage comes out of the fold, and a new piece is walked from there; at most fold_exits
  /// such restarts per walk (0: none).
  int fold_exits = 4;
  double fold_exit_reach = 3.0;
  /// d = 2, end_on_rim: rounds of walks from where the rim's tracing crosses S2 edges that no
  /// walk gave a piece (edges that dip into the band of distances with both vertices outside
  /// it), each followed by tracing on from where those walks end (0: none).
  int rim_walk_rounds = 16;
};

struct ProjectionOptions {
  /// Projection directions at the S1 vertices, d+1 numbers per vertex (vertex-major); they are
  /// normalised, so the distance mu along them is a length. Empty (default): averaged vertex
  /// normals of S1 (area-weighted for d = 2, length-weighted for d = 1).
  std::vector<double> directions = {};
  /// "newton" (hand-written damped Newton, default) or "ceres" (ceres::TinySolver).
  std::string solver = "newton";
  /// Solvers stop when the residual is below this times the element diameter.
  double solver_tolerance = 1e-12;
  /// Largest admissible |mu| (distance along the unit direction). Infinite by default.
  double max_distance = std::numeric_limits<double>::infinity();
  /// If true, max_distance is a multiple of the diagonal of S1's bounding box; else a length.
  bool max_distance_is_relative = false;
  /// Accept images behind S1 (mu < 0, down to -max_distance), as for slightly penetrating
  /// bodies in contact. The solution with the smallest |mu| wins. Default: only mu >= 0.
  bool allow_negative_distance = false;
  TargetNormalCheck normal_check = TargetNormalCheck::none;
  /// Worker threads for the vertex preimages, ghost nodes and edge walks; 0 = all cores. The
  /// result does not depend on it.
  unsigned threads = 1;
  /// How many nearest S1 (S2) elements seed the search for a vertex preimage (ray hit).
  int search_seeds = 8;
  /// Passed to MapBuilder: the single snapping rule of plmap (local coordinates).
  double snap_tolerance = 1e-10;
  /// Orientation of the map: 0 = automatic (majority), +1 preserving, -1 reversing.
  int orientation = 0;
  /// Where two sheets of S1 project onto the same part of S2 (the projection is not injective
  /// there: a steep hill whose flanks fan out over the plain around it, two bodies one above
  /// the other), keep the nearer sheet: a face whose image overlaps the image of a nearer face
  /// is left out of D (ProjectionReport::occluded_faces), as a vertex preimage keeps the nearest
  /// solution. With false such maps are returned as they are, and fail verify's coverage check.
  bool keep_nearer_sheet = true;
  /// d = 2: a region whose corners' rays pass a focal point of their element before their images
  /// (the projection folds there) is left out of D. With true (default), one that also has an
  /// unfolded corner is cut along the fold instead and keeps its unfolded part
  /// (ProjectionReport::folded_regions_cut; construct/src/folded_regions.hpp). false leaves every
  /// such region out whole, as plmap did before 2026-12-07 (to compare the two).
  bool cut_folded_regions = true;
  /// d = 2: where S2 leaves the band of admissible distances, D ends on the curve where the
  /// rays' distance to S2 reaches the band's bound, inside the S1 elements it crosses, instead of
  /// at the last S1 edge an S2 edge's preimage crosses before it: mu = 0 where S2 passes behind
  /// S1 (unless negative distances are allowed; there the two surfaces meet), mu = max_distance
  /// (and -max_distance with negative distances) where that is finite. A walk that stops there
  /// ends at a rim node where its S2 edge reaches the bound, and the curve is traced across S1
  /// as rim edges (MapBuilder::add_rim_node, add_rim_edge). false: D ends at the last crossing,
  /// as before.
  bool end_on_rim = true;
  /// d = 2: where a walk stops at a fold and the S2 edge comes out over an unfolded sheet beyond
  /// it, the sheet before the fold and the one beyond meet at one point of the edge that both
  /// reach, and the preimages of the segments joining such points across an S2 triangle are
  /// traced on both sheets as rim edges, so that the faces on both sides close
  /// (construct/src/projection_fold_rim.hpp). false: the piece before the fold ends at its last
  /// crossing and the one beyond starts at its first, as before 2026-12-07.
  bool fold_rim = true;
  /// Told the phase ("rays from S1 vertices", "S2 vertex preimages", "S2 edges", "finalize")
  /// at its start and end, and every 4096 edges in "S2 edges"; called from the calling thread
  /// only. Optional; a callback that throws cancels the projection.
  ProgressCallback progress = {};
  /// Copies in spatial order for inputs in a poor one; see SpatialRenumbering.
  SpatialRenumbering renumbering = SpatialRenumbering::automatic;
  /// Limits and slacks of the searches; see ProjectionSearchLimits.
  ProjectionSearchLimits search_limits = {};
};

/// The acceptance rules these options give (their distance band, normal check and direction
/// field) for surfaces of dimension d: what project<d>() records in the map it returns
/// (PlMap::provenance), and what a ray check of the map applies unless told otherwise.
ProjectionRules projection_rules(const ProjectionOptions& options, int dimension);

}  // namespace plmap
