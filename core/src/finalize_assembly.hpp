#pragma once
// finalize(), phase 3: assembly. Each S1 element is written into the flat arrays right after it
// is closed, into the part of the map that belongs to its block of elements (numbered from 0 in
// the block); joining (finalize_joining.hpp) adds the offsets. Only faces mapped with the map's
// orientation become regions. Private to the builder.
//
// The parts, and the joined map finalize_triangles returns, are in the builder's own form, not
// yet PlMap's: the nodes, regions, neighbour entries and edge_node_begin are complete, but
// neighbor_begin, edge_node and region_neighbors hold values only for the elements that have
// neighbour entries (those their regions do not tile), in element order (AssembledMap's
// graph_elements; neighbor_begin: one end per node of those elements after its leading 0); the
// other elements' edge_node_begin ranges are empty. Those are the only elements whose graph the
// stored form keeps (hand_over_stored_form), so the rest was written only to be dropped: 29 MiB
// of the peak on the 200k plane pair and 46 MiB on the L7 spheres, and 7.5 and 12 MiB more for
// neighbor_begin.

#include "builder_nodes.hpp"
#include "finalize_buckets.hpp"
#include "finalize_closure.hpp"
#include "finalize_phases.hpp"
#include "finalize_region_maps.hpp"

#include <plmap/core/pl_map.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace plmap::detail {

/// Where the next element's values go in its block's part, and what the block counted.
struct AssemblyCursor {
  std::size_t elements = 0, nodes = 0, entries = 0, edge_nodes = 0, regions = 0;
  double spare_room = 0.0;  // BuilderOptions::spare_room: extra capacity of node and region arrays
  std::size_t graph_regions = 0;  // region_neighbors written: regions of elements with neighbour entries
  std::size_t graph_nodes = 0;    // neighbor_begin written (after its leading 0): nodes of those elements
  std::vector<Index> graph_elements;  // those elements, numbered in the block
  Index reversed_faces = 0;  // faces with a target element but the other orientation
  Index unmapped_faces = 0;  // faces inside S1's corners whose nodes share no S2 element
  /// The S1 measure of what the elements leave out (FinalizeReport::MeasureLeftOut), in units of
  /// S1's measure / 2^60: integers, so that the sums do not depend on how the elements are split
  /// into blocks (the thread count).
  struct LeftOutTally {
    std::int64_t outside = 0, reversed = 0, unmapped = 0, enclosed = 0;
    LeftOutTally& operator+=(const LeftOutTally& o) {
      outside += o.outside;
      reversed += o.reversed;
      unmapped += o.unmapped;
      enclosed += o.enclosed;
      return *this;
    }
    FinalizeReport::MeasureLeftOut measures(double s1_measure) const;
  };
  LeftOutTally left_out;
  std::vector<Index> triangle_region;  // per closure triangle of the element: its region, or invalid
  bool split_kept = false;  // the element keeps triangles of an unmapped face (number_regions)
  std::vector<Index> split_targets;  // the S2 elements of those triangles' regions (FinalizeReport::split_targets)
  // those of the regions that come from faces at a corner without a node, numbered in the block
  // (FinalizeReport::regions_split_off_outside_faces)
  std::vector<Index> outside_split_regions;
  /// Region maps deferred (finalize_region_maps.hpp): region_map is not written, and this
  /// collects the part's kept omitted weights instead (by node of the part, in increasing order).
  /// Null: region_map is written with the regions.
  std::vector<KeptOmittedWeight>* kept_omitted_weights = nullptr;
};

/// What the part of a block of elements holds at most (nodes and edge entries exactly): a
/// triangulation of n points, h of them on the element boundary, has 2n - h - 2 triangles and
/// 3n - h - 3 sides, which is exact unless faces lie outside D.
struct PartBounds {
  std::size_t elements = 0, nodes = 0, on_edges = 0, triangles = 0, sides = 0;
  PartBounds& operator+=(const PartBounds& other);
};

/// The bounds of the part for elements [begin, end).
PartBounds part_bounds(const BuilderContents<2>& in, const NodesAndSegmentsByPlace<2>& where, Index begin, Index end);

/// Sizes the arrays of a part before it is assembled: nodes and edge arrays exactly to `own`
/// (written in place: a push_back per value costs more than the store), the rest reserved by
/// `own`'s bounds. Growing by push_back instead would copy the map several times and first-touch
/// up to twice its memory, and the final shrink_to_fit would copy it again. Every array gets the
/// capacity of `room` as well (address space only): the first block is given the whole map's
/// bounds, so that joining (finalize_joining.hpp) keeps its arrays where they are and appends
/// the other blocks, instead of copying and first-touching the whole map once more. With
/// at.kept_omitted_weights, region_map is left empty (and the kept omitted weights start empty).
void size_part(const PartBounds& own, const PartBounds& room, MapData<2>& part, const AssemblyCursor& at);

/// Writes the element closed in w into the part at the cursor, which it advances.
void assemble_element(const BuilderContents<2>& in, const ClosureWorkspace& w, int orientation, MapData<2>& part,
                      AssemblyCursor& at);

/// Keeps the graph of the element at the cursor (its `nodes` nodes' neighbor_begin values, written
/// at at.graph_nodes on) if it has neighbour entries from `first_entry` on; otherwise takes back
/// the edge nodes and region neighbours it wrote from `first_edge_node` and `first_graph_region`
/// on: an element without neighbour entries keeps no graph (see the top of this file), and its
/// edge_node_begin ranges become empty.
void keep_or_drop_graph_of_element(std::size_t nodes, std::size_t first_entry, std::size_t first_edge_node,
                                   std::size_t first_graph_region, MapData<2>& part, AssemblyCursor& at);

/// Cuts the arrays sized ahead back to what was written (the element and node arrays too: a
/// part may close fewer elements than it was sized for).
void trim_part(const AssemblyCursor& at, MapData<2>& part);

/// The joined map's hand-over to PlMap in its stored form (PlMap's second constructor): the
/// graph arrays of the elements that have neighbour entries (those their regions do not tile,
/// write_nodes; the only ones the map has neighbour ends, edge nodes and region neighbours of)
/// move into the returned StoredGraph, and all graph arrays of the map are released.
/// Nothing is derived or compared: that is what keeps finalize as fast as before.
StoredGraph hand_over_stored_form(AssembledMap& assembled);

}  // namespace plmap::detail
