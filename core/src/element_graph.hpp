#pragma once
// One element's graph arrays, taken out of a triangle map's stored form: from its stored graph
// (PlMap::stored_graph) where it keeps one, else derived from its regions
// (map_graph_derivation.hpp). The operations that change a finished map element by element
// (face removal on the stored form, face_removal_stored_form.cpp; region clipping,
// region_clipping.cpp) read and write graphs in this form and hand the map over in its stored
// form, with a stored graph for exactly the elements whose regions do not give theirs back.

#include "map_graph_derivation.hpp"
#include "stored_graph_offsets.hpp"

#include <plmap/core/pl_map.hpp>

#include <array>
#include <cstddef>
#include <optional>
#include <vector>

namespace plmap::detail {

/// The graph arrays of one element, laid out as in StoredGraph: node by node, then the three
/// local edges, then region by region. Node and region indices are global.
struct ElementGraph {
  Index element = invalid_index;
  std::vector<Index> neighbor_count;
  std::vector<Index> neighbor;
  std::vector<GraphEdgeKind> kind;
  std::vector<Index> edge_node_count;
  std::vector<Index> edge_node;
  std::vector<std::array<Index, 3>> region_neighbors;

  bool operator==(const ElementGraph&) const = default;

  /// Entry of neighbour b in the list of node a (an index into `neighbor`), or invalid_index.
  Index entry(const std::vector<Index>& list_begin, Index local_a, Index b) const {
    for (Index i = list_begin[static_cast<std::size_t>(local_a)]; i < list_begin[static_cast<std::size_t>(local_a) + 1]; ++i)
      if (neighbor[static_cast<std::size_t>(i)] == b) return i;
    return invalid_index;
  }
};

/// Element e (a position in g.element) of the stored graph.
ElementGraph stored_element_graph(const StoredGraph& g, const StoredGraphOffsets& at, std::size_t e);

/// Element t's graph as its regions give it, or nothing where they do not determine one.
std::optional<ElementGraph> derived_element_graph(const MapData<2>& m, const Surface<2>& target, Index t,
                                                  GraphDerivationScratch& scratch);

/// Start of each node's list in g's entries (one more than nodes).
std::vector<Index> list_begins(const ElementGraph& g);

/// Appends g to a stored graph (elements in increasing order).
void append(const ElementGraph& g, StoredGraph& out);

/// The pieces' graphs, one after the other.
StoredGraph join_in_order(std::vector<StoredGraph>& pieces);

}  // namespace plmap::detail
