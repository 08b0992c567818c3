#pragma once
/// \file
/// What normal projection returns: the map, a report of what was built and what was not (with
/// reasons and places), timings per phase, and the covered measures.

#include <plmap/core/pl_map.hpp>

#include <array>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace plmap {

enum class EdgeFailureReason {
  /// The walk across S1 found no continuation inside S1: the projection is not continuous there
  /// (paper Fig. 5 right), e.g. the next S1 element is hidden behind the current one.
  discontinuity,
  /// The solver of eq. (4) did not converge on an S1 edge where the walk had to continue.
  solver_failure,
  /// The continuation lies farther than the distance limit (or behind S1 when negative
  /// distances are not allowed).
  distance_limit,
  /// The walk runs through an S1 vertex that is already the preimage of another S2 vertex.
  vertex_conflict,
  /// An endpoint of the edge has no preimage and the edge does not leave S1 through its
  /// boundary either (e.g. the vertex is beyond the distance limit).
  endpoint_without_preimage,
  /// The walk did not end within the step limit.
  walk_limit,
  /// MapBuilder rejected the preimage (detail holds its message).
  builder_rejected,
  /// The preimage crosses another edge's preimage or runs through a node on S1: the projection
  /// is not injective there (it folds), so the edge was left out of the map.
  overlap,
  /// The continuation lies beyond a focal point of the direction field (neighbouring rays meet
  /// before they reach S2, e.g. under a concave part of S1): the projection is folded there
  /// (solvers/focal_points.hpp).
  fold,
  /// The continuation lies behind a nearer sheet of S2: the ray from the crossing meets another
  /// part of S2 first (offset copies of neighbouring bodies that interpenetrate), so the points
  /// there take that nearer hit and the walk ends at its last visible crossing.
  hidden,
};

std::string_view to_string(EdgeFailureReason reason);

/// An S2 edge (d = 2) or segment (d = 1) whose preimage is missing, completely or in part.
template <int d>
struct EdgeNotInserted {
  Index target_edge = invalid_index;
  EdgeFailureReason reason = EdgeFailureReason::discontinuity;
  /// Where the walk stopped: an S1 element containing the point, the point on S1, and the
  /// parameter along the S2 edge (0 at its smaller-index vertex) reached so far.
  Index domain_element = invalid_index;
  WorldPoint<d> domain_point = WorldPoint<d>::Zero();
  double target_parameter = 0.0;
  std::string detail;
};

/// Wall-clock seconds per phase.
struct ProjectionTimings {
  double setup = 0.0;  ///< directions, normals and search trees
  double vertex_preimages = 0.0;
  double ghost_nodes = 0.0;
  double edge_walks = 0.0;  ///< boundary entries and walks (eq. 4)
  double insertion = 0.0;   ///< entering nodes and edges into the builder
  double finalize = 0.0;
  /// the copies in spatial order and the translation of the map back to the caller's numbers
  /// (ProjectionOptions::renumbering); 0 when neither surface was renumbered
  double renumbering = 0.0;
  double total = 0.0;
};

template <int d>
struct ProjectionReport {
  Index target_vertices = 0;
  Index vertex_preimages = 0;  ///< S2 vertices with a preimage on S1
  /// S2 vertices whose preimage was found but not entered: it fell onto an S1 vertex that
  /// already carries another preimage, or onto the same point of an S1 edge or element as
  /// another (the nearest one is kept).
  Index vertex_conflicts = 0;
  /// Of vertex_preimages: those found only by the second search, from the S1 vertices whose
  /// rays hit S2 next to the S2 vertex (e.g. under a nearer sheet of S1 that does not reach it).
  Index vertices_found_by_ray_hits = 0;
  Index domain_vertices = 0;
  Index ghost_nodes = 0;  ///< S1 vertices mapped into S2 (not onto an S2 vertex)
  /// S1 vertices whose ray hits S2 exactly at an S2 vertex that has no preimage of its own: they
  /// become that vertex's preimage.
  Index vertices_mapped_by_ray = 0;
  Index ghost_conflicts = 0;  ///< rays that hit an S2 vertex whose preimage lies elsewhere
  Index target_edges = 0;
  Index edges_inserted = 0;         ///< complete preimages
  Index edges_partly_inserted = 0;  ///< edges inserted as one or more pieces
  Index edge_pieces = 0;            ///< pieces entered (ending at S1's boundary)
  Index boundary_entries = 0;       ///< points where S2 edges enter S1 across its boundary
  Index edges_outside = 0;          ///< edges with no part over S1 (not a failure)
  /// Faces of the graph left out of D because they map with the orientation opposite to the
  /// map's (FinalizeReport::reversed_faces): a fold that no edge failure reports.
  Index reversed_faces = 0;
  /// Faces left out of D because their nodes map into no one S2 element
  /// (FinalizeReport::unmapped_faces): an S2 edge's preimage that would split them is missing,
  /// also where no edge failure names it (a walk that stopped at a fold and went on beyond it).
  Index unmapped_faces = 0;
  /// Faces that lost regions because their images overlap on S2 the images of regions whose
  /// points lie nearer to their images (ProjectionOptions::keep_nearer_sheet), and the regions
  /// left out: the overlapping regions only, unless that would leave a hole strictly inside an
  /// element (then the whole face, and an element whose face lay strictly inside it loses all its
  /// regions; core/face_removal.hpp, remove_regions).
  Index occluded_faces = 0;
  Index occluded_regions = 0;
  /// Faces that lost regions with a corner whose ray passes a focal point of their element before
  /// its image: closed from a ghost node whose ray is unfolded only in other elements at its
  /// vertex (docs/projection.md step 2), and the regions left out (by the rule of occluded_faces,
  /// cleared elements included).
  Index folded_faces = 0;
  Index folded_regions = 0;
  /// d = 2: regions with a folded and an unfolded corner, cut along the fold: the part on the
  /// unfolded side stays in D (construct/src/folded_regions.hpp, core/region_clipping.hpp); not
  /// counted in folded_regions.
  Index folded_regions_cut = 0;
  /// d = 2: regions that finalize split off a face at an S1 corner without a node and that the
  /// rays do not back: at one of their sample points the ray meets the plane of their S2 element
  /// more than half an edge from Xi there (at S2's silhouette along the rays, or at a fold). They
  /// are left out of D with the folded regions (construct/src/split_region_rays.hpp);
  /// folded_faces counts the faces of both.
  Index unbacked_regions = 0;
  /// d = 2: the measure of S1 outside D, by why. With ProjectionMeasures::covered_domain these
  /// add up to S1's measure (up to rounding), so a user can tell where a coverage below 1 comes
  /// from; `plmap check --against-rays` tells it for sampled points, by what the rays find.
  struct MeasureLeftOut {
    /// Beyond D's reach: the faces at S1 corners whose rays found no admissible image (past S2's
    /// boundary, beyond the distance limit, behind a rim), and elements the map does not reach.
    double outside = 0.0;
    double reversed = 0.0;  ///< the reversed faces
    double unmapped = 0.0;  ///< the unmapped faces
    /// Regions of elements that left D whole because reversed or unmapped faces lay strictly
    /// inside them (FinalizeReport::unmapped_faces).
    double enclosed = 0.0;
    double folded = 0.0;    ///< the regions left out as folded (folded_faces), cleared elements included
    double unbacked = 0.0;  ///< the unbacked regions themselves (unbacked_regions)
    double occluded = 0.0;  ///< the regions left out as occluded (occluded_faces), cleared elements included

    /// Every measure above with its name (the key of `plmap project --json`'s left_out_measure),
    /// for the code that goes over all of them (the JSON of the CLI and of Python, the scaling
    /// back to the user's units, the checks that they add up): a new reason is one member and
    /// one entry here.
    static constexpr std::array<std::pair<const char*, double MeasureLeftOut::*>, 7> fields() {
      return {{{"outside", &MeasureLeftOut::outside},
               {"reversed", &MeasureLeftOut::reversed},
               {"unmapped", &MeasureLeftOut::unmapped},
               {"enclosed", &MeasureLeftOut::enclosed},
               {"folded", &MeasureLeftOut::folded},
               {"unbacked", &MeasureLeftOut::unbacked},
               {"occluded", &MeasureLeftOut::occluded}}};
    }
    /// Their sum: with ProjectionMeasures::covered_domain, S1's measure.
    double sum() const {
      double total = 0.0;
      for (const auto& [name, measure] : fields()) total += this->*measure;
      return total;
    }
  };
  MeasureLeftOut left_out;
  /// d = 2, end_on_rim: nodes and edges of the rim of D where S2 leaves the band of admissible
  /// distances, behind S1 or beyond max_distance (rim nodes inside elements and on S1 edges;
  /// ghost nodes the rim passes are not counted).
  Index rim_nodes = 0;
  Index rim_edges = 0;
  /// d = 2, fold_rim: where the sheets on both sides of a fold meet, the points on S2 edges
  /// (fold_rim_nodes: a node on each sheet) and the rim edges traced between them (fold_rim_edges).
  Index fold_rim_nodes = 0;
  Index fold_rim_edges = 0;
  std::vector<EdgeNotInserted<d>> edges_not_inserted;
  /// Whether the projection worked on a copy of S1 (S2) renumbered in spatial order
  /// (ProjectionOptions::renumbering). Every number in the map and this report is the caller's.
  bool renumbered_domain = false;
  bool renumbered_target = false;
  /// Solver calls and how many did not converge (eq. 3 and eq. 4 together).
  long long solver_calls = 0;
  long long solver_failures = 0;
  ProjectionTimings seconds;
};

struct ProjectionMeasures {
  double domain = 0.0;          ///< measure of S1
  double target = 0.0;          ///< measure of S2
  double covered_domain = 0.0;  ///< measure of D (the regions on S1)
  double covered_target = 0.0;  ///< measure of Xi(D) on S2
};

template <int d>
struct ProjectionResult {
  PlMap<d> map;
  ProjectionReport<d> report;
  ProjectionMeasures measures;
};

}  // namespace plmap
