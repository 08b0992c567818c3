#pragma once
/// \file
/// Re-expressing a point of a surface in the local coordinates of another element that
/// contains it. Exact for points on shared vertices and edges: barycentric weights are moved by
/// vertex identity, not recomputed from world positions.

#include <plmap/core/surface.hpp>

#include <optional>

namespace plmap {

/// Local coordinates of `p` on element `to`, or nullopt if `to` does not contain the support of
/// `p` (the vertices with a barycentric weight above `zero_tolerance`).
template <int d>
std::optional<LocalPoint<d>> transfer_to_element(const Surface<d>& surface, const SurfacePoint<d>& p,
                                                 Index to, double zero_tolerance = 1e-12) {
  if (p.element == to) return p.local;
  const Barycentric<d> b = barycentric_from_local<d>(p.local);
  Barycentric<d> out = Barycentric<d>::Zero();
  for (int k = 0; k <= d; ++k) {
    if (std::abs(b(k)) <= zero_tolerance) continue;
    const int j = surface.local_corner(to, surface.element(p.element)[k]);
    if (j < 0) return std::nullopt;
    out(j) = b(k);
  }
  out /= out.sum();
  return local_from_barycentric<d>(out);
}

}  // namespace plmap
