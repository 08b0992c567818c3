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
/// node, sorted, each once (conflicts with rim edges are settled by dropping the rim edges:
/// ElementConflicts::rim_edges).
std::vector<Index> conflicting_edges(const BuilderContents<2>& in, const NodesAndSegmentsByPlace<2>& where, Index t);

/// Drops the stretch of S2 edge e's preimage on S1 element t (its segments inside t and along
/// t's edges): the rest of the preimage stays and ends at the crossings on t's boundary, so a
/// conflict costs the faces around that stretch, not the whole preimages of e's S2 triangles.
/// Returns whether anything was still there to drop (the buckets are then stale).
bool drop_stretch_on_element(const BuilderContents<2>& in, const NodesAndSegmentsByPlace<2>& where, Index e, Index t,
                             DroppedEdges& dropped);

/// What to drop on an S1 element whose graph cannot be closed, found from the buckets alone (the
/// drops of a round change no bucket: they are rebuilt after it, so the failed elements of a
/// round are looked at side by side, and the drops made after, in element order).
struct ElementConflicts {
  /// Rim edges (MapBuilder::add_rim_edge) on the element and along its edges that go: those
  /// that cross another graph or rim edge there, or pass through a node. D then ends at the last
  /// crossings next to them, as without a rim; the other rim edges stay and keep their faces in D
  /// (on the bones pair a third of the rim edges on such elements cross something). If none
  /// does, the rim stays where S2 edges conflict among themselves (their stretches go instead);
  /// else the element failed for another reason (e.g. two nodes that coincide) and all its rim
  /// edges go.
  std::vector<Index> rim_edges;
  /// conflicting_edges: the S2 edges whose stretches on the element go.
  std::vector<Index> edges;
};
ElementConflicts conflicts_on_element(const BuilderContents<2>& in, const NodesAndSegmentsByPlace<2>& where, Index t);

/// Drops what `conflicts` names on element t: its rim edges, then the stretches of its S2 edges
/// (drop_stretch_on_element). Returns whether anything was still there to drop (the buckets
/// are then stale).
bool drop_conflicts_on_element(const BuilderContents<2>& in, const NodesAndSegmentsByPlace<2>& where, Index t,
                               const ElementConflicts& conflicts, DroppedEdges& dropped);

/// Drops the rim nodes whose rim edges have all been dropped (ElementConflicts), and the
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
