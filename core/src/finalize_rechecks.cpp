// finalize(): the elements to close again after drops (finalize_rechecks.hpp).

#include "finalize_rechecks.hpp"

#include "finalize_reuse.hpp"

#include <algorithm>
#include <numeric>

namespace plmap::detail {

std::vector<Index> elements_to_close_again(const BuilderContents<2>& in, const DroppedEdges::Changes& changes,
                                           std::span<const Index> failed) {
  std::vector<Index> elements;
  if (changes.whole_edges) {  // the intersection nodes of those edges went everywhere
    elements.resize(static_cast<std::size_t>(in.s1.element_count()));
    std::iota(elements.begin(), elements.end(), Index{0});
    return elements;
  }
  elements.assign(failed.begin(), failed.end());
  auto around_edge = [&](Index edge) {
    for (const EdgeIncidence& incidence : in.s1.edge_elements(edge)) elements.push_back(incidence.element);
  };
  for (const Index s : changes.segments) {
    const Segment& seg = in.segments[s];
    if (seg.along_edge)
      around_edge(seg.where);
    else
      elements.push_back(seg.where);
  }
  for (const Index n : changes.nodes) {
    const Place<2>& place = in.nodes[n].place;
    if (place.kind == PlaceKind::element) {
      elements.push_back(place.index);
    } else if (place.kind == PlaceKind::edge) {
      around_edge(place.index);
    } else {
      const auto star = in.s1.vertex_elements(place.index);
      elements.insert(elements.end(), star.begin(), star.end());
    }
  }
  std::sort(elements.begin(), elements.end());
  elements.erase(std::unique(elements.begin(), elements.end()), elements.end());
  return elements;
}

std::vector<Index> elements_next_to_partial_preimages(const BuilderContents<2>& in, const ElementReuse* reuse) {
  // Piece ends of partly inserted S2 edges, as (edge, node) pairs seen once among their
  // segments' ends. An edge that only leaves S1 across its boundary (a larger S2: the planes of
  // docs/benchmarks.md) has no end inside, and its elements are not suspect.
  std::vector<std::pair<Index, Index>> ends;
  bool rim = false;
  for (const Segment& seg : in.segments) {
    if (seg.target_edge == invalid_index) {
      rim = true;
    } else if (in.edge_inserted[static_cast<std::size_t>(seg.target_edge)] == edge_partial) {
      ends.emplace_back(seg.target_edge, seg.a);
      ends.emplace_back(seg.target_edge, seg.b);
    }
  }
  if (ends.empty() && !rim) return {};
  std::sort(ends.begin(), ends.end());
  std::vector<char> stopped_inside(in.edge_inserted.size(), 0);
  for (std::size_t i = 0; i < ends.size();) {
    std::size_t j = i + 1;
    while (j < ends.size() && ends[j] == ends[i]) ++j;
    const BuilderNode<2>& node = in.nodes[static_cast<std::size_t>(ends[i].second)];
    const Place<2>& at = node.place;
    const bool on_boundary = (at.kind == PlaceKind::edge && in.s1.edge_elements(at.index).size() == 1) ||
                             (at.kind == PlaceKind::vertex && in.s1.is_boundary_vertex(at.index));
    if (j - i == 1 && node.kind != BuilderNodeKind::vertex_preimage && !on_boundary)
      stopped_inside[static_cast<std::size_t>(ends[i].first)] = 1;
    i = j;
  }
  const auto n1 = static_cast<std::size_t>(in.s1.element_count());
  std::vector<char> marked(n1, 0);
  for (const Segment& seg : in.segments) {
    if (seg.target_edge != invalid_index && !stopped_inside[static_cast<std::size_t>(seg.target_edge)]) continue;
    if (seg.along_edge)
      for (const EdgeIncidence& incidence : in.s1.edge_elements(seg.where)) marked[static_cast<std::size_t>(incidence.element)] = 1;
    else
      marked[static_cast<std::size_t>(seg.where)] = 1;
  }
  std::vector<Index> elements;
  for (std::size_t t = 0; t < n1; ++t)
    if (marked[t] && (reuse == nullptr || !reuse->reuses(static_cast<Index>(t)))) elements.push_back(static_cast<Index>(t));
  return elements;
}

}  // namespace plmap::detail
