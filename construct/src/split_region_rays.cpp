// Regions split off faces without a target that the rays do not back (split_region_rays.hpp).

#include "split_region_rays.hpp"

#include <plmap/core/evaluation.hpp>
#include <plmap/core/parallel_ranges.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace plmap::projection {

namespace {

/// Local coordinates on S1 element t of a world point on its plane (a node of a neighbouring
/// element, on the common edge).
LocalPoint<2> local_on(const Surface<2>& s, Index t, const WorldPoint<2>& x) {
  const WorldPoint<2> c0 = s.corner(t, 0);
  const WorldPoint<2> e1 = s.corner(t, 1) - c0, e2 = s.corner(t, 2) - c0, v = x - c0;
  const double a = e1.dot(e1), b = e1.dot(e2), c = e2.dot(e2);
  const double p = e1.dot(v), q = e2.dot(v);
  const double det = a * c - b * b;
  return LocalPoint<2>((c * p - b * q) / det, (a * q - b * p) / det);
}

/// Whether the ray from S1 point `local` of element t along the interpolated field meets the
/// plane of `target` within `reach` of Xi there.
bool ray_backs(const PlMap<2>& map, std::span<const WorldPoint<2>> directions, Index t, Index region,
               const LocalPoint<2>& local, Index target, double reach) {
  const Surface<2>& s1 = map.domain();
  const Surface<2>& s2 = map.target();
  const auto& corners = s1.element(t);
  const WorldPoint<2> nu = directions[corners[0]] + local(0) * (directions[corners[1]] - directions[corners[0]]) +
                           local(1) * (directions[corners[2]] - directions[corners[0]]);
  const WorldPoint<2> x = s1.world_position(t, local);
  const WorldPoint<2> y = evaluate_in_region(map, region, local).world;
  const WorldPoint<2> p0 = s2.corner(target, 0);
  const WorldPoint<2> normal = (s2.corner(target, 1) - p0).cross(s2.corner(target, 2) - p0);
  const double along = nu.dot(normal);
  if (!(std::abs(along) > 0.0)) return false;  // the ray runs parallel to the element
  const WorldPoint<2> hit = x + ((p0 - x).dot(normal) / along) * nu;
  return (hit - y).norm() <= reach;
}

}  // namespace

std::vector<Index> split_regions_off_their_rays(const PlMap<2>& map, std::span<const WorldPoint<2>> directions,
                                                std::span<const Index> split_targets, unsigned threads) {
  if (split_targets.empty()) return {};
  const Surface<2>& s1 = map.domain();
  const Surface<2>& s2 = map.target();
  const auto& m = map.stored();
  // a look-up per region, not a search: most regions of a large map are on other elements
  std::vector<char> listed(static_cast<std::size_t>(s2.element_count()), 0);
  for (Index t2 : split_targets) listed[t2] = 1;
  constexpr std::size_t chunk = 4096;
  const auto n1 = static_cast<std::size_t>(s1.element_count());
  std::vector<std::vector<Index>> found((n1 + chunk - 1) / chunk);
  parallel_for_chunks(n1, chunk, threads, [&](std::size_t begin, std::size_t end) {
    auto& list = found[begin / chunk];
    for (auto t = static_cast<Index>(begin); t < static_cast<Index>(end); ++t)
      for (Index r = map.regions_begin(t); r < map.regions_end(t); ++r) {
        const Index target = m.region_target[r];
        if (!listed[target]) continue;
        std::array<LocalPoint<2>, 3> at;
        for (int k = 0; k < 3; ++k) {
          const Index n = m.region_corners[r][k];
          at[k] = n >= map.nodes_begin(t) && n < map.nodes_end(t) ? m.node_position[n]
                                                                   : local_on(s1, t, map.node_domain_world(n));
        }
        double edges = 0.0;
        for (int k = 0; k < 3; ++k) edges += (s2.corner(target, (k + 1) % 3) - s2.corner(target, k)).norm();
        const double reach = 0.5 * edges / 3.0;
        const std::array<LocalPoint<2>, 4> samples{(at[0] + at[1] + at[2]) / 3.0, 0.5 * (at[0] + at[1]),
                                                   0.5 * (at[1] + at[2]), 0.5 * (at[2] + at[0])};
        if (!std::all_of(samples.begin(), samples.end(), [&](const LocalPoint<2>& local) {
              return ray_backs(map, directions, t, r, local, target, reach);
            }))
          list.push_back(r);
      }
  });
  std::vector<Index> regions;
  for (const auto& list : found) regions.insert(regions.end(), list.begin(), list.end());
  return regions;  // chunks in element order, regions in order within each: sorted
}

}  // namespace plmap::projection
