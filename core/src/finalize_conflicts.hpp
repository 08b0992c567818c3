#pragma once
// finalize(): what to drop when BuilderOptions::drop_conflicting_edges asks for it. An element
// whose graph cannot be closed (pieces that cross, or pass through a node) names the S2 edges
// involved; a preimage that meets an element in more than one piece breaks the minimal
// embedding (DESIGN.md §4.3). Either way only those edges' stretches on that element are
// dropped. Private to the builder.

#include "builder_nodes.hpp"
#include "finalize_buckets.hpp"

#include <vector>

namespace plmap::detail {

/// The S2 edges whose pieces on S1 element t cross another S2 edge's piece or pass through a
/// node, sorted, each once (conflicts with rim edges are left to drop_rim_edges_on_element).
std::vector<Index> conflicting_edges(const BuilderContents<2>& in, const NodesAndSegmentsByPlace<2>& where, Index t);

/// Drops the stretch of S2 edge e's preimage on S1 element t (its segments inside t and along
/// t's edges): the rest of the preimage stays and ends at the crossings on t's boundary, so a
/// conflict costs the faces around that stretch, not the whole preimages of e's S2 triangles.
/// Returns whether anything was still there to drop (the buckets are then stale).
bool drop_stretch_on_element(const BuilderContents<2>& in, const NodesAndSegmentsByPlace<2>& where, Index e, Index t,
                             DroppedEdges& dropped);

/// Drops the rim edges (MapBuilder::add_rim_edge) on S1 element t and along its edges that
/// cross another graph or rim edge there, or pass through a node: where an element with rim
/// edges cannot be closed, those go, and D ends at the last crossings next to them, as without
/// a rim. The other rim edges stay and keep their faces in D (on the bones pair a third of the
/// rim edges on such elements cross something). If none does, the rim stays where S2 edges
/// conflict among themselves (their stretches go instead, conflicting_edges); else t failed for
/// another reason (e.g. two nodes that coincide) and all its rim edges go. Returns whether any
/// was still there to drop.
bool drop_rim_edges_on_element(const BuilderContents<2>& in, const NodesAndSegmentsByPlace<2>& where, Index t,
                               DroppedEdges& dropped);

/// Drops the rim nodes whose rim edges have all been dropped (drop_rim_edges_on_element), and the
/// last segments of S2 edge pieces that end at them: such a node no longer bounds D, but its
/// image (often on another sheet of S2) would keep the face around it from mapping into one S2
/// triangle, so the face would leave D. Does nothing unless a rim edge was dropped. Returns
/// whether any node was dropped (the buckets are then stale).
bool drop_rim_nodes_left_without_rim(const BuilderContents<2>& in, DroppedEdges& dropped);

/// Drops, on each S1 element that the preimage of an S2 edge meets in two or more separate
/// pieces (where a projection is discontinuous a preimage can enter an element twice), that
/// edge's stretch on the element. Returns whether any was dropped (the buckets are then stale).
bool drop_split_preimages(const BuilderContents<2>& in, const NodesAndSegmentsByPlace<2>& where,
                          DroppedEdges& dropped);

}  // namespace plmap::detail
