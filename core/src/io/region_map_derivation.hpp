#pragma once
/// \file
/// The affine maps of a map's regions recomputed from its nodes, so that the binary map file
/// need not store them (they are a third of its bytes): the map taking the corners' positions on
/// the S1 element to their images re-expressed on the region's S2 element (affine_through, as
/// MapBuilder::finalize and smoothing compute them).
///
/// The recomputation is exact for the regions the builder made, not necessarily for maps edited
/// or read from elsewhere, so the writer compares every recomputed map bit for bit with the
/// stored one and stores the ones that differ ("exceptions"); the reader recomputes, applies the
/// exceptions and compares the CRC-32 of the result with the writer's. Private to core.

#include "../weights_by_vertex_identity.hpp"

#include <plmap/core/affine_through.hpp>
#include <plmap/core/pl_map.hpp>

#include <optional>

namespace plmap::binary {

/// The local coordinates on S2 element `t` of a node image stored on element p.element: weights
/// of t's corners 1..d, moved by vertex identity (the weight of p.element's corner 0 is the one
/// not stored, 1 - sum). nullopt if p.element or t is not an element of `s2`.
template <int d>
std::optional<LocalPoint<d>> image_on_element(const Surface<d>& s2, const SurfacePoint<d>& p, Index t) {
  const auto elements = static_cast<std::size_t>(s2.element_count());
  if (static_cast<std::size_t>(static_cast<std::uint32_t>(t)) >= elements ||
      static_cast<std::size_t>(static_cast<std::uint32_t>(p.element)) >= elements) {
    return std::nullopt;
  }
  if (p.element == t) return p.local;
  return detail::weights_by_vertex_identity<d>(s2.element(p.element), s2.element(t), p.local,
                                               [&] { return 1.0 - p.local.sum(); });
}

/// The recomputed affine map of region r, or nullopt if its indices are out of range (the
/// reader runs this before the PlMap constructor's checks). Region corners must be node indices
/// below m.node_position.size() (the caller guarantees it).
template <int d>
std::optional<AffineMap<d>> derived_region_map(const MapData<d>& m, const Surface<d>& s2, std::size_t r) {
  std::array<LocalPoint<d>, d + 1> from, to;
  for (int k = 0; k <= d; ++k) {
    const Index n = m.region_corners[r][k];
    from[k] = m.node_position[n];
    const std::optional<LocalPoint<d>> y = image_on_element(s2, m.node_image(n), m.region_target[r]);
    if (!y) return std::nullopt;
    to[k] = *y;
  }
  return affine_through<d>(from, to);
}

}  // namespace plmap::binary
