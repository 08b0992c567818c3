#pragma once
// Normal projection, d = 2: D ends where the sheets on both sides of a fold meet.
//
// Where S1 curves more tightly than its distance to S2, neighbouring rays cross before they
// reach S2 and the projection folds: along an S2 edge's preimage there are then three sheets,
// the one before the fold, the folded one, and the one beyond, and the first and the last both
// reach a stretch of the edge (between the images of the two fold curves). A walk stops at the
// last crossing before the fold and the next piece starts at the first unfolded crossing beyond
// it (the fold exit, fold_reentry.hpp), so the edge's preimage had a gap on both sheets, and the
// faces next to it, on both sheets, stayed outside D: the `next_to_fold` class of the ray check.
//
// Instead, both pieces now end at one point of the edge that both sheets reach (fold_meeting,
// projection_edge_walker.hpp): a node on each sheet with the same image. Across an S2 triangle
// two such points on two of its edges are joined by a straight segment of the triangle, and its
// preimage on each sheet (traced here, crossing by crossing, as an edge walk does) becomes a
// chain of rim edges (MapBuilder::add_rim_edge) through rim nodes on the S1 edges it crosses.
// The triangle's part on one side of the segment is then the image of faces on one sheet, the
// rest the image of faces on the other, and the two tile the triangle without a gap or an
// overlap. Where a preimage cannot be traced (it meets a fold, leaves S1, or needs more than
// `max_steps` elements), or the triangle has a meeting point on one edge only, the meeting node
// stays the end of its piece, a slit into its element: the faces around it close where their
// nodes map into one S2 triangle, as before (on the real-mesh pairs such slits keep more than
// they cost; docs/projection.md, step 4).

#include "projection_context.hpp"

#include <plmap/core/types.hpp>

#include <span>
#include <vector>

namespace plmap::projection {

/// A node of the builder (`node`) where a piece of S2 edge `target_edge` ends or starts at a
/// point where the sheets on both sides of a fold meet: inside S1 element `element` at `local`,
/// its image at parameter `eta` of the edge (from the edge's first vertex). `toward_first`: the
/// piece runs from the node towards the edge's first vertex (it ends there); else towards the
/// second.
struct FoldRimNode {
  Index target_edge = invalid_index;
  Index node = invalid_index;
  Index element = invalid_index;
  LocalPoint<2> local = LocalPoint<2>::Zero();
  double eta = 0.0;
  bool toward_first = true;
};

/// Where a traced preimage crosses an S1 edge: the S1 edge, the parameter along it (0 at its
/// smaller-index vertex), and the image's local point on the path's S2 triangle.
struct FoldRimCrossing {
  Index domain_edge = invalid_index;
  double lambda = 0.0;
  LocalPoint<2> image = LocalPoint<2>::Zero();
};

/// The preimage on one sheet of the segment of S2 triangle `target` between the images of two
/// fold rim nodes (`from` and `to`, builder nodes): the S1 edges it crosses, in order.
struct FoldRimPath {
  Index target = invalid_index;
  Index from = invalid_index, to = invalid_index;
  std::vector<FoldRimCrossing> crossings;
};

/// The fold rim's paths: for every S2 triangle with fold rim nodes on exactly two of its edges
/// (at most one per edge and side), the preimage of the segment between them on the sheet that
/// holds the triangle's corner between those edges, and on the sheet that holds the rest. The
/// same for every thread count (it runs on the calling thread, in the order of `nodes`).
template <class Solver>
std::vector<FoldRimPath> trace_fold_rims(const ProjectionContext<2>& ctx, const Solver& solver,
                                         std::span<const FoldRimNode> nodes);

}  // namespace plmap::projection
