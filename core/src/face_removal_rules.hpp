#pragma once
// What remove_faces (face_removal.hpp) decides per element, shared by its two paths: the one
// on a map's full arrays (face_removal.cpp) and the one on a triangle map's stored form
// (face_removal_stored_form.cpp).

#include <plmap/core/pl_map.hpp>

#include <array>
#include <cstdint>

namespace plmap::detail {

/// Bit k is set when node n lies on local edge k of its element (edge k joins corners k and
/// k + 1, so corner k lies on edges k and k + 2).
inline std::uint8_t element_edges_through(const MapData<2>& m, Index n) {
  const int k = m.node_location[n];
  if (is_at_corner(m.node_type[n])) return static_cast<std::uint8_t>((1u << k) | (1u << ((k + 2) % 3)));
  if (is_on_edge(m.node_type[n])) return static_cast<std::uint8_t>(1u << k);
  return 0;
}

/// Whether a region with corners c has the side a-b (either direction).
template <std::size_t n>
bool has_side(const std::array<Index, n>& c, Index a, Index b) {
  for (std::size_t i = 0; i < n; ++i) {
    const Index x = c[i], y = c[(i + 1) % n];
    if ((x == a && y == b) || (x == b && y == a)) return true;
  }
  return false;
}

}  // namespace plmap::detail
