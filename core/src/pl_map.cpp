#include <plmap/core/errors.hpp>
#include <plmap/core/parallel_ranges.hpp>
#include <plmap/core/pl_map.hpp>

#include "map_graph_derivation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>

namespace plmap {

namespace {

template <class T>
std::size_t bytes_of(const std::vector<T>& v) {
  return v.capacity() * sizeof(T);
}

/// The stored graph holds exactly what it needs, whichever path filled it (memory_bytes() is
/// then the same for a map built, loaded from either format or copied).
void shrink_stored_graph(StoredGraph& g) {
  g.element.shrink_to_fit();
  g.neighbor_count.shrink_to_fit();
  g.neighbor.shrink_to_fit();
  g.neighbor_edge_kind.shrink_to_fit();
  g.edge_node_count.shrink_to_fit();
  g.edge_node.shrink_to_fit();
  g.region_neighbors.shrink_to_fit();
}

void require(bool ok, const char* what) {
  if (!ok) throw InvalidMapError(fmt::format("map arrays are inconsistent: {}", what));
}

}  // namespace

template <int d>
  requires SurfaceDimension<d>
PlMap<d>::PlMap(std::shared_ptr<const Surface<d>> domain, std::shared_ptr<const Surface<d>> target,
                MapData<d> data)
    : domain_(std::move(domain)), target_(std::move(target)), data_(std::move(data)) {
  check_stored_arrays();
  const auto& m = data_;
  const std::size_t nt = static_cast<std::size_t>(domain_->element_count());
  const std::size_t nn = m.node_type.size(), nr = m.region_target.size();
  require(m.neighbor_begin.size() == nn + 1 && m.neighbor_begin.front() == 0, "neighbor_begin");
  require(std::is_sorted(m.neighbor_begin.begin(), m.neighbor_begin.end()), "neighbor_begin order");
  require(m.neighbor.size() == static_cast<std::size_t>(m.neighbor_begin.back()) &&
              m.neighbor_edge_kind.size() == m.neighbor.size(),
          "neighbor array sizes");
  if constexpr (d == 2) {
    require(m.edge_node_begin.size() == 3 * nt + 1 && m.edge_node_begin.front() == 0,
            "edge_node_begin size");
    require(std::is_sorted(m.edge_node_begin.begin(), m.edge_node_begin.end()),
            "edge_node_begin order");
    require(m.edge_node.size() == static_cast<std::size_t>(m.edge_node_begin.back()),
            "edge_node size");
  }
  require(m.region_neighbors.size() == nr, "region array sizes");
  auto below = [](Index i, std::size_t n) { return static_cast<std::size_t>(static_cast<std::uint32_t>(i)) < n; };
  bool neighbors_ok = true;
  for (const auto& rn : m.region_neighbors)
    for (Index q : rn) neighbors_ok &= (q == invalid_index) | below(q, nr);
  require(neighbors_ok, "region neighbor out of range");
  bool indices_ok = true;
  for (Index x : m.neighbor) indices_ok &= below(x, nn);
  require(indices_ok, "neighbor index");
  for (Index x : m.edge_node) indices_ok &= below(x, nn);
  require(indices_ok, "edge node index");
  if constexpr (d == 2) keep_only_underived_graph();
}

template <int d>
  requires SurfaceDimension<d>
PlMap<d>::PlMap(std::shared_ptr<const Surface<d>> domain, std::shared_ptr<const Surface<d>> target,
                MapData<d> stored, StoredGraph graph)
  requires(d == 2)
    : domain_(std::move(domain)), target_(std::move(target)), data_(std::move(stored)), stored_graph_(std::move(graph)) {
  const auto& m = data_;
  require(m.neighbor_begin.empty() && m.neighbor.empty() && m.neighbor_edge_kind.empty() &&
              m.edge_node_begin.empty() && m.edge_node.empty() && m.region_neighbors.empty(),
          "the stored form holds graph arrays (they belong in StoredGraph)");
  check_stored_arrays();
  check_stored_graph();
  shrink_stored_graph(stored_graph_);
}

template <int d>
  requires SurfaceDimension<d>
void PlMap<d>::check_stored_arrays() const {
  require(domain_ && target_, "missing surface");
  const auto& m = data_;
  const std::size_t nt = static_cast<std::size_t>(domain_->element_count());
  require(m.node_begin.size() == nt + 1 && m.node_begin.front() == 0, "node_begin size");
  require(std::is_sorted(m.node_begin.begin(), m.node_begin.end()), "node_begin order");
  const std::size_t nn = static_cast<std::size_t>(m.node_begin.back());
  require(m.node_position.size() == nn && m.node_type.size() == nn &&
              m.node_location.size() == nn && m.node_image_element.size() == nn &&
              m.node_image_local.size() == nn && m.node_target.size() == nn,
          "node array sizes");
  require(m.region_begin.size() == nt + 1 && m.region_begin.front() == 0, "region_begin size");
  require(std::is_sorted(m.region_begin.begin(), m.region_begin.end()), "region_begin order");
  const std::size_t nr = static_cast<std::size_t>(m.region_begin.back());
  require(m.region_corners.size() == nr && m.region_target.size() == nr && m.region_map.size() == nr,
          "region array sizes");
  require(m.start_region.size() == nt, "start_region size");
  require(m.orientation == 1 || m.orientation == -1, "orientation must be +1 or -1");
  // Indices that queries dereference must be in range, so that a corrupt file cannot make an
  // evaluation read out of bounds. verify/ checks everything else. These loops run over every
  // region and node of maps with millions of them, so each check is a branch-free reduction (an
  // index i is in [0, n) exactly when it is below n as an unsigned number).
  const auto n2 = static_cast<std::uint32_t>(target_->element_count());
  auto below = [](Index i, std::size_t n) { return static_cast<std::size_t>(static_cast<std::uint32_t>(i)) < n; };
  bool targets_ok = true, corners_ok = true;
  for (std::size_t r = 0; r < nr; ++r) {
    targets_ok &= below(m.region_target[r], n2);
    for (Index c : m.region_corners[r]) corners_ok &= below(c, nn);
  }
  require(targets_ok, "region_target out of range");
  require(corners_ok, "region corner out of range");
  for (std::size_t t = 0; t < nt; ++t) {
    const Index s = m.start_region[t];
    require(s == invalid_index ? m.region_begin[t] == m.region_begin[t + 1]
                               : (s >= m.region_begin[t] && s < m.region_begin[t + 1]),
            "start_region outside its element");
  }
  bool images_ok = true;
  for (const Index element : m.node_image_element) images_ok &= below(element, n2);
  require(images_ok, "node image element out of range");
}


template <int d>
  requires SurfaceDimension<d>
void PlMap<d>::check_stored_graph() const {
  const StoredGraph& g = stored_graph_;
  const auto& m = data_;
  if constexpr (d == 1) {
    require(g == StoredGraph{}, "a segment map stores its graph in its arrays");
    return;
  }
  const Index nt = domain_->element_count();
  const std::size_t nn = m.node_type.size(), nr = m.region_target.size();
  auto below = [](Index i, std::size_t n) { return static_cast<std::size_t>(static_cast<std::uint32_t>(i)) < n; };
  std::size_t nodes = 0, regions = 0;
  for (std::size_t e = 0; e < g.element.size(); ++e) {
    const Index t = g.element[e];
    require(t >= 0 && t < nt && (e == 0 || g.element[e - 1] < t), "stored graph elements out of order or range");
    nodes += static_cast<std::size_t>(m.node_begin[t + 1] - m.node_begin[t]);
    regions += static_cast<std::size_t>(m.region_begin[t + 1] - m.region_begin[t]);
  }
  require(g.neighbor_count.size() == nodes && g.edge_node_count.size() == 3 * g.element.size() &&
              g.region_neighbors.size() == regions,
          "stored graph sizes");
  std::size_t entries = 0, edge_entries = 0;
  bool counts_ok = true;
  for (Index c : g.neighbor_count) {
    counts_ok &= c >= 0;
    entries += static_cast<std::size_t>(c);
  }
  for (Index c : g.edge_node_count) {
    counts_ok &= c >= 0;
    edge_entries += static_cast<std::size_t>(c);
  }
  require(counts_ok && g.neighbor.size() == entries && g.neighbor_edge_kind.size() == entries &&
              g.edge_node.size() == edge_entries,
          "stored graph sizes");
  bool indices_ok = true;
  for (Index x : g.neighbor) indices_ok &= below(x, nn);
  require(indices_ok, "neighbor index");
  for (GraphEdgeKind k : g.neighbor_edge_kind) indices_ok &= static_cast<int>(k) <= 1;
  require(indices_ok, "neighbor edge kind");
  for (Index x : g.edge_node) indices_ok &= below(x, nn);
  require(indices_ok, "edge node index");
  for (const auto& rn : g.region_neighbors)
    for (Index q : rn) indices_ok &= (q == invalid_index) | below(q, nr);
  require(indices_ok, "region neighbor out of range");
}

namespace {

template <class T>
void release(std::vector<T>& v) {
  std::vector<T>().swap(v);
}

/// The graph arrays that a triangle map derives instead of storing.
template <class Visit>
void for_each_graph_array(MapData<2>& m, Visit&& visit) {
  visit(m.neighbor_begin);
  visit(m.neighbor);
  visit(m.neighbor_edge_kind);
  visit(m.edge_node_begin);
  visit(m.edge_node);
  visit(m.region_neighbors);
}

template <class T>
bool slice_equals(const std::vector<T>& derived, const std::vector<T>& given, std::size_t begin) {
  return begin + derived.size() <= given.size() &&
         std::equal(derived.begin(), derived.end(), given.begin() + static_cast<std::ptrdiff_t>(begin));
}

}  // namespace

template <int d>
  requires SurfaceDimension<d>
void PlMap<d>::keep_only_underived_graph() {
  if constexpr (d == 2) {
    MapData<2>& m = data_;
    const Index nt = domain_->element_count();
    // Whether each element's graph is what the derivation gives: a pure per-element comparison,
    // so it runs on all cores (it costs ~100 ns per node, which a 2-million-node map would
    // otherwise pay serially at every construction and load). The rare elements that differ are
    // gathered afterwards, in element order, on one thread.
    std::vector<unsigned char> derivable_element(static_cast<std::size_t>(nt), 0);
    parallel_for_chunks(static_cast<std::size_t>(nt), 2048, 0, [&](std::size_t begin, std::size_t end) {
      detail::GraphDerivationScratch scratch;
      std::vector<std::array<Index, 3>> region_neighbors;
      std::vector<Index> count, neighbor, edge_count, edge_node;
      std::vector<GraphEdgeKind> kind;
      for (auto t = static_cast<Index>(begin); t < static_cast<Index>(end); ++t) {
        const Index nb = m.node_begin[t];
        const Index rb = m.region_begin[t], re = m.region_begin[t + 1];
        region_neighbors.resize(static_cast<std::size_t>(re - rb));
        count.clear();
        neighbor.clear();
        kind.clear();
        edge_count.clear();
        edge_node.clear();
        bool derivable = detail::derive_region_neighbors(m, t, region_neighbors, scratch) &&
                         slice_equals(region_neighbors, m.region_neighbors, static_cast<std::size_t>(rb)) &&
                         detail::derive_neighbor_lists(m, *target_, t, region_neighbors, count, neighbor, kind, scratch);
        for (std::size_t i = 0; derivable && i < count.size(); ++i)
          derivable = count[i] == m.neighbor_begin[static_cast<std::size_t>(nb) + i + 1] -
                                      m.neighbor_begin[static_cast<std::size_t>(nb) + i];
        const auto entries = static_cast<std::size_t>(m.neighbor_begin[static_cast<std::size_t>(nb)]);
        derivable = derivable && slice_equals(neighbor, m.neighbor, entries) &&
                    slice_equals(kind, m.neighbor_edge_kind, entries);
        if (derivable) {
          detail::derive_edge_nodes(m, t, edge_count, edge_node);
          for (int k = 0; derivable && k < 3; ++k)
            derivable = edge_count[static_cast<std::size_t>(k)] ==
                        m.edge_node_begin[3 * static_cast<std::size_t>(t) + static_cast<std::size_t>(k) + 1] -
                            m.edge_node_begin[3 * static_cast<std::size_t>(t) + static_cast<std::size_t>(k)];
          derivable = derivable && slice_equals(edge_node, m.edge_node,
                                                static_cast<std::size_t>(m.edge_node_begin[3 * static_cast<std::size_t>(t)]));
        }
        derivable_element[static_cast<std::size_t>(t)] = derivable ? 1 : 0;
      }
    });
    StoredGraph& kept = stored_graph_;
    for (Index t = 0; t < nt; ++t) {
      if (derivable_element[static_cast<std::size_t>(t)]) continue;
      const Index nb = m.node_begin[t], ne = m.node_begin[t + 1];
      const Index rb = m.region_begin[t], re = m.region_begin[t + 1];
      kept.element.push_back(t);
      for (Index n = nb; n < ne; ++n) {
        kept.neighbor_count.push_back(m.neighbor_begin[n + 1] - m.neighbor_begin[n]);
        for (Index j = m.neighbor_begin[n]; j < m.neighbor_begin[n + 1]; ++j) {
          kept.neighbor.push_back(m.neighbor[j]);
          kept.neighbor_edge_kind.push_back(m.neighbor_edge_kind[j]);
        }
      }
      for (std::size_t i = 3 * static_cast<std::size_t>(t); i < 3 * static_cast<std::size_t>(t) + 3; ++i) {
        kept.edge_node_count.push_back(m.edge_node_begin[i + 1] - m.edge_node_begin[i]);
        for (Index j = m.edge_node_begin[i]; j < m.edge_node_begin[i + 1]; ++j) kept.edge_node.push_back(m.edge_node[j]);
      }
      for (Index r = rb; r < re; ++r) kept.region_neighbors.push_back(m.region_neighbors[r]);
    }
    for_each_graph_array(m, [](auto& v) { release(v); });
    kept.known_minimal = true;  // every element was compared above
    check_stored_graph();
    shrink_stored_graph(kept);
  }
}

template <int d>
  requires SurfaceDimension<d>
PlMap<d>::PlMap(const PlMap& other)
    : domain_(other.domain_),
      target_(other.target_),
      data_(other.data_),
      stored_graph_(other.stored_graph_),
      provenance_(other.provenance_) {
  if constexpr (d == 2) for_each_graph_array(data_, [](auto& v) { release(v); });
}

template <int d>
  requires SurfaceDimension<d>
PlMap<d>& PlMap<d>::operator=(const PlMap& other) {
  if (this != &other) *this = PlMap(other);
  return *this;
}

template <int d>
  requires SurfaceDimension<d>
PlMap<d>::~PlMap() = default;

template <int d>
  requires SurfaceDimension<d>
void PlMap<d>::set_provenance(MapProvenance provenance) {
  validate_provenance(provenance);
  provenance_ = std::move(provenance);
}

template <int d>
  requires SurfaceDimension<d>
void PlMap<d>::derive_region_neighbors() const {
  if constexpr (d == 2) {
    MapData<2>& m = data_;
    const Index nt = domain_->element_count();
    m.region_neighbors.resize(m.region_target.size());
    detail::GraphDerivationScratch scratch;
    std::size_t kept = 0, kept_region = 0;
    for (Index t = 0; t < nt; ++t) {
      const auto rb = static_cast<std::size_t>(m.region_begin[t]), re = static_cast<std::size_t>(m.region_begin[t + 1]);
      if (kept < stored_graph_.element.size() && stored_graph_.element[kept] == t) {
        std::copy_n(stored_graph_.region_neighbors.begin() + static_cast<std::ptrdiff_t>(kept_region), re - rb,
                    m.region_neighbors.begin() + static_cast<std::ptrdiff_t>(rb));
        kept_region += re - rb;
        ++kept;
        continue;
      }
      // Elements that store no graph are tiled by their regions, so the derivation succeeds;
      // where a damaged file says otherwise, the element's regions get no neighbours (verify
      // reports the element, and walks stay inside the element's regions).
      const auto out = std::span(m.region_neighbors).subspan(rb, re - rb);
      if (!detail::derive_region_neighbors(m, t, out, scratch))
        std::fill(out.begin(), out.end(), std::array<Index, 3>{invalid_index, invalid_index, invalid_index});
    }
  }
}

template <int d>
  requires SurfaceDimension<d>
void PlMap<d>::derive_graph() const {
  if constexpr (d == 2) {
    region_neighbors();
    MapData<2>& m = data_;
    m.neighbor.clear();
    m.neighbor_edge_kind.clear();
    m.edge_node.clear();
    const StoredGraph& kept = stored_graph_;
    const Index nt = domain_->element_count();
    const std::size_t nn = m.node_type.size();
    std::vector<Index> count, edge_count;
    count.reserve(nn);
    edge_count.reserve(3 * static_cast<std::size_t>(nt));
    m.neighbor.reserve(6 * nn);
    m.neighbor_edge_kind.reserve(6 * nn);
    detail::GraphDerivationScratch scratch;
    std::size_t e = 0, node = 0, entry = 0, edge = 0, edge_entry = 0;
    for (Index t = 0; t < nt; ++t) {
      if (e < kept.element.size() && kept.element[e] == t) {
        for (Index n = m.node_begin[t]; n < m.node_begin[t + 1]; ++n) {
          const Index c = kept.neighbor_count[node++];
          count.push_back(c);
          for (Index j = 0; j < c; ++j, ++entry) {
            m.neighbor.push_back(kept.neighbor[entry]);
            m.neighbor_edge_kind.push_back(kept.neighbor_edge_kind[entry]);
          }
        }
        for (int k = 0; k < 3; ++k) {
          const Index c = kept.edge_node_count[edge++];
          edge_count.push_back(c);
          for (Index j = 0; j < c; ++j) m.edge_node.push_back(kept.edge_node[edge_entry++]);
        }
        ++e;
        continue;
      }
      const auto rb = static_cast<std::size_t>(m.region_begin[t]), re = static_cast<std::size_t>(m.region_begin[t + 1]);
      const std::size_t counted = count.size(), entries = m.neighbor.size();
      if (!detail::derive_neighbor_lists(m, *target_, t,
                                         std::span<const std::array<Index, 3>>(m.region_neighbors).subspan(rb, re - rb),
                                         count, m.neighbor, m.neighbor_edge_kind, scratch)) {
        // a damaged file (see derive_region_neighbors above): no neighbour lists on this element
        count.resize(counted);
        count.resize(counted + static_cast<std::size_t>(m.node_begin[t + 1] - m.node_begin[t]), 0);
        m.neighbor.resize(entries);
        m.neighbor_edge_kind.resize(entries);
      }
      detail::derive_edge_nodes(m, t, edge_count, m.edge_node);
    }
    auto prefix = [](const std::vector<Index>& c, std::vector<Index>& begin) {
      begin.resize(c.size() + 1);
      begin[0] = 0;
      for (std::size_t i = 0; i < c.size(); ++i) begin[i + 1] = begin[i] + c[i];
    };
    prefix(count, m.neighbor_begin);
    prefix(edge_count, m.edge_node_begin);
    m.neighbor.shrink_to_fit();
    m.neighbor_edge_kind.shrink_to_fit();
    m.edge_node.shrink_to_fit();
  }
}

template <int d>
  requires SurfaceDimension<d>
const MapData<d>& PlMap<d>::data() const {
  if constexpr (d == 2) {
    if (!derived_->graph_ready.load(std::memory_order_acquire)) {
      std::call_once(derived_->graph, [this] { derive_graph(); });
      derived_->graph_ready.store(true, std::memory_order_release);
    }
  }
  return data_;
}

template <int d>
  requires SurfaceDimension<d>
std::span<const std::array<Index, d + 1>> PlMap<d>::region_neighbors() const {
  if constexpr (d == 2) {
    if (!derived_->region_neighbors_ready.load(std::memory_order_acquire)) {
      std::call_once(derived_->region_neighbors, [this] { derive_region_neighbors(); });
      derived_->region_neighbors_ready.store(true, std::memory_order_release);
    }
  }
  return data_.region_neighbors;
}

template <int d>
  requires SurfaceDimension<d>
MapData<d> PlMap<d>::release_data() && {
  data();
  return std::move(data_);
}

template <int d>
  requires SurfaceDimension<d>
std::pair<MapData<d>, StoredGraph> PlMap<d>::release_stored_form() &&
  requires(d == 2)
{
  for (auto* v : {&data_.neighbor_begin, &data_.neighbor, &data_.edge_node_begin, &data_.edge_node})
    std::vector<Index>().swap(*v);
  std::vector<GraphEdgeKind>().swap(data_.neighbor_edge_kind);
  std::vector<std::array<Index, d + 1>>().swap(data_.region_neighbors);
  return {std::move(data_), std::move(stored_graph_)};
}

template <int d>
  requires SurfaceDimension<d>
WorldPoint<d> PlMap<d>::node_domain_world(Index n) const {
  return domain_->world_position(node_element(n), data_.node_position[n]);
}

template <int d>
  requires SurfaceDimension<d>
WorldPoint<d> PlMap<d>::node_target_world(Index n) const {
  const SurfacePoint<d> img = data_.node_image(n);
  return target_->world_position(img.element, img.local);
}

template <int d>
  requires SurfaceDimension<d>
Index PlMap<d>::node_element(Index n) const {
  const auto it = std::upper_bound(data_.node_begin.begin(), data_.node_begin.end(), n);
  return static_cast<Index>(it - data_.node_begin.begin()) - 1;
}

template <int d>
  requires SurfaceDimension<d>
std::size_t PlMap<d>::memory_bytes() const {
  const auto& m = data_;
  const std::size_t graph = bytes_of(m.neighbor_begin) + bytes_of(m.neighbor) + bytes_of(m.neighbor_edge_kind) +
                            bytes_of(m.edge_node_begin) + bytes_of(m.edge_node) + bytes_of(m.region_neighbors);
  const auto& g = stored_graph_;
  const std::size_t kept = bytes_of(g.element) + bytes_of(g.neighbor_count) + bytes_of(g.neighbor) +
                           bytes_of(g.neighbor_edge_kind) + bytes_of(g.edge_node_count) + bytes_of(g.edge_node) +
                           bytes_of(g.region_neighbors);
  return bytes_of(m.node_begin) + bytes_of(m.node_position) + bytes_of(m.node_type) +
         bytes_of(m.node_location) + bytes_of(m.node_image_element) + bytes_of(m.node_image_local) +
         bytes_of(m.node_target) +
         bytes_of(m.region_begin) + bytes_of(m.region_corners) + bytes_of(m.region_target) +
         bytes_of(m.region_map) + bytes_of(m.start_region) + kept + (d == 2 ? 0 : graph);
}

template <int d>
  requires SurfaceDimension<d>
std::size_t PlMap<d>::derived_bytes() const {
  if constexpr (d == 1) return 0;
  const auto& m = data_;
  return bytes_of(m.neighbor_begin) + bytes_of(m.neighbor) + bytes_of(m.neighbor_edge_kind) +
         bytes_of(m.edge_node_begin) + bytes_of(m.edge_node) + bytes_of(m.region_neighbors);
}

template class PlMap<1>;
template class PlMap<2>;

}  // namespace plmap
