// Regions on a folded part of the projection (folded_regions.hpp).

#include "folded_regions.hpp"

#include <plmap/core/parallel_ranges.hpp>
#include <plmap/solvers/focal_points.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

namespace plmap::projection {

namespace {

/// The fold test of one element's rays: whether the ray of local point xi, from its point on S1
/// along the interpolated field to a given image, passes a focal point of the element first.
template <int d>
class ElementFoldTest {
 public:
  ElementFoldTest(const Surface<d>& s1, Index t, std::span<const WorldPoint<d>> directions, double free)
      : s1_(s1), t_(t), free_(free) {
    for (int k = 0; k <= d; ++k) {
      corners_[k] = s1.corner(t, k);
      nus_[k] = directions[s1.element(t)[k]];
    }
  }

  bool folded(const LocalPoint<d>& xi, const WorldPoint<d>& image) const {
    WorldPoint<d> nu = nus_[0];
    for (int i = 0; i < d; ++i) nu += xi(i) * (nus_[i + 1] - nus_[0]);
    const double nn = nu.squaredNorm();
    if (!(nn > 0.0)) return false;
    const double mu = (image - s1_.world_position(t_, xi)).dot(nu) / nn;
    // most elements are unfolded up to far beyond their nodes' distances: no polynomial there
    return !(std::abs(mu) <= free_) && !reaches_without_focal_point<d>(corners_, nus_, xi, mu);
  }

 private:
  const Surface<d>& s1_;
  Index t_;
  double free_;
  std::array<WorldPoint<d>, d + 1> corners_, nus_;
};

/// Per region with a folded corner (in element order): the region and which of its corners are
/// folded (bit k for corner k).
/// `elements` (sorted), if not empty, restricts the search to those S1 elements.
template <int d>
std::vector<std::pair<Index, unsigned>> folded_corners(const PlMap<d>& map, std::span<const WorldPoint<d>> directions,
                                                       std::span<const double> focal_free_reach, unsigned threads,
                                                       std::span<const Index> elements = {}) {
  const Surface<d>& s1 = map.domain();
  const auto& m = map.stored();
  // The lists are joined in chunk order, so the chunks only balance the threads: 512 elements,
  // because with 4096 the bones pair of the peer benchmark (4,200 elements) was one chunk and a
  // sliver, one thread's work.
  constexpr std::size_t chunk = 512;
  const auto n1 = elements.empty() ? static_cast<std::size_t>(s1.element_count()) : elements.size();
  std::vector<std::vector<std::pair<Index, unsigned>>> found((n1 + chunk - 1) / chunk);
  parallel_for_chunks(n1, chunk, threads, [&](std::size_t begin, std::size_t end) {
    auto& list = found[begin / chunk];
    // Per node of the element: not judged yet (-1), unfolded (0), folded (1). A node is a corner
    // of up to six regions; its test (the image's world position, mu, maybe the focal
    // polynomial) is made once.
    std::vector<signed char> judged;
    for (std::size_t i_element = begin; i_element < end; ++i_element) {
      const auto t = elements.empty() ? static_cast<Index>(i_element) : elements[i_element];
      if (map.regions_begin(t) == map.regions_end(t)) continue;
      // Equal corner directions (a flat S1 with its exact normals): no ray of the element meets a
      // focal point at any distance, so no node is judged folded (its finite mu is below the
      // infinite reach), and the element's nodes need not be looked at.
      if (focal_free_reach[t] == std::numeric_limits<double>::infinity()) continue;
      const ElementFoldTest<d> test(s1, t, directions, focal_free_reach[t]);
      const Index first_node = map.nodes_begin(t);
      judged.assign(static_cast<std::size_t>(map.nodes_end(t) - first_node), -1);
      // (node_target_world gives the image; the node's point is taken in element t, without
      // node_domain_world's search for the element, a binary search over all elements, which
      // was 40 % of this test on the spheres)
      const auto folded_once = [&](Index n) {
        const auto i = static_cast<std::size_t>(n - first_node);
        if (n < first_node || i >= judged.size()) return test.folded(m.node_position[n], map.node_target_world(n));
        if (judged[i] < 0) judged[i] = test.folded(m.node_position[n], map.node_target_world(n)) ? 1 : 0;
        return judged[i] == 1;
      };
      for (Index r = map.regions_begin(t); r < map.regions_end(t); ++r) {
        unsigned mask = 0;
        for (int k = 0; k <= d; ++k)
          if (folded_once(m.region_corners[r][k])) mask |= 1u << k;
        if (mask) list.emplace_back(r, mask);
      }
    }
  });
  std::vector<std::pair<Index, unsigned>> regions;
  for (const auto& list : found) regions.insert(regions.end(), list.begin(), list.end());
  return regions;  // chunks in element order, regions in order within each: sorted
}

}  // namespace

template <int d>
  requires SurfaceDimension<d>
std::vector<Index> regions_with_folded_corners(const PlMap<d>& map, std::span<const WorldPoint<d>> directions,
                                               std::span<const double> focal_free_reach, unsigned threads) {
  std::vector<Index> regions;
  for (const auto& [r, mask] : folded_corners(map, directions, focal_free_reach, threads)) regions.push_back(r);
  return regions;
}

FoldCuts fold_cuts(const PlMap<2>& map, std::span<const WorldPoint<2>> directions,
                   std::span<const double> focal_free_reach, unsigned threads, std::span<const Index> elements) {
  const auto& m = map.stored();
  const Surface<2>& s1 = map.domain();
  const Surface<2>& s2 = map.target();
  const std::vector<std::pair<Index, unsigned>> folded = folded_corners(map, directions, focal_free_reach, threads, elements);
  // Each region's cut is planned on its own (two bisections of 40 fold tests), on all threads;
  // the lists keep the regions' order.
  std::vector<std::optional<RegionClip>> planned(folded.size());
  parallel_for_chunks(folded.size(), 16, threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      // (named, not a structured binding: the lambda below captures r, which clang before
      // C++20's capture rule for bindings refuses)
      const Index r = folded[i].first;
      const unsigned mask = folded[i].second;
      if (mask == 7u) continue;  // every corner folded: the region leaves whole
      const auto& c = m.region_corners[r];
      const Index t = map.node_element(c[0]);
      const ElementFoldTest<2> test(s1, t, directions, focal_free_reach[t]);
      // Xi at a local point of the region: its affine map (the function the cut must not change)
      const auto folded_at = [&](const LocalPoint<2>& xi) {
        return test.folded(xi, s2.world_position(m.region_target[r], apply<2>(m.region_map[r], xi)));
      };
      // On each side from an unfolded corner u to a folded one f, the last unfolded point found by
      // bisection, moved back towards u by a hundredth of the side: the cut's node there is
      // unfolded with a margin for the rounding of other tests of the same rays.
      std::array<LocalPoint<2>, 2> ends;
      int found = 0;
      for (int k = 0; k < 3; ++k)
        for (int j : {(k + 1) % 3, (k + 2) % 3}) {
          if ((mask >> k) & 1u || !((mask >> j) & 1u)) continue;  // k unfolded, j folded
          const LocalPoint<2> u = m.node_position[c[k]], f = m.node_position[c[j]];
          double lo = 0.0, hi = 1.0;
          for (int step = 0; step < 40; ++step) {
            const double mid = 0.5 * (lo + hi);
            (folded_at(u + mid * (f - u)) ? hi : lo) = mid;
          }
          const LocalPoint<2> end_point = u + std::max(0.0, lo - 0.01) * (f - u);
          if (found < 2) ends[static_cast<std::size_t>(found)] = end_point;
          ++found;
        }
      if (found != 2 || !((ends[1] - ends[0]).norm() > 1e-9)) continue;  // no cut: leaves whole
      // the line through both ends, the unfolded corners on its positive side
      const LocalPoint<2> along = ends[1] - ends[0];
      LocalPoint<2> normal(-along.y(), along.x());
      for (int k = 0; k < 3; ++k)
        if (!((mask >> k) & 1u)) {
          if (normal.dot(m.node_position[c[k]] - ends[0]) < 0.0) normal = -normal;
          break;
        }
      planned[i] = RegionClip{r, normal, -normal.dot(ends[0])};
    }
  });
  FoldCuts cuts;
  for (std::size_t i = 0; i < folded.size(); ++i) {
    if (planned[i])
      cuts.clips.push_back(*planned[i]);
    else
      cuts.whole.push_back(folded[i].first);
  }
  return cuts;
}

template std::vector<Index> regions_with_folded_corners<1>(const PlMap<1>&, std::span<const WorldPoint<1>>,
                                                           std::span<const double>, unsigned);
template std::vector<Index> regions_with_folded_corners<2>(const PlMap<2>&, std::span<const WorldPoint<2>>,
                                                           std::span<const double>, unsigned);

}  // namespace plmap::projection
