#pragma once
// Deriving a triangle map's graph arrays (region neighbours, neighbour lists with their edge
// kinds, edge arrays) from what the compact form stores: the nodes and the regions' corners and
// S2 elements. Private to PlMap (pl_map.cpp), which stores these arrays only for the elements
// whose graph does not follow from their regions (docs/data-model.md, "What is stored and what
// is derived").
//
// Every function works on one S1 element, reads only that element's nodes and regions, and
// returns false when the element's regions do not determine its graph (a corner outside the
// element, a directed side used twice, a node whose regions form more than one fan). The
// derivation is combinatorial except for the order along an element edge, which compares the
// nodes' exact local coordinates: no tolerance is involved.

#include <plmap/core/pl_map.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace plmap::detail {

/// Reusable buffers of the derivation (one per thread).
struct GraphDerivationScratch {
  struct Side {
    std::uint64_t key;         // the side's two nodes (element-local), smaller first
    std::uint32_t region_side;  // 3 * (region - first region of the element) + opposite corner
  };
  std::vector<Side> sides;
  std::vector<Index> incidence_begin;    // per node of the element + 1
  std::vector<Index> incidence;          // region * 3 + corner, grouped by node
  std::vector<Index> incidence_fill;
};

/// Whether nodes x and y lie on one edge of S2 (whose preimage then contains the side x-y): two
/// vertices of the region's S2 element t2, a vertex and an edge through it, or one edge (a ghost
/// node's edge: the one its image lies on with an exactly zero weight). The kind of a side with
/// no region across.
bool on_common_target_edge(const MapData<2>& m, const Surface<2>& target, Index t2, Index x, Index y);

/// Region neighbours of element t: out[r - region_begin[t]][i] is the region of t across the side
/// of r opposite corner i, or invalid_index.
bool derive_region_neighbors(const MapData<2>& m, Index t, std::span<std::array<Index, 3>> out,
                             GraphDerivationScratch& scratch);

/// Neighbour lists of element t's nodes, in the order the builder writes them (counter-clockwise;
/// a node on the element's boundary starts right after the outside, an interior node at its
/// smallest neighbour), appended to `neighbor` and `kind`; `count` gets one entry per node.
/// `region_neighbors` are element t's (from derive_region_neighbors).
/// A side is the preimage of an S2 edge if the regions on its two sides map into different S2
/// elements, or, with no region across, if its two nodes lie on one edge of S2 (vertices of the
/// region's S2 element, intersection nodes of that edge, ghost nodes whose image lies on it);
/// otherwise it is a closure edge.
bool derive_neighbor_lists(const MapData<2>& m, const Surface<2>& target, Index t,
                           std::span<const std::array<Index, 3>> region_neighbors,
                           std::vector<Index>& count, std::vector<Index>& neighbor,
                           std::vector<GraphEdgeKind>& kind, GraphDerivationScratch& scratch);

/// Edge arrays of element t: the nodes on local edge k (corner and ghost nodes at its two ends,
/// touching and intersection nodes on it), ordered from corner k to corner (k+1) mod 3 by their
/// local coordinates, appended to `edge_node`; `count` gets three entries.
void derive_edge_nodes(const MapData<2>& m, Index t, std::vector<Index>& count,
                       std::vector<Index>& edge_node);

}  // namespace plmap::detail
