// Pairs of elements that meet without sharing a vertex (self_intersections.hpp).

#include <plmap/verify/self_intersections.hpp>

#include "cgal_triangles.hpp"

#include <plmap/core/parallel_ranges.hpp>

#include <algorithm>

namespace plmap {

template <int d>
  requires SurfaceDimension<d>
std::vector<std::pair<Index, Index>> self_intersections(const Surface<d>& s, unsigned threads) {
  using namespace verify_detail;
  const TargetTriangles<d> triangles(s);
  Tree tree(triangles.triangles.cbegin(), triangles.triangles.cend());
  tree.build();
  const SelfCrossings<d> crossings(s, triangles, tree);
  // the tree's queries are read-only once it is built: pieces of the triangles on all threads
  constexpr std::size_t chunk = 8192;
  const std::size_t n = triangles.triangles.size();
  std::vector<std::vector<std::pair<Index, Index>>> found((n + chunk - 1) / chunk);
  parallel_for_chunks(n, chunk, threads, [&](std::size_t begin, std::size_t end) {
    auto& list = found[begin / chunk];
    std::vector<TriangleIterator> candidates;
    for (std::size_t i = begin; i < end; ++i) {
      const Index a = triangles.element[i];
      crossings.for_each_met(i, candidates, [&](std::size_t j) {
        if (const Index b = triangles.element[j]; a < b) list.emplace_back(a, b);
      });
    }
  });
  std::vector<std::pair<Index, Index>> pairs;
  for (const auto& list : found) pairs.insert(pairs.end(), list.begin(), list.end());
  // a curve's segment is two triangles, which may both meet the other's
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

template std::vector<std::pair<Index, Index>> self_intersections<1>(const Surface<1>&, unsigned);
template std::vector<std::pair<Index, Index>> self_intersections<2>(const Surface<2>&, unsigned);

}  // namespace plmap
