// S2's vertex stars as the quadrilateral steps read them; see s2_stars.hpp.

#include "s2_stars.hpp"

#include <plmap/strategies/smoothing/uniform_weights.hpp>

#include <algorithm>
#include <utility>

namespace plmap::smoothing {

S2Stars::S2Stars(const Surface<2>& target, AnySmoothingWeights weights)
    : s2_(target),
      weights_(std::move(weights)),
      ring_known_(static_cast<std::size_t>(target.vertex_count()), 0),
      ring_edges_(static_cast<std::size_t>(target.vertex_count())),
      star_weights_(static_cast<std::size_t>(target.vertex_count())) {}

const std::vector<Index>* S2Stars::ring_edges(Index v) {
  signed char& known = ring_known_[static_cast<std::size_t>(v)];
  if (known == 0) {
    // S2's cyclic order of v's neighbours: next(x) = y for each S2 triangle (v, x, y)
    known = -1;
    const auto star = s2_.vertex_elements(v);
    if (star.empty()) return nullptr;
    thread_local std::vector<std::pair<Index, Index>> next;
    next.clear();
    for (Index s : star) {
      const int k = s2_.local_corner(s, v);
      next.push_back({s2_.element(s)[(k + 1) % 3], s2_.element(s)[(k + 2) % 3]});
    }
    thread_local std::vector<Index> cycle;
    cycle.assign(1, next.front().first);
    while (cycle.size() <= next.size()) {
      const auto it = std::find_if(next.begin(), next.end(), [&](const auto& xy) { return xy.first == cycle.back(); });
      if (it == next.end()) return nullptr;
      if (it->second == cycle.front()) break;
      cycle.push_back(it->second);
    }
    if (cycle.size() != next.size()) return nullptr;
    std::vector<Index>& edges = ring_edges_[static_cast<std::size_t>(v)];
    for (Index x : cycle) edges.push_back(s2_.find_edge(v, x));
    known = 1;
  }
  return known > 0 ? &ring_edges_[static_cast<std::size_t>(v)] : nullptr;
}

std::vector<double> S2Stars::compute(Index v, std::span<const Eigen::Vector3d> ring, bool& fallback) const {
  auto w = weights_(s2_.vertex(v), ring);
  fallback = !w;
  if (!w) w = UniformWeights{}.weights(s2_.vertex(v), ring);
  return std::move(*w);
}

std::span<const double> S2Stars::weights(Index v, std::span<const Eigen::Vector3d> ring, bool whole_star, bool& fallback) {
  if (!whole_star) {
    scratch_ = compute(v, ring, fallback);
    return scratch_;
  }
  CachedWeights& cached = star_weights_[static_cast<std::size_t>(v)];
  if (!cached.known) {
    cached.values = compute(v, ring, cached.fallback);
    cached.known = true;
  }
  fallback = cached.fallback;
  return cached.values;
}

}  // namespace plmap::smoothing
