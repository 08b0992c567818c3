// Merging vertices at exactly the same position (vertex_merging.hpp).

#include <plmap/core/vertex_merging.hpp>

#include <algorithm>
#include <numeric>
#include <vector>

namespace plmap {

template <int d>
  requires SurfaceDimension<d>
Surface<d> merge_coincident_vertices(const Surface<d>& s, VertexMergeReport* report) {
  const Index nv = s.vertex_count();
  // Vertices sorted by position (ties by number): each run of equal positions is one vertex,
  // the first of the run by number. (Comparing with < and == treats 0.0 and -0.0 as equal.)
  std::vector<Index> by_position(static_cast<std::size_t>(nv));
  std::iota(by_position.begin(), by_position.end(), Index{0});
  auto less = [&](Index a, Index b) {
    const WorldPoint<d>&p = s.vertex(a), &q = s.vertex(b);
    for (int i = 0; i <= d; ++i)
      if (p[i] != q[i]) return p[i] < q[i];
    return a < b;
  };
  std::sort(by_position.begin(), by_position.end(), less);
  std::vector<Index> kept_as(static_cast<std::size_t>(nv));
  for (std::size_t i = 0; i < by_position.size(); ++i) {
    const Index v = by_position[i];
    kept_as[v] = i > 0 && s.vertex(by_position[i - 1]) == s.vertex(v) ? kept_as[by_position[i - 1]] : v;
  }
  // New numbers in the old order, only for the vertices that stay.
  std::vector<Index> number(static_cast<std::size_t>(nv), invalid_index);
  std::vector<WorldPoint<d>> vertices;
  VertexMergeReport r;
  for (Index v = 0; v < nv; ++v) {
    if (kept_as[v] == v) {
      number[v] = static_cast<Index>(vertices.size());
      vertices.push_back(s.vertex(v));
    } else {
      ++r.merged_vertices;
    }
  }
  std::vector<ElementCorners<d>> elements(s.elements());
  for (ElementCorners<d>& e : elements)
    for (Index& v : e) v = number[kept_as[v]];
  // Duplicates: elements with the same corners, found by sorting the sorted corner lists.
  std::vector<ElementCorners<d>> keys(elements);
  for (ElementCorners<d>& k : keys) std::sort(k.begin(), k.end());
  std::vector<Index> order(elements.size());
  std::iota(order.begin(), order.end(), Index{0});
  std::sort(order.begin(), order.end(), [&](Index a, Index b) { return keys[a] != keys[b] ? keys[a] < keys[b] : a < b; });
  std::vector<char> duplicate(elements.size(), 0);
  for (std::size_t i = 1; i < order.size(); ++i)
    if (keys[order[i]] == keys[order[i - 1]]) duplicate[order[i]] = 1;
  std::vector<ElementCorners<d>> kept;
  kept.reserve(elements.size());
  for (std::size_t t = 0; t < elements.size(); ++t) {
    if (duplicate[t])
      ++r.duplicate_elements;
    else
      kept.push_back(elements[t]);
  }
  if (report) *report = r;
  return Surface<d>(std::move(vertices), std::move(kept));
}

template Surface<1> merge_coincident_vertices<1>(const Surface<1>&, VertexMergeReport*);
template Surface<2> merge_coincident_vertices<2>(const Surface<2>&, VertexMergeReport*);

}  // namespace plmap
