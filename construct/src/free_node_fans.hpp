#pragma once
// The counter-clockwise neighbours of the free (interior) nodes of one S1 element, read from the
// element's regions: for a node whose regions close one fan they are exactly the neighbour list
// that PlMap derives from the regions (map_graph_derivation.cpp: counter-clockwise from the
// smallest neighbour), without deriving the graph of the whole map. The element smoothing
// (smooth.cpp) reads them on maps where no element stores its graph, so every element's graph
// is that derivation; deriving it for the whole map cost a tenth of the smoothing of CGAL's
// femur → 500 map.

#include <plmap/core/pl_map.hpp>

#include <array>
#include <span>
#include <vector>

namespace plmap::smoothing {

class FreeNodeFans {
 public:
  /// Gathers the spokes of element t: for each region (v, a, b) (counter-clockwise) at a node v
  /// with free[v - node_begin[t]], the pair (a, b).
  void collect(const MapData<2>& m, Index t, std::span<const char> free) {
    const Index nb = m.node_begin[t];
    const std::size_t nodes = static_cast<std::size_t>(m.node_begin[t + 1] - nb);
    begin_.assign(nodes + 1, 0);
    for (Index r = m.region_begin[t]; r < m.region_begin[t + 1]; ++r)
      for (Index c : m.region_corners[r])
        if (free[static_cast<std::size_t>(c - nb)]) ++begin_[static_cast<std::size_t>(c - nb) + 1];
    for (std::size_t v = 0; v < nodes; ++v) begin_[v + 1] += begin_[v];
    spokes_.resize(static_cast<std::size_t>(begin_.back()));
    fill_.assign(begin_.begin(), begin_.end() - 1);
    for (Index r = m.region_begin[t]; r < m.region_begin[t + 1]; ++r) {
      const auto& c = m.region_corners[r];
      for (int i = 0; i < 3; ++i) {
        const auto v = static_cast<std::size_t>(c[i] - nb);
        if (free[v]) spokes_[static_cast<std::size_t>(fill_[v]++)] = {c[(i + 1) % 3], c[(i + 2) % 3]};
      }
    }
    node_begin_ = nb;
  }

  /// The neighbours of free node n of the collected element, counter-clockwise from the smallest,
  /// if its regions close one fan around it; empty otherwise (an open star, or regions that do
  /// not form one fan). Valid until the next call.
  std::span<const Index> ring(Index n) {
    const auto v = static_cast<std::size_t>(n - node_begin_);
    const std::span<const std::array<Index, 2>> spokes(spokes_.data() + begin_[v], spokes_.data() + begin_[v + 1]);
    ring_.clear();
    if (spokes.empty()) return {};
    std::size_t at = 0;
    for (std::size_t k = 1; k < spokes.size(); ++k)
      if (spokes[k][0] < spokes[at][0]) at = k;
    const Index first = spokes[at][0];
    for (std::size_t steps = 0; steps < spokes.size(); ++steps) {
      ring_.push_back(spokes[at][0]);
      const Index following = spokes[at][1];
      if (following == first) {
        if (steps + 1 != spokes.size()) return {};  // a closed fan that misses some regions
        return ring_;
      }
      std::size_t next = spokes.size();
      for (std::size_t k = 0; k < spokes.size(); ++k)
        if (spokes[k][0] == following) {
          if (next != spokes.size()) return {};  // two regions leave n along one side
          next = k;
        }
      if (next == spokes.size()) return {};  // the fan does not close
      at = next;
    }
    return {};
  }

 private:
  Index node_begin_ = 0;
  std::vector<Index> begin_, fill_, ring_;
  std::vector<std::array<Index, 2>> spokes_;
};

}  // namespace plmap::smoothing
