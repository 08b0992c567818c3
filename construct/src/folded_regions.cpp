// Regions on a folded part of the projection (folded_regions.hpp).

#include "folded_regions.hpp"

#include <plmap/core/parallel_ranges.hpp>
#include <plmap/solvers/focal_points.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace plmap::projection {

template <int d>
  requires SurfaceDimension<d>
std::vector<Index> regions_with_folded_corners(const PlMap<d>& map, std::span<const WorldPoint<d>> directions,
                                               std::span<const double> focal_free_reach, unsigned threads) {
  const Surface<d>& s1 = map.domain();
  const auto& m = map.stored();
  constexpr std::size_t chunk = 4096;
  const auto n1 = static_cast<std::size_t>(s1.element_count());
  std::vector<std::vector<Index>> found((n1 + chunk - 1) / chunk);
  parallel_for_chunks(n1, chunk, threads, [&](std::size_t begin, std::size_t end) {
    auto& list = found[begin / chunk];
    // Per node of the element: not judged yet (-1), unfolded (0), folded (1). A node is a corner
    // of up to six regions; its test (the image's world position, mu, maybe the focal
    // polynomial) is made once.
    std::vector<signed char> judged;
    for (auto t = static_cast<Index>(begin); t < static_cast<Index>(end); ++t) {
      if (map.regions_begin(t) == map.regions_end(t)) continue;
      // Equal corner directions (a flat S1 with its exact normals): no ray of the element meets a
      // focal point at any distance, so no node is judged folded (its finite mu is below the
      // infinite reach), and the element's nodes need not be looked at.
      if (focal_free_reach[t] == std::numeric_limits<double>::infinity()) continue;
      std::array<WorldPoint<d>, d + 1> corners, nus;
      for (int k = 0; k <= d; ++k) {
        corners[k] = s1.corner(t, k);
        nus[k] = directions[s1.element(t)[k]];
      }
      // most elements are unfolded up to far beyond their nodes' distances: no polynomial there
      const double free = focal_free_reach[t];
      // node_domain(n): the world position of node n of element `owner`, as node_domain_world
      // gives it, without its search for the element (a binary search over all elements, which
      // was 40 % of this test on the spheres)
      const auto folded = [&](Index n, Index owner) {
        const LocalPoint<d>& xi = m.node_position[n];
        WorldPoint<d> nu = nus[0];
        for (int i = 0; i < d; ++i) nu += xi(i) * (nus[i + 1] - nus[0]);
        const double nn = nu.squaredNorm();
        if (!(nn > 0.0)) return false;
        const double mu = (map.node_target_world(n) - s1.world_position(owner, xi)).dot(nu) / nn;
        return !(std::abs(mu) <= free) && !reaches_without_focal_point<d>(corners, nus, xi, mu);
      };
      const Index first_node = map.nodes_begin(t);
      judged.assign(static_cast<std::size_t>(map.nodes_end(t) - first_node), -1);
      const auto folded_once = [&](Index n) {
        const auto i = static_cast<std::size_t>(n - first_node);
        if (n < first_node || i >= judged.size()) return folded(n, map.node_element(n));  // not this element's node
        if (judged[i] < 0) judged[i] = folded(n, t) ? 1 : 0;
        return judged[i] == 1;
      };
      for (Index r = map.regions_begin(t); r < map.regions_end(t); ++r)
        if (std::any_of(m.region_corners[r].begin(), m.region_corners[r].end(), folded_once)) list.push_back(r);
    }
  });
  std::vector<Index> regions;
  for (const auto& list : found) regions.insert(regions.end(), list.begin(), list.end());
  return regions;  // chunks in element order, regions in order within each: sorted
}

template std::vector<Index> regions_with_folded_corners<1>(const PlMap<1>&, std::span<const WorldPoint<1>>,
                                                           std::span<const double>, unsigned);
template std::vector<Index> regions_with_folded_corners<2>(const PlMap<2>&, std::span<const WorldPoint<2>>,
                                                           std::span<const double>, unsigned);

}  // namespace plmap::projection
