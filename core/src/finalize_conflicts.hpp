#pragma once
// finalize(): which S2 edges to drop when BuilderOptions::drop_conflicting_edges asks for it. An
// element whose graph cannot be closed (pieces that cross, or pass through a node) names the S2
// edges involved; a preimage that meets an element in more than one piece breaks the minimal
// embedding (DESIGN.md §4.3). Private to the builder.

#include "builder_nodes.hpp"
#include "finalize_buckets.hpp"

#include <vector>

namespace plmap::detail {

/// The S2 edges whose pieces on S1 element t cross another piece or pass through a node, sorted,
/// each once.
std::vector<Index> conflicting_edges(const BuilderContents<2>& in, const NodesAndSegmentsByPlace<2>& where, Index t);

/// Drops every S2 edge whose preimage meets some S1 element in two or more separate pieces (where
/// a projection is discontinuous a preimage can enter an element twice). Returns whether any was
/// dropped (the buckets are then stale).
bool drop_split_preimages(const BuilderContents<2>& in, const NodesAndSegmentsByPlace<2>& where,
                          DroppedEdges& dropped);

}  // namespace plmap::detail
