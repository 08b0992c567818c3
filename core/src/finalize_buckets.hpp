#pragma once
// finalize(), phase 1: bucketing. The builder's nodes and segments grouped by where they live on
// S1 (element, or S1 edge for d = 2), leaving out those of dropped S2 edges. Private to the
// builder.

#include "builder_nodes.hpp"

#include <span>
#include <vector>

namespace plmap::detail {

/// Items grouped by a key in [0, groups) as CSR arrays: two allocations for all groups, where a
/// vector per group would cost one per S1 element or edge (millions on large maps).
class Buckets {
 public:
  /// key_of(i) is the group of item i in [0, items), or -1 to leave the item out. Items keep
  /// their order within a group.
  template <class KeyOf>
  void build(Index groups, Index items, KeyOf&& key_of) {
    begin_.assign(static_cast<std::size_t>(groups) + 1, 0);
    for (Index i = 0; i < items; ++i)
      if (const Index g = key_of(i); g >= 0) ++begin_[static_cast<std::size_t>(g) + 1];
    for (std::size_t g = 1; g < begin_.size(); ++g) begin_[g] += begin_[g - 1];
    items_.resize(static_cast<std::size_t>(begin_.back()));
    std::vector<Index> cursor(begin_.begin(), begin_.end() - 1);
    for (Index i = 0; i < items; ++i)
      if (const Index g = key_of(i); g >= 0) items_[static_cast<std::size_t>(cursor[static_cast<std::size_t>(g)]++)] = i;
  }
  Index group_count() const { return static_cast<Index>(begin_.size()) - 1; }
  std::span<const Index> operator[](Index g) const { return {items_.data() + begin_[g], items_.data() + begin_[g + 1]}; }
  std::span<Index> group(Index g) { return {items_.data() + begin_[g], items_.data() + begin_[g + 1]}; }
  /// Gives the memory back (the buckets are empty afterwards).
  void release() {
    std::vector<Index>().swap(begin_);
    std::vector<Index>().swap(items_);
  }

 private:
  std::vector<Index> begin_, items_;
};

/// The live nodes and segments of a builder by their place on S1.
template <int d>
struct NodesAndSegmentsByPlace {
  Buckets interior_nodes;    ///< per S1 element: the nodes inside it
  Buckets edge_nodes;        ///< per S1 edge (d = 2): the nodes on it, in order along it
  Buckets element_segments;  ///< per S1 element: the segments inside it
  Buckets edge_segments;     ///< per S1 edge (d = 2): the segments along it

  /// (Re)builds the buckets. Throws BuilderError if two nodes lie at the same point of an S1 edge.
  void build(const BuilderContents<d>& in, const DroppedEdges& dropped);
  void release();
};

extern template struct NodesAndSegmentsByPlace<1>;
extern template struct NodesAndSegmentsByPlace<2>;

}  // namespace plmap::detail
