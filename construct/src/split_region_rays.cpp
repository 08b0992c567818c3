// Regions split off faces at a corner without a node that the rays do not back
// (split_region_rays.hpp).

#include "split_region_rays.hpp"

#include <plmap/core/evaluation.hpp>
#include <plmap/core/parallel_ranges.hpp>
#include <plmap/solvers/focal_points.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace plmap::projection {

namespace {

/// Whether the ray from S1 point `local` of element t along the interpolated field meets the
/// plane of `target` within `reach` of Xi there, before any focal point of the element's field
/// (`free`: its focal-free distance).
bool ray_backs(const PlMap<2>& map, std::span<const WorldPoint<2>> directions, double free, Index t, Index region,
               const LocalPoint<2>& local, Index target, double reach) {
  const Surface<2>& s1 = map.domain();
  const Surface<2>& s2 = map.target();
  std::array<WorldPoint<2>, 3> corners, nus;
  for (int k = 0; k < 3; ++k) {
    corners[k] = s1.corner(t, k);
    nus[k] = directions[s1.element(t)[k]];
  }
  const WorldPoint<2> nu = nus[0] + local(0) * (nus[1] - nus[0]) + local(1) * (nus[2] - nus[0]);
  const WorldPoint<2> x = s1.world_position(t, local);
  const WorldPoint<2> y = evaluate_in_region(map, region, local).world;
  const WorldPoint<2> p0 = s2.corner(target, 0);
  const WorldPoint<2> normal = (s2.corner(target, 1) - p0).cross(s2.corner(target, 2) - p0);
  const double along = nu.dot(normal);
  if (!(std::abs(along) > 0.0)) return false;  // the ray runs parallel to the element
  const double mu = (p0 - x).dot(normal) / along;
  if (!((x + mu * nu - y).norm() <= reach)) return false;
  return std::abs(mu) <= free || reaches_without_focal_point<2>(corners, nus, local, mu);
}

}  // namespace

std::vector<Index> split_regions_off_their_rays(const PlMap<2>& map, std::span<const WorldPoint<2>> directions,
                                                std::span<const double> focal_free_reach,
                                                std::span<const Index> candidates, unsigned threads) {
  const Surface<2>& s2 = map.target();
  const auto& m = map.stored();
  std::vector<char> off(candidates.size(), 0);
  parallel_for_chunks(candidates.size(), 256, threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const Index r = candidates[i];
      // a region's corners are nodes of its own element, numbered with it
      const auto t = static_cast<Index>(std::upper_bound(m.region_begin.begin(), m.region_begin.end(), r) -
                                        m.region_begin.begin() - 1);
      const Index target = m.region_target[r];
      std::array<LocalPoint<2>, 3> at;
      for (int k = 0; k < 3; ++k) at[k] = m.node_position[m.region_corners[r][k]];
      double edges = 0.0;
      for (int k = 0; k < 3; ++k) edges += (s2.corner(target, (k + 1) % 3) - s2.corner(target, k)).norm();
      const double reach = 0.5 * edges / 3.0;
      const std::array<LocalPoint<2>, 4> samples{(at[0] + at[1] + at[2]) / 3.0, 0.5 * (at[0] + at[1]),
                                                 0.5 * (at[1] + at[2]), 0.5 * (at[2] + at[0])};
      off[i] = !std::all_of(samples.begin(), samples.end(), [&](const LocalPoint<2>& local) {
        return ray_backs(map, directions, focal_free_reach[t], t, r, local, target, reach);
      });
    }
  });
  std::vector<Index> regions;
  for (std::size_t i = 0; i < candidates.size(); ++i)
    if (off[i]) regions.push_back(candidates[i]);
  return regions;
}

}  // namespace plmap::projection
