#pragma once
// Sizing the flat arrays of a map (MapData) while finalize() writes them. Private to the builder.

#include <plmap/core/huge_page_allocator.hpp>
#include <plmap/core/parallel_ranges.hpp>
#include <plmap/core/pl_map.hpp>

#include <cstddef>
#include <functional>
#include <vector>

namespace plmap::detail {

/// Sizes the per-node arrays of a map (or of a part of one) for `nodes` nodes.
template <int d>
void size_node_arrays(MapData<d>& m, std::size_t nodes) {
  m.node_position.resize(nodes);
  m.node_type.resize(nodes);
  m.node_location.resize(nodes);
  m.node_image_element.resize(nodes);
  m.node_image_local.resize(nodes);
  m.node_target.resize(nodes);
  m.neighbor_begin.resize(nodes + 1);
}

/// n entries and the spare room beyond them that BuilderOptions::spare_room asks for.
inline std::size_t with_spare_room(std::size_t n, double spare_room) {
  return spare_room > 0.0 ? n + static_cast<std::size_t>(spare_room * static_cast<double>(n)) + 1024 : n;
}

/// v.shrink_to_fit() (down to `capacity` entries, at least its size), with the copy's pages
/// backed in one call (reserve_for_writing) instead of faulting in one by one as it is written;
/// the room beyond the size is not touched.
template <class Vector>
void shrink_array(Vector& v, std::size_t capacity = 0) {
  Vector copy;
  reserve_on_huge_pages(copy, std::max(capacity, v.size()));
  back_pages(copy.data(), v.size() * sizeof(v[0]));
  copy.assign(v.begin(), v.end());
  v.swap(copy);
}

/// Gives back the slack of arrays that were reserved by an upper bound, so the map holds about
/// what it needs; slack under 1/16 of an array is kept, as copying the array to save it would
/// cost more time (and first-touched memory) than the slack is worth.
template <class... Arrays>
void shrink_arrays(Arrays&... v) {
  ((v.capacity() - v.size() > v.size() / 16 ? shrink_array(v) : void()), ...);
}

/// shrink_arrays for every array of a map.
template <int d>
void shrink_to_fit(MapData<d>& m) {
  shrink_arrays(m.node_begin, m.node_position, m.node_type, m.node_location, m.node_image_element,
                m.node_image_local, m.node_target, m.neighbor_begin, m.neighbor, m.neighbor_edge_kind,
                m.edge_node_begin, m.edge_node,
                m.region_begin, m.region_corners, m.region_neighbors, m.region_target, m.region_map,
                m.start_region);
}

/// shrink_to_fit for the arrays a triangle map keeps in its stored form, all but the graph
/// arrays (hand_over_stored_form moves what is kept of those into a StoredGraph). Called as soon
/// as they are final, while little else is resident: each copy is resident together with its
/// original, and the original stays resident in malloc's heap after it is freed. The arrays are
/// copied on up to `threads` threads, one array per task: on one thread the copies took a
/// serial stretch of a two-thread projection (about 3 ms on the femur pair).
inline void shrink_stored_form(MapData<2>& m, unsigned threads = 1, double spare_room = 0.0) {
  std::vector<std::function<void()>> copies;
  // the node and region arrays keep the spare room (BuilderOptions::spare_room)
  auto add = [&](double spare, auto&... v) {
    ((v.capacity() - v.size() > v.size() / 16
          ? copies.push_back([&v, spare] { shrink_array(v, with_spare_room(v.size(), spare)); })
          : void()),
     ...);
  };
  add(0.0, m.node_begin, m.region_begin, m.start_region);
  add(spare_room, m.node_position, m.node_type, m.node_location, m.node_image_element, m.node_image_local,
      m.node_target, m.region_corners, m.region_target, m.region_map);
  parallel_for_pieces_of_size(copies.size(), 1, threads, [&](std::size_t k, std::size_t, std::size_t) { copies[k](); });
}

}  // namespace plmap::detail
