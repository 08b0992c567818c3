#pragma once
/// κ_Ξ of a region as smoothing sees it: the condition number of the linear map from the region's
/// triangle on S1 (world coordinates) to its image triangle on S2, the same quantity verify's
/// quality report measures (DESIGN.md §4.7). construct/ does not depend on verify/, so the
/// smoothing guards compute it here; both use the closed form of a 2 × 2 problem.

#include <plmap/core/element_transfer.hpp>
#include <plmap/core/pl_map.hpp>
#include <plmap/core/scaled_geometry.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace plmap::smoothing {

/// Pieces this well conditioned (κ, dimensionless) may get worse in a smoothing step: near an
/// isometry a guard would only stop the weights from trading one good piece for another. So
/// every guard allows κ up to max(its old value, free_condition).
constexpr double free_condition = 3.0;

/// power_of_two_scale<2>({u, v}) (core/scaled_geometry.hpp), the same value without the library
/// calls ilogb and ldexp: for a normal largest coordinate the power of two at or below it is the
/// number with its mantissa bits cleared. κ is evaluated for every region a few times per sweep,
/// and the two calls were a twentieth of the smoothing.
inline double frame_scale(const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
  const double largest = std::max(u.cwiseAbs().maxCoeff(), v.cwiseAbs().maxCoeff());
  if (!(largest >= std::numeric_limits<double>::min()) || !std::isfinite(largest))
    return power_of_two_scale<2>({u, v});  // zero, subnormal, not finite: the general path
  return std::bit_cast<double>(std::bit_cast<std::uint64_t>(largest) & 0x7ff0000000000000ULL);
}

/// The edge vectors p1 - p0, p2 - p0 of a triangle in an orthonormal frame of its plane (first
/// axis along p1 - p0, second towards p2): upper triangular. Scaled by a power of two first, so
/// that the squares inside the norms stay in range. The same frame as verify's quality report,
/// so that a guard here and the reported κ agree even on slivers, where rounding dominates.
inline Eigen::Matrix2d frame_coordinates(const std::array<Eigen::Vector3d, 3>& p) {
  const Eigen::Vector3d du = p[1] - p[0], dv = p[2] - p[0];
  const double scale = frame_scale(du, dv);
  const Eigen::Vector3d u = du / scale, v = dv / scale;
  Eigen::Matrix2d m = Eigen::Matrix2d::Zero();
  const double lu = u.norm();
  if (lu == 0.0) return m;
  const Eigen::Vector3d e1 = u / lu;
  m(0, 0) = lu;
  m(0, 1) = v.dot(e1);
  m(1, 1) = (v - m(0, 1) * e1).norm();
  return scale * m;
}

/// triangle_condition (below) from the two triangles' frame_coordinates: a guard that tries
/// several positions of a region's corners against the same image computes the image's frame once.
inline double frames_condition(const Eigen::Matrix2d& p, const Eigen::Matrix2d& q) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  if (!(p(0, 0) * p(1, 1) > 0.0)) return inf;
  const Eigen::Matrix2d a = q * p.inverse();
  // singular values of a 2 × 2 matrix in closed form
  const double e = 0.5 * (a(0, 0) + a(1, 1)), f = 0.5 * (a(0, 0) - a(1, 1));
  const double g = 0.5 * (a(1, 0) + a(0, 1)), h = 0.5 * (a(1, 0) - a(0, 1));
  const double r1 = std::hypot(e, h), r2 = std::hypot(f, g);
  const double largest = r1 + r2, smallest = std::abs(r1 - r2);
  return smallest > 0.0 ? largest / smallest : inf;
}

/// Condition number of the affine map taking triangle `from` to triangle `to` (both in 3D, each
/// within its own plane); infinite if `from` is degenerate or the map is singular.
inline double triangle_condition(const std::array<Eigen::Vector3d, 3>& from, const std::array<Eigen::Vector3d, 3>& to) {
  return frames_condition(frame_coordinates(from), frame_coordinates(to));
}

/// World position on S2 of corner k of region r, as the quality report takes it: the corner's
/// image moved onto the region's S2 element exactly where it can be (a vertex, an edge), else
/// the region's affine map at the corner (remote_intersection in core/regions.hpp).
/// The same in the local coordinates of the region's S2 element; `fitted` (if given) is set when
/// the position came from the region's affine map (the image is not on that element's closure).
inline LocalPoint<2> region_corner_target_local(const PlMap<2>& map, Index r, int k, bool* fitted = nullptr) {
  const auto& m = map.stored();
  const Index n = m.region_corners[r][k];
  const std::optional<LocalPoint<2>> moved = transfer_to_element(map.target(), m.node_image(n), m.region_target[r]);
  if (fitted != nullptr) *fitted = !moved;
  return moved ? *moved : LocalPoint<2>(apply<2>(m.region_map[r], m.node_position[n]));
}
inline Eigen::Vector3d region_corner_target_world(const PlMap<2>& map, Index r, int k) {
  return map.target().world_position(map.stored().region_target[r], region_corner_target_local(map, r, k));
}

/// κ of region r of a surface map.
inline double region_condition(const PlMap<2>& map, Index r) {
  const auto& c = map.stored().region_corners[r];
  return triangle_condition({map.node_domain_world(c[0]), map.node_domain_world(c[1]), map.node_domain_world(c[2])},
                            {region_corner_target_world(map, r, 0), region_corner_target_world(map, r, 1),
                             region_corner_target_world(map, r, 2)});
}

/// The κ of each region of S1 element t into `out` (if given; indexed by region - region_begin[t])
/// and the largest of them (1 for an element without regions): exactly region_condition(map, r)
/// for each, with each node's world position computed once instead of once per region corner (a
/// node is a corner of about six regions).
inline double region_conditions_of_element(const PlMap<2>& map, Index t, double* out) {
  const auto& m = map.stored();
  const Index nb = m.node_begin[t], ne = m.node_begin[t + 1];
  thread_local std::vector<Eigen::Vector3d> world;
  world.resize(static_cast<std::size_t>(ne - nb));
  for (Index n = nb; n < ne; ++n) world[static_cast<std::size_t>(n - nb)] = map.domain().world_position(t, m.node_position[n]);
  double worst = 1.0;
  for (Index r = m.region_begin[t]; r < m.region_begin[t + 1]; ++r) {
    const auto& c = m.region_corners[r];
    const auto at = [&](int k) { return world[static_cast<std::size_t>(c[k] - nb)]; };
    const double kappa = triangle_condition({at(0), at(1), at(2)},
                                            {region_corner_target_world(map, r, 0), region_corner_target_world(map, r, 1),
                                             region_corner_target_world(map, r, 2)});
    if (out != nullptr) out[r - m.region_begin[t]] = kappa;
    worst = std::max(worst, kappa);
  }
  return worst;
}

/// The largest κ of the regions of S1 element t (1 for an element without regions).
inline double worst_condition_of_element(const PlMap<2>& map, Index t) { return region_conditions_of_element(map, t, nullptr); }

/// Per S1 element, the largest κ of its regions (1 for an element without regions).
inline std::vector<double> worst_condition_per_element(const PlMap<2>& map) {
  std::vector<double> worst(static_cast<std::size_t>(map.domain().element_count()), 1.0);
  for (Index t = 0; t < map.domain().element_count(); ++t) worst[static_cast<std::size_t>(t)] = worst_condition_of_element(map, t);
  return worst;
}

/// κ of every region of a map (region order) and, per S1 element, the largest of its regions':
/// what the smoothing's guards read, kept up to date as elements change, and handed out so that
/// a caller's κ report need not evaluate the map again (SmoothOptions::summarize_kappa).
struct MapConditions {
  std::vector<double> region;   ///< per region
  std::vector<double> element;  ///< per S1 element: max(1, its regions')

  static MapConditions of(const PlMap<2>& map) {
    MapConditions c;
    c.region.assign(static_cast<std::size_t>(map.region_count()), 1.0);
    c.element.assign(static_cast<std::size_t>(map.domain().element_count()), 1.0);
    for (Index t = 0; t < map.domain().element_count(); ++t) c.update(map, t);
    return c;
  }
  /// Element t of `map` changed, its regions' indices did not.
  void update(const PlMap<2>& map, Index t) {
    element[static_cast<std::size_t>(t)] =
        region_conditions_of_element(map, t, region.data() + map.stored().region_begin[t]);
  }
  /// The values for `map`, whose elements marked in `changed` differ from those of `old_map`
  /// (for which these values are) and whose other elements have the same regions, possibly at
  /// other indices.
  MapConditions moved_to(const PlMap<2>& old_map, const PlMap<2>& map, const std::vector<char>& changed) const {
    MapConditions c;
    c.region.assign(static_cast<std::size_t>(map.region_count()), 1.0);
    c.element = element;
    const auto& from = old_map.stored().region_begin;
    const auto& to = map.stored().region_begin;
    for (Index t = 0; t < map.domain().element_count(); ++t) {
      // (a region count that differs means the element did change: recomputed, never misread)
      if (changed[static_cast<std::size_t>(t)] || from[t + 1] - from[t] != to[t + 1] - to[t]) {
        c.update(map, t);
        continue;
      }
      std::copy(region.begin() + from[t], region.begin() + from[t + 1], c.region.begin() + to[t]);
    }
    return c;
  }
};

}  // namespace plmap::smoothing
