#pragma once
// Normal projection, phase 4: edge walks (paper eq. 4). For every S2 edge, walk across S1 along
// its preimage, solving p(lambda) + mu nu(lambda) = q(eta) on the S1 edges of the current element
// and taking the crossing with the next larger eta. Walks start at the preimage of the edge's
// first vertex and at every point where the edge enters S1 across S1's boundary, and end at the
// preimage of the second vertex or where the edge leaves S1 across its boundary; what they walk
// becomes the edge's pieces, planned here and entered into the builder by the insertion. The
// walks read nothing the insertion changes, so edges are planned in parallel, block by block.

#include "projection_context.hpp"

#include <plmap/construct/projection_result.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace plmap::projection {

/// What the edge walks plan for the S2 edges of one block, in flat arrays owned by one worker
/// thread and reused from block to block: once they have grown, planning allocates nothing per
/// edge or per walk (the per-edge vectors of pieces and crossings this replaces were millions of small
/// allocations).
/// Where an S2 edge leaves the admissible band of distances over S1 (d = 2: it passes behind S1,
/// or beyond the distance limit) and a walk along its preimage that stopped there ends: a point
/// inside S1 element `element`, whose ray meets the edge at the bound ProjectionContext::
/// rim_level(level), and the edge parameter there (0 at the edge's smaller-index vertex). The
/// piece ends at a rim node there (end_on_rim). With level fold_rim_level: a point inside the
/// element where a sheet of the projection meets the sheet beyond a fold on the edge.
template <int d>
struct RimPoint {
  Index element = invalid_index;
  LocalPoint<d> local = LocalPoint<d>::Zero();
  double eta = 0.0;
  int level = 0;
};

/// RimPoint::level of a point where the sheets before and beyond a fold meet on an S2 edge
/// (projection_fold_rim.hpp), not on a bound of the band.
inline constexpr int fold_rim_level = 2;

/// A point where the rim crosses S2 edge `target_edge` that no walk reached (ProjectionInsertion::
/// take_unwalked_rim_crossings): a walk starts there into the band (plan_rim_walks).
template <int d>
struct RimStart {
  Index target_edge = invalid_index;
  RimPoint<d> at;
};

template <int d>
struct PlanBuffer {
  static constexpr std::uint32_t no_rim = ~std::uint32_t{0};
  /// A piece of an S2 edge's preimage: crossings [begin, end) of `crossings`; a piece that starts
  /// at a rim node (PieceStart::rim_node) has its point in rim_points[start_rim], one that ends
  /// at a rim node (PieceEnd::rim_node) in rim_points[end_rim]. A piece can do both: the
  /// stretch of an edge that comes out from behind S1 and passes behind it again.
  struct Piece {
    std::uint32_t begin, end;
    PieceStart starts_at;
    PieceEnd ends_at;
    std::uint32_t start_rim = no_rim;
    std::uint32_t end_rim = no_rim;
  };
  std::vector<Crossing<d>> crossings;
  std::vector<Piece> pieces;
  std::vector<RimPoint<d>> rim_points;
  std::vector<EdgeNotInserted<d>> failures;
  /// scratch of the walks: the S1 elements at the current point and at the walk's end
  std::vector<Index> candidates, end_elements;

  /// Keeps a walk's rim point for a piece, its parameter measured from the edge's first vertex
  /// (`backwards`: the walk ran from the second vertex); returns its index.
  std::uint32_t keep_rim(RimPoint<d> rim, bool backwards) {
    if (backwards) rim.eta = 1.0 - rim.eta;
    rim_points.push_back(rim);
    return static_cast<std::uint32_t>(rim_points.size() - 1);
  }

  void clear() {
    crossings.clear();
    pieces.clear();
    rim_points.clear();
    failures.clear();
  }
};

/// The plan of one S2 edge: which worker's PlanBuffer holds it and where.
struct PlannedEdge {
  unsigned worker = 0;
  std::uint32_t pieces_begin = 0, pieces_end = 0, failures_begin = 0, failures_end = 0;
  bool outside = false;
};

/// S2 edges planned per block (see walk_and_insert_edges in project.cpp): small enough that the
/// blocks spread evenly over the threads and that the plans of the blocks in flight take little
/// memory. (With 1024 the bones pair of the peer benchmark, 8,600 S2 edges, was nine blocks of
/// about 4 ms, and one thread planned the last alone: 256 took its two-thread run from 97 to
/// 95 ms. A plan does not depend on its block, so the maps are the same.)
inline constexpr Index edge_plan_block = 256;

/// Points where S2 edges cross S1's boundary (d = 2: a boundary edge, d = 1: a boundary vertex
/// with a ghost image), by S2 edge, each edge's sorted by the edge parameter; walks start there
/// too. Reads state.vertex_state and vertex_image. The same for every ctx.threads.
template <int d, class Solver>
BoundaryEntries<d> find_boundary_entries(const ProjectionContext<d>& ctx, const ProjectionState<d>& state,
                                         const Solver& solver);

/// Plans S2 edges [block, block_end) on the calling thread into `buffer` (cleared here), which the
/// caller numbers `slot`: planned[e - block] (resized here) holds edge e's pieces and failures.
/// Independent of ctx.threads.
template <int d, class Solver>
void plan_edge_block(const ProjectionContext<d>& ctx, const ProjectionState<d>& state, const Solver& solver,
                     Index block, Index block_end, unsigned slot, PlanBuffer<d>& buffer,
                     std::vector<PlannedEdge>& planned);

/// d = 2: plans the walks from unwalked rim crossings (sorted by edge, then edge parameter) into
/// `buffer` (cleared here): per S2 edge with a piece, its index in `edges` and its plan in
/// `planned`. From each crossing the walk runs into the band (the direction in which the
/// distance along the rays moves away from the crossed bound) and ends at the next rim crossing,
/// a vertex preimage, S1's boundary or a failure; a crossing that an earlier walk of the same
/// edge reached is skipped.
template <int d, class Solver>
void plan_rim_walks(const ProjectionContext<d>& ctx, const ProjectionState<d>& state, const Solver& solver,
                    std::span<const RimStart<d>> starts, PlanBuffer<d>& buffer, std::vector<Index>& edges,
                    std::vector<PlannedEdge>& planned);

}  // namespace plmap::projection
