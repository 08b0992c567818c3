#pragma once
// Where each element that stores its graph (PlMap::stored_graph) finds it in the StoredGraph's
// arrays: prefix sums over the stored elements, in their order, of their nodes, neighbour
// entries, edge entries and regions. Read by the structural validation (map_validation.cpp)
// and by the face removal on the stored form (face_removal_stored_form.cpp).

#include <plmap/core/pl_map.hpp>

#include <algorithm>
#include <cstddef>
#include <vector>

namespace plmap::detail {

struct StoredGraphOffsets {
  /// Each of size (stored elements + 1): stored element e's entries are [x[e], x[e + 1]).
  std::vector<std::size_t> node, entry, edge_entry, region;

  /// `m` gives each element's node and region ranges (node_begin, region_begin).
  template <int d>
  StoredGraphOffsets(const MapData<d>& m, const StoredGraph& g) {
    const std::size_t n = g.element.size();
    node.assign(n + 1, 0);
    entry.assign(n + 1, 0);
    edge_entry.assign(n + 1, 0);
    region.assign(n + 1, 0);
    for (std::size_t e = 0; e < n; ++e) {
      const Index t = g.element[e];
      node[e + 1] = node[e] + static_cast<std::size_t>(m.node_begin[t + 1] - m.node_begin[t]);
      region[e + 1] = region[e] + static_cast<std::size_t>(m.region_begin[t + 1] - m.region_begin[t]);
      entry[e + 1] = entry[e];
      for (std::size_t i = node[e]; i < node[e + 1]; ++i) entry[e + 1] += static_cast<std::size_t>(g.neighbor_count[i]);
      edge_entry[e + 1] = edge_entry[e];
      for (std::size_t k = 3 * e; k < 3 * e + 3; ++k) edge_entry[e + 1] += static_cast<std::size_t>(g.edge_node_count[k]);
    }
  }

  /// The position of element t among the stored elements (sorted), or -1.
  static std::ptrdiff_t find(const StoredGraph& g, Index t) {
    const auto it = std::lower_bound(g.element.begin(), g.element.end(), t);
    return it != g.element.end() && *it == t ? it - g.element.begin() : -1;
  }
};

}  // namespace plmap::detail
