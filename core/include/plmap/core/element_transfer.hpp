#pragma once
/// \file
/// Re-expressing a point of a surface in the local coordinates of another element that
/// contains it. Exact for points on shared vertices and edges: barycentric weights are moved by
/// vertex identity, not recomputed from world positions.

#include <plmap/core/surface.hpp>

#include <algorithm>
#include <optional>
#include <vector>

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
  // (a division by exactly 1 changes no bit, and the weights nearly always sum to exactly 1: the
  // division's latency was a sixth of the image measures' time, core/src/regions.cpp)
  if (const double sum = out.sum(); sum != 1.0) out /= sum;
  return local_from_barycentric<d>(out);
}

/// The elements other than p.element that contain the edge or vertex p lies on, when p lies on
/// the boundary of its element (barycentric weights within `tolerance` of zero: one zero weight
/// for an edge of a triangle, all but one for a vertex); empty for interior points. These are the
/// elements on which p can also be given (transfer_to_element).
template <int d>
std::vector<Index> elements_sharing_boundary_point(const Surface<d>& surface, const SurfacePoint<d>& p,
                                                   double tolerance) {
  const Barycentric<d> b = barycentric_from_local<d>(p.local);
  int nonzero = 0, zero_corner = -1, support_corner = -1;
  for (int k = 0; k <= d; ++k) {
    if (b(k) <= tolerance)
      zero_corner = k;
    else
      ++nonzero, support_corner = k;
  }
  std::vector<Index> out;
  if (nonzero == d + 1 || nonzero == 0) return out;
  if (nonzero == 1) {
    const auto star = surface.vertex_elements(surface.element(p.element)[support_corner]);
    out.assign(star.begin(), star.end());
  } else if constexpr (d == 2) {
    // on the edge opposite the zero corner: local edge (zero_corner + 1) mod 3
    for (const EdgeIncidence& inc : surface.edge_elements(surface.element_edge(p.element, (zero_corner + 1) % 3)))
      out.push_back(inc.element);
  }
  std::erase(out, p.element);
  return out;
}

}  // namespace plmap
