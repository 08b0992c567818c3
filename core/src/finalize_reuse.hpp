#pragma once
// finalize(), for MapBuilder::finalize_reusing: an element whose part of the graph is known to be
// that of an element of a previous map is copied from that map instead of closed again (closure
// is most of finalize). Private to the builder.
//
// The copy is written into the block's part exactly as assemble_element writes an element of
// the stored form hand_over_stored_form expects: nodes, regions, and the graph arrays only where
// the previous map stores them (an element its regions tile gets no neighbour entries there; its
// edge-node and region-neighbour entries are placeholders, which hand_over_stored_form drops).

#include "builder_nodes.hpp"
#include "finalize_assembly.hpp"
#include "finalize_buckets.hpp"

#include <plmap/core/pl_map.hpp>

#include <span>
#include <vector>

namespace plmap::detail {

class ElementReuse {
 public:
  /// `reuse[t]` != 0: element t is copied from `previous`.
  ElementReuse(const PlMap<2>& previous, std::span<const char> reuse);
  bool reuses(Index t) const { return reuse_[static_cast<std::size_t>(t)] != 0; }
  /// Writes element t of the previous map into the part at the cursor, which it advances.
  /// Throws BuilderError if its node count is not the one the builder's contents give element t
  /// (size_part sized the part by them): the caller's promise does not hold.
  void copy_element(const BuilderContents<2>& in, const NodesAndSegmentsByPlace<2>& where, Index t, MapData<2>& part,
                    AssemblyCursor& at) const;

 private:
  const PlMap<2>& previous_;
  std::span<const char> reuse_;
  /// Per element: its position among the previous map's stored-graph elements, or -1; and the
  /// prefix sums locating those elements' arrays in its StoredGraph.
  std::vector<std::ptrdiff_t> stored_position_;
  std::vector<std::size_t> node_, entry_, edge_entry_, region_;
};

}  // namespace plmap::detail
