#include <plmap/core/errors.hpp>
#include <plmap/core/pl_map.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>

namespace plmap {

namespace {

template <class T>
std::size_t bytes_of(const std::vector<T>& v) {
  return v.capacity() * sizeof(T);
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
  require(domain_ && target_, "missing surface");
  const auto& m = data_;
  const std::size_t nt = static_cast<std::size_t>(domain_->element_count());
  require(m.node_begin.size() == nt + 1 && m.node_begin.front() == 0, "node_begin size");
  require(std::is_sorted(m.node_begin.begin(), m.node_begin.end()), "node_begin order");
  const std::size_t nn = static_cast<std::size_t>(m.node_begin.back());
  require(m.node_position.size() == nn && m.node_type.size() == nn &&
              m.node_location.size() == nn && m.node_image.size() == nn &&
              m.node_target.size() == nn,
          "node array sizes");
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
  require(m.region_begin.size() == nt + 1 && m.region_begin.front() == 0, "region_begin size");
  require(std::is_sorted(m.region_begin.begin(), m.region_begin.end()), "region_begin order");
  const std::size_t nr = static_cast<std::size_t>(m.region_begin.back());
  require(m.region_corners.size() == nr && m.region_neighbors.size() == nr &&
              m.region_target.size() == nr && m.region_map.size() == nr,
          "region array sizes");
  require(m.start_region.size() == nt, "start_region size");
  require(m.orientation == 1 || m.orientation == -1, "orientation must be +1 or -1");
  // Indices that queries dereference must be in range, so that a corrupt file cannot make an
  // evaluation read out of bounds. verify/ checks everything else. These loops run over every
  // region, node and neighbour of maps with millions of them, so each check is a branch-free
  // reduction (an index i is in [0, n) exactly when it is below n as an unsigned number).
  const auto n2 = static_cast<std::uint32_t>(target_->element_count());
  auto below = [](Index i, std::size_t n) { return static_cast<std::size_t>(static_cast<std::uint32_t>(i)) < n; };
  bool targets_ok = true, corners_ok = true, neighbors_ok = true;
  for (std::size_t r = 0; r < nr; ++r) {
    targets_ok &= below(m.region_target[r], n2);
    for (Index c : m.region_corners[r]) corners_ok &= below(c, nn);
    for (Index q : m.region_neighbors[r]) neighbors_ok &= (q == invalid_index) | below(q, nr);
  }
  require(targets_ok, "region_target out of range");
  require(corners_ok, "region corner out of range");
  require(neighbors_ok, "region neighbor out of range");
  for (std::size_t t = 0; t < nt; ++t) {
    const Index s = m.start_region[t];
    require(s == invalid_index ? m.region_begin[t] == m.region_begin[t + 1]
                               : (s >= m.region_begin[t] && s < m.region_begin[t + 1]),
            "start_region outside its element");
  }
  bool indices_ok = true;
  for (Index x : m.neighbor) indices_ok &= below(x, nn);
  require(indices_ok, "neighbor index");
  for (Index x : m.edge_node) indices_ok &= below(x, nn);
  require(indices_ok, "edge node index");
  for (const auto& img : m.node_image) indices_ok &= below(img.element, n2);
  require(indices_ok, "node image element out of range");
}

template <int d>
  requires SurfaceDimension<d>
WorldPoint<d> PlMap<d>::node_domain_world(Index n) const {
  return domain_->world_position(node_element(n), data_.node_position[n]);
}

template <int d>
  requires SurfaceDimension<d>
WorldPoint<d> PlMap<d>::node_target_world(Index n) const {
  const auto& img = data_.node_image[n];
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
  return bytes_of(m.node_begin) + bytes_of(m.node_position) + bytes_of(m.node_type) +
         bytes_of(m.node_location) + bytes_of(m.node_image) + bytes_of(m.node_target) +
         bytes_of(m.neighbor_begin) + bytes_of(m.neighbor) + bytes_of(m.neighbor_edge_kind) +
         bytes_of(m.edge_node_begin) + bytes_of(m.edge_node) + bytes_of(m.region_begin) +
         bytes_of(m.region_corners) + bytes_of(m.region_neighbors) + bytes_of(m.region_target) +
         bytes_of(m.region_map) + bytes_of(m.start_region);
}

template class PlMap<1>;
template class PlMap<2>;

}  // namespace plmap
